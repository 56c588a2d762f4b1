//! What `constraints:` generates, checked through the generated code: `φ`,
//! `G`, `φ̇` and `γ` against finite differences of `φ` along a straight
//! path `q + s q̇` (on which `q̈ = 0`, so `φ̈ = γ`), `constrained_system`
//! against the separate methods, and the `Holonomic` impl reached through
//! `Lagrangian::visit_constraints`.

use lagrange::Holonomic;
use lagrange::constraints::{ConstraintSettings, Visitor};
use lagrange::nalgebra::Vector3;
use lagrange::prelude::*;

lagrangian! {
    /// A bead on a rotating, bobbing ring (rheonomic) that is also held on
    /// a plane through the ring's centre: two constraints on three
    /// Cartesian coordinates.
    pub struct BeadOnMovingRing {
        coordinates: x, y, z;
        parameters: m, r, w, a, g;
        let zc = a*sin(w*t);
        kinetic: m/2*(dot(x)^2 + dot(y)^2 + dot(z)^2);
        potential: m*g*z;
        constraints:
            ring: x^2 + y^2 + (z - zc)^2 = r^2,
            plane: x*sin(w*t) = y*cos(w*t);
    }
}

lagrangian! {
    pub struct FreeParticle {
        coordinates: x, y, z;
        parameters: m;
        kinetic: m/2*(dot(x)^2 + dot(y)^2 + dot(z)^2);
        potential: 0;
    }
}

fn model() -> BeadOnMovingRing {
    BeadOnMovingRing::new(1.3, 0.7, 2.1, 0.3, 9.81)
}

const STATES: [(f64, [f64; 3], [f64; 3]); 3] = [
    (0.2, [0.5, -0.4, 0.1], [0.3, 1.2, -0.7]),
    (1.7, [-0.3, 0.6, 0.9], [-1.1, 0.4, 0.2]),
    (-0.8, [0.1, 0.2, -0.5], [0.0, -0.6, 1.5]),
];

#[test]
fn bead_on_a_moving_ring_matches_finite_differences_of_its_constraints() {
    let model = model();
    let h = 1e-4;
    for (t, q, v) in STATES {
        let (q, v) = (Vector3::from(q), Vector3::from(v));
        let phi = |s: f64| model.constraints(t + s, &(q + v * s));
        let g = model.constraint_jacobian(t, &q);
        for j in 0..3 {
            let e = Vector3::ith(j, h);
            let d = (model.constraints(t, &(q + e)) - model.constraints(t, &(q - e))) / (2.0 * h);
            assert!((g.column(j) - d).norm() < 1e-7, "G column {j}");
        }
        let phidot = (phi(h) - phi(-h)) / (2.0 * h);
        assert!((model.constraint_velocities(t, &q, &v) - phidot).norm() < 1e-7);
        let h = 1e-3;
        let phiddot = (phi(h) - 2.0 * phi(0.0) + phi(-h)) / (h * h);
        assert!((model.constraint_bias(t, &q, &v) - phiddot).norm() < 1e-4);
    }
}

#[test]
fn constrained_system_is_the_separate_methods_together() {
    let model = model();
    for (t, q, v) in STATES {
        let (q, v) = (Vector3::from(q), Vector3::from(v));
        let (m, f, g, gamma) = model.constrained_system(t, &q, &v);
        let (m2, f2) = model.mass_matrix_and_forcing(t, &q, &v);
        assert!((m - m2).norm() < 1e-14 && (f - f2).norm() < 1e-14);
        assert!((g - model.constraint_jacobian(t, &q)).norm() < 1e-14);
        assert!((gamma - model.constraint_bias(t, &q, &v)).norm() < 1e-14);
    }
}

/// Returns what a generic integrator would learn of a model's constraints.
struct Count;

impl Visitor<f64, 3> for Count {
    type Output = (usize, &'static str);
    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<f64>) -> Self::Output
    where
        H: Holonomic<3, C, Scalar = f64> + ?Sized,
    {
        let _ = model;
        (C, H::CONSTRAINTS[0])
    }
}

#[test]
fn a_constrained_model_is_reached_through_visit_constraints() {
    assert_eq!(BeadOnMovingRing::<f64>::CONSTRAINTS, ["ring", "plane"]);
    assert_eq!(model().visit_constraints(Count), Some((2, "ring")));
    assert_eq!(FreeParticle::new(1.0).visit_constraints(Count), None);
}
