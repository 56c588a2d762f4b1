//! The midpoint-rule variational integrator: the discrete Euler–Lagrange
//! equations of the model's own Lagrangian, with forces by the discrete
//! Lagrange–d'Alembert principle.
//!
//! # The discrete equations
//!
//! The action over one step of length `h` is approximated by the midpoint
//! rule, `L_d(q_k, q_{k+1}) = h L(t̄, q̄, v̄)` with `t̄ = t_k + h/2`,
//! `q̄ = (q_k + q_{k+1})/2` and `v̄ = (q_{k+1} − q_k)/h`, so
//!
//! ```text
//! D1 L_d = (h/2) ∂L/∂q − ∂L/∂q̇,    D2 L_d = (h/2) ∂L/∂q + ∂L/∂q̇    (at t̄, q̄, v̄)
//! ```
//!
//! and the forces enter as `f_d⁻ = f_d⁺ = (h/2) Q(t̄, q̄, v̄)`. Stationarity of
//! the discrete action with forces, `D2 L_d(q_{k−1}, q_k) + f_d⁺ + D1 L_d(q_k,
//! q_{k+1}) + f_d⁻ = 0`, written with the discrete momenta `p_k = −D1 L_d −
//! f_d⁻` and `p_{k+1} = D2 L_d + f_d⁺`, is a one-step map `(q_k, p_k) ↦
//! (q_{k+1}, p_{k+1})`:
//!
//! ```text
//! r(v̄) = p_k + (h/2) (∂L/∂q + Q) − ∂L/∂q̇ = 0,        q_{k+1} = q_k + h v̄,
//! p_{k+1} = ∂L/∂q̇ + (h/2) (∂L/∂q + Q) = p_k + h (∂L/∂q + Q).
//! ```
//!
//! Its continuous limit is `ṗ = ∂L/∂q + Q`, the Euler–Lagrange equations with
//! the forces of [`Lagrangian::nonconservative_forces`].

use nalgebra::{ComplexField, RealField, SMatrix, SVector};

use super::steps_to_cover;
use super::{invalid, newton_noise_floor, Integrator, Recorder};
use crate::solve::{lu_solve, solve_mass_matrix, SolveError};
use crate::{
    Failure, IntegrationError, IntegrationResult, InvalidInput, Lagrangian, NonFiniteValue, Stats,
};

