//! Constraints that do not move: the spherical and the elastic pendulum,
//! and the cart-pole (its cart driven by a prescribed force).

use crate::support::closed_form::*;
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;

// ---------------------------------------------------------------------------
// Spherical pendulum: bob m on a massless rod l, θ polar angle from the
// downward vertical, φ azimuth.
// ---------------------------------------------------------------------------

lagrangian! {
    pub struct SphericalPendulum {
        coordinates: theta, phi;
        parameters: m, l, g;
        let x = l*sin(theta)*cos(phi);
        let y = l*sin(theta)*sin(phi);
        let z = -l*cos(theta);
        kinetic: m/2*(dot(x)^2 + dot(y)^2 + dot(z)^2);
        potential: m*g*z;
    }
}

#[test]
fn spherical_pendulum_matches_textbook_equations() {
    // T = ½ m l² (θ̇² + sin²θ φ̇²), V = −m g l cos θ, so
    //   M = diag(m l², m l² sin²θ)
    //   m l² θ̈ = m l² sin θ cos θ φ̇² − m g l sin θ
    //   d/dt(m l² sin²θ φ̇) = 0, i.e. m l² sin²θ φ̈ = −2 m l² sin θ cos θ θ̇ φ̇.
    let mut rng = rng(20);
    for _ in 0..SAMPLES {
        let (m, l, g) = (positive(&mut rng), positive(&mut rng), gravity(&mut rng));
        let model = SphericalPendulum::new(m, l, g);
        let t = time(&mut rng);
        let q = Vector2::new(angle(&mut rng), angle(&mut rng));
        let qd = Vector2::new(rate(&mut rng), rate(&mut rng));
        let qdd = Vector2::new(rate(&mut rng), rate(&mut rng));
        let (th, thd, phd) = (q[0], qd[0], qd[1]);
        let (s, c) = (th.sin(), th.cos());
        let ml2 = m * l * l;

        // The zero off-diagonal is judged against the scale of the diagonal:
        // the Cartesian route may leave round-off there instead of an exact 0.
        let zero = Closed {
            value: 0.0,
            scale: ml2,
        };
        let mass = [
            [Closed::sum(&[ml2]), zero],
            [zero, Closed::sum(&[ml2 * s * s])],
        ];
        assert_matrix_close("M", &model.mass_matrix(t, &q), &mass);
        let forcing = [
            Closed::sum(&[ml2 * s * c * phd * phd, -m * g * l * s]),
            Closed::sum(&[-2.0 * ml2 * s * c * thd * phd]),
        ];
        assert_vector_close("f", &model.forcing(t, &q, &qd), &forcing);
        let lhs = [
            Closed::sum(&[ml2 * qdd[0], -ml2 * s * c * phd * phd, m * g * l * s]),
            Closed::sum(&[ml2 * s * s * qdd[1], 2.0 * ml2 * s * c * thd * phd]),
        ];
        assert_vector_close("M q̈ − f", &residual(&model, t, &q, &qd, &qdd), &lhs);
        let energy = Closed::sum(&[
            ml2 * thd * thd / 2.0,
            ml2 * s * s * phd * phd / 2.0,
            -m * g * l * c,
        ]);
        assert_close("T + V", model.energy(t, &q, &qd), energy);
    }
}

#[test]
fn spherical_pendulum_declares_its_coordinates_and_parameters() {
    assert_eq!(SphericalPendulum::<f64>::DOF, 2);
    assert_eq!(SphericalPendulum::<f64>::COORDINATES, ["theta", "phi"]);
    assert_eq!(SphericalPendulum::<f64>::PARAMETERS, ["m", "l", "g"]);
    let p = SphericalPendulum::new(1.0, 2.0, 3.0);
    assert_eq!([p.m, p.l, p.g], [1.0, 2.0, 3.0]);
}

#[test]
fn spherical_pendulum_computes_m_and_f_together_exactly_as_apart() {
    assert_combined_call_is_bitwise_separate(&SphericalPendulum::new(1.3, 0.7, 9.81), 21);
}

// ---------------------------------------------------------------------------
// Elastic pendulum: bob m on a massless spring of stiffness k and natural
// length l0, polar coordinates (r, θ), θ from the downward vertical.
// ---------------------------------------------------------------------------

