//! Ensembles in SIMD lanes: one model evaluated for four or eight states
//! at once, each state in a lane of a SIMD value, stepped together by a
//! fixed-step method.
//!
//! `lagrangian!` writes every model's `M` and `f` for any
//! `SimdRealField` scalar, nalgebra's SIMD scalars included: a
//! `DoublePendulum<AutoF64x4>` holds four sets of parameters and evaluates
//! `M` and `f` for four states in one pass, lane by lane, without a
//! branch. An [`Ensemble`] steps such a model the way a
//! [`Stepper`](crate::stepper::Stepper) steps a scalar one: frame by
//! frame, every interval cut into the fewest equal steps no longer than
//! `h`, with [`ExplicitEuler`](crate::ExplicitEuler),
//! [`SymplecticEuler`](crate::SymplecticEuler) or [`Rk4`](crate::Rk4).
//!
//! **Each lane's values are its scalar run's, bit for bit**: the same
//! arithmetic in the same order on every lane (the sines and cosines from
//! the same kernel, `M` factored by the same row form, or the same
//! recursion over a tree of links for a model that has one, the same
//! step, taken by the same loop: the fixed-step loop of the runs,
//! `driver::fixed::Course::walk`, walks the lanes as it walks a run), so
//! that a lane of an ensemble is a `Stepper` of the same model, method and
//! start, under the same target features (`tests/trajectories/ensemble.rs`
//! compares them). A lane whose mass matrix the fast path cannot take as
//! the scalar solve would (not positive definite, ill-conditioned, not
//! finite) is solved again alone by the scalar solve: its answer (LU where
//! Cholesky refused `M`) or its error.
//!
//! What it takes: a model in minimal coordinates without inputs or
//! contacts ([`LaneModel`], which `lagrangian!` implements for exactly
//! those; a constrained model's `M q̈ = f` is not its dynamics, and it has
//! none), and a fixed-step explicit method ([`LaneStep`]).
//!
//! **Adaptive steps**: an [`AdaptiveEnsemble`] steps the lanes by
//! Dormand–Prince 5(4) with [`Dopri5`](crate::Dopri5)'s tolerances and one
//! step shared by every lane, the shortest any lane needs: each lane meets
//! its tolerance, and the easier lanes take more steps than they would
//! alone. Control per lane would take the lanes apart (each stage
//! evaluates every lane at one time); the steps the sharing costs are
//! measured in `BENCHMARKS.md`, "Ensembles in SIMD lanes". Its lanes are
//! not their scalar runs' bits: the steps differ.
//!
//! Failures are typed and say which lane: [`EnsembleError::Lane`] holds the
//! lane's [`IntegrationError`] as its scalar run would report it (at which
//! `t`, in which state). All lanes stop together at the last step they
//! all completed: [`t`](Ensemble::t), [`q`](Ensemble::q) and
//! [`qdot`](Ensemble::qdot) are there, nothing computed before is lost, and
//! [`set_lane`](Ensemble::set_lane) replaces the lane that failed before
//! going on. The runs' growth guard watches every lane, in both ensembles:
//! a lane beyond its method's stability limit stops them with its
//! [`Unstable`](IntegrationError::Unstable).
//! One check differs from a `Stepper`'s: a parameter that is not finite is
//! not refused up front (a lane model has no such check); it shows as its
//! lane's `M` or `f` not finite, at the first step.
//!
//! Speed: four `f64` or eight `f32` lanes fill an AVX2 register. On an
//! x86-64 CPU with AVX2, a build without it (the default target) steps the
//! lanes in a copy of its loop and of the slope compiled for AVX2, chosen
//! at run time ([`advance_to`](Ensemble::advance_to)); built with
//! `-C target-cpu=native`, everything is. `BENCHMARKS.md`, "Ensembles in
//! SIMD lanes", has the throughput over scalar steppers, 2.8–4.2× per core
//! for the double pendulum and the 5-link chain (`cargo bench -p
//! lagrange-studies --bench ensemble`).
//!
//! ```
//! use lagrange_runtime::ensemble::{AutoF64x4, Ensemble, LaneModel};
//! use lagrange_runtime::nalgebra::{SMatrix, SVector, SimdValue, Vector1};
//! use lagrange_runtime::Rk4;
//!
//! /// A spring of stiffness `k` and unit mass, on any scalar or lanes.
//! struct Spring<S> {
//!     k: S,
//! }
//!
//! impl LaneModel<1> for Spring<AutoF64x4> {
//!     type Lanes = AutoF64x4;
//!     const COORDINATES: [&'static str; 1] = ["x"];
//!     fn mass_matrix_and_forcing(
//!         &self,
//!         _t: AutoF64x4,
//!         q: &SVector<AutoF64x4, 1>,
//!         _qdot: &SVector<AutoF64x4, 1>,
//!     ) -> (SMatrix<AutoF64x4, 1, 1>, SVector<AutoF64x4, 1>) {
//!         (SMatrix::from_element(AutoF64x4::splat(1.0)), -q * self.k)
//!     }
//! }
//!
//! // Four springs, stiffer lane by lane, all released from x = 1.
//! let springs = Spring { k: AutoF64x4::new(1.0, 2.0, 3.0, 4.0) };
//! let starts = [Vector1::new(1.0); 4];
//! let rest = [Vector1::new(0.0); 4];
//! let mut ensemble = Ensemble::new(springs, Rk4::new(1e-3), 0.0, &starts, &rest)?;
//! ensemble.advance_to(1.0)?;
//! for lane in 0..4 {
//!     let omega = ((lane + 1) as f64).sqrt();
//!     // RK4's global error at h = 1e-3 over one unit of time: below 1e-10.
//!     assert!((ensemble.q(lane)[0] - omega.cos()).abs() < 1e-10);
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod adaptive;
mod solve;

