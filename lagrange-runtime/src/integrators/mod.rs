//! Time integrators, one per file, all behind [`Integrator`].
//!
//! Each integrator advances the first-order system `y = (q, q̇)`,
//! `ẏ = (q̇, q̈)` with `q̈` from [`acceleration`], and records the state at
//! the requested sample times only. [`Variational`] is the exception: it
//! advances `(q, p)` by the discrete Euler–Lagrange equations of the
//! Lagrangian itself, and converts to `(q, q̇)` at the boundaries.
//!
//! Shared rules, so that methods can be swapped without surprises:
//!
//! - Input is validated before the first step: non-finite `t0`, `q0`, `q̇0`
//!   or model parameters, and sample times that are not finite, decrease, or
//!   precede `t0` are [`InvalidInput`].
//! - Integration runs forward from `t0` to the last sample time. Samples
//!   equal to `t0` are the initial state, unchanged.
//! - A failure returns the samples computed so far in [`Failure`].
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
//! ([`pivot_ratio`]): an ill-conditioned mass
//! matrix (a light body beside a heavy one) makes the accelerations, and so
//! the corrections, only that accurate. If it diverges, or has not
//! converged in `max_iterations`, the step fails with
//! [`NewtonDivergence`](IntegrationError::NewtonDivergence): take a smaller
//! step.
//!
//! Fixed-step methods supply one step to a shared driver that lands on the
//! sample times; adaptive methods share Hairer's initial step guess and the
//! tolerance checks.

mod dop853;
mod dop853_tableau;
mod dopri5;
mod euler;
mod gauss_legendre;
mod implicit_midpoint;
mod implicit_rk;
mod lu;
mod radau5;
mod rk4;
mod second_order;
mod symplectic_euler;
mod variational;

pub use dop853::Dop853;
pub use dopri5::Dopri5;
pub use euler::ExplicitEuler;
pub use gauss_legendre::GaussLegendre;
pub use implicit_midpoint::ImplicitMidpoint;
pub use radau5::Radau5;
pub use rk4::Rk4;
pub use symplectic_euler::SymplecticEuler;
pub use variational::Variational;

use nalgebra::{ComplexField, RealField, SVector};

use crate::solve::{acceleration, pivot_ratio};
use crate::{
    Failure, IntegrationError, IntegrationResult, InvalidInput, Lagrangian, NonFiniteValue, Stats,
    Trajectory,
};

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
        L: Lagrangian<N, Scalar = S>;
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

/// Records samples as an integrator passes them and counts its work; owns
/// the trajectory that a success or a [`Failure`] hands back.
pub(crate) struct Recorder<'a, S: RealField + Copy, const N: usize> {
    times: &'a [S],
    next: usize,
    trajectory: Trajectory<S, N>,
    pub(crate) stats: Stats,
}

impl<'a, S: RealField + Copy, const N: usize> Recorder<'a, S, N> {
    /// Validates the call and records the samples at `t0`.
    pub(crate) fn start<L: Lagrangian<N, Scalar = S>>(
        model: &L,
        t0: S,
        q0: &SVector<S, N>,
        qdot0: &SVector<S, N>,
        times: &'a [S],
    ) -> Result<Self, Box<Failure<S, N>>> {
        validate(model, t0, q0, qdot0, times).map_err(invalid)?;
        let mut recorder = Self {
            times,
            next: 0,
            trajectory: Trajectory::with_capacity(times.len()),
            stats: Stats::default(),
        };
        while recorder.pending() == Some(t0) {
            recorder.record(t0, *q0, *qdot0);
        }
        Ok(recorder)
    }

    /// The next sample time not yet recorded.
    pub(crate) fn pending(&self) -> Option<S> {
        self.times.get(self.next).copied()
    }

    /// The last sample time, where integration ends.
    pub(crate) fn end(&self) -> Option<S> {
        self.times.last().copied()
    }

    pub(crate) fn record(&mut self, t: S, q: SVector<S, N>, qdot: SVector<S, N>) {
        self.trajectory.push(t, q, qdot);
        self.next += 1;
    }

