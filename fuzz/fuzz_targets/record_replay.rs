//! The `record_replay` fuzz target: see `fuzz_targets::record_replay`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_targets::record_replay(data));
