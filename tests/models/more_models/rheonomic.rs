//! Constraints that move with `t`: a spinning hoop, a rod of prescribed
//! length, a shaken support.

use super::{assert_term_matters, state1};
use crate::support::closed_form::*;
use lagrange::prelude::*;

// ---------------------------------------------------------------------------
// Bead of mass m on a hoop of radius r spinning at the prescribed constant
// rate Ω about the vertical: one coordinate θ, from the bottom of the hoop.
// ---------------------------------------------------------------------------

lagrangian! {
    pub struct BeadOnSpinningHoop {
        coordinates: theta;
        parameters: m, r, omega, g;
        let x = r*sin(theta)*cos(omega*t);
        let y = r*sin(theta)*sin(omega*t);
        let z = -r*cos(theta);
        kinetic: m/2*(dot(x)^2 + dot(y)^2 + dot(z)^2);
        potential: m*g*z;
    }
}

#[test]
fn bead_on_spinning_hoop_matches_textbook_equations() {
    // T = ½ m r² (θ̇² + Ω² sin²θ), V = −m g r cos θ, so
    //   m r² θ̈ = m r² Ω² sin θ cos θ − m g r sin θ.
    // The hoop's rotation is in the positions only through t, so the
    // centrifugal term comes from ∂L/∂θ of the t-dependent positions; the
    // t-dependent parts of ∂T/∂θ̇ cancel (p = m r² θ̇), as they must.
    let mut rng = rng(26);
    let mut centrifugal_share = 0.0f64;
    for _ in 0..SAMPLES {
        let (m, r, omega, g) = (
            positive(&mut rng),
            positive(&mut rng),
            uniform(&mut rng, 1.0, 6.0),
            gravity(&mut rng),
        );
        let model = BeadOnSpinningHoop::new(m, r, omega, g);
        let (t, q, qd, qdd) = state1(&mut rng);
        let (s, c) = (q[0].sin(), q[0].cos());
        let mr2 = m * r * r;

        assert_close("M", model.mass_matrix(t, &q)[(0, 0)], Closed::sum(&[mr2]));
        let centrifugal = mr2 * omega * omega * s * c;
        let forcing = Closed::sum(&[centrifugal, -m * g * r * s]);
        centrifugal_share = centrifugal_share.max(centrifugal.abs() / forcing.scale.max(1.0));
        assert_close("f", model.forcing(t, &q, &qd)[0], forcing);
        let lhs = Closed::sum(&[mr2 * qdd[0], -centrifugal, m * g * r * s]);
        assert_close("M q̈ − f", residual(&model, t, &q, &qd, &qdd)[0], lhs);
        // The energy function T + V (not conserved here: the motor does work).
        let energy = Closed::sum(&[
            mr2 * qd[0] * qd[0] / 2.0,
            mr2 * omega * omega * s * s / 2.0,
            -m * g * r * c,
        ]);
        assert_close("T + V", model.energy(t, &q, &qd), energy);
    }
    assert_term_matters(
        "the centrifugal term m r² Ω² sin θ cos θ",
        centrifugal_share,
    );
}

#[test]
fn bead_on_spinning_hoop_declares_its_coordinates_and_parameters() {
    assert_eq!(BeadOnSpinningHoop::<f64>::DOF, 1);
    assert_eq!(BeadOnSpinningHoop::<f64>::COORDINATES, ["theta"]);
    assert_eq!(
        BeadOnSpinningHoop::<f64>::PARAMETERS,
        ["m", "r", "omega", "g"]
    );
    let p = BeadOnSpinningHoop::new(1.0, 2.0, 3.0, 4.0);
    assert_eq!([p.m, p.r, p.omega, p.g], [1.0, 2.0, 3.0, 4.0]);
}

#[test]
fn bead_on_spinning_hoop_computes_m_and_f_together_exactly_as_apart() {
    assert_combined_call_is_bitwise_separate(&BeadOnSpinningHoop::new(0.3, 0.5, 4.0, 9.81), 27);
}

