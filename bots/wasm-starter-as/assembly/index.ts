// A starter bot for the server to host, in AssemblyScript: TypeScript-like
// code that compiles to WebAssembly with nothing but npm (no Rust).
//
//   npm ci && npm run build        # writes build/starter.wasm
//
// It follows the contract of the server's hosted bots (docs/hosted-bots.md):
// it exports `memory`, `chapaev_alloc` and `chapaev_decide`, and imports only
// `chapaev.simulate` and `chapaev.random`. For each decision it reads the
// request's JSON ({"me": side, "view": the public match view}), aims each of
// its pieces straight at each enemy piece at three speeds, simulates all of
// them in one batch on the server's own engine, and plays the one that
// knocks off the most enemies for the fewest of its own (ties broken by the
// decision's random stream). It keeps its side under the pie rule.

import { Json, parse } from "./json";

// ---- the host --------------------------------------------------------------

/** Plays `count` shots (SHOT_FIELDS f64 each at `shots`) on the board at
 * `board` (BOARD_FIELDS f64) and writes STRIDE f64 per shot at `out`;
 * 0 when played, a negative status otherwise. */
@external("chapaev", "simulate")
declare function hostSimulate(board: usize, shots: usize, count: i32, out: usize): i32;

/** The next 64 bits of the decision's random stream. */
@external("chapaev", "random")
declare function hostRandom(): i64;

/** `x, y` of piece id `k` at `2k`, NaN when it is off the board. */
const BOARD_FIELDS: i32 = 32;
/** `piece, vx, vy, noise_angle, noise_speed` (NaN noise: no draw). */
const SHOT_FIELDS: i32 = 5;
/** Numbers per simulated shot in the answer (layout below). */
const STRIDE: i32 = 56;
/** Row offsets: status (0 played), verdict (0 shoot-again), and the
 * pieces of each side knocked off. */
const ROW_STATUS: i32 = 0;
const ROW_VERDICT: i32 = 1;
const ROW_WHITE_LOST: i32 = 6;
const ROW_BLACK_LOST: i32 = 7;

/** Fractions of the maximum speed tried (just under 1 at full power: a
 * unit direction times the maximum can round a hair above it). */
const SPEEDS: f64[] = [0.5, 0.75, 0.999];

const RESIGN = '{"type":"resign"}';

// ---- the decision ----------------------------------------------------------

function isWhite(id: i32): bool {
  return id < 8;
}

/** The answer, as the JSON of a client message, for one request. */
function decide(request: Json): string {
  const view = request.get("view");
  const meField = request.get("me");
  if (view == null || meField == null) return RESIGN;
  const white = meField.str == "white";
  const phase = view.get("phase");
  if (phase != null) {
    const name = phase.get("phase");
    if (name != null && name.str == "pie-decision") {
      return '{"type":"pie-decision","swap":false}';
    }
  }
  const config = view.get("config");
  const boardField = view.get("board");
  if (config == null || boardField == null) return RESIGN;
  const maxSpeedField = config.get("max_speed");
  if (maxSpeedField == null) return RESIGN;
  const maxSpeed = maxSpeedField.num;

  // The board as the host reads it, and whose piece is where.
  const board = new Float64Array(BOARD_FIELDS);
  board.fill(NaN);
  const mine = new Array<i32>();
  const theirs = new Array<i32>();
  for (let i = 0; i < boardField.items.length; i++) {
    const piece = boardField.items[i];
    const idField = piece.get("id");
    const pos = piece.get("pos");
    if (idField == null || pos == null || pos.items.length != 2) continue;
    const id = <i32>idField.num;
    if (id < 0 || id >= BOARD_FIELDS / 2) continue;
    board[2 * id] = pos.items[0].num;
    board[2 * id + 1] = pos.items[1].num;
    if (isWhite(id) == white) mine.push(id);
    else theirs.push(id);
  }
  if (mine.length == 0) return RESIGN;

  // Every candidate: each of mine straight at each of theirs, three speeds.
  const pieces = new Array<i32>();
  const vxs = new Array<f64>();
  const vys = new Array<f64>();
  for (let a = 0; a < mine.length; a++) {
    const m = mine[a];
    for (let b = 0; b < theirs.length; b++) {
      const t = theirs[b];
      const dx = board[2 * t] - board[2 * m];
      const dy = board[2 * t + 1] - board[2 * m + 1];
      const len = Math.sqrt(dx * dx + dy * dy);
      if (!(len > 0)) continue;
      for (let k = 0; k < SPEEDS.length; k++) {
        const speed = SPEEDS[k] * maxSpeed;
        pieces.push(m);
        vxs.push((dx / len) * speed);
        vys.push((dy / len) * speed);
      }
    }
  }
  const count = pieces.length;
  if (count == 0) return shot(mine[0], 0.0, (white ? 0.5 : -0.5) * maxSpeed);

  const shots = new Float64Array(count * SHOT_FIELDS);
  for (let c = 0; c < count; c++) {
    shots[c * SHOT_FIELDS] = <f64>pieces[c];
    shots[c * SHOT_FIELDS + 1] = vxs[c];
    shots[c * SHOT_FIELDS + 2] = vys[c];
    shots[c * SHOT_FIELDS + 3] = NaN;
    shots[c * SHOT_FIELDS + 4] = NaN;
  }
  const out = new Float64Array(count * STRIDE);
  const status = hostSimulate(board.dataStart, shots.dataStart, count, out.dataStart);
  if (status != 0) return shot(pieces[0], vxs[0], vys[0]);

  let best = -1;
  let bestScore = -Infinity;
  const myLost = white ? ROW_WHITE_LOST : ROW_BLACK_LOST;
  const theirLost = white ? ROW_BLACK_LOST : ROW_WHITE_LOST;
  for (let c = 0; c < count; c++) {
    const row = c * STRIDE;
    if (out[row + ROW_STATUS] != 0.0) continue; // refused: not a shot to play
    const tie = <f64>(<u64>hostRandom() >> 11) / 9007199254740992.0 * 0.01;
    let score = out[row + theirLost] - 1.5 * out[row + myLost] + tie;
    if (out[row + ROW_VERDICT] == 0.0) score += 0.5;
    if (score > bestScore) {
      bestScore = score;
      best = c;
    }
  }
  if (best < 0) return RESIGN;
  return shot(pieces[best], vxs[best], vys[best]);
}

/** A shot message. */
function shot(piece: i32, vx: f64, vy: f64): string {
  return '{"type":"shot","piece":' + piece.toString() + ',"velocity":[' +
    vx.toString() + "," + vy.toString() + "]}";
}

// ---- the exports -----------------------------------------------------------

/** `len` writable bytes for the request (the instance lives for one
 * decision, so nothing is ever freed). */
export function chapaev_alloc(len: i32): usize {
  return heap.alloc(<usize>max(len, 0));
}

/** Reads the request at `ptr..ptr+len`, decides, and returns the answer's
 * place packed as `ptr << 32 | len`. */
export function chapaev_decide(ptr: usize, len: i32): i64 {
  const request = parse(String.UTF8.decodeUnsafe(ptr, <usize>max(len, 0)));
  const answer = request == null ? RESIGN : decide(request);
  const bytes = String.UTF8.encode(answer);
  return (<i64>changetype<usize>(bytes) << 32) | <i64>bytes.byteLength;
}
