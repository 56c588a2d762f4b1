//! The damped two-mass chain, with Rayleigh damping or damping forces,
//! free or driven.

use crate::support::closed_form::*;
use lagrange::models::RayleighTwoMassChain;
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;

// ---------------------------------------------------------------------------
// Damped two-mass spring chain: wall–k1–m1–k2–m2–k3–wall, a damper c_i in
// parallel with each spring k_i.
// ---------------------------------------------------------------------------

lagrangian! {
    /// The same chain with the dampers written out as generalized forces,
    /// and a harmonic force `F0 cos(ω t)` pushing the first mass.
    pub struct ForcedDampedChain {
        coordinates: x1, x2;
        parameters: m1, m2, k1, k2, k3, c1, c2, c3, f0, omega;
        kinetic: m1/2*dot(x1)^2 + m2/2*dot(x2)^2;
        potential: k1/2*x1^2 + k2/2*(x2 - x1)^2 + k3/2*x2^2;
        forces:
            x1 = -(c1 + c2)*dot(x1) + c2*dot(x2) + f0*cos(omega*t),
            x2 = c2*dot(x1) - (c2 + c3)*dot(x2);
    }
}

/// Parameters of the chain; `f0 = 0` for the unforced one.
#[derive(Clone, Copy)]
struct Chain {
    m1: f64,
    m2: f64,
    k1: f64,
    k2: f64,
    k3: f64,
    c1: f64,
    c2: f64,
    c3: f64,
    f0: f64,
    omega: f64,
}

impl Chain {
    fn random(rng: &mut rand::rngs::StdRng) -> Self {
        Chain {
            m1: positive(rng),
            m2: positive(rng),
            k1: uniform(rng, 1.0, 20.0),
            k2: uniform(rng, 1.0, 20.0),
            k3: uniform(rng, 1.0, 20.0),
            c1: uniform(rng, 0.1, 2.0),
            c2: uniform(rng, 0.1, 2.0),
            c3: uniform(rng, 0.1, 2.0),
            f0: uniform(rng, 0.5, 5.0),
            omega: uniform(rng, 0.5, 5.0),
        }
    }

    fn rayleigh(&self) -> RayleighTwoMassChain {
        let c = *self;
        RayleighTwoMassChain::new(c.m1, c.m2, c.k1, c.k2, c.k3, c.c1, c.c2, c.c3)
    }

    fn forced(&self) -> ForcedDampedChain {
        let c = *self;
        ForcedDampedChain::new(
            c.m1, c.m2, c.k1, c.k2, c.k3, c.c1, c.c2, c.c3, c.f0, c.omega,
        )
    }

    /// `M = diag(m1, m2)`.
    fn mass(&self) -> [[Closed; 2]; 2] {
        [
            [Closed::sum(&[self.m1]), Closed::sum(&[0.0])],
            [Closed::sum(&[0.0]), Closed::sum(&[self.m2])],
        ]
    }

    /// From the textbook equations
    ///   m1 ẍ1 + (c1+c2) ẋ1 − c2 ẋ2 + (k1+k2) x1 − k2 x2 = F1(t)
    ///   m2 ẍ2 − c2 ẋ1 + (c2+c3) ẋ2 − k2 x1 + (k2+k3) x2 = 0
    /// with F1 = F0 cos(ω t): everything but the accelerations, moved right.
    fn forcing(&self, t: f64, x: &Vector2<f64>, v: &Vector2<f64>) -> [Closed; 2] {
        let Chain {
            k1,
            k2,
            k3,
            c1,
            c2,
            c3,
            f0,
            omega,
            ..
        } = *self;
        let f1 = f0 * (omega * t).cos();
        [
            Closed::sum(&[
                -(c1 + c2) * v[0],
                c2 * v[1],
                -(k1 + k2) * x[0],
                k2 * x[1],
                f1,
            ]),
            Closed::sum(&[c2 * v[0], -(c2 + c3) * v[1], k2 * x[0], -(k2 + k3) * x[1]]),
        ]
    }

    /// The textbook left-hand sides minus right-hand sides, term by term.
    fn residual(
        &self,
        t: f64,
        x: &Vector2<f64>,
        v: &Vector2<f64>,
        a: &Vector2<f64>,
    ) -> [Closed; 2] {
        let Chain {
            m1,
            m2,
            k1,
            k2,
            k3,
            c1,
            c2,
            c3,
            f0,
            omega,
        } = *self;
        let f1 = f0 * (omega * t).cos();
        [
            Closed::sum(&[
                m1 * a[0],
                (c1 + c2) * v[0],
                -c2 * v[1],
                (k1 + k2) * x[0],
                -k2 * x[1],
                -f1,
            ]),
            Closed::sum(&[
                m2 * a[1],
                -c2 * v[0],
                (c2 + c3) * v[1],
                -k2 * x[0],
                (k2 + k3) * x[1],
            ]),
        ]
    }

