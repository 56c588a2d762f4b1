//! Dead centres: constraints that lose rank stop every method with
//! `SingularConstraints`, its time and state, and the samples before it;
//! never a NaN.

use crate::models::{ParallelAtOne, VanishingGradient};
use lagrange::Method;
use lagrange_runtime::nalgebra::{Vector2, Vector3};
use lagrange_runtime::prelude::*;

/// Two planes whose normals coincide at `t = 1`: every method reaches
/// `t = 1`, where the equilibrated `G M⁻¹ Gᵀ` has the pivot
/// `(1 − t)² / (1 + (1 − t)²)`, below `2 ε` within 1e-8 of it. The
/// adaptive methods shrink their step towards it until it underflows and
/// report the last failed evaluation, within 1e-7 of `t = 1`.
#[test]
fn constraints_turning_parallel_are_singular_with_the_samples_before() {
    let times = [0.25, 0.5, 0.75, 1.0];
    let (q0, qdot0) = (Vector3::zeros(), Vector3::new(1.0, 0.0, 0.0));
    for method in Method::ALL {
        let failure = method
            .integrator(0.01, 1e-8)
            .integrate(&ParallelAtOne, 0.0, q0, qdot0, &times)
            .unwrap_err();
        let IntegrationError::SingularConstraints { t, q, qdot } = failure.error else {
            panic!("{method:?}: {}", failure.error);
        };
        assert!((t - 1.0).abs() < 1e-7, "{method:?}: t = {t}");
        assert!(
            q.iter().chain(qdot.iter()).all(|x| x.is_finite()),
            "{method:?}"
        );
        assert_eq!(failure.trajectory.times(), &times[..3], "{method:?}");
        // x moves freely at unit speed, y = z = 0.
        for s in &failure.trajectory {
            assert!(
                (s.q - Vector3::new(s.t, 0.0, 0.0)).amax() < 1e-9,
                "{method:?}"
            );
        }
        let message = failure.to_string();
        assert!(message.contains("singular or redundant"), "{message}");
    }
}

/// `φ = x²` at `x = 0` is satisfied, with a vanishing gradient: singular
/// at the start, for `C = 1`, where no pivot ratio could tell; the sample
/// at `t0` is kept.
#[test]
fn a_vanishing_constraint_gradient_is_singular_from_the_start() {
    let (q0, qdot0) = (Vector2::new(0.0, 1.0), Vector2::new(0.0, 1.0));
    for method in Method::ALL {
        let failure = method
            .integrator(0.01, 1e-8)
            .integrate(&VanishingGradient, 0.0, q0, qdot0, &[0.0, 1.0])
            .unwrap_err();
        assert_eq!(
            failure.error,
            IntegrationError::SingularConstraints {
                t: 0.0,
                q: q0,
                qdot: qdot0
            },
            "{method:?}"
        );
        assert_eq!(failure.trajectory.times(), &[0.0]);
    }
}
