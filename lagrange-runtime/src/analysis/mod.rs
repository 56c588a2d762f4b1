//! Small motions: linearization at any state, equilibria, normal modes.
//!
//! The equations of motion `M(t, q) q̈ = f(t, q, q̇)` are a first-order
//! system `ẋ = F(t, x)` in `x = (q, q̇)`. Near a state, a small deviation
//! `δx` evolves by the linearization
//!
//! ```text
//! δẋ = A δx (+ B δu),   A = [[0, I], [∂q̈/∂q, ∂q̈/∂q̇]],   B = [[0], [M⁻¹ ∂f/∂u]],
//! ```
//!
//! what controller design (LQR, pole placement), stability of a motion
//! and the Newton iterations of implicit methods all start from.
//!
//! # The blocks, and the term that is easy to forget
//!
//! Differentiating the residual `r = M(t, q) q̈ − f(t, q, q̇) = 0` along a
//! motion gives `∂q̈/∂q = −M⁻¹ ∂r/∂q` and `∂q̈/∂q̇ = −M⁻¹ ∂r/∂q̇`, with
//!
//! ```text
//! ∂r/∂q = ∂(M q̈)/∂q − ∂f/∂q,
//! ```
//!
//! evaluated at the state's own `q̈`. At an equilibrium `q̈ = 0` and the
//! first term vanishes; at any other operating point (a pendulum held at an
//! angle by a motor, a swinging arm) it does not, and `−M⁻¹ ∂f/∂q` alone is
//! wrong. [`linearize`] includes it.
//!
//! # Exact or by differences
//!
//! A model written with `#[lagrange(jacobians)]` provides `∂r/∂q` and
//! `∂r/∂q̇` symbolically ([`Lagrangian::residual_jacobians`]): then every
//! analysis here is exact up to rounding ([`Derivatives::Exact`]), and a
//! linearization costs one `M` factorization and `2N` triangular solves.
//! Otherwise the derivatives are central differences
//! ([`Derivatives::CentralDifferences`]): `4N` right-hand sides for
//! [`linearize`], `2N` forcings for equilibria and modes, with steps
//! `h = ε^(1/3) max(1, |x|)` that balance truncation `O(h²)` against
//! rounding `O(ε / h)`, leaving a relative error `≈ ε^(2/3)` (`4·10⁻¹¹` in
//! `f64`, times the ratio of the model's third to first derivatives).
//! Each result says which it is. `B` always comes from the model's exact
//! [`input_jacobian`](crate::model::inputs::Actuated::input_jacobian).
//!
//! # Equilibria and modes
//!
//! An equilibrium is a `q` where the model can stay at rest:
//! `f(t, q, 0) = 0` (for a model with inputs, at the inputs it holds).
//! [`equilibrium`] finds one by Newton's method from a guess (and, for a
//! family of them, the member nearest it and the neutral directions), with
//! `∂f/∂q` at rest as above; [`is_equilibrium`] tests a point with a
//! tolerance relative to the model's own stiffness, free of units.
//!
//! About an equilibrium, `M δq̈ = −K δq` with the stiffness
//! `K = −∂f/∂q`, symmetric for conservative forces (`K = ∇²V`). Its
//! [`modes`] solve `K v = ω² M v`: `ω² > 0` oscillates at `ω`, `ω² < 0`
//! grows at `√−ω²` (an unstable equilibrium), `ω² ≈ 0` is neutral. Damping
//! and gyroscopic forces are not in `K`; the eigenvalues of `A`
//! ([`Linearization::state_matrix`]) include them.
//!
//! ```
//! use lagrange::models::DoublePendulum;
//! use lagrange_runtime::analysis::{equilibrium, linearize, modes};
//! use lagrange_runtime::nalgebra::Vector2;
//!
//! let pendulum = DoublePendulum::unit();
//! let hanging = equilibrium(&pendulum, 0.0, &Vector2::new(0.2, -0.1))?.q;
//! let modes = modes(&pendulum, 0.0, &hanging)?;
//! assert!(modes.is_stable());
//!
//! // Away from equilibrium: swinging through the bottom.
//! let lin = linearize(&pendulum, 0.0, &Vector2::new(0.3, 0.1), &Vector2::new(2.0, -1.0))?;
//! assert!(lin.dqddot_dqdot.amax() > 0.0); // Coriolis terms
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Constrained models
//!
//! A model with holonomic constraints moves on `φ(t, q) = 0`, and its `N`
//! coordinates are not independent there. The analyses work in
//! independent coordinates on that manifold: `δq = T δz` for an
//! orthonormal basis `T` of the null space of `G = ∂φ/∂q` at the point
//! (`N − C` columns), with velocities kept on `φ̇ = 0`, and the constrained
//! (saddle-point) accelerations, which carry how the constraint forces
//! change with the state (a hanging Cartesian pendulum is stiffened by its
//! rod's tension, not by gravity). [`linearize_on_manifold`] gives the
//! reduced `A` with `T` to map back ([`ManifoldLinearization`]);
//! [`equilibrium`] projects its guess onto `φ = 0` and runs Newton on the
//! tangent force `Tᵀ f` (`f − Gᵀ λ = 0` with `λ` from the saddle system at
//! rest), projecting back after each step; [`modes`] solves
//! `K_z v = ω² M_z v` with `M_z = Tᵀ M T`, `K_z = −Tᵀ M ∂q̈/∂q T`, one mode
//! per degree of freedom, shapes `T v` in the model's coordinates. The
//! derivatives are central differences of the saddle-point `q̈`
//! ([`Derivatives::CentralDifferences`]) whatever the model provides.
//! Rank-deficient constraints (a change point) are the saddle solve's
//! [`SingularConstraints`](crate::error::IntegrationError::SingularConstraints),
//! with the state.
//!
//! ```
//! use lagrange::models::CartesianPendulum;
//! use lagrange_runtime::analysis::{equilibrium, modes};
//! use lagrange_runtime::nalgebra::Vector2;
//!
//! let (g, l): (f64, f64) = (9.81, 2.0);
//! let pendulum = CartesianPendulum::new(1.0, l, g);
//! let hanging = equilibrium(&pendulum, 0.0, &Vector2::new(0.3, -1.8))?.q; // off the circle
//! assert!((hanging - Vector2::new(0.0, -l)).amax() < 1e-14);
//! let swing = &modes(&pendulum, 0.0, &hanging)?.modes[0];
//! assert!((swing.omega_squared - g / l).abs() < 1e-8);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Not yet
//!
//! [`linearize`] and [`linearize_with_inputs`] stay in the model's own
//! coordinates and refuse a constrained model
//! ([`AnalysisError::Constrained`]): use [`linearize_on_manifold`] and
//! [`linearize_on_manifold_with_inputs`] (whose `B` is exact). Exact
//! (symbolic) derivatives of the constrained accelerations are not
//! generated: the constrained `A` differences the saddle-point `q̈`.
//!
//! The files: `linearize.rs` ([`linearize`], [`linearize_with_inputs`]),
//! `manifold.rs` (the tangent basis, [`linearize_on_manifold`]),
//! `manifold_inputs.rs` ([`linearize_on_manifold_with_inputs`]), `rest.rs`
//! (equilibria and modes of a constrained model),
//! `equilibrium.rs` ([`equilibrium`], [`EquilibriumSearch`],
//! [`is_equilibrium`]), `modes.rs` ([`modes`]), `steady.rs`
//! ([`linearize_steady_motion`], [`steady_motion_matrices`]), `crossing.rs`
//! ([`stability_crossing`]: where a family of them turns stable or
//! unstable), `derivatives.rs` (the derivatives they share), `error.rs`
//! ([`AnalysisError`]).

