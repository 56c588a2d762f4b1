//! Events and impacts: functions of the state watched along a run, located
//! in time, recorded, and acted on.
//!
//! An [`Event`] is a function `g(t, q, q̇)` whose zero crossings matter: a
//! ball reaching the floor (`g = z`), a pendulum reaching a wall, a
//! coordinate passing through a section. Each has a [`Direction`] (rising,
//! falling, or both) and an action: **record** the crossing (the default),
//! **stop** the run there, or **reset** the state by a closure, an impact
//! with restitution or a mode switch, after which the integration restarts
//! from the new state. Event functions, resets and the observer are
//! `Send + Sync` closures (plain functions of the state are), so that runs
//! and [`Stepper`](crate::stepper::Stepper)s watching them can move between threads.
//! An [`Events`] set, handed to
//! [`Integrator::integrate_with_events`](crate::integrators::Integrator::integrate_with_events),
//! holds them with the settings of the search; what happened is in
//! [`Trajectory::events`](crate::trajectory::Trajectory::events) and
//! [`Trajectory::stopped`](crate::trajectory::Trajectory::stopped).
//!
//! ```
//! use lagrange_runtime::prelude::*;
//! use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1};
//!
//! /// A ball in one dimension: `z̈ = −g`.
//! struct Ball;
//! impl Lagrangian<1> for Ball {
//!     type Scalar = f64;
//!     const COORDINATES: [&'static str; 1] = ["z"];
//!     fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
//!         SMatrix::<f64, 1, 1>::new(1.0)
//!     }
//!     fn forcing(&self, _t: f64, _q: &SVector<f64, 1>, _qd: &SVector<f64, 1>) -> SVector<f64, 1> {
//!         Vector1::new(-9.81)
//!     }
//!     fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> f64 {
//!         0.5 * qd[0] * qd[0]
//!     }
//!     fn potential_energy(&self, _t: f64, q: &SVector<f64, 1>) -> f64 {
//!         9.81 * q[0]
//!     }
//! }
//!
//! // The floor: z falls through 0, the velocity reverses with restitution 0.9.
//! let floor = Event::new("floor", |_t, q: &SVector<f64, 1>, _qd: &SVector<f64, 1>| q[0])
//!     .falling()
//!     .reset(|_t, q, qd| (*q, -0.9 * qd));
//! let events = Events::new().with(floor);
//! let run = Dopri5::new().integrate_with_events(
//!     &Ball, 0.0, Vector1::new(1.0), Vector1::new(0.0), &[2.0], &events,
//! )?;
//!
//! // Dropped from 1 m, it lands at √(2/g); the second landing follows after
//! // a flight of 2 · 0.9 · √(2/g).
//! let t1 = (2.0 / 9.81f64).sqrt();
//! let bounces = run.events();
//! assert!((bounces[0].t - t1).abs() < 1e-12);
//! assert!((bounces[1].t - t1 * (1.0 + 1.8)).abs() < 1e-12);
//! let (_, qdot_after) = bounces[0].after.unwrap();
//! assert!((qdot_after[0] + 0.9 * bounces[0].qdot[0]).abs() < 1e-15);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # How events are found
//!
//! After each accepted step `[t, t + h]`, every event function is evaluated
//! at the step's end and compared with its value at the start. A crossing
//! in the event's direction (rising: `g < 0` at the start, `g ≥ 0` at the
//! end; falling: `g > 0`, then `g ≤ 0`) is located on the step's
//! interpolant by the Illinois variant of regula falsi (`locate.rs`) to the
//! [time tolerance](Events::time_tolerance), by default `4 ε max(|t|, 1)`,
//! a few ulps of `t`. The interpolant is the method's own dense output for
//! [`Dopri5`](crate::integrators::Dopri5) (order 4), [`Dop853`](crate::integrators::Dop853) (order 7,
//! whose three extra stages are then computed on every step, 15 right-hand
//! sides instead of 12) and [`Radau5`](crate::integrators::Radau5) (order 3); for the
//! fixed-step methods it is the cubic Hermite interpolant of `(q, q̇)` with
//! slopes `(q̇, q̈)` at both ends (the end's `q̈` is one more right-hand side
//! per step, counted; the start's is the previous step's end). The event
//! time is then as accurate as the interpolant: `O(h⁴)` for the Hermite
//! interpolant, whatever the method's order. The variational integrator
//! computes `q̇` from its momenta at every step end while events are
//! watched (one conversion each, counted in `rhs_evals`). Evaluations of
//! event functions are counted in [`Stats::event_evals`](crate::trajectory::Stats::event_evals).
//!
//! # Crossings inside one step
//!
//! A function can cross zero and come back within one step (a pendulum
//! that grazes a wall, a ball that grazes the floor): its values at the
//! step's ends agree in sign. Such a dip is found from `g`'s rate along the
//! step's interpolant: where the rate at the start points towards zero and
//! the rate at the end away from it, `g` has an extremum between them; it
//! is located as the rate's root, and if it reaches across zero both
//! crossings are located and acted on like any other (the first is where
//! an impact happens). The rate is `g`'s own along the interpolant, by
//! differences over `2⁻²⁰` of the step, so an event needs nothing but its
//! function.
//!
//! - **The guarantee**: on every accepted step, a crossing of `g` along the
//!   step's interpolant is found whenever `g` has at most one extremum in
//!   the step. Two or more within one step (an oscillation of `g` faster
//!   than the step) can hide a crossing; bound the step with
//!   [`max_step`](Events::max_step) for those.
//! - **What remains between the interpolant and the truth**: the
//!   interpolant's own error (order 4 for Dopri5's, 7 for Dop853's, 3 for
//!   Radau5's, `h⁴/384 |q⁗|` for the Hermite one). A dip shallower than it
//!   can be missed, or one invented, by that much.
//! - **The cost per step**, for each event whose values at the step's ends
//!   have the same sign: two evaluations of `g` on the interpolant (its
//!   rate at both ends); where they show an extremum towards zero, its
//!   search, two evaluations per iteration, typically a few iterations,
//!   ending as soon as a value across zero is met or the extremum is
//!   clearly short of it. A pendulum on a wall (`PendulumWall`, 40
//!   impacts to t = 74, the last ones grazing) is found whole by Dop853,
//!   Dopri5, Radau5 and RK4 without a step bound.
//!
//! Other limits, by construction:
//!
//! - A function that is zero at the start (`t0`, or the time of the
//!   previous event) is not armed: no crossing is reported there, and the
//!   next one needs `g` to leave zero first. An event exactly at `t0` is not
//!   triggered. Where `g` leaves zero and comes back across it within the
//!   first step (a bounce shorter than the step), the way it left is read
//!   from `g` just after the start (`2⁻²⁰` of the step, on the
//!   interpolant: one more evaluation), and that crossing is found.
//! - Several events crossing within the same located time are handled
//!   together: all are recorded; a stop wins over resets; resets are
//!   applied in the order the events were added.
//!
//! # After an event
//!
//! - **Record**: the time and state go into the trajectory's events; the
//!   run goes on untouched (samples and steps are those of a run without
//!   the event, except that [`max_step`](Events::max_step) bounds the
//!   steps).
//! - **Stop**: samples up to the event time come from the step's
//!   interpolant; later ones are not recorded; the event is
//!   [`Trajectory::stopped`](crate::trajectory::Trajectory::stopped).
//! - **Reset**: samples up to the event time come from the step's
//!   interpolant, with the state before; then the state is replaced by the
//!   closure's and the method restarts from the event time as from a new
//!   start: the adaptive methods compute their first slope and a first step
//!   from the new state (Hairer's initial step guess), the fixed-step ones
//!   cut the interval to the next sample into equal steps no longer than
//!   `h` (the step is never lengthened). A sample within `10 ε |t|` after
//!   the event, too close to step to, takes the state just after it.
//!
//! A constrained model's state at the event is projected onto its
//! constraints like any sample from an interpolant, and so is a reset's
//! result (when the model's drift control projects, the default).
//!
//! # State of a run
//!
//! A reset that must remember something (the bounces so far, a mode) keeps
//! it as data of the run, not in its closure: [`Events::keeping`] gives
//! each run its own copy of a start value, [`Event::keeping`]'s function
//! reads it and [`Event::try_reset_keeping`]'s reset changes it. Two runs
//! of the same events, one after the other or side by side, each start
//! from the start value; a [`Stepper`](crate::stepper::Stepper)'s is read
//! with [`Stepper::data`](crate::stepper::Stepper::data). The contacts keep
//! their modes so ([`contact`](crate::contact)).
//!
//! # Guards
//!
//! - **Zeno**: a run of events accumulating in finite time (a bouncing
//!   ball coming to rest makes infinitely many bounces before a finite
//!   time) ends with [`IntegrationError::Zeno`](crate::error::IntegrationError::Zeno)
//!   when three gaps in a row between events are shorter than the
//!   [minimum separation](Events::min_separation), by default 1000 time
//!   tolerances (gaps that short are resolved to no more than three
//!   digits), and four steps for a fixed-step method (which misses an
//!   excursion shorter than a step: without the guard, the ball would then
//!   fall through the floor unseen). Restitution below about 0.5 can
//!   shrink the gaps from four steps to less than one within three bounces:
//!   set a larger separation for such a fixed-step run.
//!   The [`Failure`](crate::error::Failure) holds the trajectory and the events so
//!   far.
//! - An event function returning NaN or an infinity, or a reset returning
//!   a non-finite state, is
//!   [`IntegrationError::NonFiniteEvent`](crate::error::IntegrationError::NonFiniteEvent),
//!   naming the event.
//! - A reset that refuses the state at its event
//!   ([`Event::try_reset`]) ends the run with
//!   [`IntegrationError::ResetFailed`](crate::error::IntegrationError::ResetFailed),
//!   naming the event and saying why.
//! - Settings out of range (a negative or NaN tolerance, a non-positive
//!   step bound) are [`InvalidInput::InvalidEventSetting`],
//!   before any work.

