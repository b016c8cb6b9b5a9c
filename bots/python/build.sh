#!/usr/bin/env bash
# Builds the `chapaev` Python module and installs it, with the example
# bot's requirements, into a virtual environment:
#   $CHAPAEV_PY_VENV, default target/py-venv in the repository.
# Idempotent: a stamp in the venv holds a hash of every source the module is
# built from (this crate, game, engine, Cargo.lock, the requirements) and
# the Python version; when it matches, nothing is done (well under a second).
# The Rust build goes to $CHAPAEV_PY_TARGET (default target/py-build), a
# cargo target folder of its own, so that it never waits for the lock of a
# cargo command that is running this script (the e2e tests do).
# Prints the venv's python on its last line.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
venv="${CHAPAEV_PY_VENV:-$repo/target/py-venv}"
python="${PYTHON:-python3}"
export CARGO_TARGET_DIR="${CHAPAEV_PY_TARGET:-$repo/target/py-build}"

command -v "$python" >/dev/null || { echo "build.sh: $python not found (install Python 3.9 or later)" >&2; exit 1; }

stamp_of() {
    (
        cd "$repo"
        "$python" --version
        find bots/python/Cargo.toml bots/python/pyproject.toml bots/python/chapaev.pyi bots/python/src \
            game/Cargo.toml game/src engine/Cargo.toml engine/src Cargo.toml Cargo.lock \
            bots/examples/python/requirements.txt -type f -print0 | sort -z | xargs -0 sha256sum
    ) | sha256sum | cut -d' ' -f1
}

# One build at a time (test binaries may run this script in parallel).
mkdir -p "$(dirname "$venv")"
if command -v flock >/dev/null; then
    exec 9>"$venv.lock"
    flock 9
fi

want="$(stamp_of)"
stamp="$venv/.chapaev-stamp"
if [[ -x "$venv/bin/python" && -f "$stamp" && "$(cat "$stamp")" == "$want" ]]; then
    echo "$venv/bin/python"
    exit 0
fi

if [[ ! -x "$venv/bin/python" ]]; then
    echo "build.sh: creating $venv" >&2
    "$python" -m venv "$venv"
fi
start=$SECONDS
echo "build.sh: building chapaev and installing it into $venv (the first build takes a few minutes)" >&2
# From the repository root: the requirements' paths are relative to it.
(cd "$repo" && "$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    -r bots/examples/python/requirements.txt >&2)
"$venv/bin/python" -c "import chapaev" >&2
echo "$want" >"$stamp"
echo "build.sh: done in $((SECONDS - start)) s" >&2
echo "$venv/bin/python"
