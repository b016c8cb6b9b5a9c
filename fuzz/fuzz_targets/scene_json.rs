//! The `scene_json` fuzz target: see `fuzz_targets::scene_json`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_targets::scene_json(data));
