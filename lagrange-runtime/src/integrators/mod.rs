//! Time integrators, one per file or folder, all behind [`Integrator`].
//!
//! Each integrator advances the first-order system `y = (q, q̇)`,
//! `ẏ = (q̇, q̈)` with `q̈` from [`acceleration`](crate::dynamics::acceleration),
//! and records the state at the requested sample times only.
//! [`Variational`] is the exception: it advances `(q, p)` by the discrete
//! Euler–Lagrange equations of the Lagrangian itself, and converts to
//! `(q, q̇)` at the boundaries.
//!
//! Shared rules, so that methods can be swapped without surprises:
//!
//! - Input is validated before the first step: non-finite `t0`, `q0`, `q̇0`
//!   or model parameters, and sample times that are not finite, decrease, or
//!   precede `t0` are [`InvalidInput`].
//! - Integration runs forward from `t0` to the last sample time. Samples
//!   equal to `t0` are the initial state, unchanged.
//! - A failure returns the samples computed so far in
//!   [`Failure`](crate::error::Failure).
//! - What was asked is never changed quietly. A fixed step `h` is never
//!   lengthened: each interval between sample times is cut into the fewest
//!   equal steps no longer than `h` (up to 8 ulps of `t` forgiven to the
//!   rounding of the sample times), and an interval that alone needs more
//!   steps than `max_steps` is
//!   [`TooManySteps`](crate::error::IntegrationError::TooManySteps) before its
//!   first step. Tolerances are used as given: `rtol` below `10 ε`, a
//!   non-positive `atol`, a non-finite or non-positive `h` and
//!   `max_iterations = 0` are [`InvalidInput`], and
//!   loose tolerances are honoured (where one is too loose to keep
//!   [`Dopri5`] or [`Dop853`] within its stability region, they stop with
//!   [`Unstable`](crate::error::IntegrationError::Unstable), as a fixed step beyond
//!   its limit does; [`Radau5`], L-stable, needs no such guard).
//! - A mass matrix that is not positive definite, a kinetic energy negative
//!   for some velocities, is a modelling error:
//!   [`IndefiniteMassMatrix`](crate::error::IntegrationError::IndefiniteMassMatrix)
//!   where it is first met, at the first state for a model indefinite
//!   everywhere.
//!
//! Fixed-step methods supply one step to a shared driver that lands on the
//! sample times and watches for growth; the explicit adaptive ones supply
//! their stages, error estimate and dense output to a shared step loop with
//! the same growth guard; all adaptive methods share Hairer's initial step
//! guess and the tolerance checks. Which method
//! to choose, and what the implicit ones conserve, is in the
//! [crate documentation](crate#choosing-a-method).

pub mod fsal;
mod implicit_rk;
mod registry;
pub(crate) mod stages;

// One module per integrator, each named again by its registry entry below
// (declared here, not by the registry's macro, so that rustfmt reaches
// them: `.ci/run` checks every file).
pub(crate) mod bs3;
pub(crate) mod dop853;
pub(crate) mod dopri5;
pub(crate) mod euler;
pub(crate) mod gauss_legendre;
pub(crate) mod implicit_midpoint;
pub(crate) mod radau5;
pub(crate) mod rk4;
pub(crate) mod symplectic_euler;
pub(crate) mod tsit5;
pub(crate) mod variational;

use nalgebra::{RealField, SVector, SimdRealField};

use crate::driver::invalid;
use crate::driver::run::{Advanced, Run, Walk, integrate as drive};
use crate::error::{IntegrationError, IntegrationResult, InvalidInput};
use crate::events::Events;
use crate::model::Lagrangian;
use registry::{is_adaptive, registry, with_tolerances};