    /// One counted right-hand side evaluation.
    pub(crate) fn rhs<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        model: &L,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> Result<SVector<S, N>, IntegrationError<S, N>> {
        self.stats.rhs_evals += 1;
        acceleration(model, t, q, qdot)
    }

    pub(crate) fn finish(mut self) -> Trajectory<S, N> {
        self.trajectory.set_stats(self.stats);
        self.trajectory
    }

    pub(crate) fn fail(self, error: IntegrationError<S, N>) -> Box<Failure<S, N>> {
        Failure::boxed(error, self.finish())
    }
}

/// `(q, q̇)`, as a one-step method returns it.
pub(crate) type State<S, const N: usize> = (SVector<S, N>, SVector<S, N>);

/// The loop every fixed-step method shares, so that they all land on the
/// sample times the same way and only differ in `step`.
///
/// Sample times are hit exactly, not interpolated: each interval between
/// consecutive sample times is cut into the fewest equal steps no longer than
/// `h`. `step(rec, model, t, q, q̇, h)` advances one step, evaluating the
/// model through `rec` so that its work is counted; its error ends the
/// integration with the samples so far. Every step counts against
/// `max_steps`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn fixed_step<S, L, const N: usize, F>(
    model: &L,
    h: S,
    max_steps: usize,
    t0: S,
    q0: SVector<S, N>,
    qdot0: SVector<S, N>,
    times: &[S],
    mut step: F,
) -> IntegrationResult<S, N>
where
    S: RealField + Copy,
    L: Lagrangian<N, Scalar = S>,
    F: FnMut(
        &mut Recorder<'_, S, N>,
        &L,
        S,
        &SVector<S, N>,
        &SVector<S, N>,
        S,
    ) -> Result<State<S, N>, IntegrationError<S, N>>,
{
    if !(h.is_finite() && h > S::zero()) {
        return Err(invalid(InvalidInput::InvalidStepSize { h }));
    }
    let mut rec = Recorder::start(model, t0, &q0, &qdot0, times)?;
    let (mut t, mut q, mut qdot) = (t0, q0, qdot0);
    let mut growth = GrowthGuard::new(&q0, &qdot0);

    while let Some(target) = rec.pending() {
        let (start, span) = (t, target - t);
        let steps = steps_to_cover(start, target, h);
        let step_size = span / nalgebra::convert::<f64, S>(steps as f64);
        if start + step_size == start {
            let error = IntegrationError::StepSizeUnderflow {
                t,
                h: step_size,
                q,
                qdot,
            };
            return Err(rec.fail(error));
        }
        for k in 1..=steps {
            if rec.stats.steps_accepted >= max_steps {
                let error = IntegrationError::TooManySteps {
                    t,
                    max_steps,
                    q,
                    qdot,
                };
                return Err(rec.fail(error));
            }
            // Positions from the interval start, so rounding does not
            // accumulate in t and the last step lands on the target.
            let t_next = if k == steps {
                target
            } else {
                start + step_size * nalgebra::convert::<f64, S>(k as f64)
            };
            let (before, dt) = ((q, qdot), t_next - t);
            match step(&mut rec, model, t, &q, &qdot, dt) {
                Ok((q_next, qdot_next)) => (q, qdot) = (q_next, qdot_next),
                Err(error) => return Err(rec.fail(error)),
            }
            t = t_next;
            rec.stats.steps_accepted += 1;
            if let Some(steps) = growth.unstable(before, (&q, &qdot), dt) {
                let error = IntegrationError::Unstable {
                    t,
                    h: step_size,
                    steps,
                    q,
                    qdot,
                };
                return Err(rec.fail(error));
            }
        }
        // The last step's state is not evaluated by the model, so check it
        // here rather than record a NaN.
        if !(q.iter().chain(qdot.iter()).all(|x| x.is_finite())) {
            let value = NonFiniteValue::State;
            let error = IntegrationError::NonFiniteState { t, q, qdot, value };
            return Err(rec.fail(error));
        }
        while rec.pending() == Some(target) {
            rec.record(target, q, qdot);
        }
    }
    Ok(rec.finish())
}

