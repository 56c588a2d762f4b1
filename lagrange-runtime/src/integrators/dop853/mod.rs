//! Dormand–Prince 8(5,3): adaptive explicit Runge–Kutta of order eight with
//! dense output of order seven.
//!
//! Follows Hairer's DOP853 (Hairer, Nørsett & Wanner, *Solving Ordinary
//! Differential Equations I*, §II.5 and §II.10, and the Fortran code
//! `dop853.f`): the same twelve-stage tableau, the error estimate that blends
//! a fifth- and a third-order estimator, the step-size control with its
//! default constants, the initial step guess (`hinit`) and the continuous
//! extension `contd8` with its three extra stages. The coefficients live in
//! `tableau.rs`, the stages in the working precision in `stages.rs`, the
//! continuous extension in `dense.rs`.

use nalgebra::{RealField, SVector};

use super::StepMethod;
use super::stages::pair_settings;
use crate::driver::Recorder;
use crate::driver::check_tolerances;
use crate::driver::pair::{Controller, Embedded, EmbeddedPair, Outcome, PairWalk, Tolerances};
use crate::error::{IntegrationError, InvalidInput, NonFiniteValue};
use crate::model::Lagrangian;
use crate::trajectory::State;
use dense::Dense;
use stages::{Stages, Step, Tableau};

mod dense;
mod stages;
mod tableau;

/// Dormand–Prince 8(5,3) with adaptive steps: the method for tight
/// tolerances.
///
/// Each step costs twelve right-hand sides (eleven stages and `f` at the new
/// state, which is the next step's first stage); a rejected step costs
/// eleven. Because the controlled error falls as `h⁸`, halving the
/// tolerance shrinks the steps by only 8 % (`2^(-1/8)`), against 13 % for
/// [`Dopri5`](crate::integrators::Dopri5): at tight tolerances it needs markedly fewer
/// evaluations for the same accuracy (at `rtol = 1e-12`, 6× fewer on a
/// harmonic oscillator, 2× fewer on a double pendulum), while at loose ones
/// its twelve stages can cost more (1.3× Dopri5's evaluations on the
/// pendulum at `1e-6`). Reach for it below about `1e-9`.
///
/// The local error is estimated as in Hairer's code, from a fifth-order
/// estimate `err5` and a third-order one `err3` (RMS over `q` and `q̇`,
/// relative to `atol + rtol |y|` componentwise):
/// `err = err5² / √(err5² + 0.01 err3²)`. For small steps this behaves like
/// `h⁸`, as the error of the propagated eighth-order solution does, so the
/// steps are not cut to what a fifth-order method would need; for large
/// ones, where `err3` no longer dominates, it is the plain, cautious
/// fifth-order estimate.
///
/// Sample times never shorten a step: the state between steps comes from
/// the seventh-order continuous extension, which costs three more
/// right-hand sides on each step that has a sample strictly inside it. The
/// steps, and so the final state, do not depend on the sample times; the
/// evaluation count does.
///
/// A stage where the model cannot be evaluated (singular `M`, NaN) rejects
/// the step and retries with a third of the step size, so a model that
/// breaks down at `t*` is integrated up to `t*` and the error is reported
/// there, within rounding.
///
/// ```
/// use lagrange_runtime::Dop853;
///
/// let tight = Dop853::new().rtol(1e-12).atol(1e-12).max_steps(1_000_000);
/// # let _: Dop853<f64> = tight;
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dop853<S> {
    settings: Tolerances<S>,
}

pair_settings!(
    Dop853,
    "The same defaults as [`Dopri5`](crate::integrators::Dopri5), so that swapping the method keeps the accuracy: `rtol = atol = 1e-8`, raised to `100 ε` for scalar types with fewer digits (`1.2e-5` for `f32`), and a budget of 100 000 steps (DOP853's `NMAX`)."
);

/// DOP853's step-size controller defaults (`WORK(2)`–`WORK(5)` of
/// `dop853.f`): `fac_min` is Hairer's 0.333, and there is no Lund
/// stabilization by default (`BETA = 0`), a pure I-controller with exponent
/// 1/8; `β` is kept so the formula reads as Hairer's.
const CONTROL: Controller = Controller {
    safety: 0.9,
    fac_min: 0.333,
    fac_max: 6.0,
    beta: 0.0,
    exponent: 1.0 / 8.0,
    beta_weight: 0.2,
    order: 8,
    stretch: 1.01,
};

impl<S: RealField + Copy> StepMethod<S> for Dop853<S> {
    type Walker<const N: usize> = PairWalk<S, Self, N>;

    fn walker<const N: usize>(&self) -> Result<Self::Walker<N>, InvalidInput<S>> {
        check_tolerances(self.settings.rtol, self.settings.atol)?;
        Ok(PairWalk::new(*self))
    }
}