/// The midpoint-rule variational integrator with a fixed step `h`: second
/// order, symplectic, and it conserves the momentum of every symmetry of the
/// Lagrangian (the discrete Noether theorem).
///
/// It integrates the Lagrangian itself rather than `M q̈ = f`, so it needs the
/// model's [`momentum`](Lagrangian::momentum) `∂L/∂q̇`,
/// [`lagrangian_gradient`](Lagrangian::lagrangian_gradient) `∂L/∂q` and
/// [`nonconservative_forces`](Lagrangian::nonconservative_forces) `Q`; models
/// from `lagrangian!` provide all three, and a model without one is refused
/// with [`ModelLacks`](InvalidInput::ModelLacks) before any work.
///
/// # What it conserves, and why
///
/// - **Momenta of symmetries, exactly.** If `L` is invariant under a
///   translation or rotation of the coordinates, so is `L_d`, since the
///   midpoint and the difference quotient transform like `q` and `q̇`. The
///   discrete Noether theorem then makes the discrete momentum map an exact
///   invariant of the discrete flow, not an `O(h²)` approximation. For a
///   cyclic coordinate (`∂L/∂q_i ≡ 0`, `Q_i = 0`) the update
///   `p_{k+1} = p_k + h (∂L/∂q + Q)` leaves `p_i` untouched: it is kept bit
///   for bit, whatever the Newton tolerance. Other symmetries (a rotation in
///   Cartesian coordinates) are kept to the Newton tolerance and rounding.
/// - **Energy, without drift.** The map `(q_k, p_k) ↦ (q_{k+1}, p_{k+1})` is
///   symplectic, so for a conservative, autonomous model the energy error
///   stays bounded, `O(h²)`, over very long times instead of growing like
///   Runge–Kutta's. That argument assumes the same `h` every step: keep the
///   sample spacing a multiple of `h`.
/// - **Forces, to second order.** With [`nonconservative_forces`](Lagrangian::nonconservative_forces),
///   the momenta change by the impulse of `Q` at the midpoint, so a damped
///   system loses energy at the right rate to `O(h²)`.
///
/// # Cost
///
/// One step solves `r(v̄) = 0` for the midpoint velocity `v̄` by Newton's
/// method (see [`max_iterations`](Variational::max_iterations)): one
/// residual at the predictor, one `N × N` Jacobian `∂r/∂v̄` by forward
/// differences of `r` (`N` residuals), then usually two or three iterations
/// of one `N × N` LU solve and one residual each (the last residual, at the
/// solution, also gives `p_{k+1}`). A residual is one call each of
/// `momentum`, `lagrangian_gradient` and `nonconservative_forces`;
/// [`Stats::rhs_evals`] counts residuals, plus the conversions between `q̇`
/// and `p` at the start and at each sample time. Nothing is allocated.
///
/// # Steps, samples and velocities
///
/// Sample times are hit exactly: as in [`Rk4`](crate::Rk4), each interval
/// between consecutive sample times is cut into the fewest equal steps no
/// longer than `h`. A step of another length is still a symplectic,
/// momentum-conserving map of `(q, p)`, so this costs nothing but the
/// constant-`h` energy argument above.
///
/// The state handed in and out is `(q, q̇)`: `p_0 = ∂L/∂q̇(t_0, q_0, q̇_0)`,
/// and at each sample `q̇ = M(t, q)⁻¹ (p − ∂L/∂q̇(t, q, 0))`, exact for any
/// Lagrangian quadratic in `q̇` (those `lagrangian!` derives: `M = ∂²T/∂q̇²`).
///
/// ```
/// use lagrange_runtime::Variational;
///
/// let variational = Variational::new(1e-2).max_iterations(8).max_steps(1_000_000);
/// assert_eq!(variational.step_size(), 1e-2);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Variational<S> {
    h: S,
    max_steps: usize,
    max_iterations: usize,
}

impl<S: RealField + Copy> Variational<S> {
    /// The variational integrator with step `h`, a budget of 10 000 000 steps
    /// and 10 Newton iterations per step.
    ///
    /// `h` is checked when integrating: it must be positive and finite.
    pub fn new(h: S) -> Self {
        Self {
            h,
            max_steps: 10_000_000,
            max_iterations: 10,
        }
    }

    /// The step budget; exceeding it is
    /// [`TooManySteps`](IntegrationError::TooManySteps), so a step size that
    /// is far too small fails instead of running for hours.
    pub fn max_steps(mut self, max_steps: usize) -> Self {
        self.max_steps = max_steps;
        self
    }

    /// Newton iterations allowed per step (at least 1); running out is
    /// [`NewtonDivergence`](IntegrationError::NewtonDivergence). A smooth
    /// problem at a sensible `h` needs two or three, so running out means `h`
    /// is too large for the nonlinearity, or the discrete equations have no
    /// solution at this `h` at all.
    pub fn max_iterations(mut self, max_iterations: usize) -> Self {
        self.max_iterations = max_iterations.max(1);
        self
    }

    /// The step size.
    pub fn step_size(&self) -> S {
        self.h
    }
}

impl<S: RealField + Copy> Integrator<S> for Variational<S> {
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
        let h = self.h;
        if !(h.is_finite() && h > S::zero()) {
            return Err(invalid(InvalidInput::InvalidStepSize { h }));
        }
        let mut rec = Recorder::start(model, t0, &q0, &qdot0, times)?;
        // Refuse a model without the three methods before the first step.
        let p0 = model.momentum(t0, &q0, &qdot0);
        let gradient = model.lagrangian_gradient(t0, &q0, &qdot0);
        let forces = model.nonconservative_forces(t0, &q0, &qdot0);
        let (Some(p0), Some(_), Some(_)) = (p0, gradient, forces) else {
            let needs = match (p0, gradient) {
                (None, _) => "momentum",
                (_, None) => "lagrangian_gradient",
                _ => "nonconservative_forces",
            };
            return Err(invalid(lacks(needs)));
        };
        rec.stats.rhs_evals += 1;
        if !all_finite(&p0) {
            let value = NonFiniteValue::Momentum;
            let (q, qdot) = (q0, qdot0);
            return Err(rec.fail(IntegrationError::NonFiniteState {
                t: t0,
                q,
                qdot,
                value,
            }));
        }

