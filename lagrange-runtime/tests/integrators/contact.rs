//! Unilateral contacts on hand-written models: a contact that opens where
//! its normal force reaches zero, two contacts decided together, and the
//! typed errors of a contact run.

use lagrange_runtime::contact::{self, Cause, ContactError, ContactSettings, Mode};
use lagrange_runtime::nalgebra::Vector2;
use lagrange_runtime::prelude::*;

use crate::models::{CartesianPendulum, Ladder, OnSphere, STOP};

/// Dop853 at 1e-12: its global error on these smooth phases of a second
/// or less is about 1e-12 (relative), which bounds what the tests below
/// can ask of a located switch.
fn method() -> Dop853<f64> {
    Dop853::new().rtol(1e-12).atol(1e-12)
}

#[test]
fn a_particle_leaves_a_sphere_where_cos_theta_is_two_thirds_of_its_start() {
    // Released from rest at θ₀ from the top of a frictionless sphere, a
    // particle leaves it where cos θ = (2/3) cos θ₀ (energy and N = 0
    // together: v² = g r cos θ = 2 g r (cos θ₀ − cos θ)).
    let sphere = OnSphere { r: 1.0, g: 9.81 };
    for theta0 in [0.1f64, 0.5, 1.0] {
        let q0 = Vector2::new(theta0.sin(), theta0.cos());
        let times: Vec<f64> = (1..=40).map(|k| f64::from(k) * 0.05).collect();
        let run = contact::integrate(
            &method(),
            &sphere,
            0.0,
            q0,
            Vector2::zeros(),
            &times,
            ContactSettings::default(),
        )
        .unwrap();
        let release = run
            .switches()
            .iter()
            .find(|s| s.cause == Cause::Release)
            .expect("it leaves the sphere");
        assert_eq!((release.from, release.to), (Mode::Closed, Mode::Open));
        let theta = release.q[0].atan2(release.q[1]);
        // The angle is as accurate as the trajectory (1e-12) and the
        // location (a few ulps of t times θ̇ ≈ 3/s).
        assert!(
            (theta.cos() - 2.0 / 3.0 * theta0.cos()).abs() < 1e-10,
            "θ₀ = {theta0}: cos θ = {}, (2/3) cos θ₀ = {}",
            theta.cos(),
            2.0 / 3.0 * theta0.cos()
        );
        // On the sphere the normal force is m (g cos θ − v²/r) ≥ 0; after
        // the release it flies on a parabola from the release state.
        let (tr, qr, vr) = (release.t, release.q, release.qdot);
        for (k, sample) in run.trajectory().iter().enumerate() {
            let forces = run.forces()[k];
            if sample.t < tr {
                let r = sample.q.norm();
                let cos = sample.q[1] / r;
                let expected = 9.81 * cos - sample.qdot.norm_squared() / r;
                assert!(
                    (forces.normal[0] - expected).abs() < 1e-10,
                    "N at t = {}",
                    sample.t
                );
            } else {
                let s = sample.t - tr;
                let parabola =
                    Vector2::new(qr[0] + vr[0] * s, qr[1] + vr[1] * s - 9.81 / 2.0 * s * s);
                // The free flight is exact for every method up to rounding
                // (a quadratic), so the error is the release state's.
                assert!((sample.q - parabola).norm() < 1e-10, "t = {}", sample.t);
                assert_eq!(forces.normal[0], 0.0);
            }
        }
    }
}

#[test]
fn a_ladder_leaves_the_wall_at_two_thirds_of_its_initial_height() {
    // A uniform ladder released from rest on a frictionless floor and wall
    // leaves the wall when its top has fallen to 2/3 of its initial height
    // (the centre moves on a circle of radius l/2 about the corner until
    // the wall's force vanishes: sin θ = (2/3) sin θ₀). Both contacts are
    // closed at the start, decided together.
    let ladder = Ladder {
        m: 3.0,
        l: 2.0,
        g: 9.81,
    };
    for theta0 in [0.6f64, 1.0, 1.4] {
        let (q0, v0) = ladder.at_rest(theta0);
        // Long enough to leave the wall from the steepest start (about
        // 1.3 s from 1.4 rad); only the samples before the ladder lies flat
        // (θ > 0.1) are checked, after it the model's two ends swap.
        let times: Vec<f64> = (1..=80).map(|k| f64::from(k) * 0.02).collect();
        let run = contact::integrate(
            &method(),
            &ladder,
            0.0,
            q0,
            v0,
            &times,
            ContactSettings::default(),
        )
        .unwrap();
        let start: Vec<_> = run
            .switches()
            .iter()
            .filter(|s| s.cause == Cause::Start)
            .collect();
        assert_eq!(
            start.len(),
            2,
            "both contacts close at the start: {:?}",
            run.switches()
        );
        let release = run
            .switches()
            .iter()
            .find(|s| s.cause == Cause::Release)
            .expect("it leaves the wall");
        assert_eq!(release.name, "wall");
        let theta = release.q[2];
        assert!(
            (theta.sin() - 2.0 / 3.0 * theta0.sin()).abs() < 1e-10,
            "θ₀ = {theta0}: sin θ = {}, (2/3) sin θ₀ = {}",
            theta.sin(),
            2.0 / 3.0 * theta0.sin()
        );
        // Frictionless, workless contacts: the energy stays within the
        // method's tolerance (about 1e-12 of the 30 J scale).
        let e0 = ladder.energy(0.0, &q0, &v0);
        let upright = run.trajectory().iter().filter(|s| s.q[2] > 0.1);
        for sample in upright.clone() {
            let e = ladder.energy(sample.t, &sample.q, &sample.qdot);
            assert!(
                (e - e0).abs() < 1e-9,
                "energy {e} against {e0} at t = {}",
                sample.t
            );
        }
        // The floor holds throughout: its gap stays within the drift of
        // the integration (a closed contact's g̈ = 0 holds exactly).
        let floor_gap = |q: &lagrange_runtime::nalgebra::Vector3<f64>| q[1] - q[2].sin();
        for sample in upright {
            assert!(floor_gap(&sample.q).abs() < 1e-10);
        }
    }
}

