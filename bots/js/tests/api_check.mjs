// The API besides `simulate`, checked from JavaScript: hostile input is a
// thrown Error with the wire code (never a crash), validateShot returns
// refusals, and the seeded functions print what the Rust test compares
// with the native ones (one JSON object on stdout).
//
//   node bots/js/tests/api_check.mjs
import assert from "node:assert/strict";
import {
  simulate, Simulator, validateShot, legalPieces, defaultConfig, standardConfig,
  configFor, initialBoard, squareCentre, isOnBoard, sceneAt, FilmPlayer, NoiseRng,
  noiseSample, applyNoise, randomRequest, randomRequests, protocolVersion,
} from "../pkg/node/index.mjs";
import init from "../pkg/node/index.mjs";

await init(); // resolves at once in Node; the same code runs in a browser

const codeOf = (f) => {
  try {
    f();
  } catch (e) {
    assert.ok(e instanceof Error, `thrown value is an Error: ${e}`);
    assert.equal(typeof e.message, "string");
    return e.code;
  }
  return null;
};

const casual = defaultConfig();
const standard = standardConfig();
assert.deepEqual(configFor("casual"), casual);
assert.deepEqual(configFor("standard"), standard);
assert.equal(codeOf(() => configFor("blitz")), "bad-config");
assert.equal(standard.variants.pie_rule, true);
assert.equal(protocolVersion(), 1);

const board = initialBoard(casual);
assert.equal(board.length, 16);
assert.deepEqual(board[4], { id: 4, pos: squareCentre(casual, 4, 0) });
assert.ok(isOnBoard(casual, [0.1, 0.1]) && !isOnBoard(casual, [-0.001, 0.1]));
assert.deepEqual(legalPieces(board, "black"), [8, 9, 10, 11, 12, 13, 14, 15]);

// The opening shot up the e-file, through every entry point.
const req = { board, piece: 4, velocity: [0, 2] };
const sim = simulate(req);
assert.ok(sim.knocked_off.includes(12));
assert.deepEqual(sim.verdict, { verdict: "shoot-again" });
assert.equal(sim.film, undefined);
assert.ok(Array.isArray(sim.played) && sim.played.length === 2);
const s = new Simulator(casual, board);
assert.deepEqual(s.play(4, [0, 2]), sim);
assert.deepEqual(s.play(4, [0, 2], null), sim);
assert.deepEqual(new Simulator(undefined, board).play(4, [0, 2]), sim);
assert.deepEqual(s.board, board);

// Noise: the Simulator, simulate and applyNoise agree.
const draw = { angle: 0.7, speed: -1.2 };
const noisy = simulate({ config: standard, board, piece: 3, velocity: [0.2, 1.5], noise: draw });
assert.deepEqual(new Simulator(standard, board).play(3, [0.2, 1.5], draw), noisy);
assert.deepEqual(applyNoise(standard, [0.2, 1.5], draw), noisy.played);
assert.deepEqual(applyNoise(casual, [0.2, 1.5], draw), [0.2, 1.5]);

// The film: the start, the end, and a FilmPlayer agreeing with sceneAt.
const filmed = simulate({ ...req, film: true });
assert.deepEqual({ ...filmed, film: undefined }, { ...sim, film: undefined });
const first = sceneAt(filmed.film, 0);
assert.equal(first.pieces.length, 16);
assert.deepEqual(first.pieces.find((p) => p.id === 4).vel, [0, 2]);
const last = sceneAt(filmed.film, filmed.duration);
assert.deepEqual(last.pieces.map((p) => ({ id: p.id, pos: p.pos })), sim.board);
const player = new FilmPlayer(filmed.film);
assert.equal(player.duration, filmed.duration);
assert.deepEqual(player.sceneAt(0.05), sceneAt(filmed.film, 0.05));

