// Same bits: reads JSON-lines SimulateRequests from the file argv[2] and
// writes one JSON line per request to stdout: the Simulation `simulate`
// returned (JSON.stringify of the very object), or {"error": code}; without
// a film, `new Simulator(config, board).play(piece, velocity, noise)` must
// give the same, or the line is {"error": "simulator-differs", ...}; and
// `playMany` on the shot (twice, around a refused shot) must give the very
// bits of `play`, or its status the code `play` threw, or the line is
// {"error": "play-many-differs", ...}.
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

// The wire codes of playMany's status numbers.
const STATUS = ["played", "bad-message", "not-finite", "zero-speed", "too-fast", "piece-off-board", "internal"];
const VERDICTS = [
  { verdict: "shoot-again" },
  { verdict: "pass-turn" },
  { verdict: "round-over", result: "won", side: "white" },
  { verdict: "round-over", result: "won", side: "black" },
  { verdict: "round-over", result: "draw" },
];
const END_REASONS = ["rest", "free", "until", "max-collisions", "max-events"];
const STRIDE = 56;

// Shot `k` of a playMany answer as the Simulation `play` returns (status 0),
// or {status}.
const unpack = (a, k) => {
  const o = STRIDE * k;
  if (a[o] !== 0) return { status: a[o] };
  const knocked = [];
  for (let i = 8; i < 24 && !Number.isNaN(a[o + i]); i++) knocked.push(a[o + i]);
  const board = [];
  for (let id = 0; id < 16; id++) {
    const x = a[o + 24 + 2 * id];
    const y = a[o + 25 + 2 * id];
    if (Number.isNaN(x) !== Number.isNaN(y)) return { status: "half-a-position" };
    if (!Number.isNaN(x)) board.push({ id, pos: [x, y] });
  }
  const white = knocked.filter((id) => id < 8).length;
  if (a[o + 6] !== white || a[o + 7] !== knocked.length - white) return { status: "bad-counts" };
  return {
    played: [a[o + 2], a[o + 3]],
    knocked_off: knocked,
    board,
    verdict: VERDICTS[a[o + 1]],
    duration: a[o + 4],
    end_reason: END_REASONS[a[o + 5]],
  };
};

// Whether playMany agrees with `play` on one request: null when it does,
// else why not.
const checkPlayMany = (s, req, played, thrown) => {
  const numbers = typeof req.piece === "number" && Array.isArray(req.velocity) && req.velocity.length === 2
    && req.velocity.every((v) => typeof v === "number")
    && (req.noise == null || (typeof req.noise.angle === "number" && typeof req.noise.speed === "number"));
  if (!numbers) return null; // a shape only `play` can be given
  // NaN, NaN is no draw to playMany, a refused one to `play`.
  if (req.noise != null && Number.isNaN(req.noise.angle) && Number.isNaN(req.noise.speed)) return null;
  const shot = [req.piece, req.velocity[0], req.velocity[1], req.noise?.angle ?? NaN, req.noise?.speed ?? NaN];
  const a = s.playMany(new Float64Array([...shot, 99, 1, 0, NaN, NaN, ...shot]));
  if (!(a instanceof Float64Array) || a.length !== 3 * STRIDE) return "wrong length";
  if (a[STRIDE] !== 1 || !a.subarray(STRIDE + 1, 2 * STRIDE).every(Number.isNaN)) return "refused shot not status 1 and NaN";
  for (const k of [0, 2]) {
    const got = unpack(a, k);
    if (thrown !== null) {
      if (STATUS[got.status] !== thrown) return `status ${got.status} for ${thrown}`;
      if (!a.subarray(STRIDE * k + 1, STRIDE * (k + 1)).every(Number.isNaN)) return "refused shot not NaN";
    } else if (stringify(got) !== played) {
      return stringify(got);
    }
  }
  return null;
};

const out = [];
for (const line of readFileSync(file, "utf8").split("\n")) {
  if (line.trim() === "") continue;
  let result;
  let req;
  try {
    req = JSON.parse(line);
    result = stringify(simulate(req));
    // The Simulator's fast path must give the very same answer.
    if (!req.film) {
      const s = new Simulator(req.config, req.board);
      const again = stringify(s.play(req.piece, req.velocity, req.noise));
      const many = checkPlayMany(s, req, again, null);
      s.free();
      if (again !== result) result = JSON.stringify({ error: "simulator-differs", simulate: result, simulator: again });
      else if (many !== null) result = JSON.stringify({ error: "play-many-differs", play: again, playMany: many });
    }
  } catch (e) {
    result = JSON.stringify({ error: e.code ?? "no-code", message: String(e.message) });
    // A refused shot on a good position: playMany's status is the same code.
    let s = null;
    try {
      if (req && !req.film) s = new Simulator(req.config, req.board);
    } catch {
      // the position itself is refused: nothing for playMany
    }
    if (s !== null) {
      const many = checkPlayMany(s, req, null, e.code);
      s.free();
      if (many !== null) result = JSON.stringify({ error: "play-many-differs", code: e.code, playMany: many });
    }
  }
  out.push(result);
}
// One write: stdout may be a pipe, and process.exit must not cut it short.
const text = out.join("\n") + "\n";
const bytes = Buffer.from(text);
for (let off = 0; off < bytes.length; ) off += writeSync(1, bytes, off);
