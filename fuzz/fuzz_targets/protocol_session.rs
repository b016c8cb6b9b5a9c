//! The `protocol_session` fuzz target: see `fuzz_targets::protocol_session`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_targets::protocol_session(data));
