//! Holonomic constraints: models in redundant coordinates, closed loops.
//!
//! A model written with a `constraints:` section implements [`Holonomic`]
//! besides [`Lagrangian`]: its constraints `φ(t, q) = 0`, their Jacobian
//! `G = ∂φ/∂q` and the bias `γ` with `φ̈ = G q̈ + γ`. The equations of motion
//! are then the saddle-point system
//!
//! ```text
//! M q̈ + Gᵀ λ = f,        G q̈ = −γ,
//! ```
//!
//! whose multipliers `λ` are the constraint forces, in the units of the
//! constraint (a constraint written in metres gives newtons).
//!
//! # The solve
//!
//! Every right-hand side ([`acceleration`](crate::dynamics::acceleration))
//! eliminates `q̈` on the stack: the Cholesky factor `L` of `M` (with the
//! checks of [`solve_mass_matrix`](crate::linalg::mass::solve_mass_matrix)),
//! `Y = L⁻¹ Gᵀ`, the Schur complement `G M⁻¹ Gᵀ = Yᵀ Y` (`C × C`) and its
//! Cholesky factor, then
//!
//! ```text
//! λ = (G M⁻¹ Gᵀ)⁻¹ (G M⁻¹ f + γ),        q̈ = M⁻¹ (f − Gᵀ λ).
//! ```
//!
//! That costs, beside `M q̈ = f`, `C` triangular solves of size `N` and a
//! `C × C` Cholesky factorization. The Schur complement is judged with the
//! rows of `G` equilibrated in the `M⁻¹` metric (unit diagonal), so its
//! rank is decided free of the constraints' units and scales: a zero
//! diagonal (a constraint whose gradient vanishes) or a pivot below `C ε`
//! (constraints that have become parallel) is
//! [`SingularConstraints`](crate::IntegrationError::SingularConstraints)
//! at that `t` and state, never a NaN.
//!
//! # Drift, and how to control it
//!
//! Integrating `q̈` keeps `φ̈ = 0` only to the method's error, so `φ` and `φ̇`
//! drift away from zero, linearly and quadratically in time. A model has
//! the default, and [`WithLayers::with_drift`](crate::model::WithLayers::with_drift) layers another on it
//! ([`Constrained`]); the run reads it from the model's visit
//! ([`Visitor::visit`]'s settings):
//!
//! - [`Drift::Projection`] (the default): after every accepted step, `q` is
//!   moved back onto `φ = 0` by Newton's method on the orthogonal
//!   projection in the metric of `M`, `Δq = −M⁻¹Gᵀ (G M⁻¹ Gᵀ)⁻¹ φ`, to
//!   rounding level (usually one or two iterations), and then `q̇` onto
//!   `φ̇ = 0` in the same metric, in one linear step. Samples from dense
//!   output are projected the same way. Cost per step: two evaluations of
//!   `M`, one of `φ̇`, one of `φ` and `G` per iteration, and the same small
//!   solves as one right-hand side; the residuals stay at rounding level
//!   for any run length. The smallest change that restores the
//!   constraints, in the kinetic energy's norm: it moves the energy by
//!   the same order as the step's own error.
//! - [`Drift::Baumgarte`]: no projection; the accelerations satisfy
//!   `φ̈ + 2α φ̇ + β² φ = 0` instead of `φ̈ = 0` (γ replaced by
//!   `γ + 2α φ̇ + β² φ`), so the drift is damped like an oscillator of rate
//!   `β` and damping `α`. Cost: one evaluation of `φ` and `φ̇` per
//!   right-hand side. The residuals stay bounded, at the size of the
//!   method's error divided by `β²`, not at rounding; rates comparable to
//!   the fast motions of the model make it stiff.
//! - [`Drift::None`]: the index-1 equations alone, for measuring the drift.
//!
//! [`Variational`](crate::Variational) needs none of this: its constrained
//! discrete equations (RATTLE) satisfy `φ = 0` and `φ̇ = 0` at every step
//! by construction, whatever the setting.
//!
//! The first-same-as-last slope of [`Dopri5`](crate::Dopri5) and
//! [`Dop853`](crate::Dop853) was evaluated at the end of the step before
//! the projection moved it, by `δ`, the size of the step's local error.
//! It is kept rather than re-evaluated (which would cost one right-hand
//! side per step): it perturbs the next step by `O(h δ)`, below the
//! tolerance it is held to.
//!
//! [`Stats`](crate::Stats) reports the largest residuals `|φ_i|` and
//! `|φ̇_i|` met at the end of accepted steps, before the projection: one
//! step's drift with projection, the accumulated drift without.
//!
//! # Initial conditions
//!
//! A start `(q0, q̇0)` is consistent when each `|φ_i|` is within
//! `100 ε ‖G_i‖₁ ‖q‖∞` and each `|φ̇_i|` within
//! `100 ε (‖G_i‖₁ ‖q̇‖∞ + |∂φ_i/∂t|)`: the rounding of evaluating them,
//! whatever the units. A consistent start is integrated as given. An
//! inconsistent one is, as the run's [`ConstraintSettings::initial`] says
//! ([`WithLayers::with_initial_conditions`](crate::model::WithLayers::with_initial_conditions)), projected
//! as after a step ([`InitialConditions::Project`], the default; the
//! sizes of the corrections are in [`Stats`](crate::Stats), and the sample
//! at `t0` is the corrected state), or refused with
//! [`InconsistentInitialConditions`](crate::InvalidInput::InconsistentInitialConditions)
//! naming the constraint and its residual ([`InitialConditions::Reject`]).
//!
//! That projection moves every coordinate, in the metric of `M`. To build
//! a start from the coordinates and velocities you know instead,
//! [`consistent_start`] keeps those you name and solves for the rest: the
//! positions by Gauss–Newton onto the holonomic constraints, the
//! velocities so that every constraint's velocity residual, rolling rows
//! included, is zero; [`state_from_body_rates`] does it for a body in a
//! unit quaternion from its body rates (a rolling ball's centre velocity
//! completed by its rolling constraints). Each refuses with a
//! [`StartError`] what it cannot do.
//!
//! # Multipliers
//!
//! The constraint force on the coordinates is `−Gᵀ λ`, so `λ` depends on
//! how the constraint is written: `φ = x² + y² − l²` (`G = 2 (x, y)`) for a
//! bob on a rod gives `λ = T / (2 l)` for a rod tension `T`, `φ = √(x² +
//! y²) − l` gives `λ = T` itself. [`Multipliers::multipliers`] gives them at
//! a state, [`annotate`] for every sample of a trajectory, with the
//! residuals `φ` and `φ̇` beside them.
//!
//! # How the integrators reach a model's constraints
//!
//! The integrators are generic over [`Lagrangian<N>`] alone, and the number
//! of constraints `C` is a second size that the trait cannot name. A
//! constrained model therefore overrides one provided method,
//! [`Lagrangian::visit_constraints`], which hands a [`Visitor`] the model as
//! a [`Holonomic<N, C>`] with its `C` known, and the run's
//! [`ConstraintSettings`]: statically dispatched, so the constrained code is
//! monomorphized for the model's own sizes and nothing is allocated.
//! `lagrangian!` writes that one line; a model in minimal coordinates keeps
//! the default (`None`) and pays nothing. A layer on the model (another
//! drift control, a controller) hands the visitor the same constraints with
//! its settings, or joined to its dynamics.
//!
//! Where it lives: the contract, [`Holonomic`], its [`Visitor`] and the
//! settings, in `model/constraints.rs` and `model/settings.rs`; the layer
//! that changes the settings, [`ConstraintHandling`], in
//! `model/handling.rs`, built by `model/with.rs`'s
//! [`WithLayers`](crate::model::WithLayers); the solve,
//! the projections, the start and [`annotate`] in `dynamics/` (`saddle.rs`,
//! `projection.rs`, `start.rs`, `annotate.rs`); a start built from the
//! coordinates known in `constraints/start.rs`; the constrained variational
//! step in `integrators/variational/` (`constrained.rs`, `rattle.rs`). This
//! module gathers what a user names.

mod start;

pub use crate::dynamics::annotate::{ConstrainedSample, annotate};
pub use crate::dynamics::saddle::Multipliers;
#[doc(no_inline)]
pub use crate::model::Lagrangian;
pub use crate::model::constraints::{Holonomic, Visitor};
pub use crate::model::handling::{Constrained, ConstraintHandling};
pub use crate::model::settings::{ConstraintSettings, Drift, InitialConditions};
pub use start::{StartError, consistent_start, state_from_body_rates};
