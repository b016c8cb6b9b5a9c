//! The one error type of the lab: what can go wrong reading scenes,
//! writing files and drawing charts.

use thiserror::Error;

/// Anything that stops the pipeline.
#[derive(Debug, Error)]
pub enum LabError {
    #[error("scene: {0}")]
    Scene(#[from] engine::SceneError),
    #[error("writing {path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    #[error("chart {path}: {message}")]
    Plot { path: String, message: String },
    #[error("{0}")]
    Invalid(String),
}
