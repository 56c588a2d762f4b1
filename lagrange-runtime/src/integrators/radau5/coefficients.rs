//! The Radau IIA coefficients, and RADAU5's transformation that splits the
//! Newton system into one real and one complex block.

use nalgebra::RealField;

/// The Radau IIA coefficients and RADAU5's transformation, in the working
/// precision.
pub(super) struct Coefficients<S> {
    /// Nodes `c₁, c₂, c₃ = 1`.
    pub(super) c: [S; 3],
    pub(super) c1m1: S,
    pub(super) c2m1: S,
    pub(super) c1mc2: S,
    /// Embedded error estimate weights, divided by `h` in use.
    pub(super) dd: [S; 3],
    /// The real eigenvalue `γ̂` of `A⁻¹`.
    pub(super) gamma: S,
    /// The complex pair `α̂ ± iβ̂` of eigenvalues of `A⁻¹`.
    pub(super) alpha: S,
    pub(super) beta: S,
    /// `T⁻¹ A⁻¹ T = [[γ̂, 0, 0], [0, α̂, −β̂], [0, β̂, α̂]]`.
    pub(super) t: [[S; 3]; 3],
    pub(super) ti: [[S; 3]; 3],
}

/// RADAU5's `T`, with the 20 digits `radau5.f` publishes (f64 keeps 17),
/// so that they can be compared with the source.
#[allow(clippy::excessive_precision)]
const T: [[f64; 3]; 3] = [
    [
        9.1232394870892942792e-2,
        -1.4125529502095420843e-1,
        -3.0029194105147424492e-2,
    ],
    [
        2.4171793270710701896e-1,
        2.0412935229379993199e-1,
        3.8294211275726193779e-1,
    ],
    [9.6604818261509293619e-1, 1.0, 0.0],
];

/// RADAU5's `T⁻¹`, likewise.
#[allow(clippy::excessive_precision)]
const TI: [[f64; 3]; 3] = [
    [
        4.3255798900631553510,
        3.3919925181580986954e-1,
        5.4177053993587487119e-1,
    ],
    [
        -4.1787185915519047273,
        -3.2768282076106238708e-1,
        4.7662355450055045196e-1,
    ],
    [
        -5.0287263494578687595e-1,
        2.5719269498556054292,
        -5.9603920482822492497e-1,
    ],
];

impl<S: RealField + Copy> Coefficients<S> {
    pub(super) fn new() -> Self {
        let sq6 = 6f64.sqrt();
        let (c1, c2) = ((4.0 - sq6) / 10.0, (4.0 + sq6) / 10.0);
        // Eigenvalues of A: one real, one complex pair; A⁻¹ has the inverses.
        let (cbrt81, cbrt9) = (81f64.cbrt(), 9f64.cbrt());
        let u1 = (6.0 + cbrt81 - cbrt9) / 30.0;
        let alph = (12.0 - cbrt81 + cbrt9) / 60.0;
        let beta = (cbrt81 + cbrt9) * 3f64.sqrt() / 60.0;
        let cno = alph * alph + beta * beta;
        let c = |x: f64| -> S { nalgebra::convert(x) };
        let m = |rows: [[f64; 3]; 3]| rows.map(|row| row.map(c));
        Self {
            c: [c(c1), c(c2), S::one()],
            c1m1: c(c1 - 1.0),
            c2m1: c(c2 - 1.0),
            c1mc2: c(c1 - c2),
            dd: [
                c(-(13.0 + 7.0 * sq6) / 3.0),
                c((-13.0 + 7.0 * sq6) / 3.0),
                c(-1.0 / 3.0),
            ],
            gamma: c(1.0 / u1),
            alpha: c(alph / cno),
            beta: c(beta / cno),
            t: m(T),
            ti: m(TI),
        }
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::{Matrix3, Vector3};

    use super::*;

    /// The Radau IIA matrix `A` from its closed form.
    fn radau_iia() -> Matrix3<f64> {
        let s = 6f64.sqrt();
        Matrix3::new(
            (88.0 - 7.0 * s) / 360.0,
            (296.0 - 169.0 * s) / 1800.0,
            (-2.0 + 3.0 * s) / 225.0,
            (296.0 + 169.0 * s) / 1800.0,
            (88.0 + 7.0 * s) / 360.0,
            (-2.0 - 3.0 * s) / 225.0,
            (16.0 - s) / 36.0,
            (16.0 + s) / 36.0,
            1.0 / 9.0,
        )
    }

    #[test]
    fn transformation_block_diagonalizes_the_inverse_of_a() {
        let k = Coefficients::<f64>::new();
        let t = Matrix3::from_fn(|i, j| k.t[i][j]);
        let ti = Matrix3::from_fn(|i, j| k.ti[i][j]);
        let a_inv = radau_iia().try_inverse().unwrap();
        let expected = Matrix3::new(
            k.gamma, 0.0, 0.0, 0.0, k.alpha, -k.beta, 0.0, k.beta, k.alpha,
        );
        // The constants have 20 digits, so only the f64 rounding of products
        // of entries ≤ 5 in size (‖A⁻¹‖ ≈ 10) remains: ~1e-14. A typo in any
        // digit that f64 keeps shows up above 1e-12.
        assert!((ti * t - Matrix3::identity()).amax() < 1e-13);
        assert!((ti * a_inv * t - expected).amax() < 1e-12);
    }

    #[test]
    fn nodes_and_error_weights_match_the_method() {
        let k = Coefficients::<f64>::new();
        // c = A 1 (row sums), the collocation condition.
        let c = radau_iia() * Vector3::repeat(1.0);
        assert!((c - Vector3::new(k.c[0], k.c[1], k.c[2])).amax() < 1e-15);
        // The estimate's right-hand side f(y₀) + Σ dᵢ Zᵢ / h vanishes when
        // the solution is a polynomial of degree ≤ 3 (Zᵢ = Σ_p a_p (cᵢh)^p,
        // f(y₀) = a₁): Σ dᵢ cᵢ = −1 and Σ dᵢ cᵢ^p = 0 for p = 2, 3, but not
        // for p = 4, so the estimate is O(h⁴). Only f64 rounding of terms
        // ≤ 10 in size: 1e-14.
        let moment = |p: i32| -> f64 { k.dd.iter().zip(k.c).map(|(d, c)| d * c.powi(p)).sum() };
        assert!((moment(1) + 1.0).abs() < 1e-14, "{}", moment(1));
        assert!(moment(2).abs() < 1e-14 && moment(3).abs() < 1e-14);
        assert!(moment(4).abs() > 0.01);
    }
}