mod crossing;
mod derivatives;
mod equilibrium;
mod error;
mod linearize;
mod manifold;
mod manifold_inputs;
mod modes;
mod neutral;
mod rest;
mod steady;

pub use crossing::{Crossing, CrossingError, SAMPLES, Turns, stability_crossing};
pub use equilibrium::{Equilibrium, EquilibriumSearch, equilibrium, is_equilibrium};
pub use error::AnalysisError;
pub use linearize::{InputLinearization, Linearization, linearize, linearize_with_inputs};
pub use manifold::{ManifoldLinearization, linearize_on_manifold};
pub use manifold_inputs::{ManifoldInputLinearization, linearize_on_manifold_with_inputs};
pub use modes::{Mode, ModeKind, Modes, modes};
pub use steady::{
    SteadyLinearization, SteadyMatrices, linearize_steady_motion, steady_motion_matrices,
};

#[cfg(doc)]
use crate::model::Lagrangian;

/// How the derivatives of a result were obtained, and so how accurate it
/// is.
///
/// ```
/// use lagrange::models::DoublePendulum;
/// use lagrange_runtime::analysis::{linearize, Derivatives};
/// use lagrange_runtime::WithLayers;
/// use lagrange_runtime::nalgebra::Vector2;
///
/// let (q, v) = (Vector2::new(0.1, 0.2), Vector2::zeros());
/// let plain = DoublePendulum::unit().without_jacobians();
/// assert_eq!(linearize(&plain, 0.0, &q, &v)?.derivatives, Derivatives::CentralDifferences);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Derivatives {
    /// From the model's symbolic Jacobians: exact up to rounding.
    Exact,
    /// Central differences: relative error `≈ ε^(2/3)`.
    CentralDifferences,
    /// Central differences at two steps, extrapolated (Richardson):
    /// relative error `≈ ε^(4/5)`.
    Extrapolated,
}
