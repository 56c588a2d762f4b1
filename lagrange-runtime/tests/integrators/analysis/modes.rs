//! Normal modes against closed forms; points that have none refused.

use lagrange::models::{DoublePendulum, TwoMassChain};
use lagrange_runtime::WithLayers;
use lagrange_runtime::analysis::{AnalysisError, Derivatives, ModeKind, Modes, modes};
use lagrange_runtime::nalgebra::{Matrix2, Vector2};

use super::models::Circulatory;

const G: f64 = 9.81;

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// `vᵢᵀ M vⱼ = δᵢⱼ` and `vᵢᵀ K vⱼ = ω²ᵢ δᵢⱼ` for the modes' shapes, with
/// `K` given: the shapes are the mass-normalized eigenvectors.
fn assert_mass_normalized(modes: &Modes<f64, 2>, m: &Matrix2<f64>, k: &Matrix2<f64>) {
    for (i, a) in modes.modes.iter().enumerate() {
        for (j, b) in modes.modes.iter().enumerate() {
            let (mass, stiffness) = (a.shape.dot(&(m * b.shape)), a.shape.dot(&(k * b.shape)));
            let (delta, w2) = if i == j {
                (1.0, a.omega_squared)
            } else {
                (0.0, 0.0)
            };
            // Rounding of a 2 × 2 solve with cond(M) ≈ 7 and |K| ≈ 20:
            // a few ε times those; 1e-12 is a hundredfold margin.
            assert!((mass - delta).abs() < 1e-12, "vᵀMv = {mass} for ({i}, {j})");
            assert!(
                (stiffness - w2).abs() < 1e-12 * G,
                "vᵀKv = {stiffness} for ({i}, {j})"
            );
        }
    }
}

/// m = l = 1 hanging: `M = [[2, 1], [1, 1]]`, `K = g diag(2, 1)`, and
/// `det(K − ω² M) = 2 (g − ω²)² − ω⁴ = 0` gives `ω² = g (2 ∓ √2)`.
#[test]
fn hanging_double_pendulum_swings_at_g_two_minus_and_plus_root_two() {
    let pendulum = DoublePendulum::new(1.0, 1.0, 1.0, 1.0, G);
    let found = modes(&pendulum, 0.0, &Vector2::zeros()).unwrap();
    assert_eq!(found.derivatives, Derivatives::Exact);
    let expected = [G * (2.0 - 2f64.sqrt()), G * (2.0 + 2f64.sqrt())];
    for (mode, w2) in found.modes.iter().zip(expected) {
        // Exact Jacobians: the eigenvalues of L⁻¹ K L⁻ᵀ carry a few ε of
        // relative error (cond(M) ≈ 7); 1e-12 as the brief asks.
        assert!(relative(mode.omega_squared, w2) < 1e-12, "{mode:?} vs {w2}");
        println!(
            "hanging ω² relative error {:e}",
            relative(mode.omega_squared, w2)
        );
        let ModeKind::Oscillating { frequency } = mode.kind else {
            panic!("{mode:?} does not oscillate");
        };
        assert!(relative(frequency, w2.sqrt()) < 1e-12);
    }
    // The slow mode swings both rods the same way, the fast one opposite.
    let (slow, fast) = (found.modes[0].shape, found.modes[1].shape);
    assert!(slow[0] * slow[1] > 0.0 && fast[0] * fast[1] < 0.0);
    assert!(relative(slow[1] / slow[0], 2f64.sqrt()) < 1e-12);
    let m = pendulum.mass_matrix(0.0, &Vector2::zeros());
    assert_mass_normalized(&found, &m, &Matrix2::new(2.0 * G, 0.0, 0.0, G));
    assert!(found.is_stable());
    assert_eq!(found.frequencies().count(), 2);
}

/// Both rods upright: `K = −g diag(2, 1)` (the pendulum stands on its
/// potential's maximum), `M` the same, so `ω² = −g (2 ± √2)`: two
/// unstable modes, the faster-growing first.
#[test]
fn upright_double_pendulum_falls_along_both_modes() {
    let pi = std::f64::consts::PI;
    let pendulum = DoublePendulum::new(1.0, 1.0, 1.0, 1.0, G);
    let found = modes(&pendulum, 0.0, &Vector2::new(pi, pi)).unwrap();
    let expected = [-G * (2.0 + 2f64.sqrt()), -G * (2.0 - 2f64.sqrt())];
    for (mode, w2) in found.modes.iter().zip(expected) {
        // As hanging, plus sin(π) ≈ 1.2e-16 ≠ 0 in K and M: ε-sized.
        assert!(relative(mode.omega_squared, w2) < 1e-12, "{mode:?} vs {w2}");
        println!(
            "upright ω² relative error {:e}",
            relative(mode.omega_squared, w2)
        );
        let ModeKind::Unstable { growth_rate } = mode.kind else {
            panic!("{mode:?} is not unstable");
        };
        assert!(relative(growth_rate, (-w2).sqrt()) < 1e-12);
    }
    assert!(!found.is_stable());
    assert_eq!(found.frequencies().count(), 0);
}

