//! # chapaev-bot-sdk — a Chapaev bot the server runs
//!
//! Write one function from a [`Context`] (your side and the public match
//! view) to a [`BotDecision`], export it with [`export_bot!`], and build
//! with `cargo build --target wasm32-unknown-unknown --release`: the
//! `.wasm` is a bot the server can host (the contract it follows is the
//! `hosted` crate's `abi` module; docs/hosted-bots.md walks through it).
//!
//! [`Context::simulate`] plays candidate shots on the server's native
//! engine, in batches ([`Outcome`] per shot), at a fixed fuel price per
//! shot; [`Context::random`] is the decision's random stream. Built for
//! any other target (your tests), both run in-process with the same
//! `game` code, so a bot can be tested natively before it is uploaded.
//!
//! ```no_run
//! use chapaev_bot_sdk::{export_bot, BotDecision, Context};
//! fn decide(ctx: &mut Context) -> BotDecision {
//!     BotDecision::Resign
//! }
//! export_bot!(decide);
//! ```

pub use game::batch::{BOARD_FIELDS, SHOT_FIELDS, STRIDE};
pub use game::decide::DecideRequest;
pub use game::session::BotDecision;
pub use game::{Board, Config, MatchView, Phase, PieceId, Shot, Side};

/// Why a batch was not simulated (the host's negative statuses).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SimulateError {
    /// A pointer outside the bot's memory (a bug in this SDK if it happens).
    OutOfBounds,
    /// The board is not playable (overlapping pieces, off the board).
    BadBoard,
    /// More shots than one call may play.
    BadCount,
    /// A status this SDK does not know.
    Other(i32),
}

/// What one simulated shot did (a row of the batch answer).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outcome {
    row: [f64; STRIDE],
}

impl Outcome {
    /// Whether the shot was played (else the game refused it: a piece not
    /// on the board, too fast).
    pub fn played(&self) -> bool {
        self.row[0] == 0.0
    }

    /// Pieces of `side` knocked off.
    pub fn lost(&self, side: Side) -> u32 {
        let k = match side {
            Side::White => 6,
            Side::Black => 7,
        };
        if self.played() {
            self.row[k] as u32
        } else {
            0
        }
    }

    /// Whether the shooter shoots again (it knocked off an enemy and lost
    /// nothing of its own, and the round goes on).
    pub fn shoots_again(&self) -> bool {
        self.played() && self.row[1] == 0.0
    }

    /// Where the pieces came to rest, as [`BOARD_FIELDS`] numbers (to
    /// simulate on from there).
    pub fn board(&self) -> [f64; BOARD_FIELDS] {
        let mut b = [f64::NAN; BOARD_FIELDS];
        b.copy_from_slice(&self.row[24..24 + BOARD_FIELDS]);
        b
    }

    /// The raw row (layout in `game::batch`).
    pub fn row(&self) -> &[f64; STRIDE] {
        &self.row
    }
}

/// One candidate shot: `piece` flicked at `velocity` (m/s), as aimed (no
/// noise draw).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Candidate {
    pub piece: PieceId,
    pub velocity: glam::DVec2,
}

/// What a decision is made from.
pub struct Context {
    /// Your side and the public view of the match.
    pub request: DecideRequest,
    #[cfg(not(target_arch = "wasm32"))]
    rng: game::noise::SplitMix64,
}

impl Context {
    /// A context for `request`; natively, `seed` keys [`Context::random`]
    /// (on the server the host keys it from the match).
    pub fn new(request: DecideRequest, seed: u64) -> Context {
        #[cfg(target_arch = "wasm32")]
        let _ = seed;
        Context {
            request,
            #[cfg(not(target_arch = "wasm32"))]
            rng: game::noise::SplitMix64::new(seed),
        }
    }

    /// Your side.
    pub fn me(&self) -> Side {
        self.request.me
    }

    /// The public view of the match.
    pub fn view(&self) -> &MatchView {
        &self.request.view
    }

    /// The current board as [`BOARD_FIELDS`] numbers.
    pub fn board(&self) -> [f64; BOARD_FIELDS] {
        game::batch::positions(&self.request.view.board)
    }

    /// The next 64 bits of the decision's random stream.
    pub fn random(&mut self) -> u64 {
        #[cfg(target_arch = "wasm32")]
        {
            // SAFETY: a host function without arguments.
            unsafe { host::random() as u64 }
        }
        #[cfg(not(target_arch = "wasm32"))]
        {
            self.rng.next_u64()
        }
    }

