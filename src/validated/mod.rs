//! The validated Taylor ODE engine.
