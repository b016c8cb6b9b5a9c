//! The budget of a hosted bot: how large its module may be, how much
//! memory it may hold, and how much computation one decision may use.

/// A hosted bot's limits.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Largest module accepted, in bytes (checked before parsing).
    pub max_module_bytes: usize,
    /// Largest linear memory, in bytes (a grow beyond it traps).
    pub max_memory_bytes: usize,
    /// Fuel for one decision, instantiation included.
    pub fuel_per_decision: u64,
    /// Fuel charged for each shot simulated through the host.
    pub shot_fuel: u64,
    /// Most shots one `simulate` call may play.
    pub max_shots_per_call: u32,
    /// Longest answer, in bytes.
    pub max_answer_bytes: u32,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            max_module_bytes: 8 << 20,
            max_memory_bytes: 64 << 20,
            fuel_per_decision: 2_000_000_000,
            shot_fuel: 100_000,
            max_shots_per_call: 4096,
            max_answer_bytes: 4096,
        }
    }
}
