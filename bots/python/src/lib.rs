//! # chapaev — Chapaev for Python
//!
//! The server's exact shot simulation ([`game::simulate`]) as the Python
//! module `chapaev`, so a bot written in Python scores its candidate shots
//! with the very bits the server will compute. Every value crosses as the
//! wire protocol's JSON shapes (dicts, lists, ints, floats: a piece is
//! `{"id": 0, "pos": [x, y]}`, a velocity `[vx, vy]`, a noise draw
//! `{"angle": a, "speed": s}`), converted by `pythonize` through the same
//! serde types the server uses; Python floats are the same IEEE doubles, so
//! nothing is rounded on the way.
//!
//! Everything coming from Python is hostile input: a malformed value
//! raises `chapaev.SimulateError` with code `bad-message` and the path of
//! the fault (`request.board[3].pos: ...`), a refused request the wire code
//! the server would give (`bad-board`, `too-fast`, ...). Nothing panics
//! into the interpreter. The simulation itself runs without the GIL.

use game::batch;
use game::board::Board;
use game::noise::{NoiseDraw, SplitMix64};
use game::simulate::{play as play_shot, random_request, SimulateRequest, Simulation};
use game::{Config, Film, Piece, PieceId, Preset, Shot, ShotError, Side};
use glam::DVec2;
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyFloat, PyInt, PyList, PyTuple};
use serde::de::DeserializeOwned;
use serde::Serialize;

create_exception!(
    chapaev,
    SimulateError,
    PyValueError,
    "A request was refused: `.code` is the wire error code (`bad-message` for a malformed value, `bad-board`, `bad-config`, `not-finite`, `zero-speed`, `too-fast`, `piece-off-board`, ...) and `.message` says why."
);

/// The `SimulateError` for `code` with `message` (`str(e)` is `code: message`).
fn refusal(py: Python<'_>, code: &str, message: String) -> PyErr {
    let err = SimulateError::new_err(format!("{code}: {message}"));
    let value = err.value(py);
    // Exception instances have a __dict__: these cannot fail.
    let _ = value.setattr("code", code);
    let _ = value.setattr("message", message);
    err
}

/// `obj` read as the serde type `T`, or `bad-message` naming where it failed.
fn from_py<T: DeserializeOwned>(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<T> {
    let mut de = pythonize::Depythonizer::from_object(obj);
    serde_path_to_error::deserialize(&mut de).map_err(|e| {
        let path = e.path().to_string();
        let at = if path == "." {
            what.to_string()
        } else if path.starts_with('[') {
            format!("{what}{path}")
        } else {
            format!("{what}.{path}")
        };
        refusal(obj.py(), "bad-message", format!("{at}: {}", e.inner()))
    })
}

/// `value` as Python objects (dicts, lists, ints, floats, strings): its
/// JSON shape, through `serde_json::Value` so that vectors (serde tuples,
/// which pythonize would make tuples) come out as lists, as `json.loads`
/// gives them. Floats keep their bits (a `Value` holds the `f64`).
fn to_py<'py, T: Serialize>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    let json = serde_json::to_value(value)
        .map_err(|e| refusal(py, "internal", format!("serialising the result: {e}")))?;
    Ok(pythonize::pythonize(py, &json)?)
}

/// The pieces of a board. The common shape (a list of dicts with an int
/// `id` and a `pos` list or tuple of two numbers) is read directly, a few
/// times faster than through serde; anything else goes through serde,
/// which accepts or refuses it with the path of the fault. Both read the
/// very same values.
fn board_from(board: &Bound<'_, PyAny>) -> PyResult<Vec<Piece>> {
    fn direct(board: &Bound<'_, PyAny>) -> Option<Vec<Piece>> {
        let list = board.cast::<PyList>().ok()?;
        let mut pieces = Vec::with_capacity(list.len());
        for item in list.iter() {
            let d = item.cast::<PyDict>().ok()?;
            let id = d.get_item("id").ok()??;
            if !id.is_exact_instance_of::<PyInt>() {
                return None;
            }
            let id = PieceId::try_from(id.extract::<u8>().ok()?).ok()?;
            pieces.push(Piece {
                id,
                pos: vec2_direct(&d.get_item("pos").ok()??)?,
            });
        }
        Some(pieces)
    }
    match direct(board) {
        Some(pieces) => Ok(pieces),
        None => from_py(board, "board"),
    }
}

