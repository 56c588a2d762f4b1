//! A model handed to another ODE crate (features named after the crates).
//!
//! - `ode_solvers`: [`ode_solvers::FirstOrder`] implements that crate's
//!   `System` for the state `y = (q, q̇)`.
//! - `diffsol`: [`diffsol::problem`] builds that crate's `OdeSolverProblem`
//!   on `y = (q, q̇)`, right-hand side and Jacobian from the generated code.

#[cfg(feature = "diffsol")]
pub mod diffsol;
#[cfg(feature = "ode_solvers")]
pub mod ode_solvers;
