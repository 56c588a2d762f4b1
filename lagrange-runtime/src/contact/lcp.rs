//! A linear complementarity problem solved by Lemke's complementary
//! pivoting: find `z ≥ 0` with `w = A z + b ≥ 0` and `zᵀ w = 0`.
//!
//! Lemke's method (Cottle, Pang and Stone, *The Linear Complementarity
//! Problem*, §4.4) adds an artificial variable `z₀` with covering vector
//! `e = 1`, pivots it in at the row of the most negative `b`, and then
//! always brings in the complement of the variable that just left, until
//! `z₀` leaves (a solution) or no row bounds the entering variable (a ray:
//! the method gives no solution, which for the contact problems here
//! happens where friction makes them unsolvable, Painlevé's paradox). It
//! solves every LCP whose matrix is copositive-plus (positive semidefinite
//! ones among them: contacts without friction) and in practice the small
//! friction problems of planar contact. Ties in the ratio test go to `z₀`,
//! then to the lowest index; the pivots are bounded, so a cycling problem
//! ends in an error, not a loop.

use nalgebra::{DMatrix, DVector, RealField};

/// Why an LCP was not solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum LcpFailure {
    /// Ray termination: no bounded pivot, the method finds no solution.
    Ray,
    /// The pivot bound was reached (cycling on a degenerate problem).
    Cycling,
    /// A value in the problem is not finite.
    NonFinite,
}

/// The solution `z` of `LCP(A, b)`.
pub(crate) fn lemke<S: RealField + Copy>(
    a: &DMatrix<S>,
    b: &DVector<S>,
) -> Result<DVector<S>, LcpFailure> {
    let n = b.len();
    if !a.iter().chain(b.iter()).all(|x| x.is_finite()) {
        return Err(LcpFailure::NonFinite);
    }
    if b.iter().all(|&x| x >= S::zero()) {
        return Ok(DVector::zeros(n));
    }
    // Columns: w (0..n), z (n..2n), z₀ (2n), right-hand side (2n + 1).
    let (z0, rhs) = (2 * n, 2 * n + 1);
    let mut t = DMatrix::<S>::zeros(n, 2 * n + 2);
    for i in 0..n {
        t[(i, i)] = S::one();
        for j in 0..n {
            t[(i, n + j)] = -a[(i, j)];
        }
        t[(i, z0)] = -S::one();
        t[(i, rhs)] = b[i];
    }
    let mut basis: Vec<usize> = (0..n).collect();
    let scale = a
        .iter()
        .chain(b.iter())
        .fold(S::one(), |m, &x| m.max(x.abs()));
    let tiny = nalgebra::convert::<f64, S>(1e3) * S::default_epsilon() * scale;

    let mut row = (0..n)
        .min_by(|&i, &j| t[(i, rhs)].partial_cmp(&t[(j, rhs)]).expect("finite"))
        .expect("n > 0");
    let mut entering = z0;
    for _ in 0..(50 * (n + 1)) {
        pivot(&mut t, row, entering);
        let leaving = core::mem::replace(&mut basis[row], entering);
        if leaving == z0 {
            let mut z = DVector::zeros(n);
            for (i, &var) in basis.iter().enumerate() {
                if (n..2 * n).contains(&var) {
                    z[var - n] = t[(i, rhs)].max(S::zero());
                }
            }
            return Ok(z);
        }
        entering = if leaving < n {
            leaving + n
        } else {
            leaving - n
        };
        // The ratio test: the row that bounds the entering variable first;
        // ties go to z₀'s row, then to the lowest index.
        let mut best: Option<(usize, S)> = None;
        for i in 0..n {
            let c = t[(i, entering)];
            if c > tiny {
                let ratio = t[(i, rhs)] / c;
                let better = match best {
                    None => true,
                    Some((j, r)) => {
                        ratio < r - tiny || (ratio <= r + tiny && basis[i] == z0 && basis[j] != z0)
                    }
                };
                if better {
                    best = Some((i, ratio));
                }
            }
        }
        row = match best {
            Some((i, _)) => i,
            None => return Err(LcpFailure::Ray),
        };
    }
    Err(LcpFailure::Cycling)
}

/// Gauss–Jordan pivot of the tableau on `(row, col)`.
fn pivot<S: RealField + Copy>(t: &mut DMatrix<S>, row: usize, col: usize) {
    let p = t[(row, col)];
    let width = t.ncols();
    for j in 0..width {
        t[(row, j)] /= p;
    }
    for i in 0..t.nrows() {
        if i != row {
            let factor = t[(i, col)];
            if factor != S::zero() {
                for j in 0..width {
                    let v = t[(row, j)];
                    t[(i, j)] -= factor * v;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `w = A z + b`, checked for the three conditions.
    fn check(a: &DMatrix<f64>, b: &DVector<f64>, z: &DVector<f64>) {
        let w = a * z + b;
        for i in 0..b.len() {
            assert!(z[i] >= 0.0, "z = {z}");
            assert!(w[i] >= -1e-12, "w = {w}");
            assert!((z[i] * w[i]).abs() < 1e-12, "z = {z}, w = {w}");
        }
    }

    #[test]
    fn solves_a_positive_definite_problem_with_some_components_active() {
        let a = DMatrix::from_row_slice(3, 3, &[2.0, 1.0, 0.0, 1.0, 2.0, 1.0, 0.0, 1.0, 2.0]);
        let b = DVector::from_vec(vec![-1.0, 1.0, -3.0]);
        let z = lemke(&a, &b).unwrap();
        check(&a, &b, &z);
        assert!(z[0] > 0.0 && z[2] > 0.0 && z[1] == 0.0, "{z}");
    }

    #[test]
    fn a_problem_without_a_solution_ends_on_a_ray() {
        // w = −z − 1 ≥ 0 has no z ≥ 0.
        let a = DMatrix::from_row_slice(1, 1, &[-1.0]);
        let b = DVector::from_vec(vec![-1.0]);
        assert_eq!(lemke(&a, &b), Err(LcpFailure::Ray));
    }

    #[test]
    fn solves_a_planar_friction_problem() {
        // One contact: λ (normal), β⁺, β⁻ (friction along ±t), σ (slip
        // rate), with the stick/slip rows of the acceleration-level
        // friction problem; a pull along t beyond μ λ: it slides.
        let (ann, ant, att, mu) = (1.0, 0.3, 1.0, 0.5);
        let a = DMatrix::from_row_slice(
            4,
            4,
            &[
                ann, ant, -ant, 0.0, //
                ant, att, -att, 1.0, //
                -ant, -att, att, 1.0, //
                mu, -1.0, -1.0, 0.0,
            ],
        );
        let b = DVector::from_vec(vec![-1.0, 2.0, -2.0, 0.0]);
        let z = lemke(&a, &b).unwrap();
        check(&a, &b, &z);
        assert!(z[3] > 0.0, "slides: {z}");
        assert!(
            (z[1] + z[2] - mu * z[0]).abs() < 1e-12,
            "at the cone's edge: {z}"
        );
    }
}