/// `[x, y]` or `(x, y)` of Python floats or ints, read directly.
fn vec2_direct(v: &Bound<'_, PyAny>) -> Option<DVec2> {
    let number = |x: Bound<'_, PyAny>| -> Option<f64> {
        if x.is_exact_instance_of::<PyFloat>() || x.is_exact_instance_of::<PyInt>() {
            x.extract::<f64>().ok()
        } else {
            None
        }
    };
    if let Ok(l) = v.cast::<PyList>() {
        if l.len() == 2 {
            return Some(DVec2::new(
                number(l.get_item(0).ok()?)?,
                number(l.get_item(1).ok()?)?,
            ));
        }
    } else if let Ok(t) = v.cast::<PyTuple>() {
        if t.len() == 2 {
            return Some(DVec2::new(
                number(t.get_item(0).ok()?)?,
                number(t.get_item(1).ok()?)?,
            ));
        }
    }
    None
}

/// A velocity or position: directly when it has the common shape, else
/// through serde (with the path of the fault).
fn vec2_from(v: &Bound<'_, PyAny>, what: &str) -> PyResult<DVec2> {
    match vec2_direct(v) {
        Some(v) => Ok(v),
        None => from_py(v, what),
    }
}

fn vec2_to_py<'py>(py: Python<'py>, v: DVec2) -> PyResult<Bound<'py, PyList>> {
    PyList::new(py, [v.x, v.y])
}

/// A `Simulation` as Python objects, built directly (the same shape and
/// key order as through serde, which the verdict and the film still take).
fn simulation_to_py<'py>(py: Python<'py>, sim: &Simulation) -> PyResult<Bound<'py, PyAny>> {
    let d = PyDict::new(py);
    d.set_item("played", vec2_to_py(py, sim.played)?)?;
    let knocked: Vec<u32> = sim
        .knocked_off
        .iter()
        .map(|&p| u32::from(u8::from(p)))
        .collect();
    d.set_item("knocked_off", knocked)?;
    let board = PyList::empty(py);
    for p in sim.board.pieces() {
        let piece = PyDict::new(py);
        piece.set_item("id", u8::from(p.id) as u32)?;
        piece.set_item("pos", vec2_to_py(py, p.pos)?)?;
        board.append(piece)?;
    }
    d.set_item("board", board)?;
    d.set_item("verdict", to_py(py, &sim.verdict)?)?;
    d.set_item("duration", sim.duration)?;
    d.set_item("end_reason", to_py(py, &sim.end_reason)?)?;
    if let Some(film) = &sim.film {
        d.set_item("film", to_py(py, film)?)?;
    }
    Ok(d.into_any())
}

/// The configuration given, or the default (casual) one for `None`.
fn config_from(config: Option<&Bound<'_, PyAny>>) -> PyResult<Config> {
    match config {
        Some(c) if !c.is_none() => from_py(c, "config"),
        _ => Ok(Config::default()),
    }
}

fn shot_refusal(py: Python<'_>, e: &ShotError) -> PyErr {
    refusal(py, e.code().as_str(), e.to_string())
}

/// Simulates one shot exactly as the server would: `request` is a
/// `SimulateRequest` (`config` (optional), `board`, `piece`, `velocity`,
/// `noise` (optional), `film` (optional)); returns the `Simulation`.
#[pyfunction]
fn simulate<'py>(py: Python<'py>, request: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    let req: SimulateRequest = from_py(request, "request")?;
    let sim = py
        .detach(|| req.run())
        .map_err(|e| refusal(py, e.code().as_str(), e.to_string()))?;
    simulation_to_py(py, &sim)
}

/// One position, checked and converted once, to score many shots on.
#[pyclass(frozen, module = "chapaev")]
struct Simulator {
    config: Config,
    board: Board,
}