    /// `T + V = ½ m1 ẋ1² + ½ m2 ẋ2² + ½ k1 x1² + ½ k2 (x2 − x1)² + ½ k3 x2²`.
    fn energy(&self, x: &Vector2<f64>, v: &Vector2<f64>) -> Closed {
        let Chain {
            m1, m2, k1, k2, k3, ..
        } = *self;
        Closed::sum(&[
            m1 * v[0] * v[0] / 2.0,
            m2 * v[1] * v[1] / 2.0,
            k1 * x[0] * x[0] / 2.0,
            k2 * (x[1] - x[0]) * (x[1] - x[0]) / 2.0,
            k3 * x[1] * x[1] / 2.0,
        ])
    }
}

/// A random chain state: displacements, velocities, accelerations.
fn chain_state(rng: &mut rand::rngs::StdRng) -> (f64, Vector2<f64>, Vector2<f64>, Vector2<f64>) {
    let t = time(rng);
    let x = Vector2::new(uniform(rng, -1.0, 1.0), uniform(rng, -1.0, 1.0));
    let v = Vector2::new(rate(rng), rate(rng));
    let a = Vector2::new(rate(rng), rate(rng));
    (t, x, v, a)
}

#[test]
fn rayleigh_damped_chain_matches_textbook_equations() {
    let mut rng = rng(1);
    for _ in 0..SAMPLES {
        let chain = Chain {
            f0: 0.0,
            ..Chain::random(&mut rng)
        };
        let model = chain.rayleigh();
        let (t, x, v, a) = chain_state(&mut rng);
        assert_matrix_close("M", &model.mass_matrix(t, &x), &chain.mass());
        assert_vector_close("f", &model.forcing(t, &x, &v), &chain.forcing(t, &x, &v));
        assert_vector_close(
            "M q̈ − f",
            &residual(&model, t, &x, &v, &a),
            &chain.residual(t, &x, &v, &a),
        );
        assert_close("T + V", model.energy(t, &x, &v), chain.energy(&x, &v));
    }
}

#[test]
fn chain_with_damping_as_forces_and_harmonic_drive_matches_textbook_equations() {
    let mut rng = rng(2);
    for _ in 0..SAMPLES {
        let chain = Chain::random(&mut rng);
        let model = chain.forced();
        let (t, x, v, a) = chain_state(&mut rng);
        assert_matrix_close("M", &model.mass_matrix(t, &x), &chain.mass());
        assert_vector_close("f", &model.forcing(t, &x, &v), &chain.forcing(t, &x, &v));
        assert_vector_close(
            "M q̈ − f",
            &residual(&model, t, &x, &v, &a),
            &chain.residual(t, &x, &v, &a),
        );
        // Generalized forces do no work on the energy function: T + V only.
        assert_close("T + V", model.energy(t, &x, &v), chain.energy(&x, &v));
    }
}

#[test]
fn rayleigh_damping_and_explicit_damping_forces_give_the_same_equations() {
    // With the drive switched off, −∂R/∂q̇ and the hand-written Q are the same
    // forces; the two routes through the engine must agree to round-off.
    let mut rng = rng(3);
    for _ in 0..SAMPLES {
        let chain = Chain {
            f0: 0.0,
            ..Chain::random(&mut rng)
        };
        let (t, x, v, _) = chain_state(&mut rng);
        let via_r = chain.rayleigh().forcing(t, &x, &v);
        let via_q = chain.forced().forcing(t, &x, &v);
        let want = chain.forcing(t, &x, &v);
        for i in 0..2 {
            let scale = Closed {
                value: via_q[i],
                scale: want[i].scale,
            };
            assert_close(&format!("f[{i}] via R vs via Q"), via_r[i], scale);
        }
    }
}

#[test]
fn chain_models_declare_their_coordinates_and_parameters() {
    assert_eq!(RayleighTwoMassChain::<f64>::DOF, 2);
    assert_eq!(RayleighTwoMassChain::<f64>::COORDINATES, ["x1", "x2"]);
    assert_eq!(
        RayleighTwoMassChain::<f64>::PARAMETERS,
        ["m1", "m2", "k1", "k2", "k3", "c1", "c2", "c3"]
    );
    let p = RayleighTwoMassChain::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0);
    assert_eq!(
        [p.m1, p.m2, p.k1, p.k2, p.k3, p.c1, p.c2, p.c3],
        [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0]
    );

    assert_eq!(ForcedDampedChain::<f64>::DOF, 2);
    assert_eq!(ForcedDampedChain::<f64>::COORDINATES, ["x1", "x2"]);
    assert_eq!(
        ForcedDampedChain::<f64>::PARAMETERS,
        [
            "m1", "m2", "k1", "k2", "k3", "c1", "c2", "c3", "f0", "omega"
        ]
    );
    let p = ForcedDampedChain::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0);
    assert_eq!(
        [
            p.m1, p.m2, p.k1, p.k2, p.k3, p.c1, p.c2, p.c3, p.f0, p.omega
        ],
        [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0]
    );
}

#[test]
fn chain_models_compute_m_and_f_together_exactly_as_apart() {
    let chain = Chain::random(&mut rng(4));
    assert_combined_call_is_bitwise_separate(&chain.rayleigh(), 5);
    assert_combined_call_is_bitwise_separate(&chain.forced(), 6);
}