#[test]
fn a_start_inside_a_contact_is_refused() {
    let sphere = OnSphere { r: 1.0, g: 9.81 };
    let failure = contact::integrate(
        &method(),
        &sphere,
        0.0,
        Vector2::new(0.0, 0.5),
        Vector2::zeros(),
        &[1.0],
        ContactSettings::default(),
    )
    .unwrap_err();
    assert!(
        matches!(failure.error, ContactError::Penetrating { contact: "sphere", gap } if gap == -0.5)
    );
    assert!(
        failure.to_string().contains("inside contact `sphere`"),
        "{failure}"
    );
}

#[test]
fn settings_out_of_range_are_refused() {
    let sphere = OnSphere { r: 1.0, g: 9.81 };
    let settings = ContactSettings {
        gap_tolerance: -1.0,
        ..ContactSettings::default()
    };
    let failure = contact::integrate(
        &method(),
        &sphere,
        0.0,
        Vector2::new(0.0, 2.0),
        Vector2::zeros(),
        &[1.0],
        settings,
    )
    .unwrap_err();
    assert!(matches!(
        failure.error,
        ContactError::InvalidSetting {
            setting: "gap_tolerance",
            ..
        }
    ));
}

#[test]
fn a_cartesian_pendulum_strikes_a_stop_with_its_rod_held_and_rebounds_at_minus_e() {
    // Released from rest at θ₀ = 0.5, the bob (on its rod, a constraint of
    // the model's own) strikes the stop at θ = −β with
    // θ̇⁻² = 2 g/l (cos β − cos θ₀) (energy). The stop's impulse along x and
    // the rod's along (x, y) together leave the bob on the circle, moving
    // along it at θ̇⁺ = −e θ̇⁻ (Poisson's law on the one free rate).
    let pendulum = CartesianPendulum::unit();
    let (q0, v0) = pendulum.state(0.5, 0.0);
    let run = contact::integrate(
        &method(),
        &pendulum,
        0.0,
        q0,
        v0,
        &[1.5],
        ContactSettings::default(),
    )
    .unwrap();
    let impact = run
        .switches()
        .iter()
        .find(|s| s.cause == Cause::Impact)
        .expect("the bob strikes the stop");
    let (beta, e) = (STOP, 0.5);
    let before = -(2.0 * 9.81 * (beta.cos() - 0.5f64.cos())).sqrt();
    let (theta, theta_dot) = pendulum.angle(&impact.q, &impact.qdot);
    // Located to the event tolerance; on the rod to the projection's
    // rounding; the rates within Dop853's 1e-12 over the swing, with room.
    assert!((theta + beta).abs() < 1e-10, "θ = {theta}");
    assert!((impact.q.norm() - 1.0).abs() < 1e-14);
    assert!(impact.q.dot(&impact.qdot).abs() < 1e-14);
    assert!(
        (theta_dot + e * before).abs() < 1e-9,
        "θ̇⁺ = {theta_dot}, −e θ̇⁻ = {}",
        -e * before
    );
    // Between switches the rod is kept to the method's error (no
    // projection after each step): at 1e-12, within 1e-10 at the end.
    let end = run.trajectory().last().unwrap();
    println!(
        "θ + β = {:.1e}, θ̇⁺ + e θ̇⁻ = {:.1e}, |q| − l at the end {:.1e}",
        theta + beta,
        theta_dot + e * before,
        end.q.norm() - 1.0
    );
    assert!((end.q.norm() - 1.0).abs() < 1e-10, "|q| = {}", end.q.norm());
}