// The registry: one entry per integrator, its module and type, then its
// named settings (each a `Method`): id, order, kind, Jacobians, how it is
// built from a step `h`, and its row of the table of methods. Everything
// else a method needs follows from this list (`registry.rs`).
registry! {
    euler::ExplicitEuler {
        ExplicitEuler = "explicit_euler", order 1, fixed, jacobians false, |h| ExplicitEuler::new(h),
        "fixed step | 1 | A baseline for convergence studies and teaching; pumps energy into oscillators.";
    }
    symplectic_euler::SymplecticEuler {
        SymplecticEuler = "symplectic_euler", order 1, fixed, jacobians false, |h| SymplecticEuler::new(h),
        "fixed step, explicit; symplectic only for constant `M` and `q̇`-free forces | 1 | Games and long oscillations where bounded energy matters more than accuracy; merely first order with `M(q)` or damping.";
    }
    rk4::Rk4 {
        Rk4 = "rk4", order 4, fixed, jacobians false, |h| Rk4::new(h),
        "fixed step | 4 | A step size you choose: reproducible steps, real-time budgets.";
    }
    implicit_midpoint::ImplicitMidpoint {
        ImplicitMidpoint = "implicit_midpoint", order 2, fixed, jacobians true, |h| ImplicitMidpoint::new(h),
        "fixed step, implicit, symmetric: the one-stage Gauss method | a Jacobian, an LU of order `2N`, 3–7 Newton iterations of 1 | Long runs without energy drift, cheapest implicit.";
    }
    gauss_legendre::GaussLegendre {
        GaussLegendre2 = "gauss_legendre_2", order 4, fixed, jacobians true, |h| GaussLegendre::two_stage(h),
        "fixed step, implicit, symmetric: two-stage Gauss | a Jacobian, an LU of order `4N`, 3–7 Newton iterations of 2 | Long runs without energy drift, accurately.";
        GaussLegendre3 = "gauss_legendre_3", order 6, fixed, jacobians true, |h| GaussLegendre::three_stage(h),
        "fixed step, implicit, symmetric: three-stage Gauss | a Jacobian, an LU of order `6N`, 3–7 Newton iterations of 3 | Long runs without energy drift, most accurately.";
    }
    variational::Variational {
        Variational = "variational", order 2, fixed, jacobians false, |h| Variational::new(h),
        "fixed step, implicit, symplectic in `(q, p)` for any `M(q)` | one `N × N` Newton solve per step | Exact discrete momentum maps (discrete Noether) and no energy drift, from the same Lagrangian.";
    }
    bs3::Bs3 {
        Bs3 = "bs3", order 3, adaptive, jacobians false, |h| Bs3::new(),
        "adaptive (estimate of order 2), cubic Hermite dense output | 3 | MATLAB's `ode23`, half Dopri5's evaluations a step; fewer evaluations in all only where stability, not accuracy, limits the step (a stiff chain); more than Dopri5 at every error measured on smooth models.";
    }
    dopri5::Dopri5 {
        Dopri5 = "dopri5", order 5, adaptive, jacobians false, |h| Dopri5::new(),
        "adaptive (estimate of order 4), dense output of order 4 | 6 | The default ([`integrate`]): smooth problems at everyday tolerances, `1e-3` to `1e-9`.";
    }
    tsit5::Tsit5 {
        Tsit5 = "tsit5", order 5, adaptive, jacobians false, |h| Tsit5::new(),
        "adaptive (estimate of order 4), dense output of order 4 from its own stages | 6 | DifferentialEquations.jl's non-stiff default: Dopri5's cost with smaller error coefficients.";
    }
    dop853::Dop853 {
        Dop853 = "dop853", order 8, adaptive, jacobians false, |h| Dop853::new(),
        "adaptive (estimates 5 and 3), dense output of order 7 | 12, +3 on steps with samples inside | Tight tolerances, below about `1e-9`: 2–6× fewer evaluations than Dopri5 at `1e-12`.";
    }
    radau5::Radau5 {
        Radau5 = "radau5", order 5, adaptive, jacobians true, |h| Radau5::new(),
        "adaptive, implicit, L-stable, dense output of order 3 | 3 per Newton iteration (1–2 typical); Jacobians and two `N × N` LUs when needed | Stiff models: hard springs beside soft ones, strong damping ([stiff models](crate#stiff-models)).";
    }
}

