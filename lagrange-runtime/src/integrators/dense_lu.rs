//! LU with partial pivoting, in place, for the Newton systems of the
//! implicit methods.
//!
//! Their dimension `2 N s` is only known at run time, and nalgebra's `LU`
//! allocates its permutation on every factorization; this one keeps the
//! pivots in a buffer allocated once per integration, so a step allocates
//! nothing.

use nalgebra::{DMatrix, DVector, RealField};

/// Row pivots of the last factorization, reused from one step to the next.
#[derive(Debug, Clone)]
pub(crate) struct DenseLu {
    pivots: Vec<usize>,
}

impl DenseLu {
    /// Room for matrices of order `n`.
    pub(crate) fn new(n: usize) -> Self {
        Self { pivots: vec![0; n] }
    }

    /// Overwrites the square matrix `a` (of the order given to [`new`](Self::new))
    /// with its LU factors. `false` when a pivot is zero or not finite, i.e.
    /// the matrix is singular or holds a NaN: solving with it would only
    /// spread NaN.
    pub(crate) fn factor<S: RealField + Copy>(&mut self, a: &mut DMatrix<S>) -> bool {
        let n = self.pivots.len();
        debug_assert_eq!(a.shape(), (n, n));
        for k in 0..n {
            let p = (k + 1..n).fold(k, |p, i| {
                if a[(i, k)].abs() > a[(p, k)].abs() {
                    i
                } else {
                    p
                }
            });
            self.pivots[k] = p;
            a.swap_rows(k, p);
            let pivot = a[(k, k)];
            if pivot == S::zero() || !pivot.is_finite() {
                return false;
            }
            for i in k + 1..n {
                a[(i, k)] /= pivot;
            }
            // Column-major: update column by column.
            for j in k + 1..n {
                let akj = a[(k, j)];
                if akj != S::zero() {
                    for i in k + 1..n {
                        let lik = a[(i, k)];
                        a[(i, j)] -= lik * akj;
                    }
                }
            }
        }
        true
    }

    /// Solves `A x = b` in place with the factors of `A` from
    /// [`factor`](Self::factor).
    pub(crate) fn solve<S: RealField + Copy>(&self, lu: &DMatrix<S>, b: &mut DVector<S>) {
        let n = self.pivots.len();
        for (k, &p) in self.pivots.iter().enumerate() {
            b.swap_rows(k, p);
        }
        for j in 0..n {
            let bj = b[j];
            for i in j + 1..n {
                b[i] -= lu[(i, j)] * bj;
            }
        }
        for j in (0..n).rev() {
            b[j] /= lu[(j, j)];
            let bj = b[j];
            for i in 0..j {
                b[i] -= lu[(i, j)] * bj;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_system_that_needs_pivoting() {
        // A zero in the first pivot position: elimination without row swaps
        // would divide by zero.
        #[rustfmt::skip]
        let a = DMatrix::from_row_slice(3, 3, &[
            0.0, 2.0, 1.0,
            1.0, 1.0, 0.0,
            3.0, 0.0, 4.0,
        ]);
        let x = DVector::from_column_slice(&[1.0, -2.0, 0.5]);
        let mut lu = a.clone();
        let mut solver = DenseLu::new(3);
        assert!(solver.factor(&mut lu));
        let mut b = &a * &x;
        solver.solve(&lu, &mut b);
        // Backward stable with cond(A) ≈ 6: error a few ε |x|.
        assert!((b - x).amax() < 1e-14);
    }

    #[test]
    fn factors_are_reused_for_several_right_hand_sides() {
        let a = DMatrix::from_fn(6, 6, |i, j| {
            if i == j {
                4.0
            } else {
                1.0 / (1 + i + 2 * j) as f64
            }
        });
        let mut lu = a.clone();
        let mut solver = DenseLu::new(6);
        assert!(solver.factor(&mut lu));
        for seed in 0..3 {
            let x = DVector::from_fn(6, |i, _| (i as f64 + 1.0) * (seed as f64 - 1.0));
            let mut b = &a * &x;
            solver.solve(&lu, &mut b);
            // Diagonally dominant, cond(A) < 2: error a few ε |x| ≤ 1e-14.
            assert!((b - x).amax() < 1e-14, "seed {seed}");
        }
    }

    #[test]
    fn singular_or_nan_matrix_is_refused() {
        let mut singular = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 4.0]);
        assert!(!DenseLu::new(2).factor(&mut singular));
        let mut nan = DMatrix::from_row_slice(2, 2, &[f64::NAN, 0.0, 0.0, 1.0]);
        assert!(!DenseLu::new(2).factor(&mut nan));
    }
}
