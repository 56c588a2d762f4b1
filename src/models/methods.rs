//! Every integrator of the runtime by name, so that a test or a study that
//! runs them all lists them once: a method added here is run everywhere.

use lagrange_runtime::{
    Dop853, Dopri5, Events, ExplicitEuler, GaussLegendre, ImplicitMidpoint, IntegrationResult,
    Integrator, Lagrangian, Radau5, Rk4, SymplecticEuler, Variational,
};
use nalgebra::{RealField, SVector};

/// One of the runtime's integrators, without its settings.
///
/// ```
/// use lagrange::models::{Method, Oscillator};
/// use lagrange::prelude::*;
/// use lagrange::nalgebra::Vector1;
///
/// let spring = Oscillator::new(1.0, 1.0, 0.0);
/// for method in Method::ALL {
///     // Fixed-step methods at h = 0.01, adaptive ones at rtol = atol = 1e-8.
///     let run = method
///         .integrator(0.01, 1e-8)
///         .integrate(&spring, 0.0, Vector1::new(1.0), Vector1::new(0.0), &[1.0])?;
///     // x = cos t; explicit Euler, first order, errs most: ≈ h t / 2.
///     let x = run.last().unwrap().q[0];
///     assert!((x - 1f64.cos()).abs() < 1e-2, "{method:?}");
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// [`ExplicitEuler`].
    ExplicitEuler,
    /// [`SymplecticEuler`].
    SymplecticEuler,
    /// [`Rk4`].
    Rk4,
    /// [`ImplicitMidpoint`]: the one-stage Gauss method.
    ImplicitMidpoint,
    /// [`GaussLegendre::two_stage`].
    GaussLegendre2,
    /// [`GaussLegendre::three_stage`].
    GaussLegendre3,
    /// [`Variational`].
    Variational,
    /// [`Dopri5`].
    Dopri5,
    /// [`Dop853`].
    Dop853,
    /// [`Radau5`].
    Radau5,
}

impl Method {
    /// Every method: the fixed-step ones, then the adaptive ones.
    pub const ALL: [Method; 10] = [
        Method::ExplicitEuler,
        Method::SymplecticEuler,
        Method::Rk4,
        Method::ImplicitMidpoint,
        Method::GaussLegendre2,
        Method::GaussLegendre3,
        Method::Variational,
        Method::Dopri5,
        Method::Dop853,
        Method::Radau5,
    ];

    /// The methods that step by a given `h`.
    pub const FIXED_STEP: [Method; 7] = [
        Method::ExplicitEuler,
        Method::SymplecticEuler,
        Method::Rk4,
        Method::ImplicitMidpoint,
        Method::GaussLegendre2,
        Method::GaussLegendre3,
        Method::Variational,
    ];

    /// The methods that choose their steps to meet a tolerance.
    pub const ADAPTIVE: [Method; 3] = [Method::Dopri5, Method::Dop853, Method::Radau5];

    /// The Gauss collocation methods, one to three stages (order `2s`):
    /// symmetric, and keeping every quadratic invariant.
    pub const GAUSS: [Method; 3] = [
        Method::ImplicitMidpoint,
        Method::GaussLegendre2,
        Method::GaussLegendre3,
    ];

    /// Whether it chooses its own steps.
    pub fn is_adaptive(self) -> bool {
        matches!(self, Method::Dopri5 | Method::Dop853 | Method::Radau5)
    }

    /// The order of its steps.
    pub fn order(self) -> usize {
        match self {
            Method::ExplicitEuler | Method::SymplecticEuler => 1,
            Method::ImplicitMidpoint | Method::Variational => 2,
            Method::Rk4 | Method::GaussLegendre2 => 4,
            Method::Dopri5 | Method::Radau5 => 5,
            Method::GaussLegendre3 => 6,
            Method::Dop853 => 8,
        }
    }

    /// Whether it solves its stages by Newton's method on `M q̈ − f`, with
    /// the model's exact Jacobians or, without them, by differences.
    pub fn uses_jacobians(self) -> bool {
        matches!(
            self,
            Method::ImplicitMidpoint
                | Method::GaussLegendre2
                | Method::GaussLegendre3
                | Method::Radau5
        )
    }

