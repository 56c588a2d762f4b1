//! The classics: what `lagrangian!` derives for the damped two-mass chain and
//! the double pendulum, against the equations every mechanics text writes
//! down. Each closed form is derived by hand, written as its list of terms
//! (see `support::closed_form::Closed`), and compared at many random states
//! and parameters. The double pendulum is the one of `lagrange::models`,
//! written through the Cartesian positions of its bobs; two more spellings
//! of it stand here.

use crate::support::closed_form::*;
use lagrange::models::{DoublePendulum, RayleighTwoMassChain};
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
        ["m1", "m2", "k1", "k2", "k3", "c1", "c2", "c3", "f0", "omega"]
    );
    let p = ForcedDampedChain::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0);
    assert_eq!(
        [p.m1, p.m2, p.k1, p.k2, p.k3, p.c1, p.c2, p.c3, p.f0, p.omega],
        [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0]
    );
}

#[test]
fn chain_models_compute_m_and_f_together_exactly_as_apart() {
    let chain = Chain::random(&mut rng(4));
    assert_combined_call_is_bitwise_separate(&chain.rayleigh(), 5);
    assert_combined_call_is_bitwise_separate(&chain.forced(), 6);
}

// ---------------------------------------------------------------------------
// Double pendulum: point masses m1, m2 on massless rods l1, l2, absolute
// angles θ1, θ2 from the downward vertical.
// ---------------------------------------------------------------------------

lagrangian! {
    /// The same model in Rust method syntax and float literals.
    pub struct DoublePendulumInMethodSyntax {
        coordinates: theta1, theta2;
        parameters: m1, m2, l1, l2, g;
        let x1 = l1*theta1.sin();
        let y1 = -l1*theta1.cos();
        let x2 = x1 + l2*theta2.sin();
        let y2 = y1 - l2*theta2.cos();
        kinetic: m1*(dot(x1).powi(2) + dot(y1).powi(2))/2.0 + 0.5*m2*(dot(x2).powi(2) + dot(y2).powi(2));
        potential: m1*g*y1 + m2*g*y2;
    }
}

lagrangian! {
    /// The double pendulum with T and V already in generalized coordinates,
    /// the coupling through the relative angle `(theta1 - theta2).cos()`.
    pub struct DoublePendulumInRelativeAngle {
        coordinates: theta1, theta2;
        parameters: m1, m2, l1, l2, g;
        kinetic: (m1 + m2)/2*l1^2*dot(theta1)^2 + m2/2*l2^2*dot(theta2)^2
            + m2*l1*l2*dot(theta1)*dot(theta2)*(theta1 - theta2).cos();
        potential: -(m1 + m2)*g*l1*theta1.cos() - m2*g*l2*theta2.cos();
    }
}

#[derive(Clone, Copy)]
struct Pendulums {
    m1: f64,
    m2: f64,
    l1: f64,
    l2: f64,
    g: f64,
}

impl Pendulums {
    fn random(rng: &mut rand::rngs::StdRng) -> Self {
        Pendulums {
            m1: positive(rng),
            m2: positive(rng),
            l1: positive(rng),
            l2: positive(rng),
            g: gravity(rng),
        }
    }

    /// `M = [[(m1+m2) l1², m2 l1 l2 cos(θ1−θ2)], [m2 l1 l2 cos(θ1−θ2), m2 l2²]]`.
    fn mass(&self, th: &Vector2<f64>) -> [[Closed; 2]; 2] {
        let Pendulums { m1, m2, l1, l2, .. } = *self;
        let coupling = Closed::sum(&[m2 * l1 * l2 * (th[0] - th[1]).cos()]);
        [
            [Closed::sum(&[(m1 + m2) * l1 * l1]), coupling],
            [coupling, Closed::sum(&[m2 * l2 * l2])],
        ]
    }

    /// The textbook equations
    ///   (m1+m2) l1² θ̈1 + m2 l1 l2 θ̈2 cos(θ1−θ2) + m2 l1 l2 θ̇2² sin(θ1−θ2) + (m1+m2) g l1 sin θ1 = 0
    ///   m2 l2² θ̈2 + m2 l1 l2 θ̈1 cos(θ1−θ2) − m2 l1 l2 θ̇1² sin(θ1−θ2) + m2 g l2 sin θ2 = 0
    /// with the accelerations kept left and the rest moved right.
    fn forcing(&self, th: &Vector2<f64>, w: &Vector2<f64>) -> [Closed; 2] {
        let Pendulums { m1, m2, l1, l2, g } = *self;
        let s12 = (th[0] - th[1]).sin();
        [
            Closed::sum(&[
                -m2 * l1 * l2 * w[1] * w[1] * s12,
                -(m1 + m2) * g * l1 * th[0].sin(),
            ]),
            Closed::sum(&[m2 * l1 * l2 * w[0] * w[0] * s12, -m2 * g * l2 * th[1].sin()]),
        ]
    }

