//! A model advanced frame by frame: the [`Stepper`], for games, control
//! loops and anything else that moves a state forward in small pieces
//! between other work.
//!
//! [`Integrator::integrate`](crate::integrators::Integrator::integrate) is a whole run:
//! it validates, picks an initial step, allocates a trajectory and returns
//! it. Called once per frame it does all of that per frame, and an adaptive
//! method starts every frame from a fresh step-size guess. A [`Stepper`]
//! does that work once, in [`Stepper::new`]; then each
//! [`advance`](Stepper::advance) or [`advance_to`](Stepper::advance_to)
//! moves the state it owns to the next time:
//!
//! - **No allocation** per call: the state, the method's slopes and its
//!   step-size control live in the stepper (a counting global allocator
//!   checks this over 10⁶ steps in the runtime's tests; watching events
//!   allocates nothing per step either, and a located crossing allocates
//!   its few small working vectors).
//! - **One loop**: a stepper runs the very loop `integrate` runs for its
//!   kind of method (`driver/run.rs`), each call an advance to the frame's
//!   time where `integrate` is one advance through the samples.
//! - **The step size is kept** between calls by the adaptive methods
//!   ([`Bs3`], [`Dopri5`], [`Tsit5`], [`Dop853`], [`Radau5`], with its
//!   Jacobian and LU factors): a frame shorter than the step the error control wants is one
//!   shortened step that lands on the frame time, and the next frame starts
//!   again from the step the control had chosen.
//!   Fixed-step methods cut each frame into the fewest equal steps no longer
//!   than `h`, as [`integrate`](crate::integrators::Integrator::integrate) cuts the
//!   intervals between samples: `h` is never lengthened.
//! - **The model is the caller's between calls**:
//!   [`model_mut`](Stepper::model_mut) changes parameters or inputs,
//!   [`set_state`](Stepper::set_state) moves the state (a respawn, a
//!   teleport); the method's slopes are recomputed from the new model or
//!   state on the next call, nothing stale is reused.
//! - **Any scalar**: `f32` as well as `f64`, with the method's tolerances in
//!   that scalar. An `f32` clock loses resolution as it grows (`1.2e-4 s`
//!   per ulp at `t = 2000 s`); [`set_time`](Stepper::set_time) keeps it
//!   small for a model that does not depend on `t`.
//! - **Events** ([`with_events`](Stepper::with_events)): the same
//!   [`Events`] as `integrate_with_events`, located on each step's
//!   interpolant; [`events`](Stepper::events) lists those of the last call,
//!   a stop ends the call at the event, a reset replaces the state and the
//!   call goes on from it as `integrate` does, as from a new start (an
//!   adaptive method guesses its first step again).
//! - **Failures are typed**: an [`IntegrationError`] with `t` and the state
//!   where it happened. The stepper keeps the last good state (the end of
//!   the last step that succeeded) and can be advanced again, for instance
//!   after the caller changed the model.
//!
//! Every method steps ([`StepMethod`]): the fixed-step ones
//! ([`ExplicitEuler`], [`SymplecticEuler`], [`Rk4`], [`ImplicitMidpoint`],
//! [`GaussLegendre`], [`Variational`]; the implicit ones' workspace and the
//! variational step's history allocated in [`Stepper::new`]), the
//! adaptive ones ([`Bs3`], [`Dopri5`], [`Tsit5`], [`Dop853`], [`Radau5`], whose `O(N²)`
//! workspace is allocated there too), and [`AnyIntegrator`], any of them
//! chosen at run time. The variational step's state between frames is
//! `(q, p)`: its `q̇` is worked out at each frame's end (one conversion,
//! counted in `rhs_evals`).
//!
//! Constrained models are kept on their constraints after each step, as in
//! `integrate` (the model's drift control; see
//! [`constraints`](crate::constraints)).
//!
//! ```
//! use lagrange_runtime::prelude::*;
//! use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1};
//!
//! /// A unit mass on a spring of stiffness `k`: `x(t) = cos(√k t)`.
//! struct Spring { k: f64 }
//!
//! impl Lagrangian<1> for Spring {
//!     type Scalar = f64;
//!     const COORDINATES: [&'static str; 1] = ["x"];
//!     fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
//!         SMatrix::<f64, 1, 1>::new(1.0)
//!     }
//!     fn forcing(&self, _t: f64, q: &SVector<f64, 1>, _qd: &SVector<f64, 1>) -> SVector<f64, 1> {
//!         -q * self.k
//!     }
//!     fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> f64 {
//!         0.5 * qd[0] * qd[0]
//!     }
//!     fn potential_energy(&self, _t: f64, q: &SVector<f64, 1>) -> f64 {
//!         0.5 * self.k * q[0] * q[0]
//!     }
//! }
//!
//! let method = Dopri5::new().rtol(1e-10).atol(1e-10);
//! let mut stepper = Stepper::new(Spring { k: 1.0 }, method, 0.0, Vector1::new(1.0), Vector1::new(0.0))?;
//! for _frame in 0..60 {
//!     stepper.advance(1.0 / 60.0)?;
//! }
//! assert!((stepper.t() - 1.0).abs() < 1e-12);
//! assert!((stepper.q()[0] - 1f64.cos()).abs() < 1e-8);
//!
//! // Stiffen the spring between frames: the next frame uses it.
//! stepper.model_mut().k = 4.0;
//! stepper.advance(1.0 / 60.0)?;
//! # Ok::<(), lagrange_runtime::IntegrationError<f64, 1>>(())
//! ```
//!
//! [`Bs3`]: crate::integrators::Bs3
//! [`Dopri5`]: crate::integrators::Dopri5
//! [`Tsit5`]: crate::integrators::Tsit5
//! [`Dop853`]: crate::integrators::Dop853
//! [`ExplicitEuler`]: crate::integrators::ExplicitEuler
//! [`SymplecticEuler`]: crate::integrators::SymplecticEuler
//! [`Rk4`]: crate::integrators::Rk4
//! [`ImplicitMidpoint`]: crate::integrators::ImplicitMidpoint
//! [`GaussLegendre`]: crate::integrators::GaussLegendre
//! [`Radau5`]: crate::integrators::Radau5
//! [`Variational`]: crate::integrators::Variational
//! [`AnyIntegrator`]: crate::integrators::AnyIntegrator
//! [`StepMethod`]: crate::integrators::StepMethod

