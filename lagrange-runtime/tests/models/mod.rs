//! Hand-written models of the runtime's tests, each chosen for a known
//! exact solution, a hand-derived Jacobian or a known way of breaking, and
//! written without the macro where that is the point. Problems that are
//! only needed as such (Kepler, the pendulums, the damped oscillator) are
//! the shared ones of `lagrange::models`.
#![allow(dead_code)]

use lagrange::models::Method;
use lagrange_runtime::nalgebra::{Matrix2, RealField, SMatrix, SVector, Vector1, Vector2};
use lagrange_runtime::Lagrangian;

/// Two coordinates with a full, symmetric mass matrix `M = [[2, 1], [1, 2]]`
/// and stiffness `ω² M`, so `q̈ = -ω² q` exactly while the integrators still
/// have to solve a coupled `M q̈ = f`.
pub struct CoupledOscillator<S> {
    pub omega: S,
}

impl<S: RealField + Copy> CoupledOscillator<S> {
    fn mass() -> Matrix2<S> {
        let (one, two) = (S::one(), S::one() + S::one());
        Matrix2::new(two, one, one, two)
    }

    /// The exact state at `t` from `(q0, q̇0)` at `t = 0`.
    pub fn exact(&self, t: S, q0: Vector2<S>, qdot0: Vector2<S>) -> (Vector2<S>, Vector2<S>) {
        let (w, (s, c)) = (self.omega, (self.omega * t).sin_cos());
        (q0 * c + qdot0 * (s / w), qdot0 * c - q0 * (w * s))
    }
}

