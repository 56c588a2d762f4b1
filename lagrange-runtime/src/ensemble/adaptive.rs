//! The adaptive ensemble: Dormand–Prince 5(4) on SIMD lanes, one step
//! shared by every lane, chosen for the lane that needs the shortest.
//!
//! Why one step for all, not one per lane: lanes stepped together must sit
//! at the same `t` (each stage evaluates every lane at once), so per-lane
//! control would take the lanes apart, lane by lane, which is the scalar
//! run again. A shared step is the smallest any lane needs: every lane
//! meets its tolerance (its error is at most the shared one), and the lanes
//! that could have taken longer steps take more than they need. Measured
//! (BENCHMARKS.md, "Ensembles in SIMD lanes"): at `1e-8` on four `f64`
//! lanes, the lanes took a fifth more steps per state than scalar `Dopri5`
//! runs (the sharing, and the steps cut at frames), for about two and a
//! half times their throughput.
//!
//! The error is each lane's own, Hairer's root mean square of the
//! estimate over `atol + rtol·max(|y|, |y_new|)`; the step is accepted when
//! the largest over the lanes is at most 1. Everything else is the scalar
//! runs' own code, not a copy of it: the loop of the embedded pairs
//! (`driver::pair::Course::walk`, which steps a run and these lanes alike:
//! the attempt, its rejection, its retry shorter where a stage fails, its
//! acceptance, the step budget per call, the underflow rule, the step-size
//! rules of [`Dopri5`]'s loop with a step that would stop within 1 % of the
//! target stretched to land on it and the state moved by exactly the step
//! the clock takes, `fl(t + h) − t`), the stage loop and the error norm of
//! the scalar pairs (`integrators::stages::fsal_step` and `Step::error`,
//! written once for scalars and lanes, over Dopri5's tableau), the growth
//! guard (each lane's, as for the fixed-step ensemble), and Hairer's first
//! step (`driver::FirstStep`, each lane's as its scalar run guesses it, the
//! smallest taken), so that every frame is reached exactly and a fix to
//! any of them reaches the lanes too. What is the lanes' own
//! (`driver::pair::Track` for them): the state, the largest of the
//! errors, the lane blamed for a failure.

use nalgebra::{ComplexField, RealField, SVector, SimdRealField, SimdValue};

use super::solve::{Element, accelerations, gather, lane_of};
use super::{EnsembleError, Guards, LaneModel, avx2_at_run_time, check_starts};
use crate::driver::FirstStep;
use crate::driver::pair::{Begun, Course, Embedded, Outcome, Track};
use crate::driver::run::{Flow, Fresh};
use crate::error::{IntegrationError, InvalidInput, NonFiniteValue};
use crate::integrators::Dopri5;
use crate::integrators::dopri5::tableau::{A, C, E};
use crate::integrators::stages::{Stages, fsal_step};
use crate::trajectory::Stats;

/// An ensemble of states stepped together in SIMD lanes by Dormand–Prince
/// 5(4) with one adaptive step for all lanes (module docs): the adaptive
/// counterpart of [`Ensemble`](super::Ensemble), frame by frame.
///
/// ```
/// use lagrange_runtime::ensemble::{AdaptiveEnsemble, AutoF64x4, LaneModel};
/// use lagrange_runtime::nalgebra::{SMatrix, SVector, SimdValue, Vector1};
/// use lagrange_runtime::Dopri5;
///
/// /// A spring of stiffness `k` and unit mass, on four lanes.
/// struct Spring {
///     k: AutoF64x4,
/// }
///
/// impl LaneModel<1> for Spring {
///     type Lanes = AutoF64x4;
///     const COORDINATES: [&'static str; 1] = ["x"];
///     fn mass_matrix_and_forcing(
///         &self,
///         _t: AutoF64x4,
///         q: &SVector<AutoF64x4, 1>,
///         _qdot: &SVector<AutoF64x4, 1>,
///     ) -> (SMatrix<AutoF64x4, 1, 1>, SVector<AutoF64x4, 1>) {
///         (SMatrix::from_element(AutoF64x4::splat(1.0)), -q * self.k)
///     }
/// }
///
/// // Four springs, stiffer lane by lane (the stiffest sets the steps).
/// let springs = Spring { k: AutoF64x4::new(1.0, 4.0, 9.0, 16.0) };
/// let starts = [Vector1::new(1.0); 4];
/// let rest = [Vector1::new(0.0); 4];
/// let method = Dopri5::new().rtol(1e-10).atol(1e-10);
/// let mut ensemble = AdaptiveEnsemble::new(springs, method, 0.0, &starts, &rest)?;
/// ensemble.advance_to(1.0)?;
/// assert_eq!(ensemble.t(), 1.0);
/// for lane in 0..4 {
///     let omega = (lane + 1) as f64;
///     // A few tolerances over one unit of time (a global error of order
///     // 1e-10 grown over at most four periods): below 1e-8.
///     assert!((ensemble.q(lane)[0] - omega.cos()).abs() < 1e-8);
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct AdaptiveEnsemble<L: LaneModel<N>, const N: usize> {
    /// The scalar pairs' loop: its step-size rules and the step they
    /// chose, Dopri5's tolerances and step budget.
    course: Course<Element<L, N>>,
    lanes: Lanes<L, N>,
}