    /// Plays each candidate on `board` (as [`Context::board`] or an
    /// [`Outcome::board`]) with exactly the server's physics.
    pub fn simulate(
        &mut self,
        board: &[f64; BOARD_FIELDS],
        shots: &[Candidate],
    ) -> Result<Vec<Outcome>, SimulateError> {
        let mut request = Vec::with_capacity(shots.len() * SHOT_FIELDS);
        for s in shots {
            let id = f64::from(u8::from(s.piece));
            request.extend_from_slice(&[id, s.velocity.x, s.velocity.y, f64::NAN, f64::NAN]);
        }
        let rows = self.simulate_raw(board, &request, shots.len())?;
        Ok(rows
            .chunks_exact(STRIDE)
            .map(|r| {
                let mut row = [f64::NAN; STRIDE];
                row.copy_from_slice(r);
                Outcome { row }
            })
            .collect())
    }

    #[cfg(target_arch = "wasm32")]
    fn simulate_raw(
        &mut self,
        board: &[f64; BOARD_FIELDS],
        shots: &[f64],
        count: usize,
    ) -> Result<Vec<f64>, SimulateError> {
        let mut out = vec![f64::NAN; count * STRIDE];
        let count = i32::try_from(count).map_err(|_| SimulateError::BadCount)?;
        // SAFETY: the pointers are to live buffers of the sizes the host reads and writes.
        let status = unsafe {
            host::simulate(
                board.as_ptr() as i32,
                shots.as_ptr() as i32,
                count,
                out.as_mut_ptr() as i32,
            )
        };
        match status {
            0 => Ok(out),
            -1 => Err(SimulateError::OutOfBounds),
            -2 => Err(SimulateError::BadBoard),
            -3 => Err(SimulateError::BadCount),
            other => Err(SimulateError::Other(other)),
        }
    }

    #[cfg(not(target_arch = "wasm32"))]
    fn simulate_raw(
        &mut self,
        board: &[f64; BOARD_FIELDS],
        shots: &[f64],
        _count: usize,
    ) -> Result<Vec<f64>, SimulateError> {
        let config = &self.request.view.config;
        let board = game::batch::board_from_positions(config, board)
            .map_err(|_| SimulateError::BadBoard)?;
        Ok(game::batch::play_many(config, &board, shots))
    }
}

#[cfg(target_arch = "wasm32")]
mod host {
    #[link(wasm_import_module = "chapaev")]
    extern "C" {
        pub fn simulate(board: i32, shots: i32, count: i32, out: i32) -> i32;
        pub fn random() -> i64;
    }
}

/// `chapaev_alloc`'s body: `len` bytes that stay (the instance lives for
/// one decision).
#[doc(hidden)]
pub fn abi_alloc(len: i32) -> i32 {
    let buf = vec![0u8; usize::try_from(len).unwrap_or(0)].leak();
    buf.as_mut_ptr() as usize as i32
}

/// `chapaev_decide`'s body: read the request, decide, leave the answer's
/// JSON in memory and return its place.
#[doc(hidden)]
pub fn abi_decide(ptr: i32, len: i32, decide: fn(&mut Context) -> BotDecision) -> i64 {
    // SAFETY: the host wrote `len` bytes at `ptr`, a buffer from `abi_alloc`.
    let text = unsafe {
        std::slice::from_raw_parts(ptr as usize as *const u8, usize::try_from(len).unwrap_or(0))
    };
    let answer = match serde_json::from_slice::<DecideRequest>(text) {
        Ok(request) => decide(&mut Context::new(request, 0)),
        Err(_) => BotDecision::Resign,
    };
    // No answer leaves an empty one, which the host takes for no decision.
    let json = game::decide::answer_message(&answer)
        .and_then(|m| serde_json::to_vec(&m).ok())
        .unwrap_or_default();
    let out = json.leak();
    ((out.as_ptr() as usize as u64) << 32 | out.len() as u64) as i64
}

/// Exports `decide` (a `fn(&mut Context) -> BotDecision`) as the module's
/// `chapaev_alloc` and `chapaev_decide`.
#[macro_export]
macro_rules! export_bot {
    ($decide:path) => {
        #[no_mangle]
        pub extern "C" fn chapaev_alloc(len: i32) -> i32 {
            $crate::abi_alloc(len)
        }
        #[no_mangle]
        pub extern "C" fn chapaev_decide(ptr: i32, len: i32) -> i64 {
            $crate::abi_decide(ptr, len, $decide)
        }
    };
}
