#!/usr/bin/env bash
# The Python binding's throughput beside the native simulator's, over the
# same requests: prints two JSON lines (binding python, binding native).
#   bots/python/bench/compare.sh [--count N] [--seed S]
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
count=10000
seed=1
while [[ $# -gt 0 ]]; do
    case "$1" in
        --count) count="$2"; shift 2 ;;
        --seed) seed="$2"; shift 2 ;;
        *) echo "usage: $0 [--count N] [--seed S]" >&2; exit 2 ;;
    esac
done
python="$("$repo/bots/python/build.sh" | tail -n 1)"
"$python" "$repo/bots/python/bench/throughput.py" --count "$count" --seed "$seed"
cd "$repo"
if cargo run --quiet --release -p bots -- throughput --help >/dev/null 2>&1; then
    cargo run --quiet --release -p bots -- throughput --count "$count" --seed "$seed"
else
    echo "compare.sh: the native twin (cargo run --release -p bots -- throughput) is not in this checkout; skipped" >&2
fi
