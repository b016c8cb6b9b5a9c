//! Chapaev rules on the engine (in progress).