lagrangian! {
    pub struct ElasticPendulum {
        coordinates: r, theta;
        parameters: m, k, l0, g;
        let x = r*sin(theta);
        let y = -r*cos(theta);
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: k/2*(r - l0)^2 + m*g*y;
    }
}

#[test]
fn elastic_pendulum_matches_textbook_equations() {
    // T = ½ m (ṙ² + r² θ̇²), V = ½ k (r − l0)² − m g r cos θ, so
    //   M = diag(m, m r²)
    //   m r̈ = m r θ̇² − k (r − l0) + m g cos θ              (radial: centripetal, spring, gravity)
    //   m r² θ̈ = −2 m r ṙ θ̇ − m g r sin θ                  (d/dt of angular momentum = torque)
    let mut rng = rng(22);
    for _ in 0..SAMPLES {
        let (m, k, l0, g) = (
            positive(&mut rng),
            uniform(&mut rng, 1.0, 50.0),
            positive(&mut rng),
            gravity(&mut rng),
        );
        let model = ElasticPendulum::new(m, k, l0, g);
        let t = time(&mut rng);
        let q = Vector2::new(uniform(&mut rng, 0.2, 3.0), angle(&mut rng));
        let qd = Vector2::new(rate(&mut rng), rate(&mut rng));
        let qdd = Vector2::new(rate(&mut rng), rate(&mut rng));
        let (r, th, rd, thd) = (q[0], q[1], qd[0], qd[1]);
        let (s, c) = (th.sin(), th.cos());

        let zero = Closed {
            value: 0.0,
            scale: m,
        };
        let mass = [[Closed::sum(&[m]), zero], [zero, Closed::sum(&[m * r * r])]];
        assert_matrix_close("M", &model.mass_matrix(t, &q), &mass);
        let forcing = [
            Closed::sum(&[m * r * thd * thd, -k * (r - l0), m * g * c]),
            Closed::sum(&[-2.0 * m * r * rd * thd, -m * g * r * s]),
        ];
        assert_vector_close("f", &model.forcing(t, &q, &qd), &forcing);
        let lhs = [
            Closed::sum(&[m * qdd[0], -m * r * thd * thd, k * (r - l0), -m * g * c]),
            Closed::sum(&[m * r * r * qdd[1], 2.0 * m * r * rd * thd, m * g * r * s]),
        ];
        assert_vector_close("M q̈ − f", &residual(&model, t, &q, &qd, &qdd), &lhs);
        let energy = Closed::sum(&[
            m * rd * rd / 2.0,
            m * r * r * thd * thd / 2.0,
            k * (r - l0) * (r - l0) / 2.0,
            -m * g * r * c,
        ]);
        assert_close("T + V", model.energy(t, &q, &qd), energy);
    }
}

#[test]
fn elastic_pendulum_declares_its_coordinates_and_parameters() {
    assert_eq!(ElasticPendulum::<f64>::DOF, 2);
    assert_eq!(ElasticPendulum::<f64>::COORDINATES, ["r", "theta"]);
    assert_eq!(ElasticPendulum::<f64>::PARAMETERS, ["m", "k", "l0", "g"]);
    let p = ElasticPendulum::new(1.0, 2.0, 3.0, 4.0);
    assert_eq!([p.m, p.k, p.l0, p.g], [1.0, 2.0, 3.0, 4.0]);
}

#[test]
fn elastic_pendulum_computes_m_and_f_together_exactly_as_apart() {
    assert_combined_call_is_bitwise_separate(&ElasticPendulum::new(0.8, 12.0, 1.1, 9.81), 23);
}

// ---------------------------------------------------------------------------
// Cart-pole: a cart of mass mc on a horizontal track (position x), a UNIFORM
// rod of mass m and length l pivoted on it (angle θ from the downward
// vertical), and a prescribed force F(t) = F0 sin(ω t) on the cart.
// ---------------------------------------------------------------------------

