//! The classics: what `lagrangian!` derives for the damped two-mass chain and
//! the double pendulum, against the equations every mechanics text writes
//! down. Each closed form is derived by hand, written as its list of terms
//! (see `support::closed_form::Closed`), and compared at many random states
//! and parameters. The double pendulum is the one of `lagrange::models`,
//! written through the Cartesian positions of its bobs; two more spellings
//! of it stand here.
//!
//! The chain is in `chain.rs`, the double pendulum in `double_pendulum.rs`.

mod chain;
mod double_pendulum;
