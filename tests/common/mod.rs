//! Fixtures shared by the integration tests: the thread CPU clock of the timing tests, interval
//! checks, the test ODEs, height fields and analytic surfaces, and the repository's scenes.
//!
//! Every test crate that declares `mod common;` compiles all of it but uses a part, so unused
//! items are allowed here.
#![allow(dead_code)]

pub(crate) mod clock;
pub(crate) mod intervals;
pub(crate) mod mangle;
pub(crate) mod near_crossing;
pub(crate) mod odes;
pub(crate) mod oracle;
pub(crate) mod rng;
pub(crate) mod scenes;
pub(crate) mod shell_checks;
pub(crate) mod spline;
pub(crate) mod surfaces;