use nalgebra::{ComplexField, SVector};

use crate::driver::Recorder;
use crate::driver::run::{Advanced, Fresh, Run, Walk};
use crate::error::{IntegrationError, InvalidInput};
use crate::events::{Events, RunData};
use crate::integrators::StepMethod;
use crate::model::Lagrangian;
use crate::trajectory::{EventRecord, Stats};

/// A model, a method and a state, advanced by the caller a piece at a time
/// without allocating; see [the module](self). `'e` is the lifetime of the
/// [events](Stepper::with_events) it watches, if any.
pub struct Stepper<'e, L, M, const N: usize>
where
    L: Lagrangian<N>,
    M: StepMethod<L::Scalar>,
{
    model: L,
    walker: M::Walker<N>,
    run: Run<'e, L::Scalar, N>,
    /// For events that keep data (a contact scene's modes): the model the
    /// run goes on with after a reset changed the data, built from the
    /// last one and the data.
    segment: Option<SegmentModel<L>>,
}

/// How a stepper's model is built anew from the run's data.
pub(crate) type SegmentModel<L> = fn(&L, &RunData) -> Option<L>;

impl<'e, L, M, const N: usize> Stepper<'e, L, M, N>
where
    L: Lagrangian<N>,
    M: StepMethod<L::Scalar>,
{
    /// A stepper at `(t0, q0, q̇0)`. The start and the method's settings are
    /// checked here, as `integrate` checks them
    /// ([`InvalidInput`] in the error), and a
    /// constrained model's start is brought onto its constraints (or
    /// refused) as its settings say.
    pub fn new(
        model: L,
        method: M,
        t0: L::Scalar,
        q0: SVector<L::Scalar, N>,
        qdot0: SVector<L::Scalar, N>,
    ) -> Result<Self, IntegrationError<L::Scalar, N>> {
        let walker = method.walker::<N>()?;
        let (rec, (q, qdot)) =
            Recorder::start(&model, t0, &q0, &qdot0, Default::default()).map_err(|f| f.error)?;
        let run = Run {
            t: t0,
            q,
            qdot,
            call_start: (rec.stats.steps_accepted, rec.stats.steps_rejected),
            rec,
            fresh: Fresh::Segment,
        };
        Ok(Self {
            model,
            walker,
            run,
            segment: None,
        })
    }

    /// Watches `events` from now on: each call locates, records and acts
    /// on the crossings in it as `integrate_with_events` does (see
    /// [`events`](crate::events)); [`events`](Self::events) lists those of
    /// the last call. A **stop** ends the call early, at the event, the
    /// stepper's state the event's, and the next call goes on from there;
    /// a **reset** replaces the state and the call goes on to its target
    /// as from a new start, as in `integrate`. The events' settings are
    /// checked here
    /// ([`InvalidEventSetting`](InvalidInput::InvalidEventSetting)), and
    /// their values taken at the current state: an event already at zero
    /// is not armed.
    pub fn with_events(
        mut self,
        events: &'e Events<'e, L::Scalar, N>,
    ) -> Result<Self, IntegrationError<L::Scalar, N>> {
        events.validate()?;
        self.run.rec.watch_events(events);
        self.changed();
        Ok(self)
    }

    /// The events that happened during the last call, in time order.
    pub fn events(&self) -> &[EventRecord<L::Scalar, N>] {
        self.run.rec.events_so_far().0
    }

    /// The event that stopped the last call before its target, if one did.
    pub fn stopped(&self) -> Option<&EventRecord<L::Scalar, N>> {
        self.run.rec.events_so_far().1
    }

    /// Whether the [observer](Events::observe) stopped the last call
    /// before its target (the stepper then at the end of that step).
    pub fn interrupted(&self) -> bool {
        self.run.rec.interrupted()
    }

    /// Advances the state by `dt`: to `t + dt`, which must be later than
    /// `t` ([`TargetNotAhead`](InvalidInput::TargetNotAhead) for a `dt`
    /// that is not positive, not finite, or too small to change `t`).
    pub fn advance(&mut self, dt: L::Scalar) -> Result<(), IntegrationError<L::Scalar, N>> {
        self.advance_to(self.run.t + dt)
    }

    /// Advances the state to time `target` (finite, later than
    /// [`t`](Self::t)).
    pub fn advance_to(&mut self, target: L::Scalar) -> Result<(), IntegrationError<L::Scalar, N>> {
        let t = self.run.t;
        if !(target.is_finite() && target > t) {
            return Err(InvalidInput::TargetNotAhead { t, target }.into());
        }
        self.run.rec.forget_events();
        self.run.begin_call();
        loop {
            let advanced = self.walker.advance(&mut self.run, &self.model, target);
            if self.run.rec.take_changed() {
                if let Some(model) = self
                    .segment
                    .and_then(|segment| segment(&self.model, self.run.rec.data()))
                {
                    self.model = model;
                }
            }
            if advanced? != Advanced::Rebuild {
                return Ok(());
            }
        }
    }

    /// Builds the model anew with `segment` each time a reset of the
    /// watched events changes the run's data (`Events::keeping`).
    pub(crate) fn with_segments(mut self, segment: SegmentModel<L>) -> Self {
        self.segment = Some(segment);
        self
    }

    /// The data of this stepper's run that its events keep
    /// ([`Events::keeping`]), if it is a `D`: where the last call left it.
    pub fn data<D: core::any::Any>(&self) -> Option<&D> {
        self.run.rec.data().downcast_ref::<D>()
    }

    /// The caller changed the model, the state, the clock or the events:
    /// the method's carried slopes and the events' values are taken anew
    /// before the next step (a start still to come stays one).
    fn changed(&mut self) {
        if self.run.fresh == Fresh::No {
            self.run.fresh = Fresh::Slopes;
        }
    }

    /// The time of the state.
    pub fn t(&self) -> L::Scalar {
        self.run.t
    }

    /// The coordinates `q`.
    pub fn q(&self) -> &SVector<L::Scalar, N> {
        &self.run.q
    }

    /// The velocities `q̇`.
    pub fn qdot(&self) -> &SVector<L::Scalar, N> {
        &self.run.qdot
    }

    /// Moves the state (a respawn, a teleport, an impact handled by the
    /// caller). Validated as a start is; the method's carried slopes are
    /// dropped, an adaptive method keeps its step size.
    pub fn set_state(
        &mut self,
        q: SVector<L::Scalar, N>,
        qdot: SVector<L::Scalar, N>,
    ) -> Result<(), IntegrationError<L::Scalar, N>> {
        let t = self.run.t;
        let stats = self.run.rec.stats;
        let (mut rec, (q, qdot)) =
            Recorder::start(&self.model, t, &q, &qdot, Default::default()).map_err(|f| f.error)?;
        rec.stats = stats;
        rec.put_watch(self.run.rec.take_watch());
        self.run.rec = rec;
        (self.run.q, self.run.qdot) = (q, qdot);
        self.changed();
        Ok(())
    }

    /// Moves the clock to `t` (finite), keeping the state: for a model that
    /// does not depend on `t` explicitly, a long-running scene can keep its
    /// clock small, where an `f32` clock keeps its resolution (at
    /// `t = 2000 s` an `f32` step of `t` is `1.2e-4 s`, and a step that no
    /// longer moves `t` is a
    /// [`StepSizeUnderflow`](IntegrationError::StepSizeUnderflow)). The
    /// carried slopes are dropped, as after [`set_state`](Self::set_state).
    pub fn set_time(&mut self, t: L::Scalar) -> Result<(), IntegrationError<L::Scalar, N>> {
        if !t.is_finite() {
            return Err(InvalidInput::NonFiniteStartTime { t0: t }.into());
        }
        self.run.t = t;
        self.changed();
        Ok(())
    }

    /// The model.
    pub fn model(&self) -> &L {
        &self.model
    }

    /// The model, to change its parameters or inputs before the next call;
    /// the method's carried slopes are recomputed from it.
    pub fn model_mut(&mut self) -> &mut L {
        self.changed();
        &mut self.model
    }

    /// The work done so far: steps, rejected steps, right-hand sides, and
    /// for a constrained model the residuals seen (as in
    /// [`Trajectory::stats`](crate::trajectory::Trajectory::stats)).
    pub fn stats(&self) -> Stats {
        self.run.rec.stats
    }
}
