// Types of the `chapaev` package (hand-written; the shapes are the wire
// protocol's, docs/protocol.md). Units are SI: metres, seconds, m/s.

/** `[x, y]` (m, or m/s for a velocity). */
export type Vec2 = [number, number];

/** 0–7 are White's pieces on files a–h, 8–15 Black's. */
export type PieceId = number;

export type Side = "white" | "black";

/** A piece standing on the board: its id and centre. */
export interface Piece {
  id: PieceId;
  pos: Vec2;
}

/** Gaussian execution noise (standard deviations). */
export interface NoiseConfig {
  /** Of the direction, radians. */
  angle_sigma: number;
  /** Of the speed, as a fraction of the aimed speed. */
  speed_sigma: number;
}

export interface Variants {
  two_row_advance: boolean;
  pie_rule: boolean;
  quick_match: boolean;
  noise: NoiseConfig | null;
  /** The rows meet two ranks apart (the `standard` rules); absent: false. */
  rows_keep_apart?: boolean;
  /** Who opens the rounds after the first; absent: "winner". */
  opening?: "winner" | "loser" | "alternate";
}

/** A match's configuration (`view.config`). Missing fields take the defaults. */
export interface Config {
  square: number;
  piece_radius: number;
  piece_mass: number;
  mu: number;
  g: number;
  restitution: number;
  max_speed: number;
  max_events_per_shot: number;
  variants: Variants;
}

/** What may be given as a configuration: any subset of one. */
export type ConfigInput = Partial<Omit<Config, "variants">> & {
  variants?: Partial<Variants>;
};

/** One draw of execution noise: two standard normal numbers. */
export interface NoiseDraw {
  angle: number;
  speed: number;
}

/** One shot to simulate (the body of `POST /api/simulate`). */
export interface SimulateRequest {
  /** The default (casual) configuration when left out. */
  config?: ConfigInput;
  /** The pieces on the board, each named once. */
  board: Piece[];
  /** The piece flicked; its side is the shooter. */
  piece: PieceId;
  /** The velocity as aimed, m/s. */
  velocity: Vec2;
  /** Applied with the configuration's noise model (ignored without one). */
  noise?: NoiseDraw | null;
  /** Whether to return the film (every piece's motion). */
  film?: boolean;
}

export type RoundResult = { result: "won"; side: Side } | { result: "draw" };

/** What the turn rule makes of a shot. */
export type Verdict =
  | { verdict: "shoot-again" }
  | { verdict: "pass-turn" }
  | ({ verdict: "round-over" } & RoundResult);

export type EndReason = "rest" | "free" | "until" | "max-collisions" | "max-events";

export interface Material {
  radius: number;
  mass: number;
  mu: number;
  restitution: number;
}

export interface Trajectory {
  t0: number;
  pos: Vec2;
  vel: Vec2;
  alpha: number;
}

export interface BodyState {
  id: number;
  material: Material;
  trajectory: Trajectory;
}

export interface Line {
  a: Vec2;
  b: Vec2;
  kind: "line" | "ray" | "segment";
  sensor?: boolean;
}

export interface Snapshot {
  t: number;
  g: number;
  bodies: BodyState[];
  points: { pos: Vec2 }[];
  lines: Line[];
}

export interface SceneDiff {
  from: number;
  to: number;
  /** `[body id, its new state, or null when it fell off]`. */
  bodies: [number, BodyState | null][];
  fixed?: { g: number; points: { pos: Vec2 }[]; lines: Line[] };
}

/** One shot's motion (a `shot-played` message's `film`). */
export interface Film {
  start: Snapshot;
  diffs: SceneDiff[];
  end: number;
}

/** What one simulated shot did. */
export interface Simulation {
  /** The velocity played: the aimed one with the noise draw applied. */
  played: Vec2;
  /** The pieces knocked off, in the order they fell. */
  knocked_off: PieceId[];
  /** Where the pieces came to rest (the pieces left, in id order). */
  board: Piece[];
  verdict: Verdict;
  /** When the last piece came to rest, s after the flick. */
  duration: number;
  end_reason: EndReason;
  /** Only when the request asked for it. */
  film?: Film;
}

