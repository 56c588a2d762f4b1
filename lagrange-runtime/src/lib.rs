//! Runtime for lagrange models: integrate `M(t, q) q̈ = f(t, q, q̇)`.
//!
//! A model is anything that implements [`Lagrangian`]: a mass matrix, a
//! forcing and the two energies. `lagrangian!` derives all of it from `T` and
//! `V`; here we write one by hand to see what the integrators consume.
//!
//! # A pendulum in five minutes
//!
//! A bob of mass `m` on a rigid rod of length `l`, angle `θ` from the
//! downward vertical: `T = ½ m l² θ̇²`, `V = -m g l cos θ`, hence
//! `M = m l²` and `f = -m g l sin θ`.
//!
//! ```
//! use lagrange_runtime::prelude::*;
//! use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1};
//!
//! struct Pendulum {
//!     m: f64,
//!     l: f64,
//!     g: f64,
//! }
//!
//! impl Lagrangian<1> for Pendulum {
//!     type Scalar = f64;
//!     const COORDINATES: [&'static str; 1] = ["theta"];
//!
//!     fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
//!         SMatrix::<f64, 1, 1>::new(self.m * self.l * self.l)
//!     }
//!     fn forcing(&self, _t: f64, q: &SVector<f64, 1>, _qd: &SVector<f64, 1>) -> SVector<f64, 1> {
//!         Vector1::new(-self.m * self.g * self.l * q[0].sin())
//!     }
//!     fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> f64 {
//!         0.5 * self.m * self.l * self.l * qd[0] * qd[0]
//!     }
//!     fn potential_energy(&self, _t: f64, q: &SVector<f64, 1>) -> f64 {
//!         -self.m * self.g * self.l * q[0].cos()
//!     }
//!     fn parameters_are_finite(&self) -> bool {
//!         self.m.is_finite() && self.l.is_finite() && self.g.is_finite()
//!     }
//! }
//!
//! let pendulum = Pendulum { m: 1.0, l: 1.0, g: 9.81 };
//! let (q0, qdot0) = (Vector1::new(0.5), Vector1::new(0.0));
//!
//! // The one call: adaptive Dormand–Prince at default tolerances, sampled
//! // where we ask (every 0.1 s for 10 s), not where the steps fall.
//! let times: Vec<f64> = (1..=100).map(|i| 0.1 * i as f64).collect();
//! let trajectory = integrate(&pendulum, 0.0, q0, qdot0, &times)?;
//! assert_eq!(trajectory.len(), 100);
//!
//! // Energy is conserved up to the tolerance.
//! let e0 = pendulum.energy(0.0, &q0, &qdot0);
//! for s in &trajectory {
//!     assert!((pendulum.energy(s.t, &s.q, &s.qdot) - e0).abs() < 1e-6);
//! }
//!
//! // Choosing a method and its settings: same call, different integrator.
//! let tight = Dopri5::new().rtol(1e-12).atol(1e-12);
//! let reference = tight.integrate(&pendulum, 0.0, q0, qdot0, &[10.0])?;
//! let fixed = Rk4::new(1e-3).integrate(&pendulum, 0.0, q0, qdot0, &[10.0])?;
//! let gap = (fixed.last().unwrap().q - reference.last().unwrap().q).norm();
//! assert!(gap < 1e-9); // RK4's O(h⁴) error at h = 1e-3
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Choosing a method
//!
//! Every method implements [`Integrator`], so switching is a one-word
//! change. Costs are right-hand side evaluations (one `M q̈ = f` solve each).
//!
//! Every method, its order, kind, cost per step and when to use it, is in
//! the table on [`Method`], written from the integrators' registry (so a
//! method added there is in it): in short, [`Dopri5`] by default, [`Dop853`]
//! for tight tolerances, [`Radau5`] for stiff models, [`Rk4`] for a step you
//! choose, the Gauss methods and [`Variational`] for long runs without
//! energy drift.
//!
//! The implicit Runge–Kutta methods are symmetric and conserve quadratic
//! invariants; they are symplectic for a constant mass matrix, and for
//! `M(q)` they keep the energy from drifting on reversible models without
//! being symplectic ([below](#implicit-methods-symmetric-and-when-symplectic)).
//! Fixed-step methods land exactly on the sample times (each interval is cut
//! into equal steps no longer than `h`); adaptive ones step freely and fill in
//! the samples from their dense output, so sampling never changes their
//! steps.
//!
//! # When things go wrong
//!
//! Nothing panics on bad input or a misbehaving model. Integrators return
//! [`IntegrationResult`]: either the [`Trajectory`], or a [`Failure`]
//! holding the [`IntegrationError`] (what happened, at which `t`, in which
//! state) and the samples computed before it.
//!
//! ```
//! # use lagrange_runtime::prelude::*;
//! # use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1};
//! # struct Pendulum { l: f64 }
//! # impl Lagrangian<1> for Pendulum {
//! #     type Scalar = f64;
//! #     const COORDINATES: [&'static str; 1] = ["theta"];
//! #     fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
//! #         SMatrix::<f64, 1, 1>::new(self.l * self.l)
//! #     }
//! #     fn forcing(&self, _t: f64, q: &SVector<f64, 1>, _qd: &SVector<f64, 1>) -> SVector<f64, 1> {
//! #         Vector1::new(-9.81 * self.l * q[0].sin())
//! #     }
//! #     fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> f64 {
//! #         0.5 * self.l * self.l * qd[0] * qd[0]
//! #     }
//! #     fn potential_energy(&self, _t: f64, q: &SVector<f64, 1>) -> f64 {
//! #         -9.81 * self.l * q[0].cos()
//! #     }
//! # }
//! // A rod of length zero has no inertia: M = 0.
//! let broken = Pendulum { l: 0.0 };
//! let failure = integrate(&broken, 0.0, Vector1::new(0.5), Vector1::new(0.0), &[1.0])
//!     .unwrap_err();
//! assert!(matches!(failure.error, IntegrationError::SingularMassMatrix { t: 0.0, .. }));
//! assert!(failure.trajectory.is_empty());
//! println!("{failure}"); // mass matrix is singular at t = 0 (q = [0.5], q̇ = [0]): ...
//! ```
//!
//! A kinetic energy that is negative for some velocities (masses of
//! opposite sign) is a modelling error too,
//! [`IndefiniteMassMatrix`](IntegrationError::IndefiniteMassMatrix), at the
//! first state. Settings are used as given, never adjusted: a fixed step is
//! never lengthened (an interval between samples that needs more steps than
//! the budget is [`TooManySteps`](IntegrationError::TooManySteps) before its
//! first step), and a tolerance too loose to keep an explicit method stable
//! ends in [`Unstable`](IntegrationError::Unstable)
//! ([the rules](integrators)).
//!
//! # Implicit methods: symmetric, and when symplectic
//!
//! [`ImplicitMidpoint`] and [`GaussLegendre`] are the Gauss collocation
//! methods applied to `y = (q, q̇)`, the only variables every model has.
//! For any model they are:
//!
//! - **symmetric**: stepping with `h` then `−h` returns to the start, so
//!   their error expansions have only even powers of `h`;
//! - **reversible** when the model is: if `T` is quadratic in `q̇` and nothing
//!   depends on `t` (no dissipation, no driving), `(q, q̇) ↦ (q, −q̇)`
//!   reverses the motion, and a symmetric Runge–Kutta method inherits that
//!   exactly (Hairer, Lubich & Wanner, *Geometric Numerical Integration*,
//!   Thm. V.1.5): run forward, flip `q̇`, run again, and you are back at the
//!   start to round-off;
//! - **conservative of quadratic invariants** of `(q, q̇)`, to round-off: the
//!   angular momentum `m (x ẏ − y ẋ)` of a particle in a central field in
//!   Cartesian coordinates, say.
//!
//! Whether they are *symplectic* depends on the mass matrix:
//!
//! - **Constant `M`**: `p = M q̇` is a linear change of variables, Runge–Kutta
//!   methods commute with those, so each step is exactly the Gauss step in
//!   canonical `(q, p)`, which is symplectic: the energy error stays bounded
//!   over exponentially long times.
//! - **`M(q)`**, most models: `p = M(q) q̇` is nonlinear and the step in
//!   `(q, q̇)` is not the Gauss step in `(q, p)`. The argument that makes Gauss
//!   methods symplectic covers 2-forms with constant coefficients in the
//!   variables they are applied to; the form the flow preserves here,
//!   `Σ dqᵢ ∧ d(M(q) q̇)ᵢ`, has not, and in general it is not preserved.
//!   What still holds is reversibility, and for reversible, integrable or
//!   nearly integrable models reversible methods show no energy drift over
//!   long times (same book, ch. XI). Measured (`tests/implicit_geometry.rs`):
//!   a pendulum on a free cart, `M(θ)`, over 10⁵ steps of `h = 0.05`
//!   (~3300 swings) keeps a bounded energy error, midpoint 3·10⁻², Gauss-2
//!   2·10⁻⁴, Gauss-3 4·10⁻⁶ of `|E| ≈ 3.5`, with a fitted drift over the run
//!   below 2·10⁻⁴ of that error, while RK4 at the same step loses 1.9.
//!   Chaotic or non-reversible models (friction, gyroscopic or driven
//!   terms) have no such guarantee. A method that is symplectic for `M(q)`
//!   must be written in `(q, p)`, with [`Lagrangian::momentum`].
//!
//! Each step solves the stage equations, `2 N s` unknowns, by simplified
//! Newton: one Jacobian of `q̈` per step (exact with
//! [`Lagrangian::residual_jacobians`], else `2 N` extra right-hand sides of
//! forward differences), one LU factorization, and `s` right-hand sides per
//! iteration, typically 3–7 iterations from a guess extrapolated from the
//! previous step. The iteration stops when the correction is below `10 ε`
//! of the state's size, so the properties above hold to round-off, not to
//! a solver tolerance; or, once it no longer contracts fast, when the
//! correction is below the noise of evaluating the equations,
//! `ε (1000 + 10 N κ)` with `κ` the pivot ratio of `M`
//! ([`pivot_ratio`](linalg::mass::pivot_ratio)): an ill-conditioned mass
//! matrix (a light body beside a heavy one) makes the accelerations, and so
//! the corrections, only that accurate. If it diverges, or has not
//! converged in `max_iterations`, the step fails with
//! [`NewtonDivergence`](IntegrationError::NewtonDivergence): take a smaller
//! step.
//!
//! # The variational integrator
//!
//! [`Variational`] integrates the discrete Euler–Lagrange equations of the
//! model's own Lagrangian (midpoint rule) instead of `M q̈ = f`. Because `L`
//! and its discretization share their symmetries, the discrete Noether
//! theorem keeps the matching momenta exactly (angular momentum of a central
//! force, the momentum of any cyclic coordinate), and because the step is a
//! symplectic map, energy errors stay bounded over very long runs. It is
//! only second order, and implicit: each step solves an `N × N` Newton
//! system whose Jacobian comes from `N` extra residuals (a residual being
//! one call each of `momentum`, `lagrangian_gradient` and
//! `nonconservative_forces`, which `lagrangian!` models provide). Use it for
//! long runs where qualitative behaviour matters more than the digits of one
//! sample: orbits, rigid bodies, molecular chains.
//!
//! # Stiff models
//!
//! A model is stiff when it has motions much faster than the ones of
//! interest, like a hard spring vibrating while the system slowly swings:
//! an explicit method must resolve the vibration just to stay stable, an
//! L-stable one damps it and steps at the pace of the swing. On a two-mass
//! chain with a stiffness ratio of 10⁶, `Radau5` needs ~200× fewer
//! right-hand sides than `Dopri5` for the same tolerance. On non-stiff
//! models both work with similar numbers of right-hand sides; `Dopri5` does
//! no linear algebra (`O(N³)` per LU for `Radau5`) and its dense output is
//! more accurate between steps.
//!
//! # Map of the crate
//!
//! From the bottom up; a module imports only from the ones above it
//! (`src/layers.rs` checks it), ARCHITECTURE.md draws the whole.
//!
//! - [`linalg`]: the linear algebra, knowing no models:
//!   [`solve_mass_matrix`](linalg::mass::solve_mass_matrix) (an inlined
//!   `L D Lᵀ`), singular cases caught; the saddle-point system, the heap
//!   LU and the block solve of the implicit Runge–Kutta methods.
//! - [`trig`]: the sine and cosine the generated code calls, an inline
//!   `f64` kernel within one ulp that runs several angles side by side.
//! - [`model`]: the contract a model fulfils, [`Lagrangian`], and the one
//!   list of its optional capabilities (constraints, inputs, named `let`s,
//!   residual Jacobians); [`Layered`](model::Layered) models, the one way a
//!   setting (constraint handling, a controller, finite differences) wraps
//!   a model while passing every other capability through.
//! - [`dynamics`]: `q̈` (and `λ`) of a model at a state,
//!   [`acceleration`](dynamics::acceleration), constrained or not, every
//!   method's right-hand side; `∂q̈/∂q` and `∂q̈/∂q̇`
//!   ([`acceleration_jacobians`](dynamics::acceleration_jacobians)); whom
//!   to blame for a non-finite value; projection onto the constraints.
//! - [`constraints`] and [`inputs`]: the user's doors to those
//!   capabilities: [`Holonomic`] and its drift control (projection by
//!   default, Baumgarte, none), consistent initial conditions, the
//!   multipliers; [`Actuated`] models and the
//!   [`Controlled`](inputs::Controlled) model a controller drives.
//! - `driver/` (private): the run loops, one per kind of method (a walker;
//!   [`integrate`] and the [`Stepper`] both drive it, `run.rs`): fixed
//!   steps (`fixed.rs`) and the embedded pairs (`pair.rs`), Radau5's and
//!   the variational step's in their methods' folders
//!   (`integrators/radau5/walk.rs`, `integrators/variational/walk.rs`);
//!   sample recording, event location and actions (`events.rs`), input
//!   validation, the growth guard, step-size control, Newton's noise floor.
//! - [`integrators`]: the [`Integrator`] trait and one file or folder per
//!   method, each one entry of the registry (`integrators/mod.rs`) that
//!   generates [`Method`], [`AnyIntegrator`] and the lists: [`ExplicitEuler`],
//!   [`SymplecticEuler`] and [`Rk4`] (fixed step), [`Dopri5`] (adaptive, the
//!   default), [`Bs3`], [`Tsit5`] (each its coefficients over
//!   `integrators/fsal.rs`) and [`Dop853`] (adaptive), [`ImplicitMidpoint`] and
//!   [`GaussLegendre`] (implicit, fixed step, sharing `implicit_rk.rs`),
//!   [`Variational`] (fixed step, structure preserving), [`Radau5`]
//!   (adaptive, implicit, L-stable, for stiff models). [`Method`]'s table
//!   says which to choose.
//! - [`events`]: functions of the state whose crossings are located on
//!   each step's interpolant and recorded, or stop the run, or reset the
//!   state (impacts) and restart it: [`Event`], [`Events`], through
//!   [`Integrator::integrate_with_events`]; with the Zeno guard.
//! - [`stepper`]: the [`Stepper`], one frame at a time for a real-time
//!   loop, any method, no allocation per frame.
//! - [`ensemble`]: many states of one model in SIMD lanes, stepped
//!   together frame by frame ([`Ensemble`](ensemble::Ensemble), with the
//!   fixed-step explicit methods, [`LaneStep`]), each lane bit for bit its
//!   scalar `Stepper`.
//! - [`analysis`]: small motions, [`linearize`](analysis::linearize) at
//!   any state (`A`, and `B` for models with inputs), equilibria by
//!   Newton's method (with the neutral directions of a family), normal
//!   modes about them; exact with a model's residual Jacobians, else by
//!   central differences.
//! - [`Trajectory`] (`trajectory.rs`): the samples, the events that
//!   happened and the [`Stats`] of the work done.
//! - [`error`]: [`IntegrationError`], [`InvalidInput`], [`Failure`].
//!
//! Everything is generic over the model's scalar: `f64` and `f32` both work
//! (and lanes of them, `SimdRealField`, for an ensemble).

