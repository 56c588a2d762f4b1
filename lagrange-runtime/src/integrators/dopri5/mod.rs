//! Dormand–Prince 5(4): adaptive explicit Runge–Kutta with dense output.
//!
//! Follows Hairer's DOPRI5 (Hairer, Nørsett & Wanner, *Solving Ordinary
//! Differential Equations I*, §II.4–II.6, and the Fortran code `dopri5.f`):
//! the same tableau, error norm, initial step guess (`hinit`), stabilized
//! step-size control and continuous extension.

use nalgebra::{RealField, SVector};

use super::StepMethod;
use crate::driver::Recorder;
use crate::driver::check_tolerances;
use crate::driver::pair::{Controller, Embedded, EmbeddedPair, Outcome, PairWalk, Tolerances};
use crate::error::{IntegrationError, InvalidInput};
use crate::integrators::stages::{Step, pair_settings};
use crate::model::Lagrangian;
use crate::trajectory::State;
use tableau::{Dense, Stages, Tableau};

pub(crate) mod tableau;

/// Dormand–Prince 5(4) with adaptive steps: the default method.
///
/// Each step costs six right-hand sides (the seventh is reused as the first
/// of the next step, "FSAL"). The local error of the fourth-order embedded
/// solution is kept below `atol + rtol |y|` componentwise (RMS over `q` and
/// `q̇`), and the fifth-order solution is propagated.
///
/// Sample times never shorten a step: the state between steps comes from the
/// fourth-order continuous extension, so asking for 10 or 10 000 samples
/// takes the same steps and gives the same final state.
///
/// A stage where the model cannot be evaluated (singular `M`, NaN) rejects
/// the step and retries with a fifth of the step size, so a model that
/// breaks down at `t*` is integrated up to `t*` and the error is reported
/// there, within rounding.
///
/// ```
/// use lagrange_runtime::Dopri5;
///
/// let tight = Dopri5::new().rtol(1e-10).atol(1e-12).max_steps(1_000_000);
/// # let _: Dopri5<f64> = tight;
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dopri5<S> {
    settings: Tolerances<S>,
}

pair_settings!(
    Dopri5,
    "Defaults: `rtol = atol = 1e-8`, raised to `100 ε` for scalar types with fewer digits (`1.2e-5` for `f32`), and a budget of 100 000 steps (DOPRI5's `NMAX`)."
);

/// DOPRI5's step-size controller: its defaults, with Lund stabilization
/// (`β = 0.04`).
const CONTROL: Controller = Controller {
    safety: 0.9,
    fac_min: 0.2,
    fac_max: 10.0,
    beta: 0.04,
    exponent: 0.2,
    beta_weight: 0.75,
    order: 5,
    stretch: 1.01,
};

impl<S: RealField + Copy> StepMethod<S> for Dopri5<S> {
    type Walker<const N: usize> = PairWalk<S, Self, N>;

    fn walker<const N: usize>(&self) -> Result<Self::Walker<N>, InvalidInput<S>> {
        check_tolerances(self.settings.rtol, self.settings.atol)?;
        Ok(PairWalk::new(*self))
    }
}

impl<S: RealField + Copy, const N: usize> Embedded<S, N> for Dopri5<S> {
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

/// One integration's tableau, tolerances, and the stages of the last
/// step attempted (the first holds `q̈` at the current state: the last
/// stage of the previous step, first same as last).
pub struct Pair<S, const N: usize> {
    tab: Tableau<S>,
    rtol: S,
    atol: S,
    k: Stages<S, N>,
}

impl<S: RealField + Copy, const N: usize> EmbeddedPair<S, N> for Pair<S, N> {
    type Step = Step<S, N>;
    type Dense = Dense<S, N>;

    /// Six right-hand sides; the step is rejected when the error exceeds
    /// the tolerance.
    fn attempt<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        (t, t_new, h): (S, S, S),
        (q, qdot): (&SVector<S, N>, &SVector<S, N>),
    ) -> Result<Outcome<S, Step<S, N>>, IntegrationError<S, N>> {
        let step = self
            .tab
            .step(rec, model, (t, t_new, h), (q, qdot), &mut self.k)?;
        step.judge((self.rtol, self.atol), (q, qdot), t_new)
    }

    fn end(step: &Step<S, N>) -> State<S, N> {
        (step.q, step.qdot)
    }

    fn dense(
        &self,
        h: S,
        (q, qdot): (&SVector<S, N>, &SVector<S, N>),
        step: &Step<S, N>,
    ) -> Dense<S, N> {
        Dense::new(h, q, qdot, step, &self.k)
    }

    fn dense_at(dense: &Dense<S, N>, theta: S) -> State<S, N> {
        dense.at(theta)
    }

    fn advance(&mut self, _: &Step<S, N>) {
        self.k.first_same_as_last(6);
    }
}