/// The lanes as the pair loop walks them ([`Track`]): the model, the
/// state of every lane, the slopes, the growth guards.
struct Lanes<L: LaneModel<N>, const N: usize> {
    model: L,
    rtol: Element<L, N>,
    atol: Element<L, N>,
    t: Element<L, N>,
    q: SVector<L::Lanes, N>,
    qdot: SVector<L::Lanes, N>,
    /// The slopes of the last step; the first, `q̈` at `(t, q, q̇)`, is
    /// the next step's first stage (FSAL).
    k: Stages<L::Lanes, N, 7>,
    /// Dopri5's nodes in the working precision.
    c: [Element<L, N>; 7],
    /// The growth guard of every lane, as the scalar pairs' loop guards
    /// each run: a lane beyond the method's stability limit stops the
    /// ensemble with [`Unstable`](IntegrationError::Unstable).
    guards: Guards<Element<L, N>>,
    /// The lane that last set the step, blamed if it underflows.
    worst: usize,
    /// [`Fresh::Segment`] at the start and after
    /// [`set_lane`](AdaptiveEnsemble::set_lane): the first step is
    /// guessed again.
    fresh: Fresh,
    /// The steps attempted when the current call began.
    call_start: usize,
    /// The attempted step's end.
    end: (SVector<L::Lanes, N>, SVector<L::Lanes, N>),
    /// Whether to step in the copy of the loop compiled for AVX2, as
    /// [`Ensemble`](super::Ensemble) does.
    avx2: bool,
    stats: Stats,
}

impl<L: LaneModel<N>, const N: usize> AdaptiveEnsemble<L, N> {
    /// An ensemble at `t0`, lane `i` starting at `(q0[i], q̇0[i])`, stepped
    /// with `method`'s tolerances and step budget (per call of
    /// [`advance_to`](Self::advance_to), accepted and rejected steps
    /// together); checked as a run checks them. Evaluates `q̈` at the start.
    pub fn new(
        model: L,
        method: Dopri5<Element<L, N>>,
        t0: Element<L, N>,
        q0: &[SVector<Element<L, N>, N>],
        qdot0: &[SVector<Element<L, N>, N>],
    ) -> Result<Self, EnsembleError<Element<L, N>, N>> {
        let tolerances = <Dopri5<Element<L, N>> as Embedded<Element<L, N>, N>>::tolerances(&method);
        crate::driver::check_tolerances(tolerances.rtol, tolerances.atol)?;
        check_starts::<L, N>(&model, t0, q0, qdot0)?;
        let (q, qdot) = (gather(q0), gather(qdot0));
        let qddot = accelerations(&model, t0, &q, &qdot)
            .map_err(|(lane, error)| EnsembleError::Lane { lane, error })?;
        let control = <Dopri5<Element<L, N>> as Embedded<Element<L, N>, N>>::CONTROL;
        Ok(Self {
            course: Course::new(&control, tolerances),
            lanes: Lanes {
                avx2: avx2_at_run_time(),
                model,
                rtol: tolerances.rtol,
                atol: tolerances.atol,
                t: t0,
                guards: Guards::new(q0, qdot0),
                k: Stages::new(&qdot, &qddot),
                c: C.map(nalgebra::convert),
                q,
                qdot,
                worst: 0,
                fresh: Fresh::Segment,
                call_start: 0,
                end: (q, qdot),
                stats: Stats {
                    rhs_evals: 1,
                    ..Stats::default()
                },
            },
        })
    }