use core::any::Any;
use core::fmt;

use nalgebra::{RealField, SVector};

use crate::error::{InvalidInput, ResetFailure};
use crate::trajectory::State;

mod guard;
mod hermite;
mod locate;
mod watch;

pub use crate::trajectory::EventRecord;
pub(crate) use hermite::Hermite;
pub(crate) use locate::{evaluate_into, first_crossing};
pub(crate) use watch::Watch;

/// What a run carries from event to event for the events that keep state
/// (the contacts' modes and switches): owned by the run, made anew for
/// each run by its [`Events`], read by the events' functions and changed
/// by their resets only. `()` for a run whose events keep nothing.
pub(crate) type RunData = dyn Any + Send + Sync;

/// An event function `g(t, q, q̇)`, given the run's data.
type Function<'a, S, const N: usize> =
    Box<dyn Fn(&RunData, S, &SVector<S, N>, &SVector<S, N>) -> S + Send + Sync + 'a>;

/// A reset `(t, q, q̇) ↦ (q⁺, q̇⁺)`, or why there is none, given the run's
/// data to change.
type ResetMap<'a, S, const N: usize> = Box<
    dyn Fn(&mut RunData, S, &SVector<S, N>, &SVector<S, N>) -> Result<State<S, N>, ResetFailure>
        + Send
        + Sync
        + 'a,