        let (mut t, mut q, mut p) = (t0, q0, p0);
        let mut velocities = VelocityHistory::new(t0, qdot0);
        while let Some(target) = rec.pending() {
            let (start, span) = (t, target - t);
            let steps = steps_to_cover(start, target, h);
            let step = span / nalgebra::convert::<f64, S>(steps as f64);
            if start + step == start {
                let underflow = |qdot| IntegrationError::StepSizeUnderflow {
                    t,
                    h: step,
                    q,
                    qdot,
                };
                return Err(fail_with_velocity(
                    rec,
                    model,
                    (t, q, p),
                    &velocities,
                    underflow,
                ));
            }
            for k in 1..=steps {
                if rec.stats.steps_accepted >= self.max_steps {
                    let max_steps = self.max_steps;
                    let budget = |qdot| IntegrationError::TooManySteps {
                        t,
                        max_steps,
                        q,
                        qdot,
                    };
                    return Err(fail_with_velocity(
                        rec,
                        model,
                        (t, q, p),
                        &velocities,
                        budget,
                    ));
                }
                // Times from the interval start, so rounding does not
                // accumulate in t and the last step lands on the target.
                let t_next = if k == steps {
                    target
                } else {
                    start + step * nalgebra::convert::<f64, S>(k as f64)
                };
                let dt = t_next - t;
                let del = DiscreteEulerLagrange {
                    model,
                    t_mid: t + dt / nalgebra::convert(2.0),
                    q,
                    p,
                    half_h: dt / nalgebra::convert(2.0),
                };
                let guess = velocities.predict(del.t_mid);
                let (v, impulse_rate) = match self.solve(&mut rec.stats, &del, guess) {
                    Ok(solution) => solution,
                    Err(StepFailure::Error(error)) => return Err(rec.fail(error)),
                    Err(StepFailure::Diverged { iterations }) => {
                        let diverged = |qdot| IntegrationError::NewtonDivergence {
                            t,
                            h: dt,
                            iterations,
                            q,
                            qdot,
                        };
                        let state = (t, q, p);
                        return Err(fail_with_velocity(rec, model, state, &velocities, diverged));
                    }
                };
                q += v * dt;
                p += impulse_rate * dt;
                velocities.push(del.t_mid, v);
                t = t_next;
                rec.stats.steps_accepted += 1;
            }
            let qdot = match velocity(&mut rec.stats, model, t, &q, &p, &velocities) {
                Ok(qdot) => qdot,
                Err(error) => return Err(rec.fail(error)),
            };
            while rec.pending() == Some(target) {
                rec.record(target, q, qdot);
            }
        }
        Ok(rec.finish())
    }
}

/// Why a step's Newton iteration stopped.
enum StepFailure<S: RealField + Copy, const N: usize> {
    /// The model failed where the step started, or lacks a method.
    Error(IntegrationError<S, N>),
    /// The iteration limit was reached, the iterates ran off to where the
    /// model is not finite, or the Newton matrix became singular although
    /// `M` is not: the step is too large. The caller adds the state.
    Diverged { iterations: usize },
}

impl<S: RealField + Copy, const N: usize> From<IntegrationError<S, N>> for StepFailure<S, N> {
    fn from(error: IntegrationError<S, N>) -> Self {
        Self::Error(error)
    }
}

