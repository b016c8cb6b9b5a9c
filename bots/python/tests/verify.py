"""Verifies each match record file given (argv[1:]) with chapaev.verify,
printing one JSON line per file: {"verified": true, scheme, commitment,
shots, draws} or {"verified": false, "code": ...}. The e2e test
tests/tests/verify_everywhere.rs compares every line with native Rust. The
record is checked both as its JSON text and parsed: the two must agree.
"""

import json
import sys

import chapaev


def outcome(record):
    try:
        return {"verified": True, **chapaev.verify(record)}
    except chapaev.SimulateError as e:
        return {"verified": False, "code": e.code}


for path in sys.argv[1:]:
    with open(path, encoding="utf-8") as f:
        text = f.read()
    from_text = outcome(text)
    if outcome(json.loads(text)) != from_text:
        raise SystemExit(f"{path}: text and dict disagree")
    print(json.dumps(from_text))
