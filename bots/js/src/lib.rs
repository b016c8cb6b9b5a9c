//! # chapaev-js — Chapaev for JavaScript and TypeScript
//!
//! The game's shot simulation compiled to WebAssembly with wasm-bindgen:
//! one shot on any position with exactly the server's physics and turn
//! rule ([`game::simulate`]), bit for bit — the same IEEE 754 arithmetic
//! natively and in wasm, and every `f64` crosses the boundary as a JS
//! number with its bits unchanged.
//!
//! Values cross as plain JS objects with the wire protocol's shapes
//! (`docs/protocol.md`), converted by `serde-wasm-bindgen`: a piece is
//! `{id: 4, pos: [x, y]}`, a velocity `[vx, vy]`, a noise draw
//! `{angle, speed}`, a configuration the object of `view.config`. Every
//! refusal is a thrown `Error` whose `code` property is the wire error code
//! (`bad-board`, `too-fast`, ...) and whose message says why; a value of
//! the wrong shape is `bad-message`. Nothing here panics on any input.
//!
//! Seeds are unsigned 64-bit integers: a `BigInt` (`0n` to `2n**64n - 1n`)
//! or a non-negative integer `number` up to `Number.MAX_SAFE_INTEGER`.
//!
//! The package (`bots/js/build.sh` writes it to `bots/js/pkg`) has its own
//! hand-written TypeScript types, `bots/js/index.d.ts`.

use game::batch;
use game::board::{is_on_board, square_centre};
use game::noise::{NoiseDraw, SplitMix64};
use game::protocol::ErrorCode;
use game::simulate::{self, random_request, SimulateRequest};
use game::{Board, Config, Film, Piece, PieceId, Preset, Rows, Shot, Side, Simulation};
use glam::DVec2;
use serde::de::DeserializeOwned;
use serde::Serialize;
use wasm_bindgen::prelude::*;

/// The most items one call makes (noise draws, random requests): a
/// mistaken count fails with `bad-message` instead of exhausting memory.
pub const MAX_BATCH: u32 = 1 << 24;

/// A JS `Error` with `code` set to the wire code.
fn error(code: ErrorCode, message: impl std::fmt::Display) -> JsValue {
    let e = js_sys::Error::new(&message.to_string());
    // Setting a property on a fresh Error object cannot fail.
    let _ = js_sys::Reflect::set(
        &e,
        &JsValue::from_str("code"),
        &JsValue::from_str(code.as_str()),
    );
    e.into()
}

/// A JS value read as `T`; a wrong shape is `bad-message`, as on the wire:
/// a missing field, a wrong type, and also (which serde-wasm-bindgen alone
/// lets through) an unknown field or an array of the wrong length.
fn from_js<T: DeserializeOwned + Serialize>(value: JsValue, what: &str) -> Result<T, JsValue> {
    let bad = |e: &dyn std::fmt::Display| error(ErrorCode::BadMessage, format!("{what}: {e}"));
    let (value, read) = match serde_wasm_bindgen::from_value::<T>(value.clone()) {
        Ok(read) => (value, read),
        // A field given as `undefined` or `null` is, in JavaScript, one left
        // out: read again without them (only when the first reading failed,
        // so the usual call copies nothing).
        Err(_) => {
            let cleaned = without_nullish(&value);
            match serde_wasm_bindgen::from_value::<T>(cleaned.clone()) {
                Ok(read) => (cleaned, read),
                Err(e) => return Err(bad(&e)),
            }
        }
    };
    // Plain values need no further check. For objects, the quick test: the
    // value's JSON read strictly (serde_json honours deny_unknown_fields and
    // array lengths). Only when that fails (a NaN or an infinity is `null` in
    // JSON, a typed array an object, a BigInt no JSON at all) is the value
    // compared field by field with what was read.
    if value.is_object() && !strict_json::<T>(&value) {
        let back = to_js(&read)?;
        let mut path = String::new();
        if let Some(e) = extra(&value, &back, &mut path) {
            return Err(bad(&e));
        }
    }
    Ok(read)
}

