"""Same bits as native Rust: reads JSON-lines SimulateRequests from the file
given as argv[1] and writes, for each, one JSON line to stdout: what
chapaev.simulate returned, or {"error": code} when it refused the request.

The e2e test tests/tests/bindings_python.rs compares every line with the
native SimulateRequest::run, bit for bit.
"""

import json
import sys

import chapaev


def main() -> int:
    if len(sys.argv) != 2:
        print("usage: same_bits.py REQUESTS.jsonl", file=sys.stderr)
        return 2
    out = []
    with open(sys.argv[1], encoding="utf-8") as f:
        for line in f:
            if not line.strip():
                continue
            request = json.loads(line)
            try:
                result = chapaev.simulate(request)
            except chapaev.SimulateError as e:
                result = {"error": e.code}
            out.append(json.dumps(result))
    sys.stdout.write("\n".join(out) + ("\n" if out else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