impl<S: RealField + Copy, const N: usize> Embedded<S, N> for Dop853<S> {
    type Pair = Pair<S, N>;
    const CONTROL: Controller = CONTROL;

    fn tolerances(&self) -> Tolerances<S> {
        self.settings
    }

    /// The pair for one run (or one [`Stepper`](crate::stepper::Stepper))
    /// from `(q̇, q̈)` at its start.
    fn pair(&self, qdot: &SVector<S, N>, qddot: &SVector<S, N>) -> Pair<S, N> {
        Pair {
            tab: Tableau::new(),
            rtol: self.settings.rtol,
            atol: self.settings.atol,
            k: Stages::new(qdot, qddot),
        }
    }
}

/// One integration's tableau, tolerances and slopes; stage 1 of `k` is `f`
/// at the current state.
pub struct Pair<S, const N: usize> {
    tab: Tableau<S>,
    rtol: S,
    atol: S,
    k: Stages<S, N>,
}

impl<S: RealField + Copy, const N: usize> EmbeddedPair<S, N> for Pair<S, N> {
    type Step = Step<S, N>;
    type Dense = Dense<S, N>;

    /// Attempts a step of size `h` from `(t, q, q̇)`, with `q̈` there in
    /// stage 1 of `k`, to `t_new`: eleven right-hand sides for the stages;
    /// if the error test passes, one more at the new state (stage 13), and
    /// three more (stages 14–16) for the dense output if a sample lies
    /// strictly inside the step, or on every step while events are watched.
    fn attempt<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        (t, t_new, h): (S, S, S),
        (q, qdot): (&SVector<S, N>, &SVector<S, N>),
    ) -> Result<Outcome<S, Step<S, N>>, IntegrationError<S, N>> {
        let (tab, k) = (&self.tab, &mut self.k);
        let step = tab.step(rec, model, (t, h), (q, qdot), k)?;
        let err = self.error_norm(h, q, qdot, &step);
        if !err.is_finite() {
            // Finite stages, infinite error: an overflow in the sums.
            return Err(IntegrationError::NonFiniteState {
                t: t_new,
                q: step.q,
                qdot: step.qdot,
                value: NonFiniteValue::State,
            });
        }
        if err > S::one() {
            return Ok(Outcome::Rejected { err });
        }
        // f at the new state: stage 13 of the dense output, and the next
        // step's first stage. Evaluating it here, before accepting, means a
        // model that breaks down at the new state rejects the step.
        let k = &mut self.k;
        k.qdot[12] = rec.rhs(model, t_new, &step.q, &step.qdot)?;
        k.q[12] = step.qdot;
        // Events are located on the dense output of every step.
        if rec.pending().is_some_and(|ts| ts < t_new) || rec.watching() {
            self.tab.stages(rec, model, (t, h), (q, qdot), 13..16, k)?;
        }
        Ok(Outcome::Accepted { step, err })
    }

    fn end(step: &Step<S, N>) -> State<S, N> {
        (step.q, step.qdot)
    }

    fn dense(
        &self,
        h: S,
        state: (&SVector<S, N>, &SVector<S, N>),
        step: &Step<S, N>,
    ) -> Dense<S, N> {
        Dense::new(h, state, step, &self.k)
    }

    fn dense_at(dense: &Dense<S, N>, theta: S) -> State<S, N> {
        dense.at(theta)
    }

    /// Stage 13 of the accepted step is the next step's stage 1.
    fn advance(&mut self, _: &Step<S, N>) {
        self.k.first_same_as_last(12);
    }
}

impl<S: RealField + Copy, const N: usize> Pair<S, N> {
    /// Hairer's blended estimate: with `err5`, `err3` the RMS of the fifth-
    /// and third-order estimates relative to `atol + rtol max(|y_old|,
    /// |y_new|)`, `err = h err5² / √(err5² + 0.01 err3²)` (see [`Dop853`]),
    /// computed as in `dop853.f`.
    fn error_norm(&self, h: S, q: &SVector<S, N>, qdot: &SVector<S, N>, step: &Step<S, N>) -> S {
        let (mut sum5, mut sum3) = (S::zero(), S::zero());
        let parts = [
            (q, &step.q, &step.err5.0, &step.err3.0),
            (qdot, &step.qdot, &step.err5.1, &step.err3.1),
        ];
        for (y0, y1, e5, e3) in parts {
            for i in 0..N {
                let sk = self.atol + self.rtol * y0[i].abs().max(y1[i].abs());
                sum5 += (e5[i] / sk).powi(2);
                sum3 += (e3[i] / sk).powi(2);
            }
        }
        let mut deno = sum5 + nalgebra::convert::<f64, S>(0.01) * sum3;
        if deno <= S::zero() {
            deno = S::one();
        }
        let n: S = nalgebra::convert((2 * N).max(1) as f64);
        h.abs() * sum5 * (S::one() / (n * deno)).sqrt()
    }
}