/// Whether `value`'s JSON text reads as a `T` without any unknown field or
/// extra array item.
fn strict_json<T: DeserializeOwned>(value: &JsValue) -> bool {
    js_sys::JSON::stringify(value)
        .ok()
        .and_then(|s| s.as_string())
        .is_some_and(|s| serde_json::from_str::<T>(&s).is_ok())
}

/// A copy of `value` with the fields of plain objects that are `null` or
/// `undefined` left out, at every depth (arrays and other values as they are,
/// their items cleaned).
fn without_nullish(value: &JsValue) -> JsValue {
    if let Some(a) = value.dyn_ref::<js_sys::Array>() {
        return a
            .iter()
            .map(|v| without_nullish(&v))
            .collect::<js_sys::Array>()
            .into();
    }
    if !value.is_object() || value.is_function() {
        return value.clone();
    }
    let out = js_sys::Object::new();
    for key in js_sys::Object::keys(value.unchecked_ref::<js_sys::Object>()).iter() {
        let v = js_sys::Reflect::get(value, &key).unwrap_or(JsValue::UNDEFINED);
        if !v.is_null() && !v.is_undefined() {
            let _ = js_sys::Reflect::set(&out, &key, &without_nullish(&v));
        }
    }
    out.into()
}

/// What `input` holds that `back` (the value read from it, written out
/// again) does not: an unknown field (one left `null` or `undefined` is
/// taken as left out) or array items beyond the expected length.
fn extra(input: &JsValue, back: &JsValue, path: &mut String) -> Option<String> {
    if !input.is_object() {
        return None;
    }
    if let (Some(a), Some(b)) = (
        input.dyn_ref::<js_sys::Array>(),
        back.dyn_ref::<js_sys::Array>(),
    ) {
        if a.length() != b.length() {
            return Some(format!(
                "{} items at {}, expected {}",
                a.length(),
                if path.is_empty() {
                    "the top"
                } else {
                    path.as_str()
                },
                b.length()
            ));
        }
        for k in 0..a.length() {
            let len = path.len();
            path.push_str(&format!("[{k}]"));
            let found = extra(&a.get(k), &b.get(k), path);
            path.truncate(len);
            if found.is_some() {
                return found;
            }
        }
        return None;
    }
    let keys = js_sys::Object::keys(input.unchecked_ref::<js_sys::Object>());
    for key in keys.iter() {
        let v = js_sys::Reflect::get(input, &key).unwrap_or(JsValue::UNDEFINED);
        if v.is_null() || v.is_undefined() {
            continue;
        }
        let name = key.as_string().unwrap_or_default();
        let len = path.len();
        if !path.is_empty() {
            path.push('.');
        }
        path.push_str(&name);
        let found = if back.is_object() && js_sys::Reflect::has(back, &key).unwrap_or(false) {
            let w = js_sys::Reflect::get(back, &key).unwrap_or(JsValue::UNDEFINED);
            extra(&v, &w, path)
        } else {
            Some(format!("unknown field {path}"))
        };
        path.truncate(len);
        if found.is_some() {
            return found;
        }
    }
    None
}

/// A configuration, the default (casual) one when `undefined` or `null`.
fn config_from_js(value: JsValue) -> Result<Config, JsValue> {
    Ok(from_js::<Option<Config>>(value, "config")?.unwrap_or_default())
}

/// A value as a plain JS object with the JSON shapes: structs and maps as
/// objects, `DVec2` as `[x, y]`, `None` as `null` (or left out where the
/// wire leaves it out).
fn to_js<T: Serialize>(value: &T) -> Result<JsValue, JsValue> {
    value
        .serialize(&serde_wasm_bindgen::Serializer::json_compatible())
        .map_err(|e| error(ErrorCode::Internal, e))
}

