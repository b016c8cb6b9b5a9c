// Verifies each match record file given, with the package's `verify`,
// printing one JSON line per file: `{"verified": true, scheme, commitment,
// shots, draws}` or `{"verified": false, "code": ...}`. The e2e test
// tests/tests/verify_everywhere.rs compares every line with native Rust.
// The record is checked both as its JSON text and parsed: the two must agree.
//
//   node bots/js/tests/verify.mjs RECORD.json...
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { verify } from "../pkg/node/index.mjs";

const outcome = (record) => {
  try {
    return { verified: true, ...verify(record) };
  } catch (e) {
    assert.ok(e instanceof Error, `thrown value is an Error: ${e}`);
    assert.equal(typeof e.code, "string");
    return { verified: false, code: e.code };
  }
};

for (const path of process.argv.slice(2)) {
  const text = readFileSync(path, "utf8");
  const fromText = outcome(text);
  assert.deepEqual(outcome(JSON.parse(text)), fromText, `${path}: text and object agree`);
  console.log(JSON.stringify(fromText));
}
