//! The host functions a hosted bot may import (see [`crate::abi`]):
//! `simulate`, shots played in batches on the native engine under the
//! match's configuration, each charged [`crate::Limits::shot_fuel`]; and
//! `random`, the decision's own random stream. Both read and write only
//! the module's memory, bounds-checked; a bad pointer is answered with a
//! status, never a panic.

use crate::abi::{self, status};
use crate::randomness::Stream;
use game::batch::{self, BOARD_FIELDS, SHOT_FIELDS, STRIDE};
use game::Config;
use wasmi::{Caller, Engine, Extern, Linker, StoreLimits, TrapCode};

/// What one decision's store holds.
pub struct HostState {
    pub(crate) limits: StoreLimits,
    pub(crate) config: Config,
    pub(crate) stream: Stream,
    pub(crate) shot_fuel: u64,
    pub(crate) max_shots: u32,
    /// Shots simulated so far in this decision.
    pub(crate) shots: u64,
}

/// The host functions, defined once per module.
pub(crate) fn linker(engine: &Engine) -> Result<Linker<HostState>, wasmi::Error> {
    let mut linker = Linker::new(engine);
    linker.func_wrap(abi::IMPORT_MODULE, abi::SIMULATE, simulate)?;
    linker.func_wrap(
        abi::IMPORT_MODULE,
        abi::RANDOM,
        |mut caller: Caller<'_, HostState>| -> i64 { caller.data_mut().stream.next_u64() as i64 },
    )?;
    Ok(linker)
}

/// `n` little-endian `f64` at `ptr` in `memory`, if they are all inside it.
fn read_f64s(memory: &[u8], ptr: i32, n: usize) -> Option<Vec<f64>> {
    let start = usize::try_from(ptr as u32).ok()?;
    let end = start.checked_add(n.checked_mul(8)?)?;
    let bytes = memory.get(start..end)?;
    Some(
        bytes
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
            .collect(),
    )
}

fn simulate(
    mut caller: Caller<'_, HostState>,
    board_ptr: i32,
    shots_ptr: i32,
    count: i32,
    out_ptr: i32,
) -> Result<i32, wasmi::Error> {
    let max = caller.data().max_shots;
    let Ok(count) = u32::try_from(count) else {
        return Ok(status::BAD_COUNT);
    };
    if count > max {
        return Ok(status::BAD_COUNT);
    }
    // Paid before it is played: a bot cannot buy physics it cannot afford.
    let price = u64::from(count) * caller.data().shot_fuel;
    let fuel = caller.get_fuel()?;
    if fuel < price {
        caller.set_fuel(0)?;
        return Err(TrapCode::OutOfFuel.into());
    }
    caller.set_fuel(fuel - price)?;
    let Some(memory) = caller.get_export(abi::MEMORY).and_then(Extern::into_memory) else {
        return Ok(status::OUT_OF_BOUNDS);
    };
    let n = count as usize;
    let data = memory.data(&caller);
    let (Some(board), Some(shots)) = (
        read_f64s(data, board_ptr, BOARD_FIELDS),
        read_f64s(data, shots_ptr, n * SHOT_FIELDS),
    ) else {
        return Ok(status::OUT_OF_BOUNDS);
    };
    let out_start = out_ptr as u32 as usize;
    let out_end = out_start + n * STRIDE * 8;
    if out_end > data.len() {
        return Ok(status::OUT_OF_BOUNDS);
    }
    let board: [f64; BOARD_FIELDS] = board.try_into().unwrap_or([f64::NAN; BOARD_FIELDS]);
    let config = &caller.data().config;
    let Ok(board) = batch::board_from_positions(config, &board) else {
        return Ok(status::BAD_BOARD);
    };
    let rows = batch::play_many(config, &board, &shots);
    let out = &mut memory.data_mut(&mut caller)[out_start..out_end];
    for (chunk, x) in out.chunks_exact_mut(8).zip(&rows) {
        chunk.copy_from_slice(&x.to_le_bytes());
    }
    caller.data_mut().shots += u64::from(count);
    Ok(status::OK)
}