/// A simulation as a plain JS object: its JSON text parsed by the engine
/// (`JSON.parse`), several times quicker than building it field by field
/// across the boundary, and exact: serde_json writes the shortest decimal
/// that reads back as the same double, and `JSON.parse` reads it correctly
/// rounded (a `-0.0` stays negative). A simulation holds only finite numbers
/// (a NaN would read back as `null`, so other values go through [`to_js`]).
fn simulation_to_js(sim: &Simulation) -> Result<JsValue, JsValue> {
    let text = serde_json::to_string(sim).map_err(|e| error(ErrorCode::Internal, e))?;
    js_sys::JSON::parse(&text)
}

/// `piece`, `velocity` and `noise` read without serde when they have the
/// usual shapes (a number, an array of two numbers, nothing or an object of
/// two numbers); `None` sends a value to [`from_js`], which reads or refuses
/// anything else.
fn piece_fast(value: &JsValue) -> Option<PieceId> {
    let n = value.as_f64()?;
    if n.fract() != 0.0 || !(0.0..=15.0).contains(&n) {
        return None;
    }
    PieceId::try_from(n as u8).ok()
}

fn vec2_fast(value: &JsValue) -> Option<DVec2> {
    let a = value.dyn_ref::<js_sys::Array>()?;
    if a.length() != 2 {
        return None;
    }
    Some(DVec2::new(a.get(0).as_f64()?, a.get(1).as_f64()?))
}

fn noise_fast(value: &JsValue) -> Option<Option<NoiseDraw>> {
    if value.is_null() || value.is_undefined() {
        return Some(None);
    }
    if !value.is_object()
        || js_sys::Object::keys(value.unchecked_ref::<js_sys::Object>()).length() != 2
    {
        return None;
    }
    let get = |k: &str| {
        js_sys::Reflect::get(value, &JsValue::from_str(k))
            .ok()?
            .as_f64()
    };
    Some(Some(NoiseDraw {
        angle: get("angle")?,
        speed: get("speed")?,
    }))
}

/// A seed: a `BigInt` or a safe non-negative integer `number`.
fn seed_from_js(value: JsValue) -> Result<u64, JsValue> {
    if let Some(n) = value.as_f64() {
        // A number must be an exact integer (serde would also take a float).
        if !(n >= 0.0 && n.fract() == 0.0 && n <= 9_007_199_254_740_991.0) {
            return Err(error(
                ErrorCode::BadMessage,
                format!("seed: {n} is not an integer from 0 to 2^53 - 1 (use a BigInt for larger seeds)"),
            ));
        }
        return Ok(n as u64);
    }
    if value.is_bigint() {
        return u64::try_from(value).map_err(|_| {
            error(
                ErrorCode::BadMessage,
                "seed: the BigInt is not within 0 to 2^64 - 1",
            )
        });
    }
    Err(error(
        ErrorCode::BadMessage,
        "seed: expected a BigInt or a non-negative integer number",
    ))
}

fn batch(count: u32, what: &str) -> Result<usize, JsValue> {
    if count > MAX_BATCH {
        return Err(error(
            ErrorCode::BadMessage,
            format!("{what}: {count} is more than {MAX_BATCH} in one call"),
        ));
    }
    Ok(count as usize)
}

/// The board of `pieces` under `config`, checked exactly as a simulation
/// request checks it (`bad-config`, `bad-board`).
fn checked_board(config: &Config, pieces: Vec<Piece>) -> Result<Board, JsValue> {
    let piece = match pieces.first() {
        Some(p) => p.id,
        None => PieceId::all()
            .next()
            .ok_or_else(|| error(ErrorCode::Internal, "no piece ids"))?,
    };
    let probe = SimulateRequest {
        config: config.clone(),
        board: pieces,
        piece,
        velocity: DVec2::new(config.max_speed, 0.0),
        noise: None,
        film: false,
    };
    match probe.validate() {
        Ok((board, _)) => Ok(board),
        // Only the probe's own shot is refused: the board itself is fine.
        Err(simulate::SimulateError::Shot(_)) => Ok(Board::from_pieces(probe.board)),
        Err(e) => Err(error(e.code(), e)),
    }
}