>;

/// How a run's data is made at its start.
type DataFactory<'a> = Box<dyn Fn() -> Box<RunData> + Send + Sync + 'a>;

/// Which zero crossings of an event function count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// From `g < 0` to `g ≥ 0`.
    Rising,
    /// From `g > 0` to `g ≤ 0`.
    Falling,
    /// Either.
    Both,
}

impl Direction {
    /// Whether `g` going from `before` to `after` is a crossing in this
    /// direction.
    pub(crate) fn crosses<S: RealField + Copy>(self, before: S, after: S) -> bool {
        let zero = S::zero();
        let rising = before < zero && after >= zero;
        let falling = before > zero && after <= zero;
        match self {
            Self::Rising => rising,
            Self::Falling => falling,
            Self::Both => rising || falling,
        }
    }
}

/// What happens at an event.
enum Action<'a, S, const N: usize> {
    Record,
    Stop,
    /// The reset, and whether it changes the run's data (the model the
    /// run integrates is then built anew from it).
    Reset(ResetMap<'a, S, N>, bool),
}

/// A function of the state whose zero crossings are located and acted on
/// (see the [module documentation](self)).
///
/// ```
/// use lagrange_runtime::events::Event;
/// use lagrange_runtime::nalgebra::SVector;
///
/// // θ₁ passing through 0 upwards, recorded (a Poincaré section).
/// let section = Event::new("theta1 = 0", |_t, q: &SVector<f64, 2>, _qd: &SVector<f64, 2>| q[0])
///     .rising();
/// assert_eq!(section.name(), "theta1 = 0");
/// ```
pub struct Event<'a, S, const N: usize> {
    name: &'static str,
    g: Function<'a, S, N>,
    direction: Direction,
    action: Action<'a, S, N>,
}