#[pymethods]
impl Simulator {
    /// `config` (a dict, or `None` for the default) and `board` (the
    /// pieces), checked as `simulate` checks them.
    #[new]
    #[pyo3(signature = (config, board))]
    fn new(
        py: Python<'_>,
        config: Option<&Bound<'_, PyAny>>,
        board: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        let config = config_from(config)?;
        let pieces = board_from(board)?;
        // The request's own checks of the configuration and the board; the
        // shot in it (a valid configuration has a finite, positive
        // max_speed) passes Shot::new by construction.
        let probe = SimulateRequest {
            velocity: DVec2::new(config.max_speed, 0.0),
            config,
            board: pieces,
            piece: PieceId::all().next().expect("16 pieces"),
            noise: None,
            film: false,
        };
        let (board, _) = probe
            .validate()
            .map_err(|e| refusal(py, e.code().as_str(), e.to_string()))?;
        Ok(Simulator {
            config: probe.config,
            board,
        })
    }

    /// Plays `piece` at `velocity` (the aimed velocity; with `noise`, a
    /// draw applied with the configuration's noise model) and returns the
    /// `Simulation` (without film): the bits `simulate` gives for the same
    /// request.
    #[pyo3(signature = (piece, velocity, noise = None))]
    fn play<'py>(
        &self,
        py: Python<'py>,
        piece: &Bound<'py, PyAny>,
        velocity: &Bound<'py, PyAny>,
        noise: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let piece: PieceId = from_py(piece, "piece")?;
        let velocity = vec2_from(velocity, "velocity")?;
        let noise: Option<NoiseDraw> = match noise {
            Some(n) if !n.is_none() => Some(from_py(n, "noise")?),
            _ => None,
        };
        // The order of SimulateRequest::validate and run.
        if let Some(n) = &noise {
            if !n.angle.is_finite() || !n.speed.is_finite() {
                return Err(refusal(
                    py,
                    "not-finite",
                    "the noise draw must be finite numbers".into(),
                ));
            }
        }
        let shot = Shot::new(piece, velocity, &self.config).map_err(|e| shot_refusal(py, &e))?;
        let played = match (&self.config.variants.noise, &noise) {
            (Some(model), Some(draw)) => draw.apply(model, shot.velocity(), self.config.max_speed),
            _ => shot.velocity(),
        };
        let sim: Simulation = py
            .detach(|| play_shot(&self.config, &self.board, &shot, played, false))
            .map_err(|e| shot_refusal(py, &e))?;
        simulation_to_py(py, &sim)
    }

    /// Many shots in one call: `shots` is a flat sequence of numbers (a
    /// list or an `array.array('d')`), 5 per shot: `piece, vx, vy,
    /// noise_angle, noise_speed` (`nan, nan` for no noise draw). Returns a
    /// list of floats, `PLAY_MANY_STRIDE` (56) per shot (layout in
    /// `chapaev.pyi`): the very bits of `play` on each. A refused shot
    /// raises nothing: its status (offset 0) is nonzero. Raises
    /// `bad-message` only when the length is not a multiple of 5.
    fn play_many(&self, py: Python<'_>, shots: Vec<f64>) -> PyResult<Vec<f64>> {
        if !shots
            .chunks_exact(batch::SHOT_FIELDS)
            .remainder()
            .is_empty()
        {
            return Err(refusal(
                py,
                "bad-message",
                format!(
                    "shots: {} numbers is not a multiple of {}",
                    shots.len(),
                    batch::SHOT_FIELDS
                ),
            ));
        }
        Ok(py.detach(|| batch::play_many(&self.config, &self.board, &shots)))
    }

    /// The configuration (a dict).
    #[getter]
    fn config<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &self.config)
    }

    /// The pieces, in id order.
    #[getter]
    fn board<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &self.board)
    }

    fn __repr__(&self) -> String {
        format!("Simulator({} pieces)", self.board.pieces().len())
    }
}