impl<S: RealField + Copy> Variational<S> {
    /// Solves `r(v̄) = 0` for the midpoint velocity and returns it with
    /// `∂L/∂q + Q` there, the rate of the momentum update.
    ///
    /// The unknown is `v̄`, not `q_{k+1}`: `v̄ = (q_{k+1} − q_k)/h` would lose
    /// the digits that `q_{k+1}` and `q_k` share (an angle after many turns),
    /// and the momenta, `∝ v̄`, would lose them too.
    ///
    /// Chord Newton: the Jacobian, by forward differences at the predictor,
    /// is kept while the iteration contracts well (`θ ≤ ½`, the usual case:
    /// `∂r/∂v̄ = −M + O(h)` changes with `q̄`, which a correction moves by
    /// only `h/2` times as much) and refreshed when it does not. The
    /// iteration stops when the next correction is estimated at `10 ε` of the
    /// velocities: either the correction itself is that small, or the
    /// contraction `θ` of the last two makes the remaining error
    /// `θ/(1 − θ) |Δv̄|` that small (Hairer & Wanner, IV.8). Tighter is
    /// rounding noise; and a correction that stops contracting (`θ > ½`)
    /// below [`newton_noise_floor`] of the velocities is that noise (an
    /// ill-conditioned `M` puts it far above `10 ε`), so it stops there too.
    fn solve<L: Lagrangian<N, Scalar = S>, const N: usize>(
        &self,
        stats: &mut Stats,
        del: &DiscreteEulerLagrange<'_, L, N>,
        guess: SVector<S, N>,
    ) -> Result<(SVector<S, N>, SVector<S, N>), StepFailure<S, N>> {
        let c = |x: f64| -> S { nalgebra::convert(x) };
        let tol = c(10.0) * epsilon::<S>();
        let mut v = guess;
        // At the predictor a failure is the model's, not Newton's.
        let (mut r, _) = del.residual(stats, &v)?;
        let mut jacobian = Some(del.jacobian(stats, &v, &r)?);
        let mut previous: Option<S> = None;

        for iteration in 1..=self.max_iterations {
            let j = match jacobian {
                Some(j) => j,
                None => {
                    let j = del
                        .jacobian(stats, &v, &r)
                        .map_err(|e| diverged(e, iteration))?;
                    *jacobian.insert(j)
                }
            };
            stats.newton_iterations += 1;
            stats.linear_solves += 1;
            let delta = match lu_solve(j, -r) {
                Ok(delta) => delta,
                Err(_) => return Err(del.singular_newton_matrix(&v, iteration)),
            };
            v += delta;
            let (r_new, rate) = del
                .residual(stats, &v)
                .map_err(|e| diverged(e, iteration))?;
            r = r_new;

            let size = delta.amax();
            let scale = v.amax().max(guess.amax());
            let theta = previous.map(|previous| size / previous);
            let remaining = theta
                .filter(|&theta| theta < S::one())
                .map(|theta| theta / (S::one() - theta) * size);
            if size <= tol * scale || remaining.is_some_and(|e| e <= tol * scale) {
                return Ok((v, rate));
            }
            if theta.is_some_and(|theta| theta > c(0.5)) {
                // Not contracting any more, but below the noise of
                // evaluating the residual: as converged as it gets.
                if size <= newton_noise_floor(del.model, del.t_mid, &del.q) * scale {
                    return Ok((v, rate));
                }
                jacobian = None;
            }
            previous = Some(size);
        }
        Err(StepFailure::Diverged {
            iterations: self.max_iterations,
        })
    }
}

/// `q̇ = M(t, q)⁻¹ (p − ∂L/∂q̇(t, q, 0))`: the velocity with momenta `p`,
/// for a Lagrangian quadratic in `q̇`.
///
/// Errors report the last midpoint velocity as `q̇`, the integrator's best
/// knowledge of it (within `O(h)`).
fn velocity<L: Lagrangian<N>, const N: usize>(
    stats: &mut Stats,
    model: &L,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
    p: &SVector<L::Scalar, N>,
    velocities: &VelocityHistory<L::Scalar, N>,
) -> Result<SVector<L::Scalar, N>, IntegrationError<L::Scalar, N>> {
    stats.rhs_evals += 1;
    let near = velocities.latest();
    let non_finite = |value| IntegrationError::NonFiniteState {
        t,
        q: *q,
        qdot: near,
        value,
    };
    if !all_finite(q) {
        return Err(non_finite(NonFiniteValue::State));
    }
    if !all_finite(p) {
        return Err(non_finite(NonFiniteValue::Momentum));
    }
    let offset = model
        .momentum(t, q, &SVector::zeros())
        .ok_or_else(|| lacks("momentum"))?;
    if !all_finite(&offset) {
        return Err(non_finite(NonFiniteValue::Momentum));
    }
    solve_mass_matrix(&model.mass_matrix(t, q), &(p - offset)).map_err(|err| match err {
        SolveError::NonFiniteMassMatrix => non_finite(NonFiniteValue::MassMatrix),
        SolveError::NonFiniteForcing => non_finite(NonFiniteValue::Momentum),
        SolveError::Singular => IntegrationError::SingularMassMatrix {
            t,
            q: *q,
            qdot: near,
        },
    })
}

