//! stub
pub struct Options;
pub fn run_pipeline() {}