/// One shot simulated: exactly `SimulateRequest::run` (the body of
/// `POST /api/simulate`). Throws on a refused request.
#[wasm_bindgen]
pub fn simulate(request: JsValue) -> Result<JsValue, JsValue> {
    let req: SimulateRequest = from_js(request, "request")?;
    let sim = req.run().map_err(|e| error(e.code(), e))?;
    simulation_to_js(&sim)
}

/// Plays candidate shots on one position, checked and converted once.
#[wasm_bindgen]
pub struct Simulator {
    config: Config,
    board: Board,
}

#[wasm_bindgen]
impl Simulator {
    /// A simulator for `board` (pieces `{id, pos}`) under `config` (the
    /// default configuration when `undefined`/`null`). Throws `bad-config`
    /// or `bad-board` as a simulation request would.
    #[wasm_bindgen(constructor)]
    pub fn new(config: JsValue, board: JsValue) -> Result<Simulator, JsValue> {
        let config = config_from_js(config)?;
        let pieces: Vec<Piece> = from_js(board, "board")?;
        let board = checked_board(&config, pieces)?;
        Ok(Simulator { config, board })
    }

    /// `piece` flicked at `velocity` (as aimed), with the configuration's
    /// noise model applied with `noise` when both are there: the very
    /// result of `simulate` on the same request, without a film.
    pub fn play(
        &self,
        piece: JsValue,
        velocity: JsValue,
        noise: JsValue,
    ) -> Result<JsValue, JsValue> {
        let piece = match piece_fast(&piece) {
            Some(p) => p,
            None => from_js(piece, "piece")?,
        };
        let velocity = match vec2_fast(&velocity) {
            Some(v) => v,
            None => from_js(velocity, "velocity")?,
        };
        let noise = match noise_fast(&noise) {
            Some(n) => n,
            None => from_js::<Option<NoiseDraw>>(noise, "noise")?,
        };
        // The steps of SimulateRequest::run after its board check.
        if let Some(n) = &noise {
            if !n.angle.is_finite() || !n.speed.is_finite() {
                let e = simulate::SimulateError::NoiseNotFinite;
                return Err(error(e.code(), e));
            }
        }
        let shot = Shot::new(piece, velocity, &self.config).map_err(|e| error(e.code(), e))?;
        let played = match (&self.config.variants.noise, &noise) {
            (Some(model), Some(draw)) => draw.apply(model, shot.velocity(), self.config.max_speed),
            _ => shot.velocity(),
        };
        let sim = simulate::play(&self.config, &self.board, &shot, played, false)
            .map_err(|e| error(e.code(), e))?;
        simulation_to_js(&sim)
    }

    /// Many shots in one call: `shots` is a flat array (a `Float64Array`
    /// or an array of numbers), 5 per shot: `piece, vx, vy, noiseAngle,
    /// noiseSpeed` (`NaN, NaN` for no noise draw). Returns a `Float64Array`
    /// of 56 numbers per shot (layout in `index.d.ts`),
    /// the very bits of `play` on each. A refused shot does not throw: its
    /// status (offset 0) is nonzero. Throws `bad-message` only when the
    /// length is not a multiple of 5 or above the batch limit.
    #[wasm_bindgen(js_name = playMany)]
    pub fn play_many(&self, shots: &[f64]) -> Result<Vec<f64>, JsValue> {
        if !shots
            .chunks_exact(batch::SHOT_FIELDS)
            .remainder()
            .is_empty()
        {
            return Err(error(
                ErrorCode::BadMessage,
                format!(
                    "shots: {} numbers is not a multiple of {}",
                    shots.len(),
                    batch::SHOT_FIELDS
                ),
            ));
        }
        let n = u32::try_from(shots.len() / batch::SHOT_FIELDS).unwrap_or(u32::MAX);
        self::batch(n, "shots")?;
        Ok(batch::play_many(&self.config, &self.board, shots))
    }

    /// The configuration it plays under.
    #[wasm_bindgen(getter)]
    pub fn config(&self) -> Result<JsValue, JsValue> {
        to_js(&self.config)
    }

    /// The pieces it plays on, in id order.
    #[wasm_bindgen(getter)]
    pub fn board(&self) -> Result<JsValue, JsValue> {
        to_js(&self.board)
    }
}