/// `error` at `(t, q, p)`, with `q̇` converted from `p` for the report; if
/// even that conversion fails, its own error instead.
fn fail_with_velocity<L: Lagrangian<N>, const N: usize>(
    mut rec: Recorder<'_, L::Scalar, N>,
    model: &L,
    (t, q, p): (L::Scalar, SVector<L::Scalar, N>, SVector<L::Scalar, N>),
    velocities: &VelocityHistory<L::Scalar, N>,
    error: impl FnOnce(SVector<L::Scalar, N>) -> IntegrationError<L::Scalar, N>,
) -> Box<Failure<L::Scalar, N>> {
    match velocity(&mut rec.stats, model, t, &q, &p, velocities) {
        Ok(qdot) => rec.fail(error(qdot)),
        Err(other) => rec.fail(other),
    }
}

/// One step's discrete Euler–Lagrange equation `r(v̄) = 0`, from `(q_k, p_k)`.
struct DiscreteEulerLagrange<'a, L: Lagrangian<N>, const N: usize> {
    model: &'a L,
    /// `t̄ = t_k + h/2`.
    t_mid: L::Scalar,
    q: SVector<L::Scalar, N>,
    p: SVector<L::Scalar, N>,
    half_h: L::Scalar,
}

impl<L: Lagrangian<N>, const N: usize> DiscreteEulerLagrange<'_, L, N> {
    /// `r(v̄) = p_k + (h/2) g − ∂L/∂q̇` and `g = ∂L/∂q + Q`, all at
    /// `(t̄, q_k + (h/2) v̄, v̄)`: one counted residual evaluation.
    #[allow(clippy::type_complexity)]
    fn residual(
        &self,
        stats: &mut Stats,
        v: &SVector<L::Scalar, N>,
    ) -> Result<(SVector<L::Scalar, N>, SVector<L::Scalar, N>), IntegrationError<L::Scalar, N>>
    {
        stats.rhs_evals += 1;
        let (t, q) = (self.t_mid, self.q + v * self.half_h);
        let non_finite = |value| IntegrationError::NonFiniteState {
            t,
            q,
            qdot: *v,
            value,
        };
        if !all_finite(&q) || !all_finite(v) {
            return Err(non_finite(NonFiniteValue::State));
        }
        let momentum = self
            .model
            .momentum(t, &q, v)
            .ok_or_else(|| lacks("momentum"))?;
        if !all_finite(&momentum) {
            return Err(non_finite(NonFiniteValue::Momentum));
        }
        let gradient = self
            .model
            .lagrangian_gradient(t, &q, v)
            .ok_or_else(|| lacks("lagrangian_gradient"))?;
        if !all_finite(&gradient) {
            return Err(non_finite(NonFiniteValue::LagrangianGradient));
        }
        let forces = self
            .model
            .nonconservative_forces(t, &q, v)
            .ok_or_else(|| lacks("nonconservative_forces"))?;
        if !all_finite(&forces) {
            return Err(non_finite(NonFiniteValue::NonconservativeForces));
        }
        let rate = gradient + forces;
        Ok((self.p + rate * self.half_h - momentum, rate))
    }

    /// `∂r/∂v̄` by forward differences of `r` around `v̄`, where `r` is
    /// `r(v̄)`: `N` counted residual evaluations, step `√ε · max(1, |v̄_i|)`
    /// as in [`jacobian`](crate::jacobian). `r` is nearly linear in `v̄`
    /// (`∂r/∂v̄ = −M + O(h)`), so the `√ε` relative error only slows the
    /// chord iteration, never stops it.
    fn jacobian(
        &self,
        stats: &mut Stats,
        v: &SVector<L::Scalar, N>,
        r: &SVector<L::Scalar, N>,
    ) -> Result<SMatrix<L::Scalar, N, N>, IntegrationError<L::Scalar, N>> {
        stats.jacobian_evals += 1;
        let one: L::Scalar = nalgebra::convert(1.0);
        let sqrt_eps = epsilon::<L::Scalar>().sqrt();
        let mut j = SMatrix::<L::Scalar, N, N>::zeros();
        for k in 0..N {
            let mut shifted = *v;
            shifted[k] += sqrt_eps * one.max(v[k].abs());
            let dv = shifted[k] - v[k]; // the step actually taken
            let (r_shifted, _) = self.residual(stats, &shifted)?;
            j.set_column(k, &((r_shifted - r) / dv));
        }
        Ok(j)
    }

    /// The Newton matrix is singular at `v̄`: `M` itself (a coordinate
    /// without inertia), or `−M + O(h)` cancelled by the `O(h)` terms, which
    /// only a step too large can do.
    fn singular_newton_matrix(
        &self,
        v: &SVector<L::Scalar, N>,
        iterations: usize,
    ) -> StepFailure<L::Scalar, N> {
        let (t, q) = (self.t_mid, self.q + v * self.half_h);
        match solve_mass_matrix(&self.model.mass_matrix(t, &q), &SVector::zeros()) {
            Err(SolveError::Singular) => {
                StepFailure::Error(IntegrationError::SingularMassMatrix { t, q, qdot: *v })
            }
            _ => StepFailure::Diverged { iterations },
        }
    }
}