    /// Its name in lower case, as in file names and tables
    /// (`explicit_euler`, `gauss_legendre_2`).
    pub fn id(self) -> &'static str {
        match self {
            Method::ExplicitEuler => "explicit_euler",
            Method::SymplecticEuler => "symplectic_euler",
            Method::Rk4 => "rk4",
            Method::ImplicitMidpoint => "implicit_midpoint",
            Method::GaussLegendre2 => "gauss_legendre_2",
            Method::GaussLegendre3 => "gauss_legendre_3",
            Method::Variational => "variational",
            Method::Dopri5 => "dopri5",
            Method::Dop853 => "dop853",
            Method::Radau5 => "radau5",
        }
    }

    /// The fixed-step methods with step `h`; the adaptive ones at their
    /// default tolerances (they have no step to set).
    pub fn with_step<S: RealField + Copy>(self, h: S) -> AnyIntegrator<S> {
        match self {
            Method::ExplicitEuler => AnyIntegrator::ExplicitEuler(ExplicitEuler::new(h)),
            Method::SymplecticEuler => AnyIntegrator::SymplecticEuler(SymplecticEuler::new(h)),
            Method::Rk4 => AnyIntegrator::Rk4(Rk4::new(h)),
            Method::ImplicitMidpoint => AnyIntegrator::ImplicitMidpoint(ImplicitMidpoint::new(h)),
            Method::GaussLegendre2 => AnyIntegrator::GaussLegendre(GaussLegendre::two_stage(h)),
            Method::GaussLegendre3 => AnyIntegrator::GaussLegendre(GaussLegendre::three_stage(h)),
            Method::Variational => AnyIntegrator::Variational(Variational::new(h)),
            Method::Dopri5 => AnyIntegrator::Dopri5(Dopri5::new()),
            Method::Dop853 => AnyIntegrator::Dop853(Dop853::new()),
            Method::Radau5 => AnyIntegrator::Radau5(Radau5::new()),
        }
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

/// Any of the runtime's integrators with its settings: an [`Integrator`]
/// itself, so that one loop runs them all.
#[derive(Clone, Copy, Debug, PartialEq)]
#[allow(missing_docs)]
pub enum AnyIntegrator<S: RealField + Copy> {
    ExplicitEuler(ExplicitEuler<S>),
    SymplecticEuler(SymplecticEuler<S>),
    Rk4(Rk4<S>),
    ImplicitMidpoint(ImplicitMidpoint<S>),
    GaussLegendre(GaussLegendre<S>),
    Variational(Variational<S>),
    Dopri5(Dopri5<S>),
    Dop853(Dop853<S>),
    Radau5(Radau5<S>),
}

impl<S: RealField + Copy> AnyIntegrator<S> {
    /// The step budget (see each method's `max_steps`).
    pub fn max_steps(self, max_steps: usize) -> Self {
        match self {
            Self::ExplicitEuler(m) => Self::ExplicitEuler(m.max_steps(max_steps)),
            Self::SymplecticEuler(m) => Self::SymplecticEuler(m.max_steps(max_steps)),
            Self::Rk4(m) => Self::Rk4(m.max_steps(max_steps)),
            Self::ImplicitMidpoint(m) => Self::ImplicitMidpoint(m.max_steps(max_steps)),
            Self::GaussLegendre(m) => Self::GaussLegendre(m.max_steps(max_steps)),
            Self::Variational(m) => Self::Variational(m.max_steps(max_steps)),
            Self::Dopri5(m) => Self::Dopri5(m.max_steps(max_steps)),
            Self::Dop853(m) => Self::Dop853(m.max_steps(max_steps)),
            Self::Radau5(m) => Self::Radau5(m.max_steps(max_steps)),
        }
    }

    /// The tolerances of an adaptive method; a fixed-step one has none and
    /// is returned unchanged.
    pub fn tolerances(self, rtol: S, atol: S) -> Self {
        match self {
            Self::Dopri5(m) => Self::Dopri5(m.rtol(rtol).atol(atol)),
            Self::Dop853(m) => Self::Dop853(m.rtol(rtol).atol(atol)),
            Self::Radau5(m) => Self::Radau5(m.rtol(rtol).atol(atol)),
            fixed => fixed,
        }
    }
}

impl<S: RealField + Copy> Integrator<S> for AnyIntegrator<S> {
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
        let e = events;
        match self {
            Self::ExplicitEuler(m) => m.integrate_with_events(model, t0, q0, qdot0, times, e),
            Self::SymplecticEuler(m) => m.integrate_with_events(model, t0, q0, qdot0, times, e),
            Self::Rk4(m) => m.integrate_with_events(model, t0, q0, qdot0, times, e),
            Self::ImplicitMidpoint(m) => m.integrate_with_events(model, t0, q0, qdot0, times, e),
            Self::GaussLegendre(m) => m.integrate_with_events(model, t0, q0, qdot0, times, e),
            Self::Variational(m) => m.integrate_with_events(model, t0, q0, qdot0, times, e),
            Self::Dopri5(m) => m.integrate_with_events(model, t0, q0, qdot0, times, e),
            Self::Dop853(m) => m.integrate_with_events(model, t0, q0, qdot0, times, e),
            Self::Radau5(m) => m.integrate_with_events(model, t0, q0, qdot0, times, e),
        }
    }
}