use nalgebra::{ComplexField, RealField, SMatrix, SVector, SimdBool, SimdRealField, SimdValue};

use crate::driver::fixed::{Course, Track};
use crate::driver::run::{Flow, Fresh};
use crate::driver::{GrowthGuard, finite_start, measure};
use crate::error::{IntegrationError, InvalidInput, NonFiniteValue};
use crate::integrators::LaneStep;
use crate::linalg::finite_lanes;
use crate::trajectory::Stats;
use solve::{Element, accelerations, gather, lane_of};

pub use adaptive::AdaptiveEnsemble;
pub use simba::simd::{AutoF32x4, AutoF32x8, AutoF64x2, AutoF64x4, AutoF64x8, AutoSimd};

/// A model whose `M` and `f` are evaluated on SIMD lanes: the contract of
/// an [`Ensemble`]. `lagrangian!` implements it for every model in minimal
/// coordinates without inputs or contacts, on any `SimdRealField` scalar
/// (`Model<AutoF64x4>`: four lanes of `f64`).
pub trait LaneModel<const N: usize> {
    /// The lanes: a SIMD value of `f64` or `f32` (nalgebra's
    /// `SimdRealField`, e.g. [`AutoF64x4`]), or a scalar (one lane).
    type Lanes: SimdRealField<Element: RealField + Copy> + Copy;