// ---------------------------------------------------------------------------
// Variable-length pendulum: bob m on a rod whose length is prescribed,
// l(t) = l0 + a sin(ω t) (a < l0), θ from the downward vertical.
// ---------------------------------------------------------------------------

lagrangian! {
    pub struct VariableLengthPendulum {
        coordinates: theta;
        parameters: m, l0, a, omega, g;
        let l = l0 + a*sin(omega*t);
        let x = l*sin(theta);
        let y = -l*cos(theta);
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*y;
    }
}

#[test]
fn variable_length_pendulum_matches_textbook_equations() {
    // T = ½ m (l̇² + l² θ̇²), V = −m g l cos θ, with l̇ = a ω cos(ω t):
    //   p = m l² θ̇, whose explicit time derivative ∂p/∂t = 2 m l l̇ θ̇ is the
    //   whole Coriolis-like term of
    //   m l² θ̈ + 2 m l l̇ θ̇ + m g l sin θ = 0.
    let mut rng = rng(28);
    let mut dp_dt_share = 0.0f64;
    for _ in 0..SAMPLES {
        let (m, l0, g) = (
            positive(&mut rng),
            uniform(&mut rng, 1.0, 2.0),
            gravity(&mut rng),
        );
        let (a, omega) = (uniform(&mut rng, 0.1, 0.8), uniform(&mut rng, 1.0, 6.0));
        let model = VariableLengthPendulum::new(m, l0, a, omega, g);
        let (t, q, qd, qdd) = state1(&mut rng);
        let (s, c) = (q[0].sin(), q[0].cos());
        let l = l0 + a * (omega * t).sin();
        let ldot = a * omega * (omega * t).cos();

        assert_close(
            "M",
            model.mass_matrix(t, &q)[(0, 0)],
            Closed::sum(&[m * l * l]),
        );
        let dp_dt = 2.0 * m * l * ldot * qd[0];
        let forcing = Closed::sum(&[-dp_dt, -m * g * l * s]);
        dp_dt_share = dp_dt_share.max(dp_dt.abs() / forcing.scale.max(1.0));
        assert_close("f", model.forcing(t, &q, &qd)[0], forcing);
        let lhs = Closed::sum(&[m * l * l * qdd[0], dp_dt, m * g * l * s]);
        assert_close("M q̈ − f", residual(&model, t, &q, &qd, &qdd)[0], lhs);
        let energy = Closed::sum(&[
            m * ldot * ldot / 2.0,
            m * l * l * qd[0] * qd[0] / 2.0,
            -m * g * l * c,
        ]);
        assert_close("T + V", model.energy(t, &q, &qd), energy);
    }
    assert_term_matters("∂p/∂t = 2 m l l̇ θ̇", dp_dt_share);
}

#[test]
fn variable_length_pendulum_declares_its_coordinates_and_parameters() {
    assert_eq!(VariableLengthPendulum::<f64>::DOF, 1);
    assert_eq!(VariableLengthPendulum::<f64>::COORDINATES, ["theta"]);
    assert_eq!(
        VariableLengthPendulum::<f64>::PARAMETERS,
        ["m", "l0", "a", "omega", "g"]
    );
    let p = VariableLengthPendulum::new(1.0, 2.0, 3.0, 4.0, 5.0);
    assert_eq!([p.m, p.l0, p.a, p.omega, p.g], [1.0, 2.0, 3.0, 4.0, 5.0]);
}

#[test]
fn variable_length_pendulum_computes_m_and_f_together_exactly_as_apart() {
    assert_combined_call_is_bitwise_separate(
        &VariableLengthPendulum::new(0.7, 1.2, 0.3, 2.5, 9.81),
        29,
    );
}