/// Watches a fixed-step run for step-size instability, by two signatures of
/// a mode that the step amplifies but cannot resolve. Both only count once
/// the state's size (largest component of `q`, `q̇`) is above 1000× its
/// starting scale, far beyond anything the start explains:
///
/// - **fast growth**: the size more than doubles on each step of a run,
///   `|R(hλ)| > 2`, until it exceeds the largest size seen before the run by
///   `2^STEPS`. A resolved motion
///   would need `λ h > 0.69` per step for that, where no method is
///   accurate. The total, not the run's length, decides: a mode that was
///   small beside the rest of the state (a kink between a light and a heavy
///   body) shows in the state's size only in its last steps before
///   overflow, growing 100× or more per step, and is stopped there.
/// - **unresolved growth**: the step is unresolved (a running mean over
///   about [`GrowthGuard::STEPS`] steps of the measure below is at least ½)
///   and the state grows [`GrowthGuard::FOLD`]-fold meanwhile. A step is
///   unresolved when the state changes by a sizable fraction of itself (it
///   turns by 30° or more, or flips sign: fewer than a dozen steps per
///   period), or when `Δq` disagrees with the trapezoidal rule on `q̇`,
///   `(h/2)(q̇ₙ + q̇ₙ₊₁)`, by as much as they measure themselves: a resolved
///   step agrees to `O(h²ω²)`, a mode that decays at rate `λ` in the model
///   but grows in the method (`R(hλ) > 1` for `hλ` past the limit on the
///   negative real axis, a stiff damper) does not agree at all. This is how
///   a mode just beyond the stability limit grows: RK4 at `hω = 1.01 · 2√2`
///   gains 7 % per step while turning by 106°, and at `hλ = −1.01 · 2.785`
///   2 % per step without turning. Too slow for the first signature, it
///   would otherwise run on into finite garbage or an overflow.
///
/// Growth that is smooth and slower than 2× per step (a physical
/// instability, or explicit Euler's slow energy gain at small `hω`) is not
/// an instability of the step and is left alone.
struct GrowthGuard<S> {
    floor: S,
    last: S,
    run: usize,
    /// The largest size seen so far, and as it was when the current run of
    /// doubling steps began.
    peak: S,
    run_peak: S,
    /// Running mean of how unresolved the steps are.
    roughness: S,
    /// Size and steps since an unresolved, above-floor stretch began.
    stretch: Option<(S, usize)>,
}

impl<S: RealField + Copy> GrowthGuard<S> {
    const STEPS: usize = 8;
    const FOLD: f64 = 8.0;

    fn new<const N: usize>(q: &SVector<S, N>, qdot: &SVector<S, N>) -> Self {
        let size = Self::size(q, qdot);
        Self {
            floor: nalgebra::convert::<f64, S>(1000.0) * size.max(S::one()),
            last: size,
            run: 0,
            peak: size,
            run_peak: size,
            roughness: S::zero(),
            stretch: None,
        }
    }

    fn size<const N: usize>(q: &SVector<S, N>, qdot: &SVector<S, N>) -> S {
        q.iter()
            .chain(qdot.iter())
            .fold(S::zero(), |m, x| m.max(x.abs()))
    }

    /// After a step of length `h` from `before` to `after`: `Some(steps)`
    /// once either signature has lasted long enough to stop, `steps` being
    /// how long.
    fn unstable<const N: usize>(
        &mut self,
        before: State<S, N>,
        after: (&SVector<S, N>, &SVector<S, N>),
        h: S,
    ) -> Option<usize> {
        let c = |x: f64| -> S { nalgebra::convert(x) };
        let size = Self::size(after.0, after.1);
        let ratio = |part: S, whole: S| {
            if whole > S::zero() {
                part / whole
            } else {
                S::zero()
            }
        };
        let dq = after.0 - before.0;
        let change = Self::size(&dq, &(after.1 - before.1));
        let trapezoid = (before.1 + after.1) * (h / c(2.0));
        let disagreement = ratio((dq - trapezoid).amax(), dq.amax() + trapezoid.amax());
        let unresolved = ratio(change, size.max(self.last)).max(disagreement);
        let steps = c(Self::STEPS as f64);
        self.roughness += (unresolved - self.roughness) / steps;
        if size > c(2.0) * self.last {
            if self.run == 0 {
                self.run_peak = self.peak;
            }
            self.run += 1;
        } else {
            self.run = 0;
        }
        self.last = size;
        self.peak = self.peak.max(size);
        if size <= self.floor {
            self.stretch = None;
            return None;
        }
        // The run must carry the size 2^STEPS past the largest size seen
        // before it (the envelope), not merely past where it started: the
        // size max(|q|, |q̇|) dips when the larger component crosses zero,
        // and a resolved oscillation climbing back out of such a dip must not
        // look like a blow-up. At least two steps: a single jump is the first
        // step from rest of a stiff spring (q̇ goes from 0 to ω q).
        if self.run >= 2 && size > c(2f64.powi(Self::STEPS as i32)) * self.run_peak {
            return Some(self.run);
        }
        if self.roughness < c(0.5) {
            self.stretch = None;
            return None;
        }
        let (start, steps) = self.stretch.get_or_insert((size, 0));
        *steps += 1;
        (size >= c(Self::FOLD) * *start).then_some(*steps)
    }
}

