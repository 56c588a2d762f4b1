//! What can stop an integration, where, and in which state.
//!
//! Every runtime failure carries the time and the state `(q, q̇)` at which it
//! was detected, and [`Failure`] carries the samples computed before it, so a
//! simulation that dies at `t = 9.7` still hands back everything up to there.

use core::fmt;

use nalgebra::{RealField, SVector};

use crate::trajectory::Trajectory;

mod non_finite;
mod reset;

pub use non_finite::NonFiniteValue;
pub use reset::ResetFailure;

pub use crate::trajectory::Name;

/// Why an integration stopped before the last requested sample time.
///
/// `t`, `q` and `qdot` are where the model was being evaluated (or the
/// integrator stood) when the problem was found. For a failing Runge–Kutta
/// stage that is a point inside the step, not necessarily a sample.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum IntegrationError<S: RealField + Copy, const N: usize> {
    /// `M(t, q)` has no usable inverse, so `M q̈ = f` does not determine the
    /// accelerations: a coordinate without inertia, or a degenerate
    /// configuration (a pendulum in a coordinate chart's pole, say).
    #[error(
        "mass matrix is singular at t = {t:?} (q = {}, q̇ = {}): M q̈ = f does not determine \
         the accelerations (a coordinate without inertia, or a degenerate configuration)",
        Row(.q), Row(.qdot)
    )]
    SingularMassMatrix {
        /// Time of the evaluation.
        t: S,
        /// Generalized coordinates at `t`.
        q: SVector<S, N>,
        /// Generalized velocities at `t`.
        qdot: SVector<S, N>,
    },

    /// `M(t, q)` is not positive definite: the kinetic energy is negative
    /// for some velocities (masses or inertias of opposite sign, or a sign
    /// error in `T`). That is a modelling error, not a numerical one, so it
    /// is reported as such where it is first met (at the first state for a
    /// model that is indefinite everywhere) instead of being solved by LU
    /// into a motion that runs away. A merely singular (semi-definite) `M`
    /// is [`SingularMassMatrix`](Self::SingularMassMatrix).
    #[error(
        "mass matrix is not positive definite at t = {t:?} (q = {}, q̇ = {}): the kinetic \
         energy is negative for some velocities (masses or inertias of opposite sign, or a \
         sign error in T); a modelling error",
        Row(.q), Row(.qdot)
    )]
    IndefiniteMassMatrix {
        /// Time of the evaluation.
        t: S,
        /// Generalized coordinates at `t`.
        q: SVector<S, N>,
        /// Generalized velocities at `t`.
        qdot: SVector<S, N>,
    },

    /// A NaN or an infinity appeared in the state, or in `M` or `f` as the
    /// model returned them, or in a sample a method's dense output
    /// interpolated; continuing would only spread it.
    #[error("{value} at t = {t:?} (q = {}, q̇ = {})", Row(.q), Row(.qdot))]
    NonFiniteState {
        /// Time of the evaluation.
        t: S,
        /// Generalized coordinates at `t` (may themselves be the culprit).
        q: SVector<S, N>,
        /// Generalized velocities at `t` (may themselves be the culprit).
        qdot: SVector<S, N>,
        /// Which value was not finite.
        value: NonFiniteValue,
    },

    /// The adaptive step size fell below what the arithmetic can resolve at
    /// `t` (`h ≤ 10 ε |t|` or `t + h == t`): usually a solution that blows
    /// up, or a model that is not smooth here.
    #[error(
        "step size underflow at t = {t:?} (q = {}, q̇ = {}): h = {h:?} no longer advances t; \
         the solution may blow up or the model may be discontinuous here",
        Row(.q), Row(.qdot)
    )]
    StepSizeUnderflow {
        /// Time reached.
        t: S,
        /// The step size that was too small.
        h: S,
        /// Generalized coordinates at `t`.
        q: SVector<S, N>,
        /// Generalized velocities at `t`.
        qdot: SVector<S, N>,
    },

    /// The step budget does not reach the last sample time: it ran out at
    /// `t`, or, for a fixed-step method, the interval from `t` to the next
    /// sample time alone needs more steps of the requested `h` than the
    /// whole budget, which is known before that interval's first step. The
    /// step is never lengthened to fit the budget.
    #[error(
        "the budget of {max_steps} steps does not reach the last sample time: stopped at \
         t = {t:?} (q = {}, q̇ = {}); raise max_steps, or lengthen the step or loosen the \
         tolerances",
        Row(.q), Row(.qdot)
    )]
    TooManySteps {
        /// Time reached.
        t: S,
        /// The step budget (accepted plus rejected steps for the adaptive
        /// methods).
        max_steps: usize,
        /// Generalized coordinates at `t`.
        q: SVector<S, N>,
        /// Generalized velocities at `t`.
        qdot: SVector<S, N>,
    },

    /// The Newton iteration of an implicit method did not converge within
    /// its iteration limit at a fixed step size `h` (adaptive methods shrink
    /// the step instead): `h` is too large for the problem's nonlinearity.
    #[error(
        "Newton iteration did not converge in {iterations} iterations at t = {t:?} with step \
         h = {h:?} (q = {}, q̇ = {}); take a smaller step",
        Row(.q), Row(.qdot)
    )]
    NewtonDivergence {
        /// Time at the start of the failing step.
        t: S,
        /// The step size tried.
        h: S,
        /// Iterations done in the failing step: the limit, or fewer when
        /// the corrections grew (the iteration was diverging); 0 when the
        /// Newton matrix was singular before the first.
        iterations: usize,
        /// Generalized coordinates at `t`.
        q: SVector<S, N>,
        /// Generalized velocities at `t`.
        qdot: SVector<S, N>,
    },

    /// An explicit method is beyond its stability limit: far past its
    /// starting size, the state kept growing geometrically in a mode the
    /// step does not resolve (by more than 2× per step; or turning, flipping
    /// sign or moving against its own velocity from one step to the next).
    /// No resolved motion does that, so this is the step size amplifying a
    /// fast mode: a fixed step too large for a stiff model, or, for
    /// [`Dopri5`](crate::integrators::Dopri5) and [`Dop853`](crate::integrators::Dop853), a tolerance
    /// so loose (`rtol` near 1 or above, or `atol` above the solution's
    /// size) that the error control no longer holds the step within the
    /// stability region. Stopped before the state overflows to infinity or
    /// turns into finite garbage.
    #[error(
        "unstable at t = {t:?} with step h = {h:?} (q = {}, q̇ = {}): the state grew \
         geometrically for {steps} steps in a mode the step does not resolve; h is beyond \
         this method's stability limit (a stiff model, or a tolerance too loose to hold the \
         step: take a smaller step or a tighter tolerance, or an implicit method such as \
         Radau5)",
        Row(.q), Row(.qdot)
    )]
    Unstable {
        /// Time reached.
        t: S,
        /// The step size (for an adaptive method, of the last step).
        h: S,
        /// Steps of growth that triggered the stop.
        steps: usize,
        /// Generalized coordinates at `t`.
        q: SVector<S, N>,
        /// Generalized velocities at `t`.
        qdot: SVector<S, N>,
    },

    /// The constraints' Jacobian `G` has lost rank in the metric of the
    /// masses: `G M⁻¹ Gᵀ` cannot be inverted, so the constraint forces are
    /// not determined (a linkage at a dead centre, two constraints that have
    /// become parallel, a constraint whose gradient vanishes). Judged scale
    /// free, on `G`'s rows equilibrated in the `M⁻¹` metric.
    #[error(
        "the constraints are singular or redundant at t = {t:?} (q = {}, q̇ = {}): G M⁻¹ Gᵀ \
         cannot be inverted, so the constraint forces are not determined (e.g. a linkage at \
         a dead centre, or two constraints that have become parallel)",
        Row(.q), Row(.qdot)
    )]
    SingularConstraints {
        /// Time of the evaluation.
        t: S,
        /// Generalized coordinates at `t`.
        q: SVector<S, N>,
        /// Generalized velocities at `t`.
        qdot: SVector<S, N>,
    },

    /// The projection of the state back onto `φ(t, q) = 0` after a step did
    /// not bring the residual to rounding level: the step left the
    /// constraint manifold too far for Newton's method to return, or the
    /// constraints are nearly singular there. Take a smaller step or a
    /// tighter tolerance.
    #[error(
        "projection onto the constraints failed at t = {t:?} (q = {}, q̇ = {}): constraint \
         `{constraint}` is still {residual:?} after {iterations} Newton iterations; take a \
         smaller step or a tighter tolerance",
        Row(.q), Row(.qdot)
    )]
    ProjectionFailed {
        /// Time of the projection.
        t: S,
        /// The constraint furthest from zero, from
        /// [`Holonomic::CONSTRAINTS`](crate::model::constraints::Holonomic::CONSTRAINTS).
        #[cfg_attr(feature = "serde", serde(with = "crate::names::one"))]
        constraint: Name,
        /// Its value `φ_i` after the last iteration.
        residual: S,
        /// Newton iterations done.
        iterations: usize,
        /// Generalized coordinates where the projection stopped.
        q: SVector<S, N>,
        /// Generalized velocities at `t`, not yet projected.
        qdot: SVector<S, N>,
    },

    /// An [event](crate::events) function returned NaN or an infinity, or
    /// an event's reset returned a non-finite state: the event cannot be
    /// located or acted on.
    #[error("event `{event}`: {value} at t = {t:?} (q = {}, q̇ = {})", Row(.q), Row(.qdot))]
    NonFiniteEvent {
        /// The event's name.
        #[cfg_attr(feature = "serde", serde(with = "crate::names::one"))]
        event: Name,
        /// Time of the evaluation.
        t: S,
        /// Generalized coordinates at `t` (for a reset, the state it
        /// returned).
        q: SVector<S, N>,
        /// Generalized velocities at `t` (likewise).
        qdot: SVector<S, N>,
        /// [`EventFunction`](NonFiniteValue::EventFunction) or
        /// [`EventReset`](NonFiniteValue::EventReset).
        value: NonFiniteValue,
    },

    /// An [event](crate::events)'s reset refused the state at the event:
    /// the reset of [`Event::try_reset`](crate::events::Event::try_reset)
    /// returned `reason`, or a contact's switch could not be decided (see
    /// [`contact`](crate::contact)). The [`Failure`] holds the samples and
    /// the events before it; `(t, q, q̇)` is the state at the event, before
    /// any reset.
    #[error(
        "event `{event}`: its reset failed at t = {t:?} (q = {}, q̇ = {}): {reason}",
        Row(.q), Row(.qdot)
    )]
    ResetFailed {
        /// The event's name.
        #[cfg_attr(feature = "serde", serde(with = "crate::names::one"))]
        event: Name,
        /// Time of the event.
        t: S,
        /// Generalized coordinates at `t`.
        q: SVector<S, N>,
        /// Generalized velocities at `t`.
        qdot: SVector<S, N>,
        /// Why. Boxed: a field with a niche of its own (an enum's tag, a
        /// `String`'s capacity) would let the compiler fold this enum's
        /// tag into it, and that layout made every adaptive run 35–45 %
        /// slower on the 2-coordinate models (issue 49's seed problem;
        /// same instructions, the time lost to how `Result`s of this type
        /// are stored and read in the stages).
        reason: Box<ResetFailure>,
    },

    /// The forces of the touching contacts are not determined in their
    /// current modes (see [`contact`](crate::contact)): their rows of `G`
    /// (and of `T` for stuck ones) are dependent in the metric of `M`, or
    /// `M` cannot be factored.
    #[error(
        "the touching contacts' forces are not determined at t = {t:?} (q = {}, q̇ = {}): \
         their constraints are dependent in the metric of M, or M is singular",
        Row(.q), Row(.qdot)
    )]
    UndeterminedContactForces {
        /// Time of the evaluation.
        t: S,
        /// Generalized coordinates at `t`.
        q: SVector<S, N>,
        /// Generalized velocities at `t`.
        qdot: SVector<S, N>,
    },

    /// Events accumulate: `gaps` gaps in a row between events were shorter
    /// than the minimum separation (a bouncing ball coming to rest bounces
    /// infinitely often before a finite time). The
    /// [`Failure`] holds the samples and the events before
    /// this one; `(t, q, q̇)` is this event's, before any reset (see
    /// [`events`](crate::events#guards)).
    #[error(
        "Zeno: {gaps} gaps in a row between events shorter than the minimum separation \
         {min_separation:?} (the last {gap:?}) at t = {t:?} (q = {}, q̇ = {}): the events \
         accumulate in finite time, as a bouncing ball's coming to rest",
        Row(.q), Row(.qdot)
    )]
    Zeno {
        /// Time of the event that completed the run of short gaps.
        t: S,
        /// How many gaps in a row were short.
        gaps: usize,
        /// The last gap.
        gap: S,
        /// The minimum separation in force.
        min_separation: S,
        /// Generalized coordinates at `t`.
        q: SVector<S, N>,
        /// Generalized velocities at `t`.
        qdot: SVector<S, N>,
    },

    /// The call itself was wrong; nothing was integrated.
    #[error("invalid input: {0}")]
    InvalidInput(InvalidInput<S>),
}