    /// The same textbook equations, left-hand sides term by term.
    fn residual(&self, th: &Vector2<f64>, w: &Vector2<f64>, a: &Vector2<f64>) -> [Closed; 2] {
        let Pendulums { m1, m2, l1, l2, g } = *self;
        let (c12, s12) = ((th[0] - th[1]).cos(), (th[0] - th[1]).sin());
        [
            Closed::sum(&[
                (m1 + m2) * l1 * l1 * a[0],
                m2 * l1 * l2 * a[1] * c12,
                m2 * l1 * l2 * w[1] * w[1] * s12,
                (m1 + m2) * g * l1 * th[0].sin(),
            ]),
            Closed::sum(&[
                m2 * l2 * l2 * a[1],
                m2 * l1 * l2 * a[0] * c12,
                -m2 * l1 * l2 * w[0] * w[0] * s12,
                m2 * g * l2 * th[1].sin(),
            ]),
        ]
    }

    /// `T = ½ (m1+m2) l1² θ̇1² + ½ m2 l2² θ̇2² + m2 l1 l2 θ̇1 θ̇2 cos(θ1−θ2)`.
    fn kinetic(&self, th: &Vector2<f64>, w: &Vector2<f64>) -> [f64; 3] {
        let Pendulums { m1, m2, l1, l2, .. } = *self;
        [
            (m1 + m2) * l1 * l1 * w[0] * w[0] / 2.0,
            m2 * l2 * l2 * w[1] * w[1] / 2.0,
            m2 * l1 * l2 * w[0] * w[1] * (th[0] - th[1]).cos(),
        ]
    }

    /// `V = −(m1+m2) g l1 cos θ1 − m2 g l2 cos θ2`.
    fn potential(&self, th: &Vector2<f64>) -> [f64; 2] {
        let Pendulums { m1, m2, l1, l2, g } = *self;
        [
            -(m1 + m2) * g * l1 * th[0].cos(),
            -m2 * g * l2 * th[1].cos(),
        ]
    }
}

fn pendulum_state(rng: &mut rand::rngs::StdRng) -> (f64, Vector2<f64>, Vector2<f64>, Vector2<f64>) {
    let t = time(rng);
    let th = Vector2::new(angle(rng), angle(rng));
    let w = Vector2::new(rate(rng), rate(rng));
    let a = Vector2::new(rate(rng), rate(rng));
    (t, th, w, a)
}

/// Every derived quantity of a double-pendulum model against the textbook.
fn assert_matches_textbook_double_pendulum<L: Lagrangian<2, Scalar = f64>>(
    build: impl Fn(Pendulums) -> L,
    seed: u64,
) {
    let mut rng = rng(seed);
    for _ in 0..SAMPLES {
        let p = Pendulums::random(&mut rng);
        let model = build(p);
        let (t, th, w, a) = pendulum_state(&mut rng);
        assert_matrix_close("M", &model.mass_matrix(t, &th), &p.mass(&th));
        assert_vector_close("f", &model.forcing(t, &th, &w), &p.forcing(&th, &w));
        assert_vector_close(
            "M q̈ − f",
            &residual(&model, t, &th, &w, &a),
            &p.residual(&th, &w, &a),
        );
        let (kinetic, potential) = (p.kinetic(&th, &w), p.potential(&th));
        assert_close("T", model.kinetic_energy(t, &th, &w), Closed::sum(&kinetic));
        assert_close("V", model.potential_energy(t, &th), Closed::sum(&potential));
        let total: Vec<f64> = kinetic.iter().chain(&potential).copied().collect();
        assert_close("T + V", model.energy(t, &th, &w), Closed::sum(&total));
    }
}

#[test]
fn double_pendulum_matches_textbook_equations() {
    assert_matches_textbook_double_pendulum(
        |p| DoublePendulum::new(p.m1, p.m2, p.l1, p.l2, p.g),
        10,
    );
}

#[test]
fn double_pendulum_in_relative_angle_form_matches_textbook_equations() {
    assert_matches_textbook_double_pendulum(
        |p| DoublePendulumInRelativeAngle::new(p.m1, p.m2, p.l1, p.l2, p.g),
        11,
    );
}

#[test]
fn double_pendulum_in_method_syntax_derives_identical_equations() {
    // Same tokens up to spelling (`sin(x)` vs `x.sin()`, `^2` vs `.powi(2)`,
    // `m/2` vs `0.5*m`), so the same simplified expressions and the same
    // floating-point operations: M, f and the energies agree bit for bit.
    let mut rng = rng(12);
    for _ in 0..SAMPLES {
        let p = Pendulums::random(&mut rng);
        let ops = DoublePendulum::new(p.m1, p.m2, p.l1, p.l2, p.g);
        let methods = DoublePendulumInMethodSyntax::new(p.m1, p.m2, p.l1, p.l2, p.g);
        let (t, th, w, _) = pendulum_state(&mut rng);
        assert_eq!(methods.mass_matrix(t, &th), ops.mass_matrix(t, &th));
        assert_eq!(methods.forcing(t, &th, &w), ops.forcing(t, &th, &w));
        assert_eq!(methods.energy(t, &th, &w), ops.energy(t, &th, &w));
    }
}