/// The fewest equal steps no longer than `h` that cover `[start, target]`,
/// forgiving the rounding of the sample times themselves: a span of exactly
/// `10 h` in decimal takes 10 steps, not 11, and samples `i h` apart by one
/// step still take one step each late in a run, where `i h` carries rounding
/// of a few ulps of `t` (at `t = 100`, ~1e-14 — far more than an ulp of `h`).
/// A step may so exceed `h` by `8 ε (|t| + span)`, which no method notices,
/// and never by more than `h / 8`: where `h` is within a few ulps of `t`
/// (`t = 1e20`, `h = 1`), forgiving 8 ulps would merge all the steps into
/// one giant one, where the callers should see that `h` no longer advances
/// `t`. Saturates at `usize::MAX`; the step budget stops it long before.
pub(super) fn steps_to_cover<S: RealField + Copy>(start: S, target: S, h: S) -> usize {
    let span = target - start;
    let eight_ulps = nalgebra::convert::<f64, S>(8.0) * S::default_epsilon();
    let forgiven = (eight_ulps * (span + start.abs().max(target.abs())))
        .min(h / nalgebra::convert::<f64, S>(8.0));
    let steps = ((span - forgiven) / h).ceil();
    let steps: f64 = nalgebra::try_convert(steps).unwrap_or(f64::MAX);
    // `as` saturates (and sends negatives to 0); a span of zero never
    // reaches here.
    (steps as usize).max(1)
}

/// The adaptive methods' default `rtol = atol`: `1e-8`, raised to `100 ε`
/// for scalar types with fewer digits (`1.2e-5` for `f32`).
pub(crate) fn default_tolerance<S: RealField + Copy>() -> S {
    nalgebra::convert::<f64, S>(1e-8).max(nalgebra::convert::<f64, S>(100.0) * S::default_epsilon())
}

/// The tolerances an adaptive method can honour: `rtol` at least `10 ε` of
/// the scalar type, `atol` positive, both finite.
pub(crate) fn check_tolerances<S: RealField + Copy>(
    rtol: S,
    atol: S,
) -> Result<(), InvalidInput<S>> {
    let min = nalgebra::convert::<f64, S>(10.0) * S::default_epsilon();
    if !(rtol.is_finite() && rtol >= min) {
        return Err(InvalidInput::InvalidRelativeTolerance { rtol, min });
    }
    if !(atol.is_finite() && atol > S::zero()) {
        return Err(InvalidInput::InvalidAbsoluteTolerance { atol });
    }
    Ok(())
}

