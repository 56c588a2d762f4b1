//! The double pendulum, in three spellings and two precisions.

use crate::support::closed_form::*;
use lagrange::models::DoublePendulum;
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;

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