    /// Names of the coordinates, in the order of `q`.
    const COORDINATES: [&'static str; N];

    /// `M` and `f` of every lane at `(t, q, q̇)`.
    fn mass_matrix_and_forcing(
        &self,
        t: Self::Lanes,
        q: &SVector<Self::Lanes, N>,
        qdot: &SVector<Self::Lanes, N>,
    ) -> (SMatrix<Self::Lanes, N, N>, SVector<Self::Lanes, N>);

    /// Whether [`accelerations`](Self::accelerations) answers: only then is
    /// it asked.
    const SOLVES_ACCELERATIONS: bool = false;

    /// `q̈` of every lane solved by the model itself, as its scalar
    /// [`Lagrangian::accelerations`](crate::model::Lagrangian::accelerations)
    /// does (a model whose masses hang on a tree of links: the recursion of
    /// [`linalg::articulated`](crate::linalg::articulated)), with the lanes
    /// it answers for; the others are solved with `M`. `None` (the
    /// default): every lane is.
    #[allow(clippy::type_complexity)]
    fn accelerations(
        &self,
        t: Self::Lanes,
        q: &SVector<Self::Lanes, N>,
        qdot: &SVector<Self::Lanes, N>,
    ) -> Option<(
        SVector<Self::Lanes, N>,
        <Self::Lanes as nalgebra::SimdValue>::SimdBool,
    )> {
        let _ = (t, q, qdot);
        None
    }
}

/// A start of every lane, as a `Stepper` checks its own: as many states as
/// lanes, `t0` finite, each state finite; and a model whose
/// `accelerations` answer without its flag refused, as a scalar run
/// refuses one ([`InvalidInput::AccelerationsNotFlagged`]).
pub(super) fn check_starts<L: LaneModel<N>, const N: usize>(
    model: &L,
    t0: Element<L, N>,
    q0: &[SVector<Element<L, N>, N>],
    qdot0: &[SVector<Element<L, N>, N>],
) -> Result<(), EnsembleError<Element<L, N>, N>> {
    let lanes = L::Lanes::LANES;
    for given in [q0.len(), qdot0.len()] {
        if given != lanes {
            return Err(EnsembleError::LaneCount { lanes, given });
        }
    }
    if !t0.is_finite() {
        return Err(InvalidInput::NonFiniteStartTime { t0 }.into());
    }
    for (lane, (q, qdot)) in q0.iter().zip(qdot0).enumerate() {
        finite_start(L::COORDINATES, q, qdot).map_err(|input| EnsembleError::Lane {
            lane,
            error: input.into(),
        })?;
    }
    if !L::SOLVES_ACCELERATIONS
        && model
            .accelerations(L::Lanes::splat(t0), &gather(q0), &gather(qdot0))
            .is_some()
    {
        return Err(InvalidInput::AccelerationsNotFlagged.into());
    }
    Ok(())
}

/// The growth guard of every lane: the guard of the runs (`driver/growth.rs`),
/// one per lane, judging each step of the lanes as it judges a run's.
pub(super) struct Guards<S> {
    growth: Vec<GrowthGuard<S>>,
    /// The guards before a step, restored if a lane stops it.
    spare: Vec<GrowthGuard<S>>,
}

impl<S: RealField + Copy> Guards<S> {
    pub(super) fn new<const N: usize>(q0: &[SVector<S, N>], qdot0: &[SVector<S, N>]) -> Self {
        let growth: Vec<_> = q0
            .iter()
            .zip(qdot0)
            .map(|(q, v)| GrowthGuard::new(q, v))
            .collect();
        Self {
            spare: growth.clone(),
            growth,
        }
    }

    /// Lane `lane` starts again from `(q, q̇)`.
    pub(super) fn restart<const N: usize>(
        &mut self,
        lane: usize,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) {
        self.growth[lane] = GrowthGuard::new(q, qdot);
    }