/// Why `side` may not play `piece` at `velocity` on `board` under
/// `config`: `null` when the shot is playable, else `{code, message}`
/// (`bad-message`, `bad-config`, `bad-board`, `not-your-piece`,
/// `piece-off-board`, `not-finite`, `zero-speed`, `too-fast`). Never
/// throws.
#[wasm_bindgen(js_name = validateShot)]
pub fn validate_shot(
    config: JsValue,
    board: JsValue,
    side: JsValue,
    piece: JsValue,
    velocity: JsValue,
) -> JsValue {
    match check_shot(config, board, side, piece, velocity) {
        Ok(()) => JsValue::NULL,
        Err(e) => {
            let code = js_sys::Reflect::get(&e, &JsValue::from_str("code"))
                .unwrap_or_else(|_| JsValue::from_str(ErrorCode::Internal.as_str()));
            let message = e
                .dyn_ref::<js_sys::Error>()
                .map(|e| JsValue::from(e.message()))
                .unwrap_or_else(|| JsValue::from_str(""));
            let out = js_sys::Object::new();
            let _ = js_sys::Reflect::set(&out, &JsValue::from_str("code"), &code);
            let _ = js_sys::Reflect::set(&out, &JsValue::from_str("message"), &message);
            out.into()
        }
    }
}

fn check_shot(
    config: JsValue,
    board: JsValue,
    side: JsValue,
    piece: JsValue,
    velocity: JsValue,
) -> Result<(), JsValue> {
    let config = config_from_js(config)?;
    let pieces: Vec<Piece> = from_js(board, "board")?;
    let side: Side = from_js(side, "side")?;
    let piece: PieceId = from_js(piece, "piece")?;
    let velocity: DVec2 = from_js(velocity, "velocity")?;
    let board = checked_board(&config, pieces)?;
    // The order of Game::check, after whose turn it is.
    let refused = |e: game::ShotError| error(e.code(), e);
    if piece.side() != side {
        return Err(refused(game::ShotError::NotYourPiece { piece, side }));
    }
    if !board.contains(piece) {
        return Err(refused(game::ShotError::PieceOffBoard(piece)));
    }
    Shot::new(piece, velocity, &config).map_err(refused)?;
    Ok(())
}

/// The ids of `side`'s pieces on `board`, in id order (each once).
#[wasm_bindgen(js_name = legalPieces)]
pub fn legal_pieces(board: JsValue, side: JsValue) -> Result<JsValue, JsValue> {
    let pieces: Vec<Piece> = from_js(board, "board")?;
    let side: Side = from_js(side, "side")?;
    let board = Board::from_pieces(pieces);
    let ids: Vec<PieceId> = board.of(side).map(|p| p.id).collect();
    to_js(&ids)
}

/// The default configuration (the `casual` rules).
#[wasm_bindgen(js_name = defaultConfig)]
pub fn default_config() -> Result<JsValue, JsValue> {
    to_js(&Config::default())
}

/// The configuration of the `standard` rules (noise and the pie rule).
#[wasm_bindgen(js_name = standardConfig)]
pub fn standard_config() -> Result<JsValue, JsValue> {
    to_js(&Config::standard())
}

/// The configuration of the rules named `name` (`casual` or `standard`);
/// `bad-config` for any other name, as the server answers.
#[wasm_bindgen(js_name = configFor)]
pub fn config_for(name: JsValue) -> Result<JsValue, JsValue> {
    let name: String = from_js(name, "rules name")?;
    let preset = Preset::parse(&name)
        .ok_or_else(|| error(ErrorCode::BadConfig, format!("no rules named {name:?}")))?;
    to_js(&preset.config())
}

/// The pieces at the start of a match under `config`: each side's eight
/// on its first row (White rank 0, Black rank 7).
#[wasm_bindgen(js_name = initialBoard)]
pub fn initial_board(config: JsValue) -> Result<JsValue, JsValue> {
    let config = config_from_js(config)?;
    config
        .validate()
        .map_err(|e| error(ErrorCode::BadConfig, e))?;
    to_js(&Board::setup(&config, Rows::initial()))
}

