//! A stiff problem with an exact solution: three masses on springs, one
//! spring `stiff` times harder than the rest and damped. Linear, so the
//! matrix exponential of its first-order form is the reference.

use crate::lagrangian;
use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

lagrangian! {
    /// Three unit masses in a row between walls; the middle spring is
    /// `stiff` times harder than the others, and damped.
    #[lagrange(jacobians)]
    pub struct StiffChain {
        coordinates: x1, x2, x3;
        parameters: k, stiff, c;
        kinetic: (dot(x1)^2 + dot(x2)^2 + dot(x3)^2)/2;
        potential: k/2*x1^2 + stiff*k/2*(x2 - x1)^2 + k/2*(x3 - x2)^2 + k/2*x3^2;
        dissipation: c/2*(dot(x2) - dot(x1))^2;
    }
}

impl StiffChain<f64> {
    /// The ratio 10⁶ of the work–precision study, with the stiff spring
    /// damped at `c = 20`.
    pub fn ratio_1e6() -> Self {
        Self::new(1.0, 1e6, 20.0)
    }

    /// The stiff spring relaxed, the others not, all at rest.
    pub fn start() -> (Vector3<f64>, Vector3<f64>) {
        (Vector3::new(0.1, 0.1, -0.05), Vector3::zeros())
    }

    /// `K` in `M q̈ = −K q − C q̇` (`M = I`).
    pub fn stiffness(&self) -> Matrix3<f64> {
        let (k, stiff) = (self.k, self.stiff);
        Matrix3::new(
            k + stiff * k,
            -stiff * k,
            0.0,
            -stiff * k,
            stiff * k + k,
            -k,
            0.0,
            -k,
            2.0 * k,
        )
    }

    /// `C`, the damper across the stiff spring.
    pub fn damping(&self) -> Matrix3<f64> {
        let c = self.c;
        Matrix3::new(c, -c, 0.0, -c, c, 0.0, 0.0, 0.0, 0.0)
    }

    /// The exact state at `t` from `(q0, q̇0)` at 0: `exp(A t) y0` for the
    /// first-order system `y = (q, q̇)`, `A = [[0, I], [−K, −C]]`: about
    /// 4e-12 from the truth for the ratio 10⁶ over 10 s (docs/guides/methods.md, "Measured").
    pub fn exact(
        &self,
        t: f64,
        q0: Vector3<f64>,
        qdot0: Vector3<f64>,
    ) -> (Vector3<f64>, Vector3<f64>) {
        let mut a = SMatrix::<f64, 6, 6>::zeros();
        a.fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&Matrix3::identity());
        a.fixed_view_mut::<3, 3>(3, 0)
            .copy_from(&(-self.stiffness()));
        a.fixed_view_mut::<3, 3>(3, 3).copy_from(&(-self.damping()));
        let mut y0 = SVector::<f64, 6>::zeros();
        y0.fixed_rows_mut::<3>(0).copy_from(&q0);
        y0.fixed_rows_mut::<3>(3).copy_from(&qdot0);
        let y = (a * t).exp() * y0;
        (
            y.fixed_rows::<3>(0).into_owned(),
            y.fixed_rows::<3>(3).into_owned(),
        )
    }
}