/// wall – k1 – m1 – k2 – m2 – k3 – wall: `M = diag(m1, m2)`,
/// `K = [[k1 + k2, −k2], [−k2, k2 + k3]]`, so `ω²` are the roots of
/// `m1 m2 ω⁴ − (m1 (k2 + k3) + m2 (k1 + k2)) ω² + (k1 + k2)(k2 + k3) − k2² = 0`.
/// The dampers act on velocities only, and modes leave them out.
#[test]
fn two_mass_chain_modes_are_the_roots_of_its_characteristic_quadratic() {
    let (m1, m2, k1, k2, k3): (f64, f64, f64, f64, f64) = (1.5, 0.5, 40.0, 25.0, 10.0);
    let chain = TwoMassChain::new(m1, m2, k1, k2, k3, 0.3, 0.2, 0.1);
    let found = modes(&chain, 0.0, &Vector2::zeros()).unwrap();
    let a = m1 * m2;
    let b = -(m1 * (k2 + k3) + m2 * (k1 + k2));
    let c = (k1 + k2) * (k2 + k3) - k2 * k2;
    let root = (b * b - 4.0 * a * c).sqrt();
    // The smaller root as 2c / (−b + √Δ), free of cancellation.
    let expected = [2.0 * c / (-b + root), (-b + root) / (2.0 * a)];
    for (mode, w2) in found.modes.iter().zip(expected) {
        // Exact Jacobians of a linear model, cond(M) = 3: rounding only.
        assert!(relative(mode.omega_squared, w2) < 1e-12, "{mode:?} vs {w2}");
        println!(
            "chain ω² relative error {:e}",
            relative(mode.omega_squared, w2)
        );
    }
    let m = Matrix2::new(m1, 0.0, 0.0, m2);
    let k = Matrix2::new(k1 + k2, -k2, -k2, k2 + k3);
    assert_mass_normalized(&found, &m, &k);
}

/// The same modes from central differences of `f` when the model has no
/// exact Jacobians: `K` is then off by `≈ ε^(2/3) |∂³f| ≈ 4e-11 g`, and
/// so are the `ω²` (a symmetric eigenproblem is perfectly conditioned in
/// the eigenvalues); 1e-9 relative leaves a margin of twenty.
#[test]
fn modes_by_differences_agree_with_exact_ones_to_their_error() {
    let pendulum = DoublePendulum::new(1.0, 0.7, 1.0, 0.8, G);
    let exact = modes(&pendulum, 0.0, &Vector2::zeros()).unwrap();
    let numeric = modes(&pendulum.without_jacobians(), 0.0, &Vector2::zeros()).unwrap();
    assert_eq!(numeric.derivatives, Derivatives::CentralDifferences);
    for (a, b) in numeric.modes.iter().zip(&exact.modes) {
        let error = relative(a.omega_squared, b.omega_squared);
        println!("ω² by differences, relative error {error:e}");
        assert!(error < 1e-9, "{error:e}");
        assert!((a.shape - b.shape).amax() < 1e-9 * b.shape.amax());
    }
}

/// A rod held out at 0.3 rad is accelerating: no modes about it.
#[test]
fn swinging_out_is_no_equilibrium_and_has_no_modes() {
    let err = modes(&DoublePendulum::unit(), 0.0, &Vector2::new(0.3, 0.0)).unwrap_err();
    let AnalysisError::NotAnEquilibrium { residual, .. } = err else {
        panic!("{err}");
    };
    assert!(residual[0] < 0.0); // gravity pulls it back
}

/// A circulatory force makes `K` asymmetric: refused, not symmetrized into
/// wrong (stable) modes.
#[test]
fn circulatory_force_is_refused_as_non_conservative() {
    let err = modes(&Circulatory { k: 4.0, c: 0.5 }, 0.0, &Vector2::zeros()).unwrap_err();
    let AnalysisError::NonConservative { asymmetry, .. } = err else {
        panic!("{err}");
    };
    // max |K − Kᵀ| / max |K| = 2c / k.
    assert!((asymmetry - 0.25).abs() < 1e-9);
}