/// The centre `[x, y]` of the square on `file`, `rank` (0–7).
#[wasm_bindgen(js_name = squareCentre)]
pub fn square_centre_js(config: JsValue, file: u8, rank: u8) -> Result<JsValue, JsValue> {
    let config = config_from_js(config)?;
    to_js(&square_centre(&config, file, rank))
}

/// Whether a centre at `pos` (`[x, y]`) is on the board (edges included).
#[wasm_bindgen(js_name = isOnBoard)]
pub fn is_on_board_js(config: JsValue, pos: JsValue) -> Result<bool, JsValue> {
    let config = config_from_js(config)?;
    let pos: DVec2 = from_js(pos, "pos")?;
    Ok(is_on_board(&config, pos))
}

/// One piece at one moment of a shot.
#[derive(Serialize)]
struct MovingPiece {
    id: PieceId,
    pos: DVec2,
    vel: DVec2,
}

/// The pieces on the board at one moment of a shot.
#[derive(Serialize)]
struct Moment {
    t: f64,
    pieces: Vec<MovingPiece>,
}

fn moment(film: &Film, t: f64) -> Moment {
    let scene = film.scene_at(t);
    let pieces = scene
        .bodies
        .iter()
        .filter_map(|b| {
            PieceId::from_body(b.id).ok().map(|id| MovingPiece {
                id,
                pos: b.pos,
                vel: b.vel,
            })
        })
        .collect();
    Moment { t, pieces }
}

/// The pieces still on the board at time `t` (s after the flick) of the
/// shot recorded in `film` (a `shot-played` message's `film`, or
/// `simulate`'s with `film: true`): `{t, pieces: [{id, pos, vel}]}`, the
/// engine's own closed form, in id order.
#[wasm_bindgen(js_name = sceneAt)]
pub fn scene_at(film: JsValue, t: f64) -> Result<JsValue, JsValue> {
    let film: Film = from_js(film, "film")?;
    to_js(&moment(&film, t))
}

/// A film converted once, for drawing many moments of one shot.
#[wasm_bindgen(js_name = FilmPlayer)]
pub struct FilmPlayer {
    film: Film,
}

#[wasm_bindgen(js_class = FilmPlayer)]
impl FilmPlayer {
    /// A player of `film`. Throws `bad-message` on a wrong shape.
    #[wasm_bindgen(constructor)]
    pub fn new(film: JsValue) -> Result<FilmPlayer, JsValue> {
        Ok(FilmPlayer {
            film: from_js(film, "film")?,
        })
    }

    /// When the last piece came to rest, s after the flick.
    #[wasm_bindgen(getter)]
    pub fn duration(&self) -> f64 {
        self.film.duration()
    }

    /// As `sceneAt(film, t)`.
    #[wasm_bindgen(js_name = sceneAt)]
    pub fn scene_at(&self, t: f64) -> Result<JsValue, JsValue> {
        to_js(&moment(&self.film, t))
    }
}

/// Checks a finished match's record (its JSON text, as
/// `GET /api/matches/ID/record` serves it, or that text parsed): the
/// revealed noise secret opens the commitment published before the first
/// shot, every shot's `played` velocity is its `aimed` one under the draw
/// the secret gives it, and the match replays to every recorded outcome.
/// Returns `{scheme, commitment, shots, draws}`; throws an `Error` whose
/// `code` says what failed (`commitment-mismatch`, `noise-mismatch`,
/// `replay-diverged`, `secret-not-revealed`, `uncommitted`, `bad-record`,
/// `unsupported-physics`).
#[wasm_bindgen]
pub fn verify(record: JsValue) -> Result<JsValue, JsValue> {
    let checked = match record.as_string() {
        Some(text) => game::verify_json(&text),
        None => game::verify(&from_js::<game::MatchRecord>(record, "record")?),
    };
    match checked {
        Ok(v) => to_js(&v),
        Err(e) => {
            let err = js_sys::Error::new(&e.to_string());
            let _ = js_sys::Reflect::set(
                &err,
                &JsValue::from_str("code"),
                &JsValue::from_str(e.code()),
            );
            Err(err.into())
        }
    }
}