impl<S: RealField + Copy, const N: usize> IntegrationError<S, N> {
    /// The time at which the integration stopped; `None` for an input
    /// refused before the first step.
    pub fn time(&self) -> Option<S> {
        match self {
            Self::SingularMassMatrix { t, .. }
            | Self::IndefiniteMassMatrix { t, .. }
            | Self::NonFiniteState { t, .. }
            | Self::StepSizeUnderflow { t, .. }
            | Self::TooManySteps { t, .. }
            | Self::NewtonDivergence { t, .. }
            | Self::Unstable { t, .. }
            | Self::SingularConstraints { t, .. }
            | Self::ProjectionFailed { t, .. }
            | Self::NonFiniteEvent { t, .. }
            | Self::ResetFailed { t, .. }
            | Self::UndeterminedContactForces { t, .. }
            | Self::Zeno { t, .. } => Some(*t),
            Self::InvalidInput(_) => None,
        }
    }
}

impl<S: RealField + Copy, const N: usize> From<InvalidInput<S>> for IntegrationError<S, N> {
    fn from(invalid: InvalidInput<S>) -> Self {
        Self::InvalidInput(invalid)
    }
}

/// A call that cannot be integrated as given, and what is wrong with it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum InvalidInput<S: RealField + Copy> {
    /// `t0` is NaN or infinite.
    #[error("the start time t0 = {t0:?} is not finite")]
    NonFiniteStartTime {
        /// The start time given.
        t0: S,
    },

    /// A component of `q0` is NaN or infinite.
    #[error("the initial position of coordinate `{coordinate}` is {value:?}, not a finite number")]
    NonFiniteInitialPosition {
        /// Name of the coordinate, from [`Lagrangian::COORDINATES`](crate::model::Lagrangian::COORDINATES).
        #[cfg_attr(feature = "serde", serde(with = "crate::names::one"))]
        coordinate: Name,
        /// The value given.
        value: S,
    },

    /// A component of `q̇0` is NaN or infinite.
    #[error("the initial velocity of coordinate `{coordinate}` is {value:?}, not a finite number")]
    NonFiniteInitialVelocity {
        /// Name of the coordinate, from [`Lagrangian::COORDINATES`](crate::model::Lagrangian::COORDINATES).
        #[cfg_attr(feature = "serde", serde(with = "crate::names::one"))]
        coordinate: Name,
        /// The value given.
        value: S,
    },

    /// [`Lagrangian::parameters_are_finite`](crate::model::Lagrangian::parameters_are_finite)
    /// returned `false`.
    #[error("a parameter of the model is NaN or infinite")]
    NonFiniteParameters,

    /// The model has control inputs that were never set (they start as
    /// NaN): integrating it would silently run on NaN, or on whatever value
    /// a default would pick. Reported for the inputs the model holds (see
    /// [`Inputs::held_inputs`](crate::inputs::Inputs::held_inputs)), through
    /// any layer on the model.
    #[error(
        "the model has control inputs ({}) that were never set: integrate \
         `model.with_controller(..)` or `model.with_inputs(..)`",
        .inputs.join(", ")
    )]
    InputsNotSet {
        /// The names of the model's inputs, from
        /// [`Inputs::NAMES`](crate::inputs::Inputs::NAMES).
        #[cfg_attr(feature = "serde", serde(with = "crate::names::list"))]
        inputs: &'static [Name],
    },

    /// The model has unilateral contacts (`contacts:`), which this run
    /// would ignore: the model would pass through its floor.
    #[error(
        "the model has contacts (`contacts:`), which this run would ignore: run it with \
         `lagrange::contact::integrate`"
    )]
    ContactsNotRun,

    /// The model's [`SOLVES_ACCELERATIONS`](crate::model::Lagrangian::SOLVES_ACCELERATIONS)
    /// is `false` while its [`accelerations`](crate::model::Lagrangian::accelerations)
    /// answers at the start: a run would never ask it, and integrate `M q̈ =
    /// f` instead. Set the flag with the method (or leave both out).
    #[error(
        "the model's `accelerations` answers but its `SOLVES_ACCELERATIONS` is false: a run \
         would ignore the method; set `const SOLVES_ACCELERATIONS: bool = true`"
    )]
    AccelerationsNotFlagged,

    /// A sample time is NaN or infinite.
    #[error("sample time times[{index}] = {time:?} is not finite")]
    NonFiniteSampleTime {
        /// Index into the sample times.
        index: usize,
        /// The value given.
        time: S,
    },

    /// The sample times decrease somewhere.
    #[error(
        "sample times must be non-decreasing, but times[{index}] = {time:?} comes after \
         times[{}] = {previous:?}",
        .index - 1
    )]
    UnsortedSampleTimes {
        /// Index of the first sample time smaller than its predecessor.
        index: usize,
        /// `times[index - 1]`.
        previous: S,
        /// `times[index]`.
        time: S,
    },

    /// A sample time precedes `t0`; integration runs forward only.
    #[error(
        "sample time times[{index}] = {time:?} is before the start time t0 = {t0:?} \
         (integration runs forward only)"
    )]
    SampleBeforeStart {
        /// Index of the offending sample time.
        index: usize,
        /// The sample time.
        time: S,
        /// The start time.
        t0: S,
    },

    /// A [`Stepper`](crate::stepper::Stepper) asked to move to a time that is not
    /// after its own (it advances forward only), or not finite; also a
    /// `dt` too small to change `t`.
    #[error(
        "the stepper is at t = {t:?} and cannot advance to {target:?}: \
         the target must be finite and later than t"
    )]
    TargetNotAhead {
        /// The stepper's time.
        t: S,
        /// The time asked for.
        target: S,
    },

    /// A fixed step size that is zero, negative or not finite.
    #[error("the step size h = {h:?} must be positive and finite")]
    InvalidStepSize {
        /// The step size given.
        h: S,
    },

    /// A relative tolerance the scalar type cannot honour.
    #[error(
        "the relative tolerance rtol = {rtol:?} must be finite and at least {min:?} \
         (10 ε of the scalar type): tighter cannot be met in its arithmetic"
    )]
    InvalidRelativeTolerance {
        /// The tolerance given.
        rtol: S,
        /// The smallest accepted value, `10 ε`.
        min: S,
    },

    /// An absolute tolerance that is zero, negative or not finite. Zero is
    /// refused because a component passing through zero would then have no
    /// error scale at all.
    #[error("the absolute tolerance atol = {atol:?} must be positive and finite")]
    InvalidAbsoluteTolerance {
        /// The tolerance given.
        atol: S,
    },

    /// A Newton iteration limit of zero: an implicit method cannot take a
    /// step without at least one iteration.
    #[error("{method} needs at least one Newton iteration per step, but max_iterations = 0")]
    NoNewtonIterations {
        /// The integrator.
        #[cfg_attr(feature = "serde", serde(with = "crate::names::one"))]
        method: Name,
    },

    /// The method needs something of the model that it does not provide
    /// (a hand-written [`Lagrangian`](crate::model::Lagrangian) without the
    /// optional method; models from `lagrangian!` provide them all).
    #[error("{method} needs `Lagrangian::{needs}`, which this model does not provide")]
    ModelLacks {
        /// The integrator.
        #[cfg_attr(feature = "serde", serde(with = "crate::names::one"))]
        method: Name,
        /// The missing trait method.
        #[cfg_attr(feature = "serde", serde(with = "crate::names::one"))]
        needs: Name,
    },

    /// The method needs every constraint on the positions, and the model
    /// has constraints on its velocities
    /// ([`Holonomic::has_velocity_constraints`](crate::model::constraints::Holonomic::has_velocity_constraints)):
    /// the variational integrator's RATTLE steps impose each constraint on
    /// the next position.
    #[error(
        "{method} imposes every constraint on the positions, and this model has constraints on its \
         velocities (rolling, a knife edge); integrate it with a method that solves for q̈ through the \
         constraints (RK4, Dopri5, Tsit5, Dop853, Radau5, GaussLegendre, ...)"
    )]
    VelocityConstraints {
        /// The integrator.
        #[cfg_attr(feature = "serde", serde(with = "crate::names::one"))]
        method: Name,
    },

    /// The initial state is off the constraints beyond rounding, and the
    /// model asked for such states to be refused rather than projected
    /// ([`InitialConditions::Reject`](crate::constraints::InitialConditions::Reject)).
    #[error(
        "the initial state violates constraint `{constraint}`: {level} = {residual:?}, beyond \
         the rounding-level tolerance {tolerance:?}; give a consistent state, or let it be \
         projected (InitialConditions::Project)"
    )]
    InconsistentInitialConditions {
        /// The first violated constraint, from
        /// [`Holonomic::CONSTRAINTS`](crate::model::constraints::Holonomic::CONSTRAINTS).
        #[cfg_attr(feature = "serde", serde(with = "crate::names::one"))]
        constraint: Name,
        /// Whether its position `φ` or its velocity `φ̇` is off.
        level: ConstraintLevel,
        /// The residual.
        residual: S,
        /// What rounding alone could explain (see
        /// [`constraints`](crate::constraints#initial-conditions)).
        tolerance: S,
    },

    /// Baumgarte stabilization with a negative or non-finite rate: it would
    /// amplify the drift instead of damping it.
    #[error(
        "Baumgarte stabilization needs finite, non-negative alpha and beta, got alpha = \
         {alpha:?}, beta = {beta:?}"
    )]
    InvalidBaumgarte {
        /// The damping rate given.
        alpha: S,
        /// The stiffness rate given.
        beta: S,
    },

    /// A setting of an [`Events`](crate::events::Events) set out of range:
    /// a tolerance, separation or step bound that is negative, zero where
    /// it must be positive, or not finite.
    #[error("the event setting {setting} = {value:?} must be {requirement}")]
    InvalidEventSetting {
        /// `time_tolerance`, `min_separation` or `max_step`.
        #[cfg_attr(feature = "serde", serde(with = "crate::names::one"))]
        setting: Name,
        /// The value given.
        value: S,
        /// What it must be.
        #[cfg_attr(feature = "serde", serde(with = "crate::names::one"))]
        requirement: Name,
    },
}