#![deny(missing_docs)]

pub mod analysis;
pub mod constraints;
pub mod contact;
mod driver;
pub mod dynamics;
pub mod ensemble;
pub mod error;
pub mod events;
pub mod export;
pub mod identify;
pub mod inputs;
pub mod integrators;
pub mod interop;
#[cfg(test)]
mod layers;
pub mod linalg;
pub mod model;
#[cfg(feature = "serde")]
mod names;
pub mod sensitivity;
pub mod stepper;
mod trajectory;
pub mod trig;

pub use constraints::Holonomic;
/// The diffsol crate (feature `diffsol`), for its solvers and traits
/// beside [`interop::diffsol`].
#[cfg(feature = "diffsol")]
pub use diffsol;
pub use error::{
    ConstraintLevel, Failure, IntegrationError, IntegrationResult, InvalidInput, NonFiniteValue,
    ResetFailure,
};
pub use events::{Event, Events};
pub use inputs::Actuated;
pub use integrators::StepMethod;
pub use integrators::all::*;
pub use integrators::{AnyIntegrator, Integrator, LaneStep, Method, integrate};
pub use model::{Domain, Lagrangian, ParameterDerivatives, ParameterError, WithLayers, lets};
pub use nalgebra;
/// The ode_solvers crate (feature `ode_solvers`), for its solvers beside
/// [`interop::ode_solvers`].
#[cfg(feature = "ode_solvers")]
pub use ode_solvers;
pub use stepper::Stepper;
pub use trajectory::{EventRecord, Sample, Samples, Stats, Trajectory};

/// The names a simulation needs: `use lagrange_runtime::prelude::*;`.
pub mod prelude {
    pub use crate::constraints::{Drift, InitialConditions, Multipliers};
    pub use crate::integrators::all::*;
    pub use crate::{
        Actuated, Event, Events, Failure, Holonomic, IntegrationError, Integrator, Lagrangian,
        StepMethod, Stepper, Trajectory, WithLayers, integrate,
    };
}