/** One piece at one moment of a shot. */
export interface MovingPiece {
  id: PieceId;
  pos: Vec2;
  vel: Vec2;
}

/** The pieces still on the board at time `t` of a shot. */
export interface Moment {
  t: number;
  pieces: MovingPiece[];
}

/** The wire error codes this package throws or returns. */
export type ErrorCode =
  | "bad-message"
  | "bad-config"
  | "bad-board"
  | "not-your-piece"
  | "piece-off-board"
  | "not-finite"
  | "zero-speed"
  | "too-fast"
  | "internal";

/** Every refusal is thrown as an `Error` with the wire code. */
export interface ChapaevError extends Error {
  code: ErrorCode;
}

/** A refusal returned by `validateShot`. */
export interface Refusal {
  code: ErrorCode;
  message: string;
}

/**
 * An unsigned 64-bit seed: a BigInt (`0n` to `2n ** 64n - 1n`) or an
 * integer number from 0 to `Number.MAX_SAFE_INTEGER`.
 */
export type Seed = bigint | number;

/**
 * Loads the WebAssembly module. Required once in the browser before any
 * other call (`await init()`; the `.wasm` is fetched next to the module, or
 * give its URL, bytes or a compiled module). In Node the module is loaded on
 * import and `init()` resolves at once.
 */
export default function init(
  input?: { module_or_path: unknown } | string | URL | ArrayBuffer | ArrayBufferView | object,
): Promise<unknown>;

/** One shot simulated: exactly the server's `POST /api/simulate`. Throws a `ChapaevError`. */
export function simulate(request: SimulateRequest): Simulation;

/** What `verify` checked of a finished match. */
export interface Verification {
  /** The noise scheme: `"chacha20"`. */
  scheme: "chacha20";
  /** SHA-256 of the revealed secret, lowercase hex: the commitment it opened. */
  commitment: string;
  /** Shots whose noise and outcome were checked. */
  shots: number;
  /** Each shot's draw, in order. */
  draws: NoiseDraw[];
}

/**
 * Checks a finished match's record (its JSON text from
 * `GET /api/matches/ID/record`, or that text parsed): the revealed secret
 * opens the commitment, every shot's `played` velocity is its `aimed` one
 * under the secret's draw, and the match replays to every recorded outcome.
 * Throws an `Error` whose `code` is `commitment-mismatch`, `noise-mismatch`,
 * `replay-diverged`, `secret-not-revealed`, `uncommitted`, `bad-record` or
 * `unsupported-physics`.
 */
export function verify(record: string | object): Verification;

/**
 * The answer of `Simulator.playMany`: 56 numbers per shot (shot `k` at
 * `56 * k`), at these offsets:
 *
 * - 0: status: 0 played, else the refusal `play` would have thrown:
 *   1 bad-message (the piece is not an integer id 0 to 15), 2 not-finite,
 *   3 zero-speed, 4 too-fast, 5 piece-off-board, 6 internal, 7 other;
 * - 1: verdict: 0 shoot-again, 1 pass-turn, 2 round over (White won),
 *   3 round over (Black won), 4 round over (draw);
 * - 2, 3: the velocity played (after noise);
 * - 4: duration, s after the flick;
 * - 5: end reason: 0 rest, 1 free, 2 until, 3 max-collisions, 4 max-events;
 * - 6, 7: how many White, Black pieces were knocked off;
 * - 8 to 23: the ids knocked off, in the order they fell, then NaN;
 * - 24 to 55: `x, y` of piece id `i` at rest at `24 + 2 * i`, NaN when
 *   that piece is not on the board (knocked off, or never there).
 *
 * A refused shot has its status and NaN everywhere else.
 */
