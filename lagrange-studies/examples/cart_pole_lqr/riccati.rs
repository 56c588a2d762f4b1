//! The continuous algebraic Riccati equation `Aᵀ P + P A − P B R⁻¹ Bᵀ P + Q = 0`,
//! solved by the matrix sign function of its Hamiltonian (Byers 1987, as in
//! Drake's `ContinuousAlgebraicRiccatiEquation`): written here because no
//! well-kept crate on nalgebra provides it (the control crates that do
//! bring their own array stacks).
//!
//! `H = [[A, −B R⁻¹ Bᵀ], [−Q, −Aᵀ]]` has no eigenvalue on the imaginary axis
//! when `(A, B)` is stabilizable and `(Q, A)` detectable; the Newton
//! iteration `Z ← (Z/c + c Z⁻¹)/2` with determinant scaling `c = |det Z|^(1/2n)`
//! converges quadratically to `sign(H)`, and `P` solves the stacked linear
//! system `[W₁₂; W₂₂ + I] P = −[W₁₁ + I; W₂₁]` with `W = sign(H)`, by least
//! squares. The residual of the equation is returned with `P` so that the
//! caller sees how well it was solved.

use lagrange::nalgebra::DMatrix;

/// `P` and the largest entry of the Riccati residual at `P`.
pub fn care(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
) -> Result<(DMatrix<f64>, f64), String> {
    let n = a.nrows();
    let r_inv = r.clone().try_inverse().ok_or("R is singular")?;
    let g = b * &r_inv * b.transpose();
    let mut z = DMatrix::<f64>::zeros(2 * n, 2 * n);
    z.view_mut((0, 0), (n, n)).copy_from(a);
    z.view_mut((0, n), (n, n)).copy_from(&(-&g));
    z.view_mut((n, 0), (n, n)).copy_from(&(-q));
    z.view_mut((n, n), (n, n)).copy_from(&(-a.transpose()));
    for _ in 0..100 {
        let inverse = z
            .clone()
            .try_inverse()
            .ok_or("the Hamiltonian has an eigenvalue on the imaginary axis")?;
        let c = z.determinant().abs().powf(1.0 / (2 * n) as f64);
        let next = (&z / c + &inverse * c) * 0.5;
        let change = (&next - &z).norm() / next.norm();
        z = next;
        if change < 1e-13 {
            break;
        }
    }
    let identity = DMatrix::<f64>::identity(n, n);
    let w11 = z.view((0, 0), (n, n)).into_owned();
    let w12 = z.view((0, n), (n, n)).into_owned();
    let w21 = z.view((n, 0), (n, n)).into_owned();
    let w22 = z.view((n, n), (n, n)).into_owned();
    let mut lhs = DMatrix::<f64>::zeros(2 * n, n);
    lhs.view_mut((0, 0), (n, n)).copy_from(&w12);
    lhs.view_mut((n, 0), (n, n)).copy_from(&(&w22 + &identity));
    let mut rhs = DMatrix::<f64>::zeros(2 * n, n);
    rhs.view_mut((0, 0), (n, n))
        .copy_from(&(-(&w11 + &identity)));
    rhs.view_mut((n, 0), (n, n)).copy_from(&(-w21));
    let p = lhs
        .svd(true, true)
        .solve(&rhs, 1e-14)
        .map_err(|e| e.to_string())?;
    let p = (&p + p.transpose()) * 0.5;
    let residual = a.transpose() * &p + &p * a - &p * &g * &p + q;
    Ok((p, residual.amax()))
}