/// After the first iteration a non-finite value means the iterates ran away,
/// which is Newton's failure, not the model's.
fn diverged<S: RealField + Copy, const N: usize>(
    error: IntegrationError<S, N>,
    iterations: usize,
) -> StepFailure<S, N> {
    match error {
        IntegrationError::NonFiniteState { .. } => StepFailure::Diverged { iterations },
        other => StepFailure::Error(other),
    }
}

/// The two latest midpoint velocities (the first is `q̇_0` at `t_0`), for the
/// predictor.
struct VelocityHistory<S, const N: usize> {
    older: Option<(S, SVector<S, N>)>,
    newer: (S, SVector<S, N>),
}

impl<S: RealField + Copy, const N: usize> VelocityHistory<S, N> {
    fn new(t0: S, qdot0: SVector<S, N>) -> Self {
        Self {
            older: None,
            newer: (t0, qdot0),
        }
    }

    fn push(&mut self, t: S, v: SVector<S, N>) {
        self.older = Some(self.newer);
        self.newer = (t, v);
    }

    fn latest(&self) -> SVector<S, N> {
        self.newer.1
    }

    /// The midpoint velocity at `t`, extrapolated linearly from the last two:
    /// `O(h²)` accurate for free, where `q̇_k` (the classic predictor
    /// `q_{k+1} ≈ q_k + h q̇_k`) would cost a solve with `M` and be only
    /// `O(h)` accurate.
    fn predict(&self, t: S) -> SVector<S, N> {
        let (t_b, v_b) = self.newer;
        match self.older {
            Some((t_a, v_a)) => v_b + (v_b - v_a) * ((t - t_b) / (t_b - t_a)),
            None => v_b,
        }
    }
}

fn lacks<S: RealField + Copy>(needs: &'static str) -> InvalidInput<S> {
    InvalidInput::ModelLacks {
        method: "Variational",
        needs,
    }
}

fn epsilon<S: RealField>() -> S {
    S::default_epsilon()
}

fn all_finite<S: RealField + Copy, const N: usize>(x: &SVector<S, N>) -> bool {
    x.iter().all(|x| x.is_finite())
}