lagrangian! {
    pub struct CartPole {
        coordinates: x, theta;
        parameters: mc, m, l, g, f0, omega;
        // The rod's centre of mass, half-way along it.
        let xr = x + l/2*sin(theta);
        let yr = -l/2*cos(theta);
        // Translation of both bodies, plus the rod's spin about its centre
        // (moment of inertia m l²/12).
        kinetic: mc/2*dot(x)^2 + m/2*(dot(xr)^2 + dot(yr)^2) + m*l^2/24*dot(theta)^2;
        potential: m*g*yr;
        forces: x = f0*sin(omega*t);
    }
}

#[test]
fn cart_pole_with_a_driven_cart_matches_textbook_equations() {
    // T = ½ (mc+m) ẋ² + ½ m l cos θ ẋ θ̇ + ⅙ m l² θ̇²,  V = −½ m g l cos θ, so
    //   M = [[mc+m, ½ m l cos θ], [½ m l cos θ, ⅓ m l²]]
    //   (mc+m) ẍ + ½ m l cos θ θ̈ − ½ m l sin θ θ̇² = F0 sin(ω t)
    //   ½ m l cos θ ẍ + ⅓ m l² θ̈ + ½ m g l sin θ = 0
    let mut rng = rng(24);
    for _ in 0..SAMPLES {
        let (mc, m, l, g) = (
            positive(&mut rng),
            positive(&mut rng),
            positive(&mut rng),
            gravity(&mut rng),
        );
        let (f0, omega) = (uniform(&mut rng, 0.5, 5.0), uniform(&mut rng, 0.5, 5.0));
        let model = CartPole::new(mc, m, l, g, f0, omega);
        let t = time(&mut rng);
        let q = Vector2::new(uniform(&mut rng, -2.0, 2.0), angle(&mut rng));
        let qd = Vector2::new(rate(&mut rng), rate(&mut rng));
        let qdd = Vector2::new(rate(&mut rng), rate(&mut rng));
        let (th, thd) = (q[1], qd[1]);
        let (s, c) = (th.sin(), th.cos());
        let push = f0 * (omega * t).sin();

        let coupling = Closed::sum(&[m * l * c / 2.0]);
        let mass = [
            [Closed::sum(&[mc, m]), coupling],
            [coupling, Closed::sum(&[m * l * l / 3.0])],
        ];
        assert_matrix_close("M", &model.mass_matrix(t, &q), &mass);
        let forcing = [
            Closed::sum(&[m * l * s * thd * thd / 2.0, push]),
            Closed::sum(&[-m * g * l * s / 2.0]),
        ];
        assert_vector_close("f", &model.forcing(t, &q, &qd), &forcing);
        let lhs = [
            Closed::sum(&[
                (mc + m) * qdd[0],
                m * l * c * qdd[1] / 2.0,
                -m * l * s * thd * thd / 2.0,
                -push,
            ]),
            Closed::sum(&[
                m * l * c * qdd[0] / 2.0,
                m * l * l * qdd[1] / 3.0,
                m * g * l * s / 2.0,
            ]),
        ];
        assert_vector_close("M q̈ − f", &residual(&model, t, &q, &qd, &qdd), &lhs);
        let energy = Closed::sum(&[
            (mc + m) * qd[0] * qd[0] / 2.0,
            m * l * c * qd[0] * thd / 2.0,
            m * l * l * thd * thd / 6.0,
            -m * g * l * c / 2.0,
        ]);
        assert_close("T + V", model.energy(t, &q, &qd), energy);
    }
}

#[test]
fn cart_pole_declares_its_coordinates_and_parameters() {
    assert_eq!(CartPole::<f64>::DOF, 2);
    assert_eq!(CartPole::<f64>::COORDINATES, ["x", "theta"]);
    assert_eq!(
        CartPole::<f64>::PARAMETERS,
        ["mc", "m", "l", "g", "f0", "omega"]
    );
    let p = CartPole::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0);
    assert_eq!(
        [p.mc, p.m, p.l, p.g, p.f0, p.omega],
        [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]
    );
}

#[test]
fn cart_pole_computes_m_and_f_together_exactly_as_apart() {
    assert_combined_call_is_bitwise_separate(&CartPole::new(1.5, 0.4, 0.9, 9.81, 2.0, 1.7), 25);
}