    /// Advances every lane to time `target` (finite, later than
    /// [`t`](Self::t)), in adaptive steps shared by all lanes, the last
    /// cut to end at `target`. On a lane's failure every lane stays where
    /// the last accepted step left them, and the error names the lane.
    ///
    /// On an x86-64 CPU with AVX2, a build without it steps in a copy of
    /// this loop compiled for AVX2, chosen at run time, as
    /// [`Ensemble::advance_to`](super::Ensemble::advance_to) does.
    pub fn advance_to(
        &mut self,
        target: Element<L, N>,
    ) -> Result<(), EnsembleError<Element<L, N>, N>> {
        #[cfg(all(target_arch = "x86_64", not(target_feature = "avx2")))]
        if self.lanes.avx2 {
            // SAFETY: `avx2` is set only where the CPU has it.
            return unsafe { self.advance_to_avx2(target) };
        }
        self.steps_to(target)
    }

    /// [`steps_to`](Self::steps_to) compiled for AVX2, with what it inlines.
    #[cfg(all(target_arch = "x86_64", not(target_feature = "avx2")))]
    #[target_feature(enable = "avx2")]
    fn advance_to_avx2(
        &mut self,
        target: Element<L, N>,
    ) -> Result<(), EnsembleError<Element<L, N>, N>> {
        self.steps_to(target)
    }

    /// The loop of [`advance_to`](Self::advance_to): the scalar pairs' own
    /// ([`Course::walk`]) on the lanes, with the largest of the lanes'
    /// errors as the step's.
    #[inline(always)]
    fn steps_to(&mut self, target: Element<L, N>) -> Result<(), EnsembleError<Element<L, N>, N>> {
        let t = self.lanes.t;
        if !(target.is_finite() && target > t) {
            return Err(InvalidInput::TargetNotAhead { t, target }.into());
        }
        let stats = &self.lanes.stats;
        self.lanes.call_start = stats.steps_accepted + stats.steps_rejected;
        self.course.walk(&mut self.lanes, target).map(|_| ())
    }

    /// Advances every lane by `dt`.
    pub fn advance(&mut self, dt: Element<L, N>) -> Result<(), EnsembleError<Element<L, N>, N>> {
        self.advance_to(self.lanes.t + dt)
    }

    /// The time of every lane's state.
    pub fn t(&self) -> Element<L, N> {
        self.lanes.t
    }

    /// Lane `lane`'s coordinates. Panics for a lane past the model's.
    pub fn q(&self, lane: usize) -> SVector<Element<L, N>, N> {
        lane_of(&self.lanes.q, lane)
    }

    /// Lane `lane`'s velocities. Panics for a lane past the model's.
    pub fn qdot(&self, lane: usize) -> SVector<Element<L, N>, N> {
        lane_of(&self.lanes.qdot, lane)
    }

    /// Every lane's coordinates and velocities, as the SIMD values they
    /// are stepped in.
    pub fn lanes(&self) -> (&SVector<L::Lanes, N>, &SVector<L::Lanes, N>) {
        (&self.lanes.q, &self.lanes.qdot)
    }

    /// Replaces lane `lane`'s state (checked as a start is), for example
    /// the lane that failed, before going on: `q̈` of every lane is
    /// evaluated again, and the next step is chosen afresh. Panics for a
    /// lane past the model's.
    pub fn set_lane(
        &mut self,
        lane: usize,
        q: SVector<Element<L, N>, N>,
        qdot: SVector<Element<L, N>, N>,
    ) -> Result<(), EnsembleError<Element<L, N>, N>> {
        assert!(lane < L::Lanes::LANES, "lane {lane} of {}", L::Lanes::LANES);
        crate::driver::finite_start(L::COORDINATES, &q, &qdot)?;
        let lanes = &mut self.lanes;
        let (mut lanes_q, mut lanes_qdot) = (lanes.q, lanes.qdot);
        for i in 0..N {
            lanes_q[i].replace(lane, q[i]);
            lanes_qdot[i].replace(lane, qdot[i]);
        }
        lanes.k.qdot[0] = lanes.slope(lanes.t, &lanes_q, &lanes_qdot)?;
        lanes.stats.rhs_evals += 1;
        (lanes.q, lanes.qdot) = (lanes_q, lanes_qdot);
        lanes.guards.restart(lane, &q, &qdot);
        lanes.fresh = Fresh::Segment;
        Ok(())
    }