impl Method {
    /// The methods that step by a given `h`.
    pub const FIXED_STEP: [Method; Self::count(false)] = Self::select(false);

    /// The methods that choose their steps to meet a tolerance.
    pub const ADAPTIVE: [Method; Self::count(true)] = Self::select(true);

    /// The Gauss collocation methods, one to three stages (order `2s`):
    /// symmetric, and keeping every quadratic invariant.
    pub const GAUSS: [Method; 3] = [
        Method::ImplicitMidpoint,
        Method::GaussLegendre2,
        Method::GaussLegendre3,
    ];

    const fn count(adaptive: bool) -> usize {
        let (mut i, mut n) = (0, 0);
        while i < Self::ALL.len() {
            if Self::ALL[i].is_adaptive() == adaptive {
                n += 1;
            }
            i += 1;
        }
        n
    }

    const fn select<const K: usize>(adaptive: bool) -> [Method; K] {
        let mut out = [Method::ALL[0]; K];
        let (mut i, mut k) = (0, 0);
        while i < Self::ALL.len() {
            if Self::ALL[i].is_adaptive() == adaptive {
                out[k] = Self::ALL[i];
                k += 1;
            }
            i += 1;
        }
        out
    }

    /// The fixed-step methods with step `h`; the adaptive ones with
    /// `rtol = atol = tol`.
    pub fn integrator<S: RealField + Copy>(self, h: S, tol: S) -> AnyIntegrator<S> {
        self.with_step(h).tolerances(tol, tol)
    }

    /// An adaptive method with `rtol = atol = tol`.
    ///
    /// # Panics
    ///
    /// For a fixed-step method, which has no tolerance.
    pub fn with_tolerance<S: RealField + Copy>(self, tol: S) -> AnyIntegrator<S> {
        assert!(
            self.is_adaptive(),
            "{self:?} has a fixed step, no tolerance"
        );
        self.integrator(S::zero(), tol)
    }
}

/// What a method is to the run loops: the walker of its kind (see
/// `driver/run.rs`), built from its settings. Every integrator implements
/// it, in its own file; [`Integrator`] and the
/// [`Stepper`](crate::stepper::Stepper) follow from it. It cannot be
/// implemented outside this crate: the walkers are the crate's own.
pub trait StepMethod<S: RealField + Copy> {
    /// The method's work between steps for a model of `N` coordinates.
    #[doc(hidden)]
    type Walker<const N: usize>: Walk<S, N>;

    /// The walker for a new run, or the method's settings refused (a step
    /// that is not positive and finite, tolerances out of range, no Newton
    /// iterations).
    #[doc(hidden)]
    fn walker<const N: usize>(&self) -> Result<Self::Walker<N>, InvalidInput<S>>;
}

/// A fixed-step explicit method that also steps SIMD lanes of states, all
/// at one time: what an [`Ensemble`](crate::ensemble::Ensemble) runs
/// ([`ExplicitEuler`], [`SymplecticEuler`], [`Rk4`]). Each
/// method's scalar runs take the same step with `V = S`, so that a lane's
/// values are, bit for bit, those its scalar run would get. It cannot be
/// implemented outside this crate.
pub trait LaneStep<S: RealField + Copy>: StepMethod<S> {
    /// The step bound `h`, checked as the scalar runs check it, and the
    /// budget of steps per call.
    #[doc(hidden)]
    fn lane_course(&self) -> Result<(S, usize), InvalidInput<S>>;

    /// One step of length `h` from `t`, for every lane of `(q, q̇)`, the
    /// accelerations from `a(t, q, q̇)`.
    #[doc(hidden)]
    fn lane_step<V, E, A, const N: usize>(
        &self,
        t: S,
        state: (&SVector<V, N>, &SVector<V, N>),
        h: S,
        a: A,
    ) -> Result<(SVector<V, N>, SVector<V, N>), E>
    where
        V: SimdRealField<Element = S> + Copy,
        A: FnMut(S, &SVector<V, N>, &SVector<V, N>) -> Result<SVector<V, N>, E>;
}