/// Whether `side` may flick `piece` at `velocity` on `board` under
/// `config`: `None`, or `(code, message)` with the wire code the server
/// would refuse it with (`not-your-piece`, `piece-off-board`, `not-finite`,
/// `zero-speed`, `too-fast`). Whose turn it is is not known here.
#[pyfunction]
fn validate_shot<'py>(
    py: Python<'py>,
    config: Option<&Bound<'py, PyAny>>,
    board: &Bound<'py, PyAny>,
    side: &Bound<'py, PyAny>,
    piece: &Bound<'py, PyAny>,
    velocity: &Bound<'py, PyAny>,
) -> PyResult<Option<Bound<'py, PyTuple>>> {
    let config = config_from(config)?;
    config
        .validate()
        .map_err(|e| refusal(py, "bad-config", format!("unplayable config: {e}")))?;
    let board = board_from(board)?;
    let side: Side = from_py(side, "side")?;
    let piece: PieceId = from_py(piece, "piece")?;
    let velocity = vec2_from(velocity, "velocity")?;
    let refused = if piece.side() != side {
        Some(ShotError::NotYourPiece { piece, side })
    } else if !board.iter().any(|p| p.id == piece) {
        Some(ShotError::PieceOffBoard(piece))
    } else {
        Shot::new(piece, velocity, &config).err()
    };
    refused
        .map(|e| PyTuple::new(py, [e.code().as_str().to_string(), e.to_string()]))
        .transpose()
}

/// The ids of `side`'s pieces on `board`, in id order.
#[pyfunction]
fn legal_pieces(board: &Bound<'_, PyAny>, side: &Bound<'_, PyAny>) -> PyResult<Vec<u32>> {
    let board = board_from(board)?;
    let side: Side = from_py(side, "side")?;
    let mut ids: Vec<u32> = board
        .iter()
        .filter(|p| p.id.side() == side)
        .map(|p| u32::from(u8::from(p.id)))
        .collect();
    ids.sort_unstable();
    ids.dedup();
    Ok(ids)
}

/// The default (casual) configuration.
#[pyfunction]
fn default_config(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    to_py(py, &Config::default())
}

/// The standard configuration (execution noise and the pie rule).
#[pyfunction]
fn standard_config(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    to_py(py, &Config::standard())
}

/// The configuration of the named rules (`casual` or `standard`).
#[pyfunction]
fn config_for<'py>(py: Python<'py>, rules: &str) -> PyResult<Bound<'py, PyAny>> {
    let preset = Preset::parse(rules).ok_or_else(|| {
        refusal(
            py,
            "bad-config",
            format!("unknown rules {rules:?} (casual or standard)"),
        )
    })?;
    to_py(py, &preset.config())
}

#[derive(Serialize)]
struct PieceState {
    id: PieceId,
    pos: DVec2,
    vel: DVec2,
}

#[derive(Serialize)]
struct SceneOut {
    t: f64,
    pieces: Vec<PieceState>,
}

/// The pieces still on the board at time `t` of a shot's `film` (clamped
/// to `[0, film["end"]]`), with their positions and velocities:
/// `{"t": t, "pieces": [{"id", "pos", "vel"}, ...]}` in id order.
#[pyfunction]
fn scene_at<'py>(py: Python<'py>, film: &Bound<'py, PyAny>, t: f64) -> PyResult<Bound<'py, PyAny>> {
    let film: Film = from_py(film, "film")?;
    if !t.is_finite() {
        return Err(refusal(
            py,
            "not-finite",
            format!("t must be finite, not {t}"),
        ));
    }
    if !film.end.is_finite() || film.end < 0.0 {
        return Err(refusal(
            py,
            "bad-message",
            format!("film.end: {} is not a finite time >= 0", film.end),
        ));
    }
    let t = t.clamp(0.0, film.end);
    let scene = film.scene_at(t);
    let mut pieces = Vec::with_capacity(scene.bodies.len());
    for b in &scene.bodies {
        let id = PieceId::from_body(b.id).map_err(|e| {
            refusal(
                py,
                "bad-message",
                format!("film: body {} is not a piece", e.0),
            )
        })?;
        pieces.push(PieceState {
            id,
            pos: b.pos,
            vel: b.vel,
        });
    }
    pieces.sort_by_key(|p| p.id);
    to_py(py, &SceneOut { t, pieces })
}

/// A generator of noise draws of a bot's own: `NoiseRng(seed).sample()`
/// gives exactly the draws of `NoiseDraw::sample` on `SplitMix64::new(seed)`.
#[pyclass(module = "chapaev")]
struct NoiseRng {
    rng: SplitMix64,
}

