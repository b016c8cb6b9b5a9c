//! # lab — speed against accuracy
//!
//! Measures the engine honestly: against an independent 320-bit reference
//! of the same model ([`reference`], on [`hp`]), against the time-stepping a
//! user would write ([`stepper`]) or pick ([`rapier_peer`]), and against
//! published quartic solvers. [`pipeline`] runs everything and writes CSV
//! data, SVG charts ([`plot`]) and the failure table into one folder:
//! [`solvers_chart`] (root solvers: time against error),
//! [`timestep_chart`] (a priori against time-stepping), [`scaling_chart`]
//! (events per second against the number of discs) and [`failures`].
//! [`hostile`] generates the scenes an engine must survive, and
//! [`revision_diff`] measures what a new engine revision changes on them.

pub mod apriori;
pub mod catalogue;
pub mod error;
pub mod failures;
pub mod files;
pub mod hostile;
pub mod hp;
pub mod outcome;
pub mod pipeline;
pub mod plot;
pub mod pressing;
pub mod rapier_peer;
pub mod reference;
pub mod revision_diff;
pub mod scaling_chart;
pub mod scenes;
pub mod solvers_chart;
pub mod stepper;
pub mod timestep_chart;

pub use error::LabError;
pub use pipeline::{run_pipeline, Options};
