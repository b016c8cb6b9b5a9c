// Same bits: reads JSON-lines SimulateRequests from the file argv[2] and
// writes one JSON line per request to stdout: the Simulation `simulate`
// returned (JSON.stringify of the very object), or {"error": code}; without
// a film, `new Simulator(config, board).play(piece, velocity, noise)` must
// give the same, or the line is {"error": "simulator-differs", ...}.
// tests/tests/bindings_js.rs compares every line with the native run.
//
//   node bots/js/tests/same_bits.mjs requests.jsonl > simulations.jsonl
import { readFileSync, writeSync } from "node:fs";
import { simulate, Simulator } from "../pkg/node/index.mjs";

const file = process.argv[2];
if (!file) {
  console.error("usage: node same_bits.mjs REQUESTS.jsonl");
  process.exit(2);
}
// JSON.stringify writes -0 as 0; keep its sign (serde_json writes -0.0).
const NEG_ZERO = "\u0000-0";
const keepSign = (_k, v) => (Object.is(v, -0) ? NEG_ZERO : v);
const stringify = (v) => JSON.stringify(v, keepSign).replaceAll('"\\u0000-0"', "-0.0");

const out = [];
for (const line of readFileSync(file, "utf8").split("\n")) {
  if (line.trim() === "") continue;
  let result;
  try {
    const req = JSON.parse(line);
    result = stringify(simulate(req));
    // The Simulator's fast path must give the very same answer.
    if (!req.film) {
      const s = new Simulator(req.config, req.board);
      const again = stringify(s.play(req.piece, req.velocity, req.noise));
      s.free();
      if (again !== result) result = JSON.stringify({ error: "simulator-differs", simulate: result, simulator: again });
    }
  } catch (e) {
    result = JSON.stringify({ error: e.code ?? "no-code", message: String(e.message) });
  }
  out.push(result);
}
// One write: stdout may be a pipe, and process.exit must not cut it short.
const text = out.join("\n") + "\n";
const bytes = Buffer.from(text);
for (let off = 0; off < bytes.length; ) off += writeSync(1, bytes, off);
