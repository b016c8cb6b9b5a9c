//! Speed against accuracy (in progress).