    /// The step the next attempt will try (zero before the first, and
    /// after [`set_lane`](Self::set_lane)).
    pub fn step_size(&self) -> Element<L, N> {
        match self.lanes.fresh {
            Fresh::Segment => nalgebra::zero(),
            _ => self.course.control.h.unwrap_or_else(nalgebra::zero),
        }
    }

    /// The work so far: steps accepted and rejected (shared by every lane)
    /// and right-hand sides (each of every lane at once).
    pub fn stats(&self) -> &Stats {
        &self.lanes.stats
    }

    /// The model, its parameters one lane each.
    pub fn model(&self) -> &L {
        &self.lanes.model
    }
}

impl<L: LaneModel<N>, const N: usize> Lanes<L, N> {
    /// `q̈` of every lane, in the AVX2 copy where the loop runs in it.
    #[inline(always)]
    fn slope(
        &self,
        t: Element<L, N>,
        q: &SVector<L::Lanes, N>,
        qdot: &SVector<L::Lanes, N>,
    ) -> Result<SVector<L::Lanes, N>, EnsembleError<Element<L, N>, N>> {
        lanes_slope(&self.model, self.avx2, t, q, qdot)
    }
}

impl<L: LaneModel<N>, const N: usize> Track<Element<L, N>> for Lanes<L, N> {
    type Error = EnsembleError<Element<L, N>, N>;

    #[inline(always)]
    fn t(&self) -> Element<L, N> {
        self.t
    }

    #[inline(always)]
    fn fresh(&self) -> Fresh {
        self.fresh
    }

    /// Hairer's first step, the smallest over the lanes, each lane's as a
    /// scalar run guesses it ([`FirstStep`]): the probe's step `h0`, then
    /// one explicit Euler probe of all lanes at the smallest `h0`, no
    /// longer than the span to `target`. The slopes are the start's
    /// already (`new`, `set_lane`).
    #[inline(always)]
    fn begin(
        &mut self,
        _: Fresh,
        first: Option<FirstStep<Element<L, N>>>,
        target: Element<L, N>,
    ) -> Result<Begun<Element<L, N>>, Self::Error> {
        self.fresh = Fresh::No;
        let Some(guess) = first else {
            return Ok(Begun {
                h: None,
                restart: true,
            });
        };
        let span = target - self.t;
        let (q, qdot, qddot) = (self.q, self.qdot, self.k.qdot[0]);
        let lane = |x: &SVector<L::Lanes, N>, i| lane_of(x, i);
        let mut h0 = span;
        for i in 0..L::Lanes::LANES {
            h0 = h0.min(guess.probe((&lane(&q, i), &lane(&qdot, i), &lane(&qddot, i))));
        }
        let step = L::Lanes::splat(h0);
        let (q1, qdot1) = (q + qdot * step, qdot + qddot * step);
        let qddot1 = self.slope(self.t + h0, &q1, &qdot1)?;
        self.stats.rhs_evals += 1;
        let mut h = span;
        for i in 0..L::Lanes::LANES {
            let at = (&lane(&q, i), &lane(&qdot, i), &lane(&qddot, i));
            h = h.min(guess.step(h0, at, (&lane(&qdot1, i), &lane(&qddot1, i))));
        }
        Ok(Begun {
            h: Some(guess.finish(h0, span, h)),
            restart: true,
        })
    }

    #[inline(always)]
    fn bound_step(&self, h: Element<L, N>) -> Element<L, N> {
        h
    }

    #[inline(always)]
    fn attempts_this_call(&self) -> usize {
        self.stats.steps_accepted + self.stats.steps_rejected - self.call_start
    }

    /// Every lane meets it at once: reported for lane 0.
    fn too_many_steps(&self, max_steps: usize) -> Self::Error {
        let (t, q, qdot) = (self.t, lane_of(&self.q, 0), lane_of(&self.qdot, 0));
        let error = IntegrationError::TooManySteps {
            t,
            max_steps,
            q,
            qdot,
        };
        EnsembleError::Lane { lane: 0, error }
    }

    /// Reported for the lane that last set the step.
    fn underflow(&self, h: Element<L, N>) -> Self::Error {
        let lane = self.worst;
        let (t, q, qdot) = (self.t, lane_of(&self.q, lane), lane_of(&self.qdot, lane));
        let error = IntegrationError::StepSizeUnderflow { t, h, q, qdot };
        EnsembleError::Lane { lane, error }
    }