/// The stepping code with the step control taken out: fixed steps show the
/// orders of the solution and of the continuous extension directly.
#[cfg(test)]
mod tests {
    use nalgebra::{Matrix2, Vector2};

    use super::*;

    /// A double pendulum with unit masses and rods, its upper joint driven by
    /// a torque `cos 3t`: nonlinear, `M(q)`, forcing quadratic in `q̇` and
    /// explicitly time-dependent, so a wrong stage time shows too.
    struct DoublePendulum;

    const G: f64 = 9.81;

    impl Lagrangian<2> for DoublePendulum {
        type Scalar = f64;
        const COORDINATES: [&'static str; 2] = ["theta1", "theta2"];
        fn mass_matrix(&self, _t: f64, q: &Vector2<f64>) -> Matrix2<f64> {
            let c = (q[0] - q[1]).cos();
            Matrix2::new(2.0, c, c, 1.0)
        }
        fn forcing(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Vector2<f64> {
            let s = (q[0] - q[1]).sin();
            Vector2::new(
                -s * qd[1] * qd[1] - 2.0 * G * q[0].sin() + (3.0 * t).cos(),
                s * qd[0] * qd[0] - G * q[1].sin(),
            )
        }
        fn kinetic_energy(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> f64 {
            0.5 * (qd.transpose() * self.mass_matrix(t, q) * qd)[0]
        }
        fn potential_energy(&self, _t: f64, q: &Vector2<f64>) -> f64 {
            -2.0 * G * q[0].cos() - G * q[1].cos()
        }
    }

    type State = (Vector2<f64>, Vector2<f64>);

    /// `steps` fixed steps of `h` from t = 0: the final state, and the dense
    /// output half-way through the last step.
    fn fixed_steps(h: f64, steps: usize) -> (State, State) {
        let (tab, model) = (Tableau::<f64>::new(), DoublePendulum);
        let (mut q, mut qdot) = (Vector2::new(0.5, -0.3), Vector2::new(0.0, 0.4));
        let (mut rec, _) = Recorder::start(&model, 0.0, &q, &qdot, &[]).unwrap();
        let (mut t, mut mid) = (0.0, (q, qdot));
        for _ in 0..steps {
            let qddot = rec.rhs(&model, t, &q, &qdot).unwrap();
            let mut k = Stages::new(&qdot, &qddot);
            let step = tab
                .step(&mut rec, &model, (t, h), (&q, &qdot), &mut k)
                .unwrap();
            k.qdot[12] = rec.rhs(&model, t + h, &step.q, &step.qdot).unwrap();
            k.q[12] = step.qdot;
            tab.stages(&mut rec, &model, (t, h), (&q, &qdot), 13..16, &mut k)
                .unwrap();
            mid = Dense::new(h, (&q, &qdot), &step, &k).at(0.5);
            (q, qdot, t) = (step.q, step.qdot, t + h);
        }
        ((q, qdot), mid)
    }

    fn distance(a: State, b: State) -> f64 {
        (a.0 - b.0).amax().max((a.1 - b.1).amax())
    }

    /// 2048 steps of 1/2048: its own error (~1e-12 · 64⁻⁸) is far below
    /// rounding, a few 1e-15.
    fn reference_at(steps_of_1_over_2048: usize) -> State {
        fixed_steps(1.0 / 2048.0, steps_of_1_over_2048).0
    }

    // Both tests halve h from 1/16 to 1/64, where the errors (1e-7 … 1e-12)
    // are far above rounding and in the asymptotic range: each halving
    // gains 2^8.3 … 2^9 here. Requiring 2^7.5 accepts order 8 with room for
    // the next term and rejects anything of order 7 or less.
    const MIN_GAIN: f64 = 181.0; // 2^7.5

    #[test]
    fn fixed_steps_are_eighth_order_on_a_nonlinear_model() {
        let reference = reference_at(2048);
        let errors: Vec<f64> = [16, 32, 64]
            .map(|k| distance(fixed_steps(1.0 / k as f64, k).0, reference))
            .to_vec();
        for pair in errors.windows(2) {
            assert!(pair[0] / pair[1] > MIN_GAIN, "errors at t = 1: {errors:?}");
        }
    }

    #[test]
    fn continuous_extension_is_seventh_order_mid_step() {
        // Its local error is O(h⁸): the same gain per halving half-way
        // through the last step, at t = 1 − h/2.
        let errors: Vec<f64> = [16, 32, 64]
            .map(|k| {
                distance(
                    fixed_steps(1.0 / k as f64, k).1,
                    reference_at(2048 - 1024 / k),
                )
            })
            .to_vec();
        for pair in errors.windows(2) {
            assert!(
                pair[0] / pair[1] > MIN_GAIN,
                "errors at t = 1 - h/2: {errors:?}"
            );
        }
    }
}