/// SplitMix64, the generator of the game's noise: draws bit for bit as
/// the Rust `NoiseDraw::sample`.
#[wasm_bindgen]
pub struct NoiseRng {
    rng: SplitMix64,
}

#[wasm_bindgen]
impl NoiseRng {
    /// A generator started from `seed` (BigInt or safe integer number).
    #[wasm_bindgen(constructor)]
    pub fn new(seed: JsValue) -> Result<NoiseRng, JsValue> {
        Ok(NoiseRng {
            rng: SplitMix64::new(seed_from_js(seed)?),
        })
    }

    /// The next noise draw `{angle, speed}` (two standard normals).
    pub fn draw(&mut self) -> Result<JsValue, JsValue> {
        to_js(&NoiseDraw::sample(&mut self.rng))
    }

    /// The next 64 random bits, as a BigInt.
    #[wasm_bindgen(js_name = nextU64)]
    pub fn next_u64(&mut self) -> u64 {
        self.rng.next_u64()
    }

    /// Uniform in `[0, 1)`, 53 random bits.
    #[wasm_bindgen(js_name = nextF64)]
    pub fn next_f64(&mut self) -> f64 {
        self.rng.next_f64()
    }
}

/// `count` successive noise draws from `SplitMix64::new(seed)`.
#[wasm_bindgen(js_name = noiseSample)]
pub fn noise_sample(seed: JsValue, count: u32) -> Result<JsValue, JsValue> {
    let count = batch(count, "count")?;
    let mut rng = SplitMix64::new(seed_from_js(seed)?);
    let draws: Vec<NoiseDraw> = (0..count).map(|_| NoiseDraw::sample(&mut rng)).collect();
    to_js(&draws)
}

/// The velocity played when `velocity` is aimed with `draw` under
/// `config`'s noise model (`velocity` itself without one), as the server
/// computes it. Throws `bad-config` or `not-finite` (a non-finite draw).
#[wasm_bindgen(js_name = applyNoise)]
pub fn apply_noise(config: JsValue, velocity: JsValue, draw: JsValue) -> Result<JsValue, JsValue> {
    let config = config_from_js(config)?;
    let velocity: DVec2 = from_js(velocity, "velocity")?;
    let draw: NoiseDraw = from_js(draw, "draw")?;
    config
        .validate()
        .map_err(|e| error(ErrorCode::BadConfig, e))?;
    if !draw.angle.is_finite() || !draw.speed.is_finite() {
        let e = simulate::SimulateError::NoiseNotFinite;
        return Err(error(e.code(), e));
    }
    let played = match &config.variants.noise {
        Some(model) => draw.apply(model, velocity, config.max_speed),
        None => velocity,
    };
    to_js(&played)
}

/// The random request `game::simulate::random_request` makes from
/// `SplitMix64::new(seed)` (for tests and benchmarks).
#[wasm_bindgen(js_name = randomRequest)]
pub fn random_request_js(seed: JsValue) -> Result<JsValue, JsValue> {
    to_js(&random_request(&mut SplitMix64::new(seed_from_js(seed)?)))
}

/// `count` successive random requests from one `SplitMix64::new(seed)`:
/// the cases of the native `bots throughput --seed S --count N`.
#[wasm_bindgen(js_name = randomRequests)]
pub fn random_requests(seed: JsValue, count: u32) -> Result<JsValue, JsValue> {
    let count = batch(count, "count")?;
    let mut rng = SplitMix64::new(seed_from_js(seed)?);
    let reqs: Vec<SimulateRequest> = (0..count).map(|_| random_request(&mut rng)).collect();
    to_js(&reqs)
}

/// The wire protocol version these shapes follow.
#[wasm_bindgen(js_name = protocolVersion)]
pub fn protocol_version() -> u32 {
    game::protocol::PROTOCOL_VERSION
}