impl<'a, S: RealField + Copy, const N: usize> Event<'a, S, N> {
    /// The event `g(t, q, q̇) = 0`, named for reports: both directions,
    /// recorded.
    pub fn new(
        name: &'static str,
        g: impl Fn(S, &SVector<S, N>, &SVector<S, N>) -> S + Send + Sync + 'a,
    ) -> Self {
        Self {
            name,
            g: Box::new(move |_, t, q, qdot| g(t, q, qdot)),
            direction: Direction::Both,
            action: Action::Record,
        }
    }

    /// An event whose `g` also reads the run's data `D` (see
    /// [`Events::keeping`]). Where the run's data is not a `D` (the events
    /// keep another type, or none), `g` is NaN, which ends the run with
    /// [`NonFiniteEvent`](crate::error::IntegrationError::NonFiniteEvent)
    /// naming the event.
    pub fn keeping<D: Any>(
        name: &'static str,
        g: impl Fn(&D, S, &SVector<S, N>, &SVector<S, N>) -> S + Send + Sync + 'a,
    ) -> Self {
        Self {
            name,
            g: Box::new(move |data, t, q, qdot| match data.downcast_ref::<D>() {
                Some(data) => g(data, t, q, qdot),
                None => S::zero() / S::zero(),
            }),
            direction: Direction::Both,
            action: Action::Record,
        }
    }