#[pymethods]
impl NoiseRng {
    #[new]
    fn new(seed: u64) -> Self {
        NoiseRng {
            rng: SplitMix64::new(seed),
        }
    }

    /// The next draw: `{"angle": a, "speed": s}`, two standard normal numbers.
    fn sample<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &NoiseDraw::sample(&mut self.rng))
    }

    /// The next 64 random bits.
    fn next_u64(&mut self) -> u64 {
        self.rng.next_u64()
    }

    /// Uniform in [0, 1).
    fn next_f64(&mut self) -> f64 {
        self.rng.next_f64()
    }
}

/// The velocity played when `velocity` is aimed with the noise `draw`
/// under `config` (as aimed when the configuration has no noise model).
#[pyfunction]
fn apply_noise<'py>(
    py: Python<'py>,
    config: Option<&Bound<'py, PyAny>>,
    velocity: &Bound<'py, PyAny>,
    draw: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let config = config_from(config)?;
    let velocity = vec2_from(velocity, "velocity")?;
    let draw: NoiseDraw = from_py(draw, "draw")?;
    if !velocity.is_finite() {
        return Err(refusal(
            py,
            "not-finite",
            "the velocity must be finite numbers".into(),
        ));
    }
    if !draw.angle.is_finite() || !draw.speed.is_finite() {
        return Err(refusal(
            py,
            "not-finite",
            "the noise draw must be finite numbers".into(),
        ));
    }
    let played = match &config.variants.noise {
        Some(model) => draw.apply(model, velocity, config.max_speed),
        None => velocity,
    };
    to_py(py, &played)
}

/// `n` random requests from one `SplitMix64::new(seed)` (the requests of
/// every binding's tests and benchmarks).
#[pyfunction]
fn random_requests(py: Python<'_>, seed: u64, n: usize) -> PyResult<Vec<Bound<'_, PyAny>>> {
    let mut rng = SplitMix64::new(seed);
    (0..n)
        .map(|_| to_py(py, &random_request(&mut rng)))
        .collect()
}

/// Checks a finished match's record (its JSON text, as
/// `GET /api/matches/ID/record` serves it, or that text parsed into a
/// dict): the revealed noise secret opens the commitment published before
/// the first shot, every shot's `played` velocity is its `aimed` one under
/// the draw the secret gives it, and the match replays to every recorded
/// outcome. Returns `{scheme, commitment, shots, draws}`; raises
/// `SimulateError` whose `code` says what failed (`commitment-mismatch`,
/// `noise-mismatch`, `replay-diverged`, `secret-not-revealed`,
/// `uncommitted`, `bad-record`, `unsupported-physics`).
#[pyfunction]
fn verify<'py>(py: Python<'py>, record: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    let checked = match record.extract::<String>() {
        Ok(text) => py.detach(|| game::verify_json(&text)),
        Err(_) => {
            let record: game::MatchRecord = from_py(record, "record")?;
            py.detach(|| game::verify(&record))
        }
    };
    match checked {
        Ok(v) => to_py(py, &v),
        Err(e) => Err(refusal(py, e.code(), e.to_string())),
    }
}

#[pymodule]
fn chapaev(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SimulateError", m.py().get_type::<SimulateError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("PROTOCOL_VERSION", game::protocol::PROTOCOL_VERSION)?;
    m.add("PLAY_MANY_STRIDE", batch::STRIDE)?;
    m.add_class::<Simulator>()?;
    m.add_class::<NoiseRng>()?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(validate_shot, m)?)?;
    m.add_function(wrap_pyfunction!(legal_pieces, m)?)?;
    m.add_function(wrap_pyfunction!(default_config, m)?)?;
    m.add_function(wrap_pyfunction!(standard_config, m)?)?;
    m.add_function(wrap_pyfunction!(config_for, m)?)?;
    m.add_function(wrap_pyfunction!(scene_at, m)?)?;
    m.add_function(wrap_pyfunction!(apply_noise, m)?)?;
    m.add_function(wrap_pyfunction!(random_requests, m)?)?;
    m.add_function(wrap_pyfunction!(verify, m)?)?;
    Ok(())
}