export type PlayManyResult = Float64Array;

/** The status numbers of `Simulator.playMany` (offset 0 of each shot). */
export type PlayManyStatus = 0 | 1 | 2 | 3 | 4 | 5 | 6 | 7;

/** Plays candidate shots on one position, checked and converted once. */
export class Simulator {
  /** Throws `bad-config` or `bad-board` as `simulate` would. */
  constructor(config: ConfigInput | null | undefined, board: Piece[]);
  /** The result of `simulate` on the same request, without a film. */
  play(piece: PieceId, velocity: Vec2, noise?: NoiseDraw | null): Simulation;
  /**
   * Many shots in one call, the very bits of `play` on each. `shots` holds
   * 5 numbers per shot: `piece, vx, vy, noiseAngle, noiseSpeed`
   * (`NaN, NaN` for no noise draw; the draw is applied only when the
   * configuration has a noise model). The answer holds
   * 56 numbers per shot, laid out as {@link PlayManyResult} says. A
   * refused shot does not throw: its status is nonzero
   * ({@link PlayManyStatus}) and every other number NaN. Throws
   * `bad-message` only when the length is not a multiple of 5.
   */
  playMany(shots: Float64Array | ArrayLike<number>): PlayManyResult;
  readonly config: Config;
  readonly board: Piece[];
  /** Releases the wasm memory now (otherwise when garbage-collected). */
  free(): void;
}

/** `null` when `side` may play `piece` at `velocity` on `board`, else why not. Never throws. */
export function validateShot(
  config: ConfigInput | null | undefined,
  board: Piece[],
  side: Side,
  piece: PieceId,
  velocity: Vec2,
): Refusal | null;

/** The ids of `side`'s pieces on `board`, in id order. */
export function legalPieces(board: Piece[], side: Side): PieceId[];

/** The `casual` rules (the defaults). */
export function defaultConfig(): Config;
/** The `standard` rules: execution noise and the pie rule. */
export function standardConfig(): Config;
/** `"casual"` or `"standard"`; throws `bad-config` for another name. */
export function configFor(name: "casual" | "standard" | string): Config;
/** The pieces at the start of a match. */
export function initialBoard(config?: ConfigInput | null): Piece[];
/** The centre of the square on `file`, `rank` (0–7). */
export function squareCentre(config: ConfigInput | null | undefined, file: number, rank: number): Vec2;
/** Whether a centre at `pos` is on the board (edges included). */
export function isOnBoard(config: ConfigInput | null | undefined, pos: Vec2): boolean;

/** The pieces on the board at time `t` (s after the flick) of a shot. */
export function sceneAt(film: Film, t: number): Moment;

/** A film converted once, for drawing many moments of one shot. */
export class FilmPlayer {
  constructor(film: Film);
  readonly duration: number;
  sceneAt(t: number): Moment;
  free(): void;
}

/** SplitMix64, the game's noise generator: draws bit for bit as the server's. */
export class NoiseRng {
  constructor(seed: Seed);
  /** The next draw, as Rust's `NoiseDraw::sample`. */
  draw(): NoiseDraw;
  nextU64(): bigint;
  /** Uniform in [0, 1). */
  nextF64(): number;
  free(): void;
}

/** `count` successive draws of `new NoiseRng(seed)`. */
export function noiseSample(seed: Seed, count: number): NoiseDraw[];

/** The velocity played when `velocity` is aimed with `draw` under `config`'s noise model. */
export function applyNoise(config: ConfigInput | null | undefined, velocity: Vec2, draw: NoiseDraw): Vec2;

/** Rust's `random_request(&mut SplitMix64::new(seed))` (tests, benchmarks). */
export function randomRequest(seed: Seed): SimulateRequest;
/** `count` successive random requests from one `SplitMix64::new(seed)`. */
export function randomRequests(seed: Seed, count: number): SimulateRequest[];

/** The wire protocol version these shapes follow. */
export function protocolVersion(): number;