    /// As [`try_reset`](Self::try_reset), with a reset that also reads
    /// and changes the run's data `D` (see [`Events::keeping`]): state of
    /// each run, which a second run of the same events does not inherit.
    /// Where the run's data is not a `D`, the reset refuses
    /// ([`ResetFailure::Refused`]).
    ///
    /// ```
    /// use lagrange_runtime::error::{IntegrationError, ResetFailure};
    /// use lagrange_runtime::events::{Event, Events};
    /// use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1};
    /// use lagrange_runtime::prelude::*;
    /// # struct Ball;
    /// # impl Lagrangian<1> for Ball {
    /// #     type Scalar = f64;
    /// #     const COORDINATES: [&'static str; 1] = ["z"];
    /// #     fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> { SMatrix::<f64, 1, 1>::new(1.0) }
    /// #     fn forcing(&self, _t: f64, _q: &SVector<f64, 1>, _qd: &SVector<f64, 1>) -> SVector<f64, 1> { Vector1::new(-9.81) }
    /// #     fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> f64 { 0.5 * qd[0] * qd[0] }
    /// #     fn potential_energy(&self, _t: f64, q: &SVector<f64, 1>) -> f64 { 9.81 * q[0] }
    /// # }
    ///
    /// // A ball that may bounce three times on z = 0, counted per run.
    /// let floor = Event::keeping("floor", |_: &usize, _t, q: &SVector<f64, 1>, _qd: &SVector<f64, 1>| q[0])
    ///     .falling()
    ///     .try_reset_keeping(|bounces: &mut usize, _t, q, qd| {
    ///         *bounces += 1;
    ///         if *bounces > 3 {
    ///             return Err(ResetFailure::refused("a fourth bounce"));
    ///         }
    ///         Ok((*q, -0.9 * qd))
    ///     });
    /// let events = Events::new().keeping(0usize).with(floor);
    /// let drop = || Dopri5::new().integrate_with_events(
    ///     &Ball, 0.0, Vector1::new(1.0), Vector1::new(0.0), &[10.0], &events,
    /// );
    /// // Each run refuses its own fourth bounce, after three.
    /// for _ in 0..2 {
    ///     let failure = drop().unwrap_err();
    ///     assert!(matches!(failure.error, IntegrationError::ResetFailed { .. }));
    ///     assert_eq!(failure.trajectory.events().len(), 3);
    /// }
    /// // A stepper's count is read from the stepper.
    /// let mut stepper = Stepper::new(Ball, Dopri5::new(), 0.0, Vector1::new(1.0), Vector1::new(0.0))?
    ///     .with_events(&events)?;
    /// stepper.advance_to(1.0)?;
    /// assert_eq!(stepper.data::<usize>(), Some(&1));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn try_reset_keeping<D: Any>(
        mut self,
        reset: impl Fn(&mut D, S, &SVector<S, N>, &SVector<S, N>) -> Result<State<S, N>, ResetFailure>
        + Send
        + Sync
        + 'a,
    ) -> Self {
        let map: ResetMap<'a, S, N> =
            Box::new(move |data, t, q, qdot| match data.downcast_mut::<D>() {
                Some(data) => reset(data, t, q, qdot),
                None => Err(ResetFailure::refused(
                    "the run's data is not the kind this event's reset keeps",
                )),
            });
        self.action = Action::Reset(map, true);
        self
    }

    /// Only crossings from `g < 0` to `g ≥ 0`.
    pub fn rising(self) -> Self {
        self.direction(Direction::Rising)
    }

    /// Only crossings from `g > 0` to `g ≤ 0`.
    pub fn falling(self) -> Self {
        self.direction(Direction::Falling)
    }

    /// Which crossings count.
    pub fn direction(mut self, direction: Direction) -> Self {
        self.direction = direction;
        self
    }

    /// Record the crossing and go on (the default).
    pub fn record(mut self) -> Self {
        self.action = Action::Record;
        self
    }

    /// Record the crossing and end the run there.
    pub fn stop(mut self) -> Self {
        self.action = Action::Stop;
        self
    }

    /// Record the crossing, replace the state by `reset(t, q, q̇)` and
    /// restart the integration from it.
    pub fn reset(
        self,
        reset: impl Fn(S, &SVector<S, N>, &SVector<S, N>) -> (SVector<S, N>, SVector<S, N>)
        + Send
        + Sync
        + 'a,
    ) -> Self {
        self.try_reset(move |t, q, qdot| Ok(reset(t, q, qdot)))
    }

    /// As [`reset`](Self::reset), with a reset that may refuse the state
    /// at the event: a [`ResetFailure`] (for a reason of its own,
    /// [`ResetFailure::refused`]) ends the run with
    /// [`IntegrationError::ResetFailed`](crate::error::IntegrationError::ResetFailed),
    /// naming the event, at its time and state, the trajectory up to it
    /// kept in the [`Failure`](crate::error::Failure).
    ///
    /// State the closure keeps (the counter below) is the events', not a
    /// run's: every run watching these events shares it, and a second run
    /// starts where the first left it. For state of each run, see
    /// [`try_reset_keeping`](Self::try_reset_keeping).
    ///
    /// ```
    /// use lagrange_runtime::error::{IntegrationError, ResetFailure};
    /// use lagrange_runtime::events::{Event, Events};
    /// use lagrange_runtime::nalgebra::SVector;
    ///
    /// // A ball that may bounce only three times on z = 0.
    /// let bounces = std::sync::atomic::AtomicUsize::new(0);
    /// let floor = Event::new("floor", |_t, q: &SVector<f64, 1>, _qd: &SVector<f64, 1>| q[0])
    ///     .falling()
    ///     .try_reset(move |_t, q, qd| {
    ///         use std::sync::atomic::Ordering::Relaxed;
    ///         if bounces.fetch_add(1, Relaxed) == 3 {
    ///             return Err(ResetFailure::refused("a fourth bounce"));
    ///         }
    ///         Ok((*q, -0.9 * qd))
    ///     });
    /// let events = Events::new().with(floor);
    /// # let _ = events;
    /// ```
    pub fn try_reset(
        mut self,
        reset: impl Fn(
            S,
            &SVector<S, N>,
            &SVector<S, N>,
        ) -> Result<(SVector<S, N>, SVector<S, N>), ResetFailure>
        + Send
        + Sync
        + 'a,
    ) -> Self {
        self.action = Action::Reset(Box::new(move |_, t, q, qdot| reset(t, q, qdot)), false);
        self
    }

    /// The name given to [`Event::new`].
    pub fn name(&self) -> &'static str {
        self.name
    }

    /// `g` at `(t, q, q̇)`, given the run's data.
    pub(crate) fn value(&self, data: &RunData, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> S {
        (self.g)(data, t, q, qdot)
    }

    pub(crate) fn crosses(&self, before: S, after: S) -> bool {
        self.direction.crosses(before, after)
    }

    /// Whether it only records: the run goes on untouched.
    pub(crate) fn records_only(&self) -> bool {
        matches!(self.action, Action::Record)
    }

    pub(crate) fn stops(&self) -> bool {
        matches!(self.action, Action::Stop)
    }

    /// The state its reset makes of `(t, q, q̇)` (changing the run's
    /// data, for a reset that keeps some), or why it makes none; `None` if
    /// it does not reset.
    pub(crate) fn apply_reset(
        &self,
        data: &mut RunData,
        t: S,
        (q, qdot): &(SVector<S, N>, SVector<S, N>),
    ) -> Option<Result<State<S, N>, ResetFailure>> {
        match &self.action {
            Action::Reset(reset, _) => Some(reset(data, t, q, qdot)),
            _ => None,
        }
    }

    /// Whether its reset changes the run's data.
    pub(crate) fn changes_data(&self) -> bool {
        matches!(self.action, Action::Reset(_, true))
    }
}

