//! Checks of the marched result against the certificates: straying and looping.

pub mod straying;
