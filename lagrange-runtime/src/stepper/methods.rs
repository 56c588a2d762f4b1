//! Which methods a stepper drives, and how each becomes its work.

use nalgebra::{RealField, SVector};

use super::adaptive::{AdaptiveWork, PairOf};
use super::fixed::{FixedStep, FixedWork};
use super::StepMethod;
use crate::driver::{check_step_size, check_tolerances, Recorder};
use crate::error::{IntegrationError, InvalidInput};
use crate::integrators::{
    euler_step, rk4_step, symplectic_step, Dop853Pair, Dopri5Pair, StageSolver, DOP853_CONTROL,
    DOPRI5_CONTROL,
};
use crate::integrators::{
    Dop853, Dopri5, ExplicitEuler, GaussLegendre, ImplicitMidpoint, Rk4, SymplecticEuler,
};
use crate::model::Lagrangian;
use crate::trajectory::State;

/// A fixed-step method's step, by name: the same function its `integrate`
/// hands to the fixed-step driver.
macro_rules! fixed_methods {
    ($($method:ident => $marker:ident($step:ident)),* $(,)?) => {$(
        #[doc(hidden)]
        pub struct $marker;

        impl<S: RealField + Copy, const N: usize> FixedStep<S, N> for $marker {
            fn step<L: Lagrangian<N, Scalar = S>>(
                &mut self,
                rec: &mut Recorder<'_, S, N>,
                model: &L,
                t: S,
                (q, qdot): (&SVector<S, N>, &SVector<S, N>),
                h: S,
            ) -> Result<State<S, N>, IntegrationError<S, N>> {
                $step(rec, model, t, q, qdot, h)
            }
        }

        impl<S: RealField + Copy, const N: usize> StepMethod<S, N> for $method<S> {
            type Work = FixedWork<S, $marker>;

            fn work(&self) -> Result<Self::Work, InvalidInput<S>> {
                let h = self.step_size();
                check_step_size(h)?;
                Ok(FixedWork {
                    step: $marker,
                    h,
                    max_steps: self.step_budget(),
                    growth: None,
                })
            }
        }
    )*};
}

fixed_methods! {
    ExplicitEuler => EulerStep(euler_step),
    SymplecticEuler => SymplecticStep(symplectic_step),
    Rk4 => Rk4Step(rk4_step),
}

/// The Gauss collocation methods step with the stage solver their
/// `integrate` uses, its workspace allocated once per stepper.
#[doc(hidden)]
pub struct Collocation<S: RealField + Copy, const N: usize>(StageSolver<S, N>);

impl<S: RealField + Copy, const N: usize> FixedStep<S, N> for Collocation<S, N> {
    fn step<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        t: S,
        (q, qdot): (&SVector<S, N>, &SVector<S, N>),
        h: S,
    ) -> Result<State<S, N>, IntegrationError<S, N>> {
        self.0.step(rec, model, t, q, qdot, h)
    }

    fn restart(&mut self) {
        self.0.restart();
    }
}

macro_rules! implicit_methods {
    ($($method:ident => $name:literal),* $(,)?) => {$(
        impl<S: RealField + Copy, const N: usize> StepMethod<S, N> for $method<S> {
            type Work = FixedWork<S, Collocation<S, N>>;

            fn work(&self) -> Result<Self::Work, InvalidInput<S>> {
                let settings = self.settings();
                check_step_size(settings.h)?;
                if settings.max_iterations == 0 {
                    return Err(InvalidInput::NoNewtonIterations { method: $name });
                }
                Ok(FixedWork {
                    step: Collocation(StageSolver::new(self.tableau(), settings.max_iterations)),
                    h: settings.h,
                    max_steps: settings.max_steps,
                    growth: None,
                })
            }
        }
    )*};
}

implicit_methods! {
    ImplicitMidpoint => "ImplicitMidpoint",
    GaussLegendre => "GaussLegendre",
}

/// An adaptive method's pair, by name: the same its `integrate` builds.
macro_rules! adaptive_methods {
    ($($method:ident => $pair:ident, $control:ident, |$m:ident, $qdot:ident, $qddot:ident| $build:expr);* $(;)?) => {$(
        impl<S: RealField + Copy, const N: usize> PairOf<S, N> for $method<S> {
            type Pair = $pair<S, N>;
            fn pair(&self, $qdot: &SVector<S, N>, $qddot: &SVector<S, N>) -> $pair<S, N> {
                let $m = self;
                $build
            }
        }

        impl<S: RealField + Copy, const N: usize> StepMethod<S, N> for $method<S> {
            type Work = AdaptiveWork<S, $method<S>, N>;

            fn work(&self) -> Result<Self::Work, InvalidInput<S>> {
                let settings = self.settings();
                check_tolerances(settings.rtol, settings.atol)?;
                Ok(AdaptiveWork {
                    method: *self,
                    control: &$control,
                    settings,
                    pair: None,
                    h: None,
                    err_old: nalgebra::convert(1e-4),
                    rejected_last: false,
                    growth: None,
                })
            }
        }
    )*};
}

adaptive_methods! {
    Dopri5 => Dopri5Pair, DOPRI5_CONTROL, |m, qdot, qddot| m.pair(qdot, qddot);
    Dop853 => Dop853Pair, DOP853_CONTROL, |m, qdot, qddot| m.pair(qdot, qddot);
}