/// Hairer's `hinit`, shared by the adaptive methods: a first step for which
/// a method of order `order` would roughly meet the tolerance, from
/// estimates of the first and second derivative at `start = (t, q, q̇, q̈)`.
/// Costs one right-hand side (an explicit Euler probe).
pub(crate) fn initial_step<S, L, const N: usize>(
    rec: &mut Recorder<'_, S, N>,
    model: &L,
    (t, q, qdot, qddot): (S, &SVector<S, N>, &SVector<S, N>, &SVector<S, N>),
    h_max: S,
    rtol: S,
    atol: S,
    order: u8,
) -> S
where
    S: RealField + Copy,
    L: Lagrangian<N, Scalar = S>,
{
    let c = |x: f64| -> S { nalgebra::convert(x) };
    let scale = |y: S| atol + rtol * y.abs();
    let y = q.iter().chain(qdot.iter());
    let f0 = qdot.iter().chain(qddot.iter());
    let dny = y
        .clone()
        .fold(S::zero(), |s, &y| s + (y / scale(y)).powi(2));
    let dnf = f0
        .zip(y.clone())
        .fold(S::zero(), |s, (&f, &y)| s + (f / scale(y)).powi(2));
    let h0 = if dnf <= c(1e-10) || dny <= c(1e-10) {
        c(1e-6)
    } else {
        (dny / dnf).sqrt() * c(0.01)
    };
    // A sum of squares that overflowed (a tiny atol makes f / atol huge)
    // leaves no estimate, only 0 or NaN: take RADAU5's default first step,
    // as Radau5 does, and let the step control adapt it.
    let h0 = if h0.is_finite() && h0 > S::zero() {
        h0
    } else {
        c(1e-6)
    };
    let h0 = h0.min(h_max);

    // One explicit Euler step estimates the second derivative.
    let (q1, qdot1) = (q + qdot * h0, qdot + qddot * h0);
    let Ok(qddot1) = rec.rhs(model, t + h0, &q1, &qdot1) else {
        // The model breaks down there; let the step control find out.
        return h0;
    };
    let f1 = qdot1.iter().chain(qddot1.iter());
    let f0 = qdot.iter().chain(qddot.iter());
    let der2 = f1
        .zip(f0)
        .zip(y)
        .fold(S::zero(), |s, ((&f1, &f0), &y)| {
            s + ((f1 - f0) / scale(y)).powi(2)
        })
        .sqrt()
        / h0;
    // h1 such that h1^order · max(|f0|, |f'|) = 0.01.
    let der12 = der2.max(dnf.sqrt());
    let h1 = if der12 <= c(1e-15) {
        c(1e-6).max(h0 * c(1e-3))
    } else {
        (c(0.01) / der12).powf(c(1.0 / f64::from(order)))
    };
    let h = (h0 * c(100.0)).min(h1).min(h_max);
    if h.is_finite() && h > S::zero() {
        h
    } else {
        h0
    }
}

/// A failure before any work: empty trajectory.
pub(crate) fn invalid<S: RealField + Copy, const N: usize>(
    invalid: InvalidInput<S>,
) -> Box<Failure<S, N>> {
    Failure::boxed(invalid.into(), Trajectory::with_capacity(0))
}

fn validate<L: Lagrangian<N>, const N: usize>(
    model: &L,
    t0: L::Scalar,
    q0: &SVector<L::Scalar, N>,
    qdot0: &SVector<L::Scalar, N>,
    times: &[L::Scalar],
) -> Result<(), InvalidInput<L::Scalar>> {
    if !t0.is_finite() {
        return Err(InvalidInput::NonFiniteStartTime { t0 });
    }
    if !model.parameters_are_finite() {
        return Err(InvalidInput::NonFiniteParameters);
    }
    for (i, coordinate) in L::COORDINATES.into_iter().enumerate() {
        if !q0[i].is_finite() {
            let value = q0[i];
            return Err(InvalidInput::NonFiniteInitialPosition { coordinate, value });
        }
        if !qdot0[i].is_finite() {
            let value = qdot0[i];
            return Err(InvalidInput::NonFiniteInitialVelocity { coordinate, value });
        }
    }
    for (index, &time) in times.iter().enumerate() {
        if !time.is_finite() {
            return Err(InvalidInput::NonFiniteSampleTime { index, time });
        }
        if time < t0 {
            return Err(InvalidInput::SampleBeforeStart { index, time, t0 });
        }
        if let Some(&previous) = index.checked_sub(1).and_then(|i| times.get(i)) {
            if time < previous {
                return Err(InvalidInput::UnsortedSampleTimes {
                    index,
                    previous,
                    time,
                });
            }
        }
    }
    Ok(())
}