impl<S: RealField + Copy> Lagrangian<2> for CoupledOscillator<S> {
    type Scalar = S;
    const COORDINATES: [&'static str; 2] = ["x", "y"];

    fn mass_matrix(&self, _t: S, _q: &Vector2<S>) -> Matrix2<S> {
        Self::mass()
    }
    fn forcing(&self, _t: S, q: &Vector2<S>, _qdot: &Vector2<S>) -> Vector2<S> {
        Self::mass() * q * -(self.omega * self.omega)
    }
    fn kinetic_energy(&self, _t: S, _q: &Vector2<S>, qdot: &Vector2<S>) -> S {
        (qdot.transpose() * Self::mass() * qdot)[0] / (S::one() + S::one())
    }
    fn potential_energy(&self, _t: S, q: &Vector2<S>) -> S {
        (q.transpose() * Self::mass() * q)[0] * self.omega * self.omega / (S::one() + S::one())
    }
    fn parameters_are_finite(&self) -> bool {
        self.omega.is_finite()
    }
}

/// A pendulum (bob `m_p`, rod `l`) hanging from a cart (`m_c`) that slides
/// freely along `x`; `θ` from the downward vertical. The mass matrix
///
/// ```text
/// M(θ) = [[m_c + m_p,     m_p l cos θ],
///         [m_p l cos θ,   m_p l²     ]]
/// ```
///
/// depends on the configuration, so the Hamiltonian is not separable.
/// `T` is quadratic in `q̇` and nothing depends on `t`: the system is
/// reversible under `q̇ → −q̇` and conserves energy; `x` is cyclic, so it is
/// integrable (one degree of freedom once `p_x` is fixed).
///
/// With `exact_jacobians` it provides `residual_jacobians`, derived by hand.
pub struct CartPole {
    pub m_cart: f64,
    pub m_bob: f64,
    pub l: f64,
    pub g: f64,
    pub exact_jacobians: bool,
}

impl CartPole {
    /// Unit masses and rod, Earth's gravity.
    pub fn new(exact_jacobians: bool) -> Self {
        Self {
            m_cart: 1.0,
            m_bob: 1.0,
            l: 1.0,
            g: 9.81,
            exact_jacobians,
        }
    }
}

impl Lagrangian<2> for CartPole {
    type Scalar = f64;
    const COORDINATES: [&'static str; 2] = ["x", "theta"];

    fn mass_matrix(&self, _t: f64, q: &Vector2<f64>) -> Matrix2<f64> {
        let coupling = self.m_bob * self.l * q[1].cos();
        Matrix2::new(
            self.m_cart + self.m_bob,
            coupling,
            coupling,
            self.m_bob * self.l * self.l,
        )
    }
    fn forcing(&self, _t: f64, q: &Vector2<f64>, qdot: &Vector2<f64>) -> Vector2<f64> {
        let (s, ml) = (q[1].sin(), self.m_bob * self.l);
        Vector2::new(ml * s * qdot[1] * qdot[1], -ml * self.g * s)
    }
    fn kinetic_energy(&self, t: f64, q: &Vector2<f64>, qdot: &Vector2<f64>) -> f64 {
        0.5 * (qdot.transpose() * self.mass_matrix(t, q) * qdot)[0]
    }
    fn potential_energy(&self, _t: f64, q: &Vector2<f64>) -> f64 {
        -self.m_bob * self.g * self.l * q[1].cos()
    }
    /// `r = M q̈ − f`: only `θ` and `θ̇` appear in it.
    fn residual_jacobians(
        &self,
        _t: f64,
        q: &Vector2<f64>,
        qdot: &Vector2<f64>,
        qddot: &Vector2<f64>,
    ) -> Option<(Matrix2<f64>, Matrix2<f64>)> {
        if !self.exact_jacobians {
            return None;
        }
        let ((s, c), ml) = (q[1].sin_cos(), self.m_bob * self.l);
        let dr_dtheta = Vector2::new(
            -ml * s * qddot[1] - ml * c * qdot[1] * qdot[1],
            -ml * s * qddot[0] + ml * self.g * c,
        );
        let dr_dq = Matrix2::from_columns(&[Vector2::zeros(), dr_dtheta]);
        let dr_dthetadot = Vector2::new(-2.0 * ml * s * qdot[1], 0.0);
        let dr_dqdot = Matrix2::from_columns(&[Vector2::zeros(), dr_dthetadot]);
        Some((dr_dq, dr_dqdot))
    }
}

/// The stages `s` of a Gauss method (order `2s`): the right-hand sides each
/// Newton iteration evaluates.
pub fn stages(method: Method) -> usize {
    assert!(
        Method::GAUSS.contains(&method),
        "{method:?} is no Gauss method"
    );
    method.order() / 2
}

/// Two unit springs; the second mass vanishes at `t_s` (its row of `M`
/// becomes zero), so `M q̈ = f` stops determining `ÿ` there.
pub struct InertiaVanishes {
    pub t_s: f64,
}

impl Lagrangian<2> for InertiaVanishes {
    type Scalar = f64;
    const COORDINATES: [&'static str; 2] = ["x", "y"];

    fn mass_matrix(&self, t: f64, _q: &Vector2<f64>) -> Matrix2<f64> {
        Matrix2::new(1.0, 0.0, 0.0, if t < self.t_s { 1.0 } else { 0.0 })
    }
    fn forcing(&self, _t: f64, q: &Vector2<f64>, _qdot: &Vector2<f64>) -> Vector2<f64> {
        -q
    }
    fn kinetic_energy(&self, t: f64, q: &Vector2<f64>, qdot: &Vector2<f64>) -> f64 {
        0.5 * (qdot.transpose() * self.mass_matrix(t, q) * qdot)[0]
    }
    fn potential_energy(&self, _t: f64, q: &Vector2<f64>) -> f64 {
        0.5 * q.norm_squared()
    }
}

/// A unit spring whose forcing returns NaN after `t_star`, as a model with a
/// `sqrt` of a quantity that turns negative would.
pub struct ForcingBreaksDown {
    pub t_star: f64,
}

impl Lagrangian<1> for ForcingBreaksDown {
    type Scalar = f64;
    const COORDINATES: [&'static str; 1] = ["x"];

    fn mass_matrix(&self, _t: f64, _q: &Vector1<f64>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(1.0)
    }
    fn forcing(&self, t: f64, q: &Vector1<f64>, _qdot: &Vector1<f64>) -> Vector1<f64> {
        Vector1::new(-q[0] + (self.t_star - t).min(0.0).sqrt())
    }
    fn kinetic_energy(&self, _t: f64, _q: &Vector1<f64>, qdot: &Vector1<f64>) -> f64 {
        0.5 * qdot[0] * qdot[0]
    }
    fn potential_energy(&self, _t: f64, q: &Vector1<f64>) -> f64 {
        0.5 * q[0] * q[0]
    }
}

/// `q̈ = 2 q³` from `q = q̇ = 1`: the solution `q = 1 / (1 - t)` reaches
/// infinity at `t = 1`, in finite time.
pub struct BlowUp;

impl Lagrangian<1> for BlowUp {
    type Scalar = f64;
    const COORDINATES: [&'static str; 1] = ["q"];

    fn mass_matrix(&self, _t: f64, _q: &Vector1<f64>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(1.0)
    }
    fn forcing(&self, _t: f64, q: &Vector1<f64>, _qdot: &Vector1<f64>) -> Vector1<f64> {
        Vector1::new(2.0 * q[0].powi(3))
    }
    fn kinetic_energy(&self, _t: f64, _q: &Vector1<f64>, qdot: &Vector1<f64>) -> f64 {
        0.5 * qdot[0] * qdot[0]
    }
    fn potential_energy(&self, _t: f64, q: &Vector1<f64>) -> f64 {
        -0.5 * q[0].powi(4)
    }
}

/// Largest `|state - exact|` (max norm over `q` and `q̇`) over a trajectory of
/// the coupled oscillator started at `(q0, q̇0)` at `t = 0`.
pub fn max_error<S: RealField + Copy>(
    model: &CoupledOscillator<S>,
    trajectory: &lagrange_runtime::Trajectory<S, 2>,
    q0: SVector<S, 2>,
    qdot0: SVector<S, 2>,
) -> S {
    trajectory.iter().fold(S::zero(), |worst, s| {
        let (q, qdot) = model.exact(s.t, q0, qdot0);
        worst.max((s.q - q).amax()).max((s.qdot - qdot).amax())
    })
}

/// `q̈ = e^q` (`L = ½ q̇² + e^q`): pushed ever harder the further it goes.
/// For a step `h` the discrete Euler–Lagrange residual
/// `r(v) = p − v + (h/2) e^{q + h v/2}` is convex in `v` with minimum
/// `p + (2/h)(1 + ln(h²/4) + q)`, positive for a large enough `h`: then the
/// discrete equations have no solution at all.
pub struct ExponentialWell;

impl Lagrangian<1> for ExponentialWell {
    type Scalar = f64;
    const COORDINATES: [&'static str; 1] = ["q"];

    fn mass_matrix(&self, _t: f64, _q: &Vector1<f64>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(1.0)
    }
    fn forcing(&self, _t: f64, q: &Vector1<f64>, _qdot: &Vector1<f64>) -> Vector1<f64> {
        Vector1::new(q[0].exp())
    }
    fn kinetic_energy(&self, _t: f64, _q: &Vector1<f64>, qdot: &Vector1<f64>) -> f64 {
        0.5 * qdot[0] * qdot[0]
    }
    fn potential_energy(&self, _t: f64, q: &Vector1<f64>) -> f64 {
        -q[0].exp()
    }
    fn momentum(&self, _t: f64, _q: &Vector1<f64>, qdot: &Vector1<f64>) -> Option<Vector1<f64>> {
        Some(*qdot)
    }
    fn lagrangian_gradient(
        &self,
        _t: f64,
        q: &Vector1<f64>,
        _qdot: &Vector1<f64>,
    ) -> Option<Vector1<f64>> {
        Some(Vector1::new(q[0].exp()))
    }
    fn nonconservative_forces(
        &self,
        _t: f64,
        _q: &Vector1<f64>,
        _qdot: &Vector1<f64>,
    ) -> Option<Vector1<f64>> {
        Some(Vector1::zeros())
    }
}

/// `inner` with some of the optional variational methods hidden, as a
/// hand-written model that skipped them would be.
pub struct Without<M> {
    pub inner: M,
    pub lacks_momentum: bool,
    pub lacks_gradient: bool,
    pub lacks_forces: bool,
}

impl<M: Lagrangian<N>, const N: usize> Lagrangian<N> for Without<M> {
    type Scalar = M::Scalar;
    const COORDINATES: [&'static str; N] = M::COORDINATES;

    fn mass_matrix(&self, t: M::Scalar, q: &SVector<M::Scalar, N>) -> SMatrix<M::Scalar, N, N> {
        self.inner.mass_matrix(t, q)
    }
    fn forcing(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> SVector<M::Scalar, N> {
        self.inner.forcing(t, q, qdot)
    }
    fn kinetic_energy(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> M::Scalar {
        self.inner.kinetic_energy(t, q, qdot)
    }
    fn potential_energy(&self, t: M::Scalar, q: &SVector<M::Scalar, N>) -> M::Scalar {
        self.inner.potential_energy(t, q)
    }
    fn momentum(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> Option<SVector<M::Scalar, N>> {
        self.inner
            .momentum(t, q, qdot)
            .filter(|_| !self.lacks_momentum)
    }
    fn lagrangian_gradient(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> Option<SVector<M::Scalar, N>> {
        self.inner
            .lagrangian_gradient(t, q, qdot)
            .filter(|_| !self.lacks_gradient)
    }
    fn nonconservative_forces(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> Option<SVector<M::Scalar, N>> {
        self.inner
            .nonconservative_forces(t, q, qdot)
            .filter(|_| !self.lacks_forces)
    }
}

/// A unit spring shaken by a force in the Lagrangian itself:
/// `L = ½ ẋ² − ½ x² + F x cos(Ω t)`, explicitly time dependent.
pub struct DrivenOscillator {
    pub force: f64,
    pub omega: f64,
}

impl DrivenOscillator {
    /// The exact `(x, ẋ)` at `t` from rest at the origin (`Ω ≠ 1`).
    pub fn exact(&self, t: f64) -> (f64, f64) {
        let a = self.force / (1.0 - self.omega * self.omega);
        let x = a * ((self.omega * t).cos() - t.cos());
        let v = a * (t.sin() - self.omega * (self.omega * t).sin());
        (x, v)
    }
}

impl Lagrangian<1> for DrivenOscillator {
    type Scalar = f64;
    const COORDINATES: [&'static str; 1] = ["x"];

    fn mass_matrix(&self, _t: f64, _q: &Vector1<f64>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(1.0)
    }
    fn forcing(&self, t: f64, q: &Vector1<f64>, _qdot: &Vector1<f64>) -> Vector1<f64> {
        Vector1::new(-q[0] + self.force * (self.omega * t).cos())
    }
    fn kinetic_energy(&self, _t: f64, _q: &Vector1<f64>, qdot: &Vector1<f64>) -> f64 {
        0.5 * qdot[0] * qdot[0]
    }
    fn potential_energy(&self, t: f64, q: &Vector1<f64>) -> f64 {
        0.5 * q[0] * q[0] - self.force * q[0] * (self.omega * t).cos()
    }
    fn momentum(&self, _t: f64, _q: &Vector1<f64>, qdot: &Vector1<f64>) -> Option<Vector1<f64>> {
        Some(*qdot)
    }
    fn lagrangian_gradient(
        &self,
        t: f64,
        q: &Vector1<f64>,
        _qdot: &Vector1<f64>,
    ) -> Option<Vector1<f64>> {
        Some(Vector1::new(-q[0] + self.force * (self.omega * t).cos()))
    }
    fn nonconservative_forces(
        &self,
        _t: f64,
        _q: &Vector1<f64>,
        _qdot: &Vector1<f64>,
    ) -> Option<Vector1<f64>> {
        Some(Vector1::zeros())
    }
}

/// Largest `|a - b|` (max norm over `q` and `q̇`) between two trajectories
/// sampled at the same times.
pub fn max_difference<const N: usize>(
    a: &lagrange_runtime::Trajectory<f64, N>,
    b: &lagrange_runtime::Trajectory<f64, N>,
) -> f64 {
    assert_eq!(a.times(), b.times());
    a.iter().zip(b).fold(0.0, |worst, (a, b)| {
        worst.max((a.q - b.q).amax()).max((a.qdot - b.qdot).amax())
    })
}

/// Least-squares slope of `log error` against `log h`: the observed order
/// of convergence over all the step sizes at once.
pub fn observed_order(hs: &[f64], errors: &[f64]) -> f64 {
    let (x, y): (Vec<f64>, Vec<f64>) = hs.iter().zip(errors).map(|(h, e)| (h.ln(), e.ln())).unzip();
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(&y).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = x.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

/// Two unit masses on a line: a soft spring `k` from the wall to the first,
/// a hard spring `K` from the first to the second, each with a light damper
/// in parallel. With `K / k = 1e6` the chain is stiff: the masses vibrate
/// against each other at `√(2K) ≈ 1414 rad/s` while the pair swings on the
/// soft spring at `≈ 0.7 rad/s`.
///
/// Linear, so [`StiffChain::exact`] gives the exact solution, and the exact
/// residual Jacobians are constant (`∂r/∂q = K`, `∂r/∂q̇ = C`); whether the
/// model reports them is up to `exact_jacobians`.
pub struct StiffChain {
    pub k_soft: f64,
    pub k_hard: f64,
    pub c_soft: f64,
    pub c_hard: f64,
    pub exact_jacobians: bool,
}

impl StiffChain {
    /// `k = 1`, `K = 1e6`; damping ratios ≈ 3.5 % on the slow mode and
    /// ≈ 0.7 % on the fast one.
    pub fn new() -> Self {
        Self {
            k_soft: 1.0,
            k_hard: 1e6,
            c_soft: 0.1,
            c_hard: 10.0,
            exact_jacobians: false,
        }
    }

    /// The stiffness matrix, `f = −K q − C q̇`.
    pub fn stiffness(&self) -> Matrix2<f64> {
        let (k, kk) = (self.k_soft, self.k_hard);
        Matrix2::new(k + kk, -kk, -kk, kk)
    }

    /// The damping matrix.
    pub fn damping(&self) -> Matrix2<f64> {
        let (c, cc) = (self.c_soft, self.c_hard);
        Matrix2::new(c + cc, -cc, -cc, cc)
    }

    /// The exact state at `t` from `(q0, q̇0)` at `t = 0`, by modal
    /// decomposition: `q = Σ aⱼ φⱼ e^{λⱼ t}` over the four roots of
    /// `det(λ² I + λ C + K) = 0`.
    pub fn exact(
        &self,
        t: f64,
        q0: Vector2<f64>,
        qdot0: Vector2<f64>,
    ) -> (Vector2<f64>, Vector2<f64>) {
        use lagrange_runtime::nalgebra::{Complex, Matrix4, Vector4};
        type C = Complex<f64>;
        let (kk, cc) = (self.stiffness(), self.damping());
        let pencil = |l: C| {
            let m = |i, j| l * l * if i == j { 1.0 } else { 0.0 } + l * cc[(i, j)] + kk[(i, j)];
            [[m(0, 0), m(0, 1)], [m(1, 0), m(1, 1)]]
        };
        let det = |l: C| {
            let b = pencil(l);
            b[0][0] * b[1][1] - b[0][1] * b[1][0]
        };
        // Roots from the companion matrix of the first-order system, then
        // polished by Newton on the quartic (the eigenvalue solver's error
        // is ε ‖A‖ ≈ 2e-10 absolute; Newton brings the slow roots to ε).
        let mut a = Matrix4::<f64>::zeros();
        a.fixed_view_mut::<2, 2>(0, 2).fill_with_identity();
        a.fixed_view_mut::<2, 2>(2, 0).copy_from(&-kk);
        a.fixed_view_mut::<2, 2>(2, 2).copy_from(&-cc);
        let roots = a.complex_eigenvalues();
        let mut modes = Matrix4::<C>::zeros();
        let mut lambdas = [C::new(0.0, 0.0); 4];
        for (j, &l0) in roots.iter().enumerate() {
            let mut l = l0;
            for _ in 0..5 {
                let d = C::new(1e-7, 0.0) * (C::new(1.0, 0.0) + l);
                let slope = (det(l + d) - det(l - d)) / (d + d);
                l -= det(l) / slope;
            }
            lambdas[j] = l;
            // Null vector of the 2×2 pencil: (−b₀₁, b₀₀), or from the second
            // row when the first vanishes.
            let b = pencil(l);
            let phi = if b[0][0].norm() + b[0][1].norm() > b[1][0].norm() + b[1][1].norm() {
                [-b[0][1], b[0][0]]
            } else {
                [-b[1][1], b[1][0]]
            };
            for i in 0..2 {
                modes[(i, j)] = phi[i];
                modes[(i + 2, j)] = phi[i] * l;
            }
        }
        let y0 = Vector4::new(q0[0], q0[1], qdot0[0], qdot0[1]).map(|x| C::new(x, 0.0));
        let amplitudes = modes.lu().solve(&y0).expect("distinct modes");
        let y = (0..4).fold(Vector4::<C>::zeros(), |y, j| {
            y + modes.column(j) * (amplitudes[j] * (lambdas[j] * t).exp())
        });
        (
            Vector2::new(y[0].re, y[1].re),
            Vector2::new(y[2].re, y[3].re),
        )
    }
}

impl Lagrangian<2> for StiffChain {
    type Scalar = f64;
    const COORDINATES: [&'static str; 2] = ["x1", "x2"];

    fn mass_matrix(&self, _t: f64, _q: &Vector2<f64>) -> Matrix2<f64> {
        Matrix2::identity()
    }
    fn forcing(&self, _t: f64, q: &Vector2<f64>, qdot: &Vector2<f64>) -> Vector2<f64> {
        -(self.stiffness() * q + self.damping() * qdot)
    }
    fn kinetic_energy(&self, _t: f64, _q: &Vector2<f64>, qdot: &Vector2<f64>) -> f64 {
        0.5 * qdot.norm_squared()
    }
    fn potential_energy(&self, _t: f64, q: &Vector2<f64>) -> f64 {
        0.5 * (q.transpose() * self.stiffness() * q)[0]
    }
    fn residual_jacobians(
        &self,
        _t: f64,
        _q: &Vector2<f64>,
        _qdot: &Vector2<f64>,
        _qddot: &Vector2<f64>,
    ) -> Option<(Matrix2<f64>, Matrix2<f64>)> {
        self.exact_jacobians
            .then(|| (self.stiffness(), self.damping()))
    }
}

/// A pendulum bob on a stiff, damped spring, in polar coordinates `(r, θ)`:
/// `T = ½ m (ṙ² + r² θ̇²)`, `V = −m g r cos θ + ½ k (r − l)²`, and a damper
/// `c` along the spring. Nonlinear, with a mass matrix that depends on `q`,
/// and stiff for large `k` (the spring vibrates at `√(k/m)`, the pendulum
/// swings at `≈ √(g/l)`).
///
/// Its exact residual Jacobians are written out by hand, and reported when
/// `exact_jacobians` is set.
pub struct ElasticPendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub k: f64,
    pub c: f64,
    pub exact_jacobians: bool,
}

impl Lagrangian<2> for ElasticPendulum {
    type Scalar = f64;
    const COORDINATES: [&'static str; 2] = ["r", "theta"];

    fn mass_matrix(&self, _t: f64, q: &Vector2<f64>) -> Matrix2<f64> {
        Matrix2::new(self.m, 0.0, 0.0, self.m * q[0] * q[0])
    }
    fn forcing(&self, _t: f64, q: &Vector2<f64>, qdot: &Vector2<f64>) -> Vector2<f64> {
        let (m, g) = (self.m, self.g);
        let ((r, th), (rd, thd)) = ((q[0], q[1]), (qdot[0], qdot[1]));
        Vector2::new(
            m * r * thd * thd + m * g * th.cos() - self.k * (r - self.l) - self.c * rd,
            -2.0 * m * r * rd * thd - m * g * r * th.sin(),
        )
    }
    fn kinetic_energy(&self, _t: f64, q: &Vector2<f64>, qdot: &Vector2<f64>) -> f64 {
        0.5 * self.m * (qdot[0] * qdot[0] + q[0] * q[0] * qdot[1] * qdot[1])
    }
    fn potential_energy(&self, _t: f64, q: &Vector2<f64>) -> f64 {
        -self.m * self.g * q[0] * q[1].cos() + 0.5 * self.k * (q[0] - self.l).powi(2)
    }
    /// `r = M q̈ − f`: `r₁ = m r̈ − m r θ̇² − m g cos θ + k (r − l) + c ṙ`,
    /// `r₂ = m r² θ̈ + 2 m r ṙ θ̇ + m g r sin θ`.
    fn residual_jacobians(
        &self,
        _t: f64,
        q: &Vector2<f64>,
        qdot: &Vector2<f64>,
        qddot: &Vector2<f64>,
    ) -> Option<(Matrix2<f64>, Matrix2<f64>)> {
        if !self.exact_jacobians {
            return None;
        }
        let (m, g) = (self.m, self.g);
        let ((r, th), (rd, thd), thdd) = ((q[0], q[1]), (qdot[0], qdot[1]), qddot[1]);
        let d_q = Matrix2::new(
            self.k - m * thd * thd,
            m * g * th.sin(),
            2.0 * m * r * thdd + 2.0 * m * rd * thd + m * g * th.sin(),
            m * g * r * th.cos(),
        );
        let d_qdot = Matrix2::new(
            self.c,
            -2.0 * m * r * thd,
            2.0 * m * r * thd,
            2.0 * m * r * rd,
        );
        Some((d_q, d_qdot))
    }
}

/// A double pendulum linearized about the bottom (unit rods, `g = 1`) whose
/// inner bob has mass `mu` and outer bob mass 1:
/// `M = [[1 + μ, 1], [1, 1]]`, `K = diag(1 + μ, 1)`. For small `μ` the
/// mass matrix has pivot ratio `(1 + μ)² / μ`: condition ~`4 / μ`, and a
/// fast kink mode of frequency ~`√(2 / μ)`.
pub struct LightJoint {
    pub mu: f64,
}

impl LightJoint {
    fn mass(&self) -> Matrix2<f64> {
        Matrix2::new(1.0 + self.mu, 1.0, 1.0, 1.0)
    }
    fn stiffness(&self) -> Matrix2<f64> {
        Matrix2::new(1.0 + self.mu, 0.0, 0.0, 1.0)
    }
}

impl Lagrangian<2> for LightJoint {
    type Scalar = f64;
    const COORDINATES: [&'static str; 2] = ["theta1", "theta2"];

    fn mass_matrix(&self, _t: f64, _q: &Vector2<f64>) -> Matrix2<f64> {
        self.mass()
    }
    fn forcing(&self, _t: f64, q: &Vector2<f64>, _qdot: &Vector2<f64>) -> Vector2<f64> {
        -(self.stiffness() * q)
    }
    fn kinetic_energy(&self, _t: f64, _q: &Vector2<f64>, qdot: &Vector2<f64>) -> f64 {
        0.5 * qdot.dot(&(self.mass() * qdot))
    }
    fn potential_energy(&self, _t: f64, q: &Vector2<f64>) -> f64 {
        0.5 * q.dot(&(self.stiffness() * q))
    }
    fn momentum(&self, _t: f64, _q: &Vector2<f64>, qdot: &Vector2<f64>) -> Option<Vector2<f64>> {
        Some(self.mass() * qdot)
    }
    fn lagrangian_gradient(
        &self,
        _t: f64,
        q: &Vector2<f64>,
        _qdot: &Vector2<f64>,
    ) -> Option<Vector2<f64>> {
        Some(-(self.stiffness() * q))
    }
    fn nonconservative_forces(
        &self,
        _t: f64,
        _q: &Vector2<f64>,
        _qdot: &Vector2<f64>,
    ) -> Option<Vector2<f64>> {
        Some(Vector2::zeros())
    }
}