/// Which level of a constraint a residual belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ConstraintLevel {
    /// The position constraint `φ(t, q) = 0`.
    Position,
    /// The velocity constraint `φ̇ = G q̇ + ∂φ/∂t = 0`.
    Velocity,
}

impl fmt::Display for ConstraintLevel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Position => "φ",
            Self::Velocity => "φ̇",
        })
    }
}

/// An integration that stopped early: the reason, and every requested
/// sample computed before it.
///
/// Integrators return it boxed (see [`IntegrationResult`]). A match
/// needs no `Box` written out: take the failure, then match its `error`
/// (a field read through the box), or move both parts out with `*`:
///
/// ```
/// use lagrange_runtime::{Failure, IntegrationError, IntegrationResult};
///
/// fn why<const N: usize>(result: IntegrationResult<f64, N>) -> String {
///     match result {
///         Ok(trajectory) => format!("{} samples", trajectory.len()),
///         Err(failure) => match failure.error {
///             IntegrationError::TooManySteps { t, .. } => {
///                 format!("out of steps at t = {t}, {} samples kept", failure.trajectory.len())
///             }
///             _ => failure.to_string(),
///         },
///     }
/// }
///
/// fn parts<const N: usize>(failure: Box<Failure<f64, N>>) {
///     let Failure { error, trajectory } = *failure;
///     # let _ = (error, trajectory);
/// }
/// # let _ = (why::<1>, parts::<1>);
/// ```
///
/// Why boxed: unboxed, the error variant of the result is at least 248
/// bytes (the trajectory's vectors and statistics beside the error and its
/// states), and Clippy's default `result_large_err` lint would then warn
/// in every function of a user's that returns an [`IntegrationResult`].
/// Boxed, it is one pointer, and the successful path stays small.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Failure<S: RealField + Copy, const N: usize> {
    /// What went wrong, where, and in which state.
    pub error: IntegrationError<S, N>,
    /// The samples at the requested times before the failure, with the work
    /// spent; empty when the input was invalid.
    pub trajectory: Trajectory<S, N>,
}

