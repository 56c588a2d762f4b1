//! The result of an integration: the state at each requested time.
//!
//! Only the requested samples are stored, never the steps in between, so
//! memory is set by the caller's sample times and not by the tolerances.

use nalgebra::{RealField, SVector};

/// The state `(q, q̇)` at each requested sample time, in order, and the work
/// it took.
///
/// ```
/// # use lagrange_runtime::Trajectory;
/// fn print_positions(trajectory: &Trajectory<f64, 2>) {
///     for sample in trajectory {
///         println!("t = {}: q = ({}, {})", sample.t, sample.q[0], sample.q[1]);
///     }
/// }
/// ```
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(bound(
        serialize = "S: serde::Serialize + nalgebra::Scalar",
        deserialize = "S: serde::Deserialize<'de> + nalgebra::Scalar"
    ))
)]
pub struct Trajectory<S, const N: usize> {
    times: Vec<S>,
    positions: Vec<SVector<S, N>>,
    velocities: Vec<SVector<S, N>>,
    stats: Stats,
    events: Vec<EventRecord<S, N>>,
    /// The index in `events` of the event that stopped the run.
    stopped: Option<usize>,
    /// The time an observer stopped the run at, if one did.
    interrupted: Option<S>,
}

/// One sample of a [`Trajectory`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(bound(
        serialize = "S: serde::Serialize + nalgebra::Scalar",
        deserialize = "S: serde::Deserialize<'de> + nalgebra::Scalar"
    ))
)]
pub struct Sample<S, const N: usize> {
    /// The sample time.
    pub t: S,
    /// Generalized coordinates at `t`.
    pub q: SVector<S, N>,
    /// Generalized velocities at `t`.
    pub qdot: SVector<S, N>,
}

/// The work an integration did, for comparing methods and tolerances.
///
/// For a model with [constraints](crate::constraints) it also tells how
/// well they were kept; those fields are zero for a model in minimal
/// coordinates.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct Stats {
    /// Steps kept.
    pub steps_accepted: usize,
    /// Steps tried and thrown away: error estimate too large, or a stage
    /// where the model could not be evaluated. Always zero for fixed steps.
    pub steps_rejected: usize,
    /// Right-hand side evaluations: one call of
    /// [`Lagrangian::mass_matrix_and_forcing`](crate::Lagrangian::mass_matrix_and_forcing)
    /// plus one solve of `M q̈ = f`. For [`Variational`](crate::Variational),
    /// which never forms `q̈`: evaluations of its discrete Euler–Lagrange
    /// residual (`momentum`, `lagrangian_gradient` and
    /// `nonconservative_forces` at one point), plus the conversions between
    /// `q̇` and `p` at the start and at each sample.
    pub rhs_evals: usize,
    /// Evaluations of the Jacobians `∂q̈/∂q`, `∂q̈/∂q̇` (exact, or by finite
    /// differences whose right-hand sides also count in `rhs_evals`), or of
    /// [`Variational`](crate::Variational)'s residual Jacobian (by finite
    /// differences, counted in `rhs_evals` too). Zero for explicit methods.
    pub jacobian_evals: usize,
    /// Solves of an implicit method's Newton system (the `M q̈ = f` solve of
    /// each right-hand side is counted in `rhs_evals`, not here).
    pub linear_solves: usize,
    /// Newton iterations of implicit methods, over all steps.
    pub newton_iterations: usize,
    /// The largest `|φ_i(t, q)|` at the end of an accepted step, before
    /// drift control (the projection) touched it, in the units of the
    /// constraint: the drift one step produces with
    /// [`Drift::Projection`](crate::constraints::Drift::Projection), the
    /// drift accumulated over the run with the other choices. The residual
    /// after the projection is
    /// [`projected_position_residual`](Self::projected_position_residual).
    pub max_position_residual: f64,
    /// The same for the velocity constraints, the largest `|φ̇_i|`.
    pub max_velocity_residual: f64,
    /// The largest `|φ_i(t, q)|` after a projection onto `φ = 0` (after
    /// each step, of each sample from dense output, and of the start): the
    /// residual the returned states carry, at rounding level. Zero when
    /// nothing was projected ([`Drift::None`](crate::constraints::Drift::None),
    /// Baumgarte, unconstrained models). The velocity projection is exact
    /// in one step (`φ̇` is linear in `q̇`), so its residual is rounding
    /// and not recorded.
    pub projected_position_residual: f64,
    /// How far the initial position was moved onto the constraints, the
    /// largest `|Δq_i|` (zero when it was consistent to rounding).
    pub initial_position_correction: f64,
    /// How far the initial velocity was moved onto `φ̇ = 0`, the largest
    /// `|Δq̇_i|`.
    pub initial_velocity_correction: f64,
    /// Newton iterations of the projections onto `φ = 0` (after each step
    /// and of samples from dense output), each one evaluation of `φ` and
    /// `G` and a `C × C` solve.
    pub projection_iterations: usize,
    /// Evaluations of [event](crate::events) functions, one call of one
    /// event's `g` each: at every step's end, and while an event is
    /// located. Zero for a run without events.
    pub event_evals: usize,
}