    /// A step of the lanes from `before` to `after`, of length `dt`
    /// (`h` the step asked for, which an error reports), judged lane by
    /// lane in lane order as the runs judge theirs: a lane whose state is
    /// not finite, or that grows beyond its method's stability limit
    /// ([`Unstable`](IntegrationError::Unstable)), stops the step with its
    /// error, the guards as they were before it.
    #[inline(always)]
    #[allow(clippy::type_complexity)]
    pub(super) fn judge<V, const N: usize>(
        &mut self,
        before: (&SVector<V, N>, &SVector<V, N>),
        (q, qdot): (&SVector<V, N>, &SVector<V, N>),
        t_next: S,
        (h, dt): (S, S),
    ) -> Result<(), EnsembleError<S, N>>
    where
        V: SimdRealField<Element = S> + Copy,
    {
        let finite = finite_lanes(&[q.as_slice(), qdot.as_slice()]);
        let step = measure(before, (q, qdot), V::splat(dt));
        let mut last = step.size;
        for (lane, growth) in self.growth.iter().enumerate() {
            last.replace(lane, growth.last());
        }
        let unresolved = step.unresolved(last);
        self.spare.clone_from_slice(&self.growth);
        for (lane, growth) in self.growth.iter_mut().enumerate() {
            let error = if finite.bitmask() & (1 << lane) == 0 {
                let (q, qdot) = (lane_of(q, lane), lane_of(qdot, lane));
                let value = NonFiniteValue::State;
                Some(IntegrationError::NonFiniteState {
                    t: t_next,
                    q,
                    qdot,
                    value,
                })
            } else {
                let size = step.size.extract(lane);
                let unresolved = unresolved.extract(lane);
                growth.judge_unresolved(size, unresolved).map(|steps| {
                    let (q, qdot) = (lane_of(q, lane), lane_of(qdot, lane));
                    IntegrationError::Unstable {
                        t: t_next,
                        h,
                        steps,
                        q,
                        qdot,
                    }
                })
            };
            if let Some(error) = error {
                self.growth.clone_from_slice(&self.spare);
                return Err(EnsembleError::Lane { lane, error });
            }
        }
        Ok(())
    }
}

/// Whether to step in the copies of the loops compiled for AVX2: the CPU
/// has it and the build does not.
pub(super) fn avx2_at_run_time() -> bool {
    #[cfg(all(target_arch = "x86_64", not(target_feature = "avx2")))]
    return std::is_x86_feature_detected!("avx2");
    #[cfg(not(all(target_arch = "x86_64", not(target_feature = "avx2"))))]
    false
}

/// What an [`Ensemble`] could not do, and for which lane.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum EnsembleError<S: RealField + Copy, const N: usize> {
    /// The method's settings or the call, refused before any step (a step
    /// size that is not positive, a target not ahead, a start time that is
    /// not finite).
    #[error(transparent)]
    InvalidInput(#[from] InvalidInput<S>),
    /// The ensemble was given a number of start states other than its
    /// number of lanes.
    #[error("{given} start states given for {lanes} lanes")]
    LaneCount {
        /// Lanes of the model's SIMD type.
        lanes: usize,
        /// States given.
        given: usize,
    },
    /// A lane's run failed, as its scalar run would have: the error holds
    /// the time and that lane's state. Every lane stops at the last step
    /// all of them completed. An error every lane meets at once (the step
    /// budget, a step too short to advance `t`) is reported for lane 0.
    #[error("lane {lane}: {error}")]
    Lane {
        /// The lane, from 0.
        lane: usize,
        /// What happened to it.
        error: IntegrationError<S, N>,
    },
}

/// An ensemble of states stepped together in SIMD lanes, frame by frame,
/// by a fixed-step method: the lane-wise [`Stepper`](crate::stepper::Stepper)
/// (module docs).
pub struct Ensemble<L: LaneModel<N>, M, const N: usize> {
    /// The fixed-step loop of the runs: the step, the budget.
    course: Course<Element<L, N>>,
    lanes: Lanes<L, M, N>,
}

/// The lanes as the fixed-step loop walks them ([`Track`]).
struct Lanes<L: LaneModel<N>, M, const N: usize> {
    model: L,
    method: M,
    t: Element<L, N>,
    q: SVector<L::Lanes, N>,
    qdot: SVector<L::Lanes, N>,
    guards: Guards<Element<L, N>>,
    /// The steps taken when the current call began.
    call_start: usize,
    /// The step's end.
    end: (SVector<L::Lanes, N>, SVector<L::Lanes, N>),
    /// Whether to step in the copy of the loop compiled for AVX2: the CPU
    /// has it and the build does not (see
    /// [`advance_to`](Ensemble::advance_to)).
    avx2: bool,
    stats: Stats,
}

impl<L, M, const N: usize> Ensemble<L, M, N>
where
    L: LaneModel<N>,
    M: LaneStep<Element<L, N>>,
{
    /// An ensemble at `t0`, lane `i` starting at `(q0[i], q̇0[i])`; as many
    /// states as the model has lanes. The method's step and the start are
    /// checked as a `Stepper` checks them.
    pub fn new(
        model: L,
        method: M,
        t0: Element<L, N>,
        q0: &[SVector<Element<L, N>, N>],
        qdot0: &[SVector<Element<L, N>, N>],
    ) -> Result<Self, EnsembleError<Element<L, N>, N>> {
        let (h, max_steps) = method.lane_course()?;
        check_starts::<L, N>(&model, t0, q0, qdot0)?;
        let guards = Guards::new(q0, qdot0);
        let (q, qdot) = (gather(q0), gather(qdot0));
        Ok(Self {
            course: Course::new(h, max_steps),
            lanes: Lanes {
                avx2: avx2_at_run_time(),
                guards,
                model,
                method,
                t: t0,
                q,
                qdot,
                call_start: 0,
                end: (q, qdot),
                stats: Stats::default(),
            },
        })
    }

    /// Advances every lane by `dt`: to `t + dt`, which must be later than
    /// `t`.
    pub fn advance(&mut self, dt: Element<L, N>) -> Result<(), EnsembleError<Element<L, N>, N>> {
        self.advance_to(self.lanes.t + dt)
    }

    /// Advances every lane to time `target` (finite, later than
    /// [`t`](Self::t)), in the fewest equal steps no longer than `h`. On a
    /// lane's failure, every lane stays at the last step all of them
    /// completed.
    ///
    /// On an x86-64 CPU with AVX2, a build without it (the default target)
    /// takes the steps in a copy of this loop compiled for AVX2, chosen at
    /// run time: four `f64` or eight `f32` lanes to a register. Its values
    /// are the same bits: the arithmetic is the same, and no multiply-add
    /// is fused that the build does not fuse (the generated code and the
    /// sine kernel fuse by the build's `target_feature = "fma"`, not by
    /// this copy's).
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

    /// [`steps_to`](Self::steps_to) compiled for AVX2 (the functions it
    /// inlines, the model's `M` and `f` among them, with it).
    #[cfg(all(target_arch = "x86_64", not(target_feature = "avx2")))]
    #[target_feature(enable = "avx2")]
    fn advance_to_avx2(
        &mut self,
        target: Element<L, N>,
    ) -> Result<(), EnsembleError<Element<L, N>, N>> {
        self.steps_to(target)
    }

    /// The loop of [`advance_to`](Self::advance_to): the runs' own
    /// ([`Course::walk`]) on the lanes.
    #[inline(always)]
    fn steps_to(&mut self, target: Element<L, N>) -> Result<(), EnsembleError<Element<L, N>, N>> {
        let t = self.lanes.t;
        if !(target.is_finite() && target > t) {
            return Err(InvalidInput::TargetNotAhead { t, target }.into());
        }
        self.lanes.call_start = self.lanes.stats.steps_accepted;
        self.course.walk(&mut self.lanes, target).map(|_| ())
    }

    /// The time of every lane's state.
    pub fn t(&self) -> Element<L, N> {
        self.lanes.t
    }

    /// Lane `lane`'s coordinates. Panics for a lane past the model's.
    pub fn q(&self, lane: usize) -> SVector<Element<L, N>, N> {
        lane_of(&self.lanes.q, self.lane(lane))
    }

    /// Lane `lane`'s velocities. Panics for a lane past the model's.
    pub fn qdot(&self, lane: usize) -> SVector<Element<L, N>, N> {
        lane_of(&self.lanes.qdot, self.lane(lane))
    }

    /// Every lane's coordinates, as the SIMD values they are stepped in.
    pub fn lanes(&self) -> (&SVector<L::Lanes, N>, &SVector<L::Lanes, N>) {
        (&self.lanes.q, &self.lanes.qdot)
    }

    /// Replaces lane `lane`'s state (checked as a start is), for example
    /// the lane that failed, before going on; its growth guard starts
    /// anew there. Panics for a lane past the model's.
    pub fn set_lane(
        &mut self,
        lane: usize,
        q: SVector<Element<L, N>, N>,
        qdot: SVector<Element<L, N>, N>,
    ) -> Result<(), EnsembleError<Element<L, N>, N>> {
        let lane = self.lane(lane);
        finite_start(L::COORDINATES, &q, &qdot)?;
        for i in 0..N {
            self.lanes.q[i].replace(lane, q[i]);
            self.lanes.qdot[i].replace(lane, qdot[i]);
        }
        self.lanes.guards.restart(lane, &q, &qdot);
        Ok(())
    }

    /// The model.
    pub fn model(&self) -> &L {
        &self.lanes.model
    }

    /// The model, to change a lane's parameters between calls.
    pub fn model_mut(&mut self) -> &mut L {
        &mut self.lanes.model
    }

    /// The work done: steps of the whole ensemble, and right-hand sides
    /// (each one evaluation of every lane).
    pub fn stats(&self) -> Stats {
        self.lanes.stats
    }

    fn lane(&self, lane: usize) -> usize {
        let lanes = L::Lanes::LANES;
        assert!(lane < lanes, "lane {lane} of an ensemble of {lanes} lanes");
        lane
    }
}

impl<L, M, const N: usize> Track<Element<L, N>> for Lanes<L, M, N>
where
    L: LaneModel<N>,
    M: LaneStep<Element<L, N>>,
{
    type Error = EnsembleError<Element<L, N>, N>;

    #[inline(always)]
    fn t(&self) -> Element<L, N> {
        self.t
    }

    /// Lanes have no events, and the methods carry nothing between steps.
    #[inline(always)]
    fn fresh(&self) -> Fresh {
        Fresh::No
    }

    fn begin(&mut self, _: Fresh, _: Element<L, N>) -> Result<Option<Element<L, N>>, Self::Error> {
        Ok(None)
    }

    #[inline(always)]
    fn next_stop(&self, target: Element<L, N>) -> Element<L, N> {
        target
    }

    /// Every lane meets it at once: reported for lane 0.
    fn underflow(&self, h: Element<L, N>) -> Self::Error {
        let (t, q, qdot) = (self.t, lane_of(&self.q, 0), lane_of(&self.qdot, 0));
        let error = IntegrationError::StepSizeUnderflow { t, h, q, qdot };
        EnsembleError::Lane { lane: 0, error }
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

    #[inline(always)]
    fn steps_this_call(&self) -> usize {
        self.stats.steps_accepted - self.call_start
    }

    #[inline(always)]
    fn step(
        &mut self,
        t: Element<L, N>,
        dt: Element<L, N>,
        _: Element<L, N>,
    ) -> Result<(), Self::Error> {
        let (model, stats, avx2) = (&self.model, &mut self.stats, self.avx2);
        self.end = self
            .method
            .lane_step(t, (&self.q, &self.qdot), dt, |t, q, qdot| {
                stats.rhs_evals += 1;
                #[cfg(all(target_arch = "x86_64", not(target_feature = "avx2")))]
                if avx2 {
                    // SAFETY: `avx2` is set only where the CPU has it.
                    return unsafe { solve::accelerations_avx2(model, t, q, qdot) };
                }
                let _ = avx2;
                accelerations(model, t, q, qdot)
            })
            .map_err(|(lane, error)| EnsembleError::Lane { lane, error })?;
        Ok(())
    }

    #[inline(always)]
    fn count(&mut self) {
        self.stats.steps_accepted += 1;
    }

    /// As the fixed-step loop judges each run's step: the step's end
    /// checked finite, then its growth, lane by lane.
    #[inline(always)]
    fn judge(
        &mut self,
        t_next: Element<L, N>,
        h_dt: (Element<L, N>, Element<L, N>),
    ) -> Result<(), Self::Error> {
        let (before, after) = ((&self.q, &self.qdot), (&self.end.0, &self.end.1));
        self.guards.judge(before, after, t_next, h_dt)
    }

    #[inline(always)]
    fn take(
        &mut self,
        (_, t_next): (Element<L, N>, Element<L, N>),
        _: Element<L, N>,
    ) -> Result<Flow, Self::Error> {
        (self.t, self.q, self.qdot) = (t_next, self.end.0, self.end.1);
        Ok(Flow::Go)
    }

    #[inline(always)]
    fn landed(&mut self) {}
}