#[test]
fn double_pendulum_in_f32_agrees_with_f64() {
    // f32 has unit round-off 6e-8; M, f and T + V are a few dozen operations
    // and four sin/cos, so their error is at most ~3e-6 of the size of the
    // terms (the inputs are f32 values, exact in f64, so the f64 model is the
    // exact answer to ~1e-16). 1e-5 leaves margin and still catches any term
    // computed wrongly in f32, e.g. a constant converted to the wrong value.
    const F32_TOL: f64 = 1e-5;
    let mut rng = rng(13);
    for _ in 0..SAMPLES {
        let p = Pendulums::random(&mut rng);
        let single = DoublePendulum::<f32>::new(
            p.m1 as f32,
            p.m2 as f32,
            p.l1 as f32,
            p.l2 as f32,
            p.g as f32,
        );
        let p = Pendulums {
            m1: single.m1 as f64,
            m2: single.m2 as f64,
            l1: single.l1 as f64,
            l2: single.l2 as f64,
            g: single.g as f64,
        };
        let double = DoublePendulum::new(p.m1, p.m2, p.l1, p.l2, p.g);
        let (t, th, w, _) = pendulum_state(&mut rng);
        let (t32, th32, w32) = (t as f32, th.cast::<f32>(), w.cast::<f32>());
        let (t, th, w) = (t32 as f64, th32.cast::<f64>(), w32.cast::<f64>());

        let (m32, f32_) = single.mass_matrix_and_forcing(t32, &th32, &w32);
        let (m64, f64_) = double.mass_matrix_and_forcing(t, &th, &w);
        let mass = p.mass(&th);
        let forcing = p.forcing(&th, &w);
        for i in 0..2 {
            for j in 0..2 {
                let want = Closed {
                    value: m64[(i, j)],
                    scale: mass[i][j].scale,
                };
                assert_close_tol(&format!("M[{i},{j}]"), m32[(i, j)] as f64, want, F32_TOL);
            }
            let want = Closed {
                value: f64_[i],
                scale: forcing[i].scale,
            };
            assert_close_tol(&format!("f[{i}]"), f32_[i] as f64, want, F32_TOL);
        }
        let energy: Vec<f64> = p
            .kinetic(&th, &w)
            .into_iter()
            .chain(p.potential(&th))
            .collect();
        let want = Closed {
            value: double.energy(t, &th, &w),
            scale: Closed::sum(&energy).scale,
        };
        assert_close_tol(
            "T + V",
            single.energy(t32, &th32, &w32) as f64,
            want,
            F32_TOL,
        );
    }
}

#[test]
fn double_pendulum_models_declare_their_coordinates_and_parameters() {
    assert_eq!(DoublePendulum::<f64>::DOF, 2);
    assert_eq!(DoublePendulum::<f64>::COORDINATES, ["theta1", "theta2"]);
    assert_eq!(
        DoublePendulum::<f64>::PARAMETERS,
        ["m1", "m2", "l1", "l2", "g"]
    );
    let p = DoublePendulum::new(1.0, 2.0, 3.0, 4.0, 5.0);
    assert_eq!([p.m1, p.m2, p.l1, p.l2, p.g], [1.0, 2.0, 3.0, 4.0, 5.0]);

    assert_eq!(DoublePendulumInMethodSyntax::<f64>::DOF, 2);
    assert_eq!(
        DoublePendulumInMethodSyntax::<f64>::COORDINATES,
        ["theta1", "theta2"]
    );
    assert_eq!(
        DoublePendulumInMethodSyntax::<f64>::PARAMETERS,
        ["m1", "m2", "l1", "l2", "g"]
    );

    assert_eq!(DoublePendulumInRelativeAngle::<f64>::DOF, 2);
    assert_eq!(
        DoublePendulumInRelativeAngle::<f64>::COORDINATES,
        ["theta1", "theta2"]
    );
    assert_eq!(
        DoublePendulumInRelativeAngle::<f64>::PARAMETERS,
        ["m1", "m2", "l1", "l2", "g"]
    );
}

#[test]
fn double_pendulum_models_compute_m_and_f_together_exactly_as_apart() {
    let p = Pendulums::random(&mut rng(14));
    assert_combined_call_is_bitwise_separate(&DoublePendulum::new(p.m1, p.m2, p.l1, p.l2, p.g), 15);
    assert_combined_call_is_bitwise_separate(
        &DoublePendulumInMethodSyntax::new(p.m1, p.m2, p.l1, p.l2, p.g),
        16,
    );
    assert_combined_call_is_bitwise_separate(
        &DoublePendulumInRelativeAngle::new(p.m1, p.m2, p.l1, p.l2, p.g),
        17,
    );
}