/// `impl LaneStep` for a fixed-step explicit method (a struct with fields
/// `h` and `max_steps`), and its step on scalars or SIMD lanes, written
/// once: `lane_step!(Rk4, fn rk4(t, q, qdot, h, a) { … })` defines
/// `fn rk4(t: S, (q, qdot), h: S, a) -> Result<(q, q̇), E>`, where `a` is
/// the slope `q̈ = a(t, q, q̇)` and `q`, `qdot` are vectors of `V`, lanes of
/// `S` (`V = S` for the scalar runs, which call it too).
macro_rules! lane_step {
    ($method:ident, fn $step:ident($t:ident, $q:ident, $qdot:ident, $h:ident, $a:ident) $body:block) => {
        impl<S: ::nalgebra::RealField + Copy> $crate::integrators::LaneStep<S> for $method<S> {
            fn lane_course(&self) -> Result<(S, usize), $crate::error::InvalidInput<S>> {
                $crate::driver::check_step_size(self.h)?;
                Ok((self.h, self.max_steps))
            }

            #[inline]
            fn lane_step<V, E, A, const N: usize>(
                &self,
                t: S,
                state: (&::nalgebra::SVector<V, N>, &::nalgebra::SVector<V, N>),
                h: S,
                a: A,
            ) -> Result<(::nalgebra::SVector<V, N>, ::nalgebra::SVector<V, N>), E>
            where
                V: ::nalgebra::SimdRealField<Element = S> + Copy,
                A: FnMut(S, &::nalgebra::SVector<V, N>, &::nalgebra::SVector<V, N>)
                    -> Result<::nalgebra::SVector<V, N>, E>,
            {
                $step(t, state, h, a)
            }
        }

        #[inline]
        fn $step<S, V, E, const N: usize>(
            $t: S,
            ($q, $qdot): (&::nalgebra::SVector<V, N>, &::nalgebra::SVector<V, N>),
            $h: S,
            mut $a: impl FnMut(S, &::nalgebra::SVector<V, N>, &::nalgebra::SVector<V, N>)
                -> Result<::nalgebra::SVector<V, N>, E>,
        ) -> Result<(::nalgebra::SVector<V, N>, ::nalgebra::SVector<V, N>), E>
        where
            S: ::nalgebra::RealField + Copy,
            V: ::nalgebra::SimdRealField<Element = S> + Copy,
        $body
    };
}
pub(crate) use lane_step;

/// A method that integrates a [`Lagrangian`] model and samples it at
/// requested times.
///
/// `S` is the model's scalar type; the integrator's own settings (step size,
/// tolerances) use it too, so `f32` models get `f32` tolerances.
///
/// ```
/// use lagrange_runtime::prelude::*;
/// use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1};
///
/// struct FreeFall;
///
/// impl Lagrangian<1> for FreeFall {
///     type Scalar = f64;
///     const COORDINATES: [&'static str; 1] = ["z"];
///     fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
///         SMatrix::<f64, 1, 1>::new(1.0)
///     }
///     fn forcing(&self, _t: f64, _q: &SVector<f64, 1>, _qd: &SVector<f64, 1>) -> SVector<f64, 1> {
///         Vector1::new(-9.81)
///     }
///     fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> f64 {
///         0.5 * qd[0] * qd[0]
///     }
///     fn potential_energy(&self, _t: f64, q: &SVector<f64, 1>) -> f64 {
///         9.81 * q[0]
///     }
/// }
///
/// /// Any method will do: the caller picks it.
/// fn height_after_one_second(method: &impl Integrator<f64>) -> f64 {
///     let trajectory = method
///         .integrate(&FreeFall, 0.0, Vector1::new(0.0), Vector1::new(0.0), &[1.0])
///         .unwrap();
///     trajectory.last().unwrap().q[0]
/// }
///
/// // z(1) = -g/2; both methods are exact for a quadratic.
/// assert!((height_after_one_second(&Rk4::new(0.1)) + 4.905).abs() < 1e-12);
/// assert!((height_after_one_second(&Dopri5::new()) + 4.905).abs() < 1e-12);
/// ```
///
/// Every method of this crate is an `Integrator` through its
/// [`StepMethod`] (one implementation for all of them, below); another crate
/// may implement the trait for a method of its own by
/// `integrate_with_events`.
pub trait Integrator<S: RealField + Copy> {
    /// Integrates `model` from `(t0, q0, q̇0)` and returns the state at each
    /// of `times` (non-decreasing, none before `t0`).
    fn integrate<L, const N: usize>(
        &self,
        model: &L,
        t0: S,
        q0: SVector<S, N>,
        qdot0: SVector<S, N>,
        times: &[S],
    ) -> IntegrationResult<S, N>
    where
        L: Lagrangian<N, Scalar = S>,
    {
        self.integrate_with_events(model, t0, q0, qdot0, times, &Events::new())
    }