// Hostile input: a thrown Error with the wire code, never a crash.
const hostile = [
  ["NaN velocity", () => simulate({ ...req, velocity: [NaN, 1] }), "not-finite"],
  ["infinite velocity", () => s.play(4, [Infinity, 0]), "not-finite"],
  ["zero velocity", () => s.play(4, [0, 0]), "zero-speed"],
  ["too fast", () => s.play(4, [0, 1e9]), "too-fast"],
  ["NaN position", () => simulate({ ...req, board: [{ id: 0, pos: [NaN, 0.1] }, ...board.slice(1)] }), "bad-board"],
  ["a piece twice", () => new Simulator(casual, [...board, board[0]]), "bad-board"],
  ["overlap", () => new Simulator(casual, [board[0], { id: 1, pos: [board[0].pos[0] + 0.01, board[0].pos[1]] }]), "bad-board"],
  ["bad config", () => simulate({ ...req, config: { mu: -1 } }), "bad-config"],
  ["NaN config", () => new Simulator({ max_speed: NaN }, board), "bad-config"],
  ["NaN noise", () => s.play(4, [0, 1], { angle: NaN, speed: 0 }), "not-finite"],
  ["piece 16", () => s.play(16, [0, 1]), "bad-message"],
  ["piece 4.5", () => s.play(4.5, [0, 1]), "bad-message"],
  ["piece -1", () => s.play(-1, [0, 1]), "bad-message"],
  ["piece as text", () => s.play("4", [0, 1]), "bad-message"],
  ["velocity of 1", () => s.play(4, [1]), "bad-message"],
  ["velocity object", () => s.play(4, { x: 0, y: 1 }), "bad-message"],
  ["no board", () => simulate({ piece: 4, velocity: [0, 1] }), "bad-message"],
  ["null request", () => simulate(null), "bad-message"],
  ["number request", () => simulate(5), "bad-message"],
  ["string board", () => new Simulator(casual, "board"), "bad-message"],
  ["noise of text", () => s.play(4, [0, 1], "noise"), "bad-message"],
  ["film of text", () => sceneAt("film", 0), "bad-message"],
  ["empty film", () => new FilmPlayer({}), "bad-message"],
  ["piece knocked off", () => new Simulator(casual, board.slice(5)).play(4, [0, 1]), "piece-off-board"],
  ["NaN draw", () => applyNoise(standard, [0, 1], { angle: 0, speed: NaN }), "not-finite"],
  ["negative seed", () => new NoiseRng(-1), "bad-message"],
  ["fractional seed", () => noiseSample(1.5, 3), "bad-message"],
  ["unsafe seed", () => randomRequest(2 ** 60), "bad-message"],
  ["BigInt seed too big", () => randomRequest(2n ** 64n), "bad-message"],
  ["text seed", () => randomRequest("7"), "bad-message"],
  ["a billion draws", () => noiseSample(1, 1e9), "bad-message"],
];
for (const [name, f, code] of hostile) assert.equal(codeOf(f), code, name);
// Still alive and exact after all that.
assert.deepEqual(s.play(4, [0, 2]), sim);
assert.deepEqual(sceneAt(filmed.film, NaN).pieces.length >= 0, true);

// validateShot: refusals returned, never thrown.
assert.equal(validateShot(casual, board, "white", 4, [0, 2]), null);
const refusals = [
  [[casual, board, "black", 4, [0, 2]], "not-your-piece"],
  [[casual, board.slice(5), "white", 4, [0, 2]], "piece-off-board"],
  [[casual, board, "white", 4, [0, 3]], "too-fast"],
  [[casual, board, "white", 4, [0, 0]], "zero-speed"],
  [[casual, board, "white", 4, [NaN, 0]], "not-finite"],
  [[casual, [...board, board[0]], "white", 4, [0, 1]], "bad-board"],
  [[{ g: 0 }, board, "white", 4, [0, 1]], "bad-config"],
  [[casual, board, "purple", 4, [0, 1]], "bad-message"],
  [[casual, null, "white", 4, [0, 1]], "bad-message"],
];
for (const [args, code] of refusals) {
  const r = validateShot(...args);
  assert.equal(r?.code, code, JSON.stringify(args.slice(2)));
  assert.equal(typeof r.message, "string");
}

// Seeds: a BigInt and the same number give the same stream.
assert.deepEqual(noiseSample(42n, 5), noiseSample(42, 5));
assert.deepEqual(randomRequest(42n), randomRequest(42));
const rng = new NoiseRng(42);
assert.deepEqual([rng.draw(), rng.draw()], noiseSample(42, 2));
assert.equal(typeof new NoiseRng(1n).nextU64(), "bigint");

// For the Rust side to compare with the native functions.
const big = 18446744073709551557n; // 2^64 - 59
const r2 = new NoiseRng(big);
const u64s = [r2.nextU64(), r2.nextU64()].map(String);
const f64s = [r2.nextF64(), r2.nextF64()];
console.log(JSON.stringify({
  noise: noiseSample(big, 1000),
  requests: randomRequests(9, 50),
  request: randomRequest(9),
  u64s,
  f64s,
  applied: applyNoise(standard, [0.3, -1.1], { angle: 1.5, speed: 2.5 }),
  noisy,
  scene: player.sceneAt(filmed.duration / 3),
  film: filmed,
}));