impl<S, const N: usize> fmt::Debug for Event<'_, S, N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let action = match self.action {
            Action::Record => "record",
            Action::Stop => "stop",
            Action::Reset(..) => "reset",
        };
        f.debug_struct("Event")
            .field("name", &self.name)
            .field("direction", &self.direction)
            .field("action", &action)
            .finish()
    }
}

/// The events a run watches, and how they are searched for.
///
/// ```
/// use lagrange_runtime::events::{Event, Events};
/// use lagrange_runtime::nalgebra::SVector;
///
/// let ground = Event::new("ground", |_t, q: &SVector<f64, 1>, _qd: &SVector<f64, 1>| q[0])
///     .falling()
///     .stop();
/// let events = Events::new()
///     .with(ground)
///     .time_tolerance(1e-12)
///     .max_step(0.01);
/// assert_eq!(events.len(), 1);
/// ```
#[derive(Debug)]
pub struct Events<'a, S, const N: usize> {
    events: Vec<Event<'a, S, N>>,
    time_tolerance: Option<S>,
    min_separation: Option<S>,
    max_step: Option<S>,
    observer: Option<Observer<'a, S, N>>,
    data: Option<Factory<'a>>,
}

/// How a run's data is made, with a `Debug` that names it only.
struct Factory<'a>(DataFactory<'a>);

impl fmt::Debug for Factory<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("RunData")
    }
}

/// What an observer tells the run: go on, or stop here.
pub type Observation = core::ops::ControlFlow<()>;

/// An observer's function `(t, q, q̇) ↦ go on or stop`.
type ObserverFn<'a, S, const N: usize> =
    Box<dyn Fn(S, &SVector<S, N>, &SVector<S, N>) -> Observation + Send + Sync + 'a>;