    /// [`integrate`](Integrator::integrate), watching `events`: each
    /// crossing located, recorded in
    /// [`Trajectory::events`](crate::trajectory::Trajectory::events), and acted on
    /// (stop, or reset and restart; see [`events`](crate::events)). With
    /// no events it is `integrate`, to the bit.
    fn integrate_with_events<L, const N: usize>(
        &self,
        model: &L,
        t0: S,
        q0: SVector<S, N>,
        qdot0: SVector<S, N>,
        times: &[S],
        events: &Events<'_, S, N>,
    ) -> IntegrationResult<S, N>
    where
        L: Lagrangian<N, Scalar = S>;
}

/// Every method with a walker integrates by driving it: the one run loop
/// of its kind (`driver::run::integrate`), the same for each method and for
/// [`AnyIntegrator`].
impl<S: RealField + Copy, M: StepMethod<S>> Integrator<S> for M {
    fn integrate_with_events<L, const N: usize>(
        &self,
        model: &L,
        t0: S,
        q0: SVector<S, N>,
        qdot0: SVector<S, N>,
        times: &[S],
        events: &Events<'_, S, N>,
    ) -> IntegrationResult<S, N>
    where
        L: Lagrangian<N, Scalar = S>,
    {
        let walker = self.walker::<N>().map_err(invalid)?;
        drive(walker, model, t0, q0, qdot0, times, events)
    }
}

/// The one call: integrates `model` with [`Dopri5`] at its default
/// tolerances and returns the state at each of `times`.
///
/// ```
/// use lagrange_runtime::integrate;
/// # use lagrange_runtime::Lagrangian;
/// # use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1};
/// # struct Spring;
/// # impl Lagrangian<1> for Spring {
/// #     type Scalar = f64;
/// #     const COORDINATES: [&'static str; 1] = ["x"];
/// #     fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
/// #         SMatrix::<f64, 1, 1>::new(1.0)
/// #     }
/// #     fn forcing(&self, _t: f64, q: &SVector<f64, 1>, _qd: &SVector<f64, 1>) -> SVector<f64, 1> {
/// #         -q
/// #     }
/// #     fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> f64 {
/// #         0.5 * qd[0] * qd[0]
/// #     }
/// #     fn potential_energy(&self, _t: f64, q: &SVector<f64, 1>) -> f64 {
/// #         0.5 * q[0] * q[0]
/// #     }
/// # }
///
/// // A unit spring released from x = 1: x(t) = cos t.
/// let times = [0.5, 1.0, 1.5];
/// let trajectory = integrate(&Spring, 0.0, Vector1::new(1.0), Vector1::new(0.0), &times)?;
/// for sample in &trajectory {
///     assert!((sample.q[0] - sample.t.cos()).abs() < 1e-7);
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn integrate<L: Lagrangian<N>, const N: usize>(
    model: &L,
    t0: L::Scalar,
    q0: SVector<L::Scalar, N>,
    qdot0: SVector<L::Scalar, N>,
    times: &[L::Scalar],
) -> IntegrationResult<L::Scalar, N> {
    Dopri5::new().integrate(model, t0, q0, qdot0, times)
}