    /// One Dormand–Prince step of `h` from `t` to `t_new`, by the scalar
    /// pairs' own stage loop ([`fsal_step`], over Dopri5's tableau): the
    /// new state (its `q̈`, the last stage, left in the stages as the next
    /// step's first) and each lane's error over its tolerance (the scalar
    /// pairs' norm, `Step::error`), the largest the step's. A lane that
    /// cannot be evaluated at a stage, or whose error is not finite, fails
    /// the attempt, which the loop retries shorter.
    #[inline(always)]
    fn attempt(
        &mut self,
        times: (Element<L, N>, Element<L, N>, Element<L, N>),
    ) -> Result<Outcome<Element<L, N>, ()>, Self::Error> {
        let (model, avx2, stats) = (&self.model, self.avx2, &mut self.stats);
        let mut slope = |t, q: &SVector<L::Lanes, N>, qdot: &SVector<L::Lanes, N>| {
            stats.rhs_evals += 1;
            lanes_slope(model, avx2, t, q, qdot)
        };
        let state = (&self.q, &self.qdot);
        let step = fsal_step(&mut slope, times, state, &mut self.k, &A, &self.c, &E)?;
        let errors = step.error((self.rtol, self.atol), &self.q, &self.qdot);
        let (err, worst) = largest(errors);
        if !err.is_finite() {
            let (q, qdot) = (lane_of(&step.q, worst), lane_of(&step.qdot, worst));
            let value = NonFiniteValue::State;
            let t = times.1;
            let error = IntegrationError::NonFiniteState { t, q, qdot, value };
            return Err(EnsembleError::Lane { lane: worst, error });
        }
        self.worst = worst;
        self.end = (step.q, step.qdot);
        Ok(if err <= nalgebra::one() {
            Outcome::Accepted { step: (), err }
        } else {
            Outcome::Rejected { err }
        })
    }

    #[inline(always)]
    fn count(&mut self, accepted: bool) {
        if accepted {
            self.stats.steps_accepted += 1;
        } else {
            self.stats.steps_rejected += 1;
        }
    }

    /// Each lane's growth judged, as the scalar pairs' loop judges a run's.
    #[inline(always)]
    fn end(
        &mut self,
        (_, t_new, h): (Element<L, N>, Element<L, N>, Element<L, N>),
    ) -> Result<(), Self::Error> {
        let (before, after) = ((&self.q, &self.qdot), (&self.end.0, &self.end.1));
        self.guards.judge(before, after, t_new, (h, h))
    }

    #[inline(always)]
    fn take(
        &mut self,
        (_, t_new, _): (Element<L, N>, Element<L, N>, Element<L, N>),
        _: Element<L, N>,
    ) -> Result<Flow, Self::Error> {
        (self.t, self.q, self.qdot) = (t_new, self.end.0, self.end.1);
        self.k.first_same_as_last(6);
        Ok(Flow::Go)
    }
}

/// `q̈` of every lane of `model`, in the AVX2 copy where the loop runs in
/// it.
#[inline(always)]
fn lanes_slope<L: LaneModel<N>, const N: usize>(
    model: &L,
    avx2: bool,
    t: Element<L, N>,
    q: &SVector<L::Lanes, N>,
    qdot: &SVector<L::Lanes, N>,
) -> Result<SVector<L::Lanes, N>, EnsembleError<Element<L, N>, N>> {
    #[cfg(all(target_arch = "x86_64", not(target_feature = "avx2")))]
    if avx2 {
        // SAFETY: `avx2` is set only where the CPU has it.
        return unsafe { super::solve::accelerations_avx2(model, t, q, qdot) }
            .map_err(|(lane, error)| EnsembleError::Lane { lane, error });
    }
    let _ = avx2;
    accelerations(model, t, q, qdot).map_err(|(lane, error)| EnsembleError::Lane { lane, error })
}

/// The largest of the lanes' errors (NaN if any is), and its lane.
fn largest<V: SimdRealField + Copy>(errors: V) -> (V::Element, usize)
where
    V::Element: RealField + Copy,
{
    let mut worst = (errors.extract(0), 0);
    for lane in 0..V::LANES {
        let e = errors.extract(lane);
        if !e.is_finite() {
            return (e, lane);
        }
        if e > worst.0 {
            worst = (e, lane);
        }
    }
    worst
}
