//! The contract between the server and a hosted bot's module.
//!
//! **Exports** (all three required):
//!
//! | name | type | does |
//! |---|---|---|
//! | `memory` | memory | the module's linear memory |
//! | `chapaev_alloc` | `(len: i32) -> i32` | returns a pointer to `len` writable bytes |
//! | `chapaev_decide` | `(ptr: i32, len: i32) -> i64` | reads the request's JSON at `ptr..ptr+len`, returns the answer's place packed as `ptr << 32 \| len` |
//!
//! For each decision the server instantiates the module afresh (a bot
//! keeps no state between decisions: a decision depends on the request
//! and its random stream alone, so a match replays from its record), calls
//! `chapaev_alloc` for the request, copies it in, calls `chapaev_decide`
//! and reads the answer: a [`game::protocol::ClientMessage`] of type
//! `shot`, `pie-decision` or `resign` (see [`game::decide`]).
//!
//! **Imports** (optional), all from the module `chapaev`:
//!
//! | name | type | does |
//! |---|---|---|
//! | `simulate` | `(board: i32, shots: i32, count: i32, out: i32) -> i32` | plays `count` shots on one board under the match's configuration |
//! | `random` | `() -> i64` | the next 64 bits of the decision's random stream |
//!
//! `simulate` reads the board at `board` as [`game::batch::BOARD_FIELDS`]
//! little-endian `f64` (`x, y` of piece id `k` at `2k`, NaN when it is
//! off the board), `count` shots at `shots` as
//! [`game::batch::SHOT_FIELDS`] `f64` each (`piece, vx, vy, noise_angle,
//! noise_speed`, NaN noise for none), and writes [`game::batch::STRIDE`]
//! `f64` per shot at `out` (the layout of [`game::batch`]). It answers
//! [`status::OK`] or a negative status, and charges
//! [`crate::Limits::shot_fuel`] per shot before it plays (out of fuel: the
//! decision ends as out of fuel).
//!
//! Any other import makes the module refused at load.

/// The module every import comes from.
pub const IMPORT_MODULE: &str = "chapaev";
/// The memory export.
pub const MEMORY: &str = "memory";
/// The allocation export.
pub const ALLOC: &str = "chapaev_alloc";
/// The decision export.
pub const DECIDE: &str = "chapaev_decide";
/// The simulation import.
pub const SIMULATE: &str = "simulate";
/// The randomness import.
pub const RANDOM: &str = "random";

/// What `simulate` answers.
pub mod status {
    /// The shots were played and their rows written.
    pub const OK: i32 = 0;
    /// A pointer and length outside the module's memory.
    pub const OUT_OF_BOUNDS: i32 = -1;
    /// The board is not a playable board (overlap, off the board).
    pub const BAD_BOARD: i32 = -2;
    /// A negative count, or more shots than one call may play.
    pub const BAD_COUNT: i32 = -3;
}

/// Packs an answer's place as `chapaev_decide` returns it.
pub fn pack(ptr: u32, len: u32) -> i64 {
    ((u64::from(ptr) << 32) | u64::from(len)) as i64
}

/// The pointer and length `chapaev_decide` returned.
pub fn unpack(packed: i64) -> (u32, u32) {
    let v = packed as u64;
    ((v >> 32) as u32, v as u32)
}

#[cfg(test)]
mod tests {
    #[test]
    fn pack_and_unpack_are_inverse() {
        for (p, l) in [(0, 0), (1, 2), (u32::MAX, u32::MAX), (65536, 300)] {
            assert_eq!(super::unpack(super::pack(p, l)), (p, l));
        }
    }
}
