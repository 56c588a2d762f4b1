//! A stiff, damped two-mass chain with its exact modal solution.

use lagrange_runtime::Lagrangian;
use lagrange_runtime::nalgebra::Matrix2;
use lagrange_runtime::nalgebra::Vector2;

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