/// An observer, with a `Debug` that names it only.
struct Observer<'a, S, const N: usize>(ObserverFn<'a, S, N>);

impl<S, const N: usize> fmt::Debug for Observer<'_, S, N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("Observer")
    }
}

impl<S: RealField + Copy, const N: usize> Default for Events<'_, S, N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<'a, S: RealField + Copy, const N: usize> Events<'a, S, N> {
    /// No events: a run that watches nothing, exactly as
    /// [`integrate`](crate::integrators::Integrator::integrate).
    pub fn new() -> Self {
        Self {
            events: Vec::new(),
            time_tolerance: None,
            min_separation: None,
            max_step: None,
            observer: None,
            data: None,
        }
    }

    /// Each run watching these events carries data of its own, a copy of
    /// `start` at the run's start, for the events made by
    /// [`Event::keeping`] to read and by [`Event::try_reset_keeping`] to
    /// change (see [the module](self#state-of-a-run)).
    pub fn keeping<D: Any + Clone + Send + Sync>(mut self, start: D) -> Self {
        self.data = Some(Factory(Box::new(move || Box::new(start.clone()))));
        self
    }

    /// A run's data at its start: `()` for events that keep none.
    pub(crate) fn fresh_data(&self) -> Box<RunData> {
        match &self.data {
            Some(make) => (make.0)(),
            None => Box::new(()),
        }
    }

    /// An observer (`Send + Sync`, like the event functions, so that a
    /// [`Stepper`](crate::stepper::Stepper) watching it can move between threads),
    /// called with `(t, q, q̇)` at the end of every accepted step (after the events located in it): a progress bar, a log, a
    /// watchdog. Returning [`Observation::Break`] stops the run cleanly
    /// there: the samples up to that time are recorded (inside the step
    /// from its interpolant), later ones are not, and
    /// [`Trajectory::interrupted`](crate::trajectory::Trajectory::interrupted) says
    /// when. A [`Stepper`](crate::stepper::Stepper) ends its call there.
    ///
    /// ```
    /// use core::ops::ControlFlow;
    /// use core::sync::atomic::{AtomicUsize, Ordering};
    /// use lagrange_runtime::prelude::*;
    /// use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1};
    /// # struct Spring;
    /// # impl Lagrangian<1> for Spring {
    /// #     type Scalar = f64;
    /// #     const COORDINATES: [&'static str; 1] = ["x"];
    /// #     fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
    /// #         SMatrix::<f64, 1, 1>::new(1.0)
    /// #     }
    /// #     fn forcing(&self, _t: f64, q: &SVector<f64, 1>, _qd: &SVector<f64, 1>) -> SVector<f64, 1> { -q }
    /// #     fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> f64 { 0.5 * qd[0] * qd[0] }
    /// #     fn potential_energy(&self, _t: f64, q: &SVector<f64, 1>) -> f64 { 0.5 * q[0] * q[0] }
    /// # }
    ///
    /// // Count the steps, and stop once t passes 2 (a budget, a cancel button).
    /// let steps = AtomicUsize::new(0);
    /// let events = Events::new().observe(|t, _q, _qdot| {
    ///     steps.fetch_add(1, Ordering::Relaxed);
    ///     if t > 2.0 { ControlFlow::Break(()) } else { ControlFlow::Continue(()) }
    /// });
    /// let times: Vec<f64> = (1..=10).map(f64::from).collect();
    /// let run = Rk4::new(0.25).integrate_with_events(&Spring, 0.0, Vector1::new(1.0), Vector1::new(0.0), &times, &events)?;
    /// assert_eq!(run.interrupted(), Some(2.25));
    /// assert_eq!(run.times(), &[1.0, 2.0]);
    /// assert_eq!(steps.load(Ordering::Relaxed), 9);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn observe(
        mut self,
        observer: impl Fn(S, &SVector<S, N>, &SVector<S, N>) -> Observation + Send + Sync + 'a,
    ) -> Self {
        self.observer = Some(Observer(Box::new(observer)));
        self
    }

    pub(crate) fn has_observer(&self) -> bool {
        self.observer.is_some()
    }

    /// Whether the observer, if any, asks to stop at `(t, q, q̇)`.
    pub(crate) fn observe_stop(&self, t: S, (q, qdot): &(SVector<S, N>, SVector<S, N>)) -> bool {
        self.observer
            .as_ref()
            .is_some_and(|o| (o.0)(t, q, qdot).is_break())
    }

    /// Adds an event; its index in [`EventRecord::index`] is the number of
    /// events added before it.
    pub fn with(mut self, event: Event<'a, S, N>) -> Self {
        self.events.push(event);
        self
    }

    /// The width of the final bracket around an event time: positive and
    /// finite. By default `4 ε max(|t|, 1)`, a few ulps of `t`; the time
    /// found is within it of the interpolant's crossing.
    pub fn time_tolerance(mut self, tolerance: S) -> Self {
        self.time_tolerance = Some(tolerance);
        self
    }

    /// The Zeno guard: a run stops with
    /// [`Zeno`](crate::error::IntegrationError::Zeno) when three gaps in a row
    /// between events are shorter than this. Non-negative and finite (zero
    /// turns the guard off). By default 1000 time tolerances, and for a
    /// fixed-step method at least four steps: events that come closer than
    /// a few steps are beyond what the step resolves.
    pub fn min_separation(mut self, separation: S) -> Self {
        self.min_separation = Some(separation);
        self
    }

    /// The longest step a method may take while these events are watched:
    /// positive and finite. Crossings inside one step are found when `g`
    /// has at most one extremum in the step (see
    /// [the module](self#crossings-inside-one-step)); a bound keeps a `g`
    /// that oscillates faster than that within reach. A fixed step is shortened to it, never lengthened; an
    /// adaptive method's last step before the final sample may be stretched
    /// by 1 % to land on it, as always.
    pub fn max_step(mut self, max_step: S) -> Self {
        self.max_step = Some(max_step);
        self
    }

    /// The number of events.
    pub fn len(&self) -> usize {
        self.events.len()
    }

    /// Whether there are no events.
    pub fn is_empty(&self) -> bool {
        self.events.is_empty()
    }

    pub(crate) fn list(&self) -> &[Event<'a, S, N>] {
        &self.events
    }

    /// The time tolerance around `t`.
    pub(crate) fn tolerance_at(&self, t: S) -> S {
        self.time_tolerance.unwrap_or_else(|| {
            nalgebra::convert::<f64, S>(4.0) * S::default_epsilon() * t.abs().max(S::one())
        })
    }

    /// The Zeno guard's separation around `t`, for a method whose steps
    /// resolve nothing shorter than `resolution` (a fixed step; zero for an
    /// adaptive method).
    pub(crate) fn separation_at(&self, t: S, resolution: S) -> S {
        self.min_separation.unwrap_or_else(|| {
            let c = nalgebra::convert::<f64, S>;
            (c(1000.0) * self.tolerance_at(t)).max(c(4.0) * resolution)
        })
    }

    pub(crate) fn max_step_bound(&self) -> Option<S> {
        self.max_step
    }

    /// The settings out of range, before any work.
    pub(crate) fn validate(&self) -> Result<(), InvalidInput<S>> {
        let bad = |setting: &'static str, value: S, requirement: &'static str| {
            Err(InvalidInput::InvalidEventSetting {
                setting,
                value,
                requirement,
            })
        };
        if let Some(tol) = self.time_tolerance {
            if !(tol.is_finite() && tol > S::zero()) {
                return bad("time_tolerance", tol, "positive and finite");
            }
        }
        if let Some(separation) = self.min_separation {
            if !(separation.is_finite() && separation >= S::zero()) {
                return bad("min_separation", separation, "non-negative and finite");
            }
        }
        if let Some(h) = self.max_step {
            if !(h.is_finite() && h > S::zero()) {
                return bad("max_step", h, "positive and finite");
            }
        }
        Ok(())
    }
}
