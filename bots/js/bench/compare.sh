#!/usr/bin/env bash
# The JavaScript binding's throughput next to native Rust, in one run, over
# the same positions (random_request from one SplitMix64 seeded S, N of them).
#
#   bots/js/bench/compare.sh [COUNT] [SEED]      (defaults 20000 1)
#
# Builds what it needs first (bots/js/build.sh, the release `bots` binary),
# then prints the JSON lines of both, and the ratio.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
count="${1:-20000}"
seed="${2:-1}"
cd "$root"
bash bots/js/build.sh >&2
if cargo run --release -q -p bots -- help throughput >/dev/null 2>&1; then
  native="$(cargo run --release -q -p bots -- throughput --count "$count" --seed "$seed")"
else
  native=""
  echo "compare.sh: this checkout's bots has no throughput command; JS only" >&2
fi
js="$(node bots/js/bench/throughput.mjs --count "$count" --seed "$seed")"
if [ -n "$native" ]; then echo "$native"; fi
echo "$js"
if [ -n "$native" ]; then
  node -e '
    const [native, ...js] = process.argv.slice(1).join("\n").split("\n").filter(Boolean).map(JSON.parse);
    for (const j of js) {
      const same = j.knocked_off === native.knocked_off ? "same pieces knocked off" : "KNOCKED-OFF COUNTS DIFFER";
      console.log(`${j.api}: ${(j.shots_per_cpu_second / native.shots_per_cpu_second * 100).toFixed(0)}% of native (${same})`);
    }' "$native" "$js"
fi
