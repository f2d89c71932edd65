//! What every swarm model shares, whatever its equations: today its parameter table
//! ([`ModelParams`]: names, ranges, units, validation), from which the host derives its
//! scenario overrides and their messages and the device its checks.

mod params;

pub(crate) use params::model_params;
pub use params::{ModelParams, ParamSpec, ParamValue, Range};