impl<S: RealField + Copy, const N: usize> Failure<S, N> {
    /// Boxes a failure; the form every integrator returns.
    pub fn boxed(error: IntegrationError<S, N>, trajectory: Trajectory<S, N>) -> Box<Self> {
        Box::new(Self { error, trajectory })
    }
}

impl<S: RealField + Copy, const N: usize> fmt::Display for Failure<S, N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kept = self.trajectory.len();
        let plural = if kept == 1 { "" } else { "s" };
        write!(f, "{} ({kept} sample{plural} kept)", self.error)
    }
}

// The message already contains the error's, so `source` stays `None`
// (reporters would otherwise print it twice).
impl<S: RealField + Copy, const N: usize> std::error::Error for Failure<S, N> {}

/// What every integrator returns: the requested samples, or the reason it
/// stopped together with the samples computed before.
pub type IntegrationResult<S, const N: usize> = Result<Trajectory<S, N>, Box<Failure<S, N>>>;

/// Formats a vector on one line, `[1.0, -0.5]`, instead of nalgebra's boxed
/// multi-line matrix layout. Scalars use `Debug`, which switches to
/// exponents for tiny and huge values (`2.2e-15`, not 17 zeros).
pub(crate) struct Row<'a, S, const N: usize>(pub(crate) &'a SVector<S, N>);

impl<S: RealField + Copy, const N: usize> fmt::Display for Row<'_, S, N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("[")?;
        for (i, x) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{x:?}")?;
        }
        f.write_str("]")
    }
}
