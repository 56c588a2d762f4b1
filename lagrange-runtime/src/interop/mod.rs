//! A model handed to another ODE crate (features named after the crates).
//!
//! - `ode_solvers`: [`ode_solvers::FirstOrder`] implements that crate's
//!   `System` for the state `y = (q, q̇)`.

#[cfg(feature = "ode_solvers")]
pub mod ode_solvers;
