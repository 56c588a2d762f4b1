//! The linear algebra of the runtime, in one place.
//!
//! - [`solve`]: `q̈` from `M q̈ = f` on the stack (Cholesky as `LDLᵀ`, LU
//!   with partial pivoting as the fallback), with singular and non-finite cases caught;
//!   every right-hand side goes through it. Also the stack LU of the
//!   variational integrator's `N × N` Newton systems.
//! - `ldlt`: `M = L D Lᵀ` (Cholesky without square roots) written out for
//!   the hot path: inlined, one division per column.
//! - [`jacobian`]: `∂q̈/∂q` and `∂q̈/∂q̇`, exact from the model or by
//!   forward differences, for the implicit methods' Newton iterations.
//! - `lu`: LU factors in storage allocated once per integration, real or
//!   complex, for the implicit Runge–Kutta methods' iteration matrices.
//! - `second_order`: the `2N × 2N` systems `(γ I − J) x = b` of those
//!   methods solved at size `N`, using `J = [[0, I], [∂q̈/∂q, ∂q̈/∂q̇]]`.
//!
//! `solve` and `jacobian` are public, at the crate root
//! (`lagrange_runtime::solve`, `lagrange_runtime::jacobian`); the other two
//! are the integrators' own.

pub mod jacobian;
pub(crate) mod ldlt;
pub(crate) mod lu;
pub(crate) mod second_order;
pub mod solve;