/// Below this size relative to the state, a Newton correction that no
/// longer shrinks is the noise of evaluating the equations, and the iterate
/// is as converged as the arithmetic allows: `ε (1000 + 10 N κ)` at
/// `(t, q)`. The 1000 ε is the evaluation of the model itself (sums with
/// cancellation); `10 N κ ε` is what the solve `M q̈ = f` adds, whose
/// relative error grows with `κ`, the pivot ratio of `M` (its condition
/// number, see [`pivot_ratio`]): a light body beside a heavy one
/// (`κ = 10⁶`) makes the accelerations, and so the corrections, noisy at
/// ~10⁻¹¹, where a floor of 1000 ε would call a converged step divergent.
pub(crate) fn newton_noise_floor<S, L, const N: usize>(model: &L, t: S, q: &SVector<S, N>) -> S
where
    S: RealField + Copy,
    L: Lagrangian<N, Scalar = S>,
{
    let c = |x: f64| -> S { nalgebra::convert(x) };
    let kappa = pivot_ratio(&model.mass_matrix(t, q))
        .filter(|kappa| kappa.is_finite())
        .unwrap_or(S::one());
    S::default_epsilon() * (c(1000.0) + c(10.0 * N as f64) * kappa)
}

#[cfg(test)]
mod tests {
    use nalgebra::Vector1;

    use super::GrowthGuard;

    /// Feeds the guard a state of each size in turn (as `q`, unit steps;
    /// `q̇` consistent with smooth exponential growth between samples when
    /// `smooth`, else zero) and returns the step (1-based) at which it stops
    /// the run, if any.
    fn stops(start: f64, sizes: &[f64], smooth: bool) -> Option<(usize, usize)> {
        let velocity = |prev: f64, next: f64| {
            if smooth && prev > 0.0 && next.is_finite() && next > 0.0 {
                next * (next / prev).ln()
            } else {
                0.0
            }
        };
        let mut guard = GrowthGuard::new(&Vector1::new(start), &Vector1::new(0.0));
        let mut before = (Vector1::new(start), Vector1::new(0.0));
        sizes.iter().enumerate().find_map(|(k, &size)| {
            let after = (
                Vector1::new(size),
                Vector1::new(velocity(before.0[0], size)),
            );
            let stop = guard.unstable(before, (&after.0, &after.1), 1.0);
            before = after;
            stop.map(|run| (k + 1, run))
        })
    }

    fn stops_at(start: f64, sizes: &[f64]) -> Option<(usize, usize)> {
        stops(start, sizes, true)
    }

    #[test]
    fn eight_doublings_past_the_floor_stop_the_run() {
        // Already near the floor (1000× the start), then 2.1× per step:
        // 2.1^8 = 378 is the first power past 2^8.
        let mut sizes = vec![500.0, 500.0];
        sizes.extend((1..=12).map(|k| 500.0 * 2.1f64.powi(k)));
        let stop = stops(1.0, &sizes, false);
        assert!(matches!(stop, Some((k, _)) if k <= 10), "{stop:?}");
    }

    /// A fast mode hidden under a larger slow motion shows in the state's
    /// size only when it overtakes it, then grows by orders of magnitude per
    /// step: stopped as soon as the total passes 256×, not after eight steps
    /// (by which time it would have overflowed).
    #[test]
    fn a_blow_up_faster_than_geometric_is_stopped_within_steps() {
        let sizes = [0.5, 0.5, 0.5, 5.0, 1e4, 1e86, f64::INFINITY];
        assert_eq!(stops_at(0.5, &sizes), Some((5, 2)));
    }

    #[test]
    fn a_single_jump_below_the_floor_is_no_alarm() {
        // 300× in one step, but still below 1000× the starting scale: a
        // fast transient, not yet a blow-up.
        assert_eq!(stops(1.0, &[1.0, 300.0, 300.0, 280.0], false), None);
    }

    #[test]
    fn slow_smooth_growth_is_never_stopped() {
        // 10 % per step, resolved (the velocity matches the growth): a
        // physical instability, not the step's.
        let sizes: Vec<f64> = (1..=200).map(|k| 1.1f64.powi(k)).collect();
        assert_eq!(stops_at(1.0, &sizes), None);
    }
}