impl<S: RealField + Copy, const N: usize> Trajectory<S, N> {
    /// An empty trajectory with room for `samples` samples, so that
    /// recording them never reallocates.
    pub(crate) fn with_capacity(samples: usize) -> Self {
        Self {
            times: Vec::with_capacity(samples),
            positions: Vec::with_capacity(samples),
            velocities: Vec::with_capacity(samples),
            stats: Stats::default(),
            events: Vec::new(),
            stopped: None,
            interrupted: None,
        }
    }

    /// Forgets the events (a stepper's, from call to call), keeping their
    /// room.
    pub(crate) fn clear_events(&mut self) {
        self.events.clear();
        self.stopped = None;
        self.interrupted = None;
    }

    /// An observer stopped the run at `t`.
    pub(crate) fn interrupt(&mut self, t: S) {
        self.interrupted = Some(t);
    }

    /// The time at which an [observer](crate::events::Events::observe)
    /// stopped the run, if one did: the samples up to it are recorded,
    /// later ones are not.
    pub fn interrupted(&self) -> Option<S>
    where
        S: Copy,
    {
        self.interrupted
    }

    /// An event that happened; `stops` if it ended the run.
    pub(crate) fn push_event(&mut self, event: EventRecord<S, N>, stops: bool) {
        if stops && self.stopped.is_none() {
            self.stopped = Some(self.events.len());
        }
        self.events.push(event);
    }

    pub(crate) fn push(&mut self, t: S, q: SVector<S, N>, qdot: SVector<S, N>) {
        self.times.push(t);
        self.positions.push(q);
        self.velocities.push(qdot);
    }

    pub(crate) fn set_stats(&mut self, stats: Stats) {
        self.stats = stats;
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// Whether there are no samples (none requested, or a failure before the
    /// first one).
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// The sample times, equal to the requested ones.
    pub fn times(&self) -> &[S] {
        &self.times
    }

    /// `q` at each sample time.
    pub fn positions(&self) -> &[SVector<S, N>] {
        &self.positions
    }

    /// `q̇` at each sample time.
    pub fn velocities(&self) -> &[SVector<S, N>] {
        &self.velocities
    }

    /// The `i`-th sample, if there is one.
    pub fn get(&self, i: usize) -> Option<Sample<S, N>> {
        Some(Sample {
            t: *self.times.get(i)?,
            q: self.positions[i],
            qdot: self.velocities[i],
        })
    }

    /// The last sample: the final state of a successful integration.
    pub fn last(&self) -> Option<Sample<S, N>> {
        self.len().checked_sub(1).and_then(|i| self.get(i))
    }

    /// The samples in time order.
    pub fn iter(&self) -> Samples<'_, S, N> {
        Samples {
            trajectory: self,
            next: 0,
        }
    }

    /// The work the integration did.
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// The [events](crate::events) that happened, in time order (several
    /// at one time in the order they were added); empty for a run without
    /// events.
    pub fn events(&self) -> &[EventRecord<S, N>] {
        &self.events
    }

    /// The event that stopped the run, if one did: no sample after its
    /// time was recorded.
    pub fn stopped(&self) -> Option<&EventRecord<S, N>> {
        self.stopped.map(|i| &self.events[i])
    }
}

impl<'a, S: RealField + Copy, const N: usize> IntoIterator for &'a Trajectory<S, N> {
    type Item = Sample<S, N>;
    type IntoIter = Samples<'a, S, N>;

    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

/// Iterator over the samples of a [`Trajectory`], from [`Trajectory::iter`].
#[derive(Debug, Clone)]
pub struct Samples<'a, S, const N: usize> {
    trajectory: &'a Trajectory<S, N>,
    next: usize,
}

impl<S: RealField + Copy, const N: usize> Iterator for Samples<'_, S, N> {
    type Item = Sample<S, N>;

    fn next(&mut self) -> Option<Self::Item> {
        let sample = self.trajectory.get(self.next)?;
        self.next += 1;
        Some(sample)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.trajectory.len() - self.next;
        (left, Some(left))
    }
}

impl<S: RealField + Copy, const N: usize> ExactSizeIterator for Samples<'_, S, N> {}

/// An event that happened: which, when, in which state, and the state a
/// reset made of it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(bound(
        serialize = "S: serde::Serialize + nalgebra::Scalar",
        deserialize = "S: serde::Deserialize<'de> + nalgebra::Scalar"
    ))
)]
#[non_exhaustive]
pub struct EventRecord<S, const N: usize> {
    /// The event's name.
    #[cfg_attr(feature = "serde", serde(with = "crate::names::one"))]
    pub name: Name,
    /// Its index in the [`Events`](crate::events::Events) set.
    pub index: usize,
    /// The located time.
    pub t: S,
    /// `q` at `t`, before any reset.
    pub q: SVector<S, N>,
    /// `q̇` at `t`, before any reset.
    pub qdot: SVector<S, N>,
    /// For a reset, the state `(q, q̇)` the run restarted from (after all
    /// resets at this time, projected onto the constraints of a constrained
    /// model); `None` for a recorded or stopping event.
    pub after: Option<(SVector<S, N>, SVector<S, N>)>,
}

/// `(q, q̇)`, as a one-step method returns it.
pub(crate) type State<S, const N: usize> = (SVector<S, N>, SVector<S, N>);

/// A name from a model's or a method's constants (a coordinate, a
/// constraint, an input, an event): `&'static str`, named so that serde
/// takes it as an owned string, not one borrowed from its input.
pub type Name = &'static str;