// ---------------------------------------------------------------------------
// Pendulum on a shaken support: the pivot moves horizontally as
// x_s = A cos(ω t); bob m on a massless rod l, θ from the downward vertical.
// ---------------------------------------------------------------------------

lagrangian! {
    pub struct PendulumOnShakenSupport {
        coordinates: theta;
        parameters: m, l, g, amplitude, omega;
        let xs = amplitude*cos(omega*t);
        let x = xs + l*sin(theta);
        let y = -l*cos(theta);
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*y;
    }
}

#[test]
fn pendulum_on_shaken_support_matches_textbook_equations() {
    // T = ½ m (ẋs² + 2 ẋs l cos θ θ̇ + l² θ̇²), V = −m g l cos θ, so
    // p = m l² θ̇ + m l ẋs cos θ carries t explicitly, ∂p/∂t = m l ẍs cos θ,
    // and with ẍs = −A ω² cos(ω t) the textbook
    //   m l θ̈ = −m g sin θ + m A ω² cos(ω t) cos θ
    // appears times l (the engine's M is ∂²T/∂θ̇² = m l²):
    //   m l² θ̈ = −m g l sin θ + m l A ω² cos(ω t) cos θ.
    let mut rng = rng(30);
    let mut dp_dt_share = 0.0f64;
    for _ in 0..SAMPLES {
        let (m, l, g) = (positive(&mut rng), positive(&mut rng), gravity(&mut rng));
        let (amp, omega) = (uniform(&mut rng, 0.1, 1.0), uniform(&mut rng, 1.0, 6.0));
        let model = PendulumOnShakenSupport::new(m, l, g, amp, omega);
        let (t, q, qd, qdd) = state1(&mut rng);
        let (s, c) = (q[0].sin(), q[0].cos());
        let xs_dot = -amp * omega * (omega * t).sin();

        assert_close(
            "M",
            model.mass_matrix(t, &q)[(0, 0)],
            Closed::sum(&[m * l * l]),
        );
        let shaking = m * l * amp * omega * omega * (omega * t).cos() * c;
        let forcing = Closed::sum(&[-m * g * l * s, shaking]);
        dp_dt_share = dp_dt_share.max(shaking.abs() / forcing.scale.max(1.0));
        assert_close("f", model.forcing(t, &q, &qd)[0], forcing);
        let lhs = Closed::sum(&[m * l * l * qdd[0], m * g * l * s, -shaking]);
        assert_close("M q̈ − f", residual(&model, t, &q, &qd, &qdd)[0], lhs);
        let energy = Closed::sum(&[
            m * xs_dot * xs_dot / 2.0,
            m * xs_dot * l * c * qd[0],
            m * l * l * qd[0] * qd[0] / 2.0,
            -m * g * l * c,
        ]);
        assert_close("T + V", model.energy(t, &q, &qd), energy);
    }
    assert_term_matters("−∂p/∂t = m l A ω² cos(ω t) cos θ", dp_dt_share);
}

#[test]
fn pendulum_on_shaken_support_declares_its_coordinates_and_parameters() {
    assert_eq!(PendulumOnShakenSupport::<f64>::DOF, 1);
    assert_eq!(PendulumOnShakenSupport::<f64>::COORDINATES, ["theta"]);
    assert_eq!(
        PendulumOnShakenSupport::<f64>::PARAMETERS,
        ["m", "l", "g", "amplitude", "omega"]
    );
    let p = PendulumOnShakenSupport::new(1.0, 2.0, 3.0, 4.0, 5.0);
    assert_eq!(
        [p.m, p.l, p.g, p.amplitude, p.omega],
        [1.0, 2.0, 3.0, 4.0, 5.0]
    );
}

#[test]
fn pendulum_on_shaken_support_computes_m_and_f_together_exactly_as_apart() {
    assert_combined_call_is_bitwise_separate(
        &PendulumOnShakenSupport::new(0.9, 1.1, 9.81, 0.4, 3.0),
        31,
    );
}
