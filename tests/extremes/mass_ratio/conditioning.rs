//! The mass matrices of both extremes, solved to their conditioning.

use super::{chain, heavy_start, light_start, reference};
use lagrange::linalg::mass::{pivot_ratio, solve_mass_matrix};
use lagrange::nalgebra::Vector2;

/// A backward-stable Cholesky solve of `M x = f` has a relative error of at
/// most `c N ε κ(M)` (Higham, *Accuracy and Stability*, Thm. 10.4, with
/// `c` a small constant; 10 N here). Along both extreme trajectories the
/// 2-norm condition number reaches ~10⁶ (light: 1e6, heavy: 4e6), the
/// factorization is Cholesky (positive pivots, ratio far above the `N ε`
/// the solve refuses), and the solve meets that bound: the conditioning is
/// handled, not refused and not turned into noise.
#[test]
fn mass_matrices_with_condition_near_1e6_are_solved_to_their_conditioning() {
    for (name, model, start) in [
        ("m2/m1 = 1e-6", chain(1.0, 1e-6), light_start()),
        ("m2/m1 = 1e6", chain(1e-6, 1.0), heavy_start()),
    ] {
        let trajectory = reference(&model, start);
        let (mut worst_kappa, mut worst_ratio, mut worst_error): (f64, f64, f64) = (0.0, 0.0, 0.0);
        for s in &trajectory {
            let m = model.mass_matrix(s.t, &s.q);
            let eigen = m.symmetric_eigenvalues();
            let kappa = eigen.max() / eigen.min();
            let pivots = pivot_ratio(&m).expect("M is positive definite: Cholesky");
            assert!(
                pivots > 1.0 && pivots < 1e-3 / f64::EPSILON,
                "{name}: pivot ratio {pivots:e} at t = {}",
                s.t
            );
            // A known answer with components along both eigenvectors.
            let expected = Vector2::new(0.3, -0.7);
            let solved = solve_mass_matrix(&m, &(m * expected)).expect("solvable");
            let error = (solved - expected).norm() / expected.norm();
            let bound = 10.0 * 2.0 * f64::EPSILON * kappa;
            assert!(
                error <= bound,
                "{name}: relative error {error:e} > {bound:e} (κ = {kappa:e}) at t = {}",
                s.t
            );
            worst_kappa = worst_kappa.max(kappa);
            worst_ratio = worst_ratio.max(pivots);
            worst_error = worst_error.max(error / (f64::EPSILON * kappa));
        }
        println!(
            "{name}: cond(M) up to {worst_kappa:.2e}, Cholesky pivot ratio up to \
             {worst_ratio:.2e}, solve error up to {worst_error:.2} κ ε (bound 20 κ ε)"
        );
        assert!(worst_kappa > 5e5, "{name}: not the conditioning we meant");
    }
}
