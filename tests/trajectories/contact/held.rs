//! Contacts on a model with constraints of its own, held with the
//! contacts: a body in a unit quaternion touching the floor (its norm), a
//! pendulum held on its circle (a constraint on positions, a closed
//! loop's kind) and a knife-edge sleigh (a constraint on velocities,
//! rolling's kind) striking walls.

use lagrange::contact::Cause;
use lagrange::models::{ChaplyginSleigh, Die, Pendulum, PendulumWall, TumblingBox, quaternion};
use lagrange::nalgebra::{SVector, UnitQuaternion, Vector1, Vector3};
use lagrange::prelude::*;

use super::{run, times};

#[test]
fn a_die_in_a_quaternion_tumbles_in_a_plane_as_the_planar_box_does_switch_for_switch() {
    // Moving in the plane y = 0 and turning about y, the die is the planar
    // tumbling box of the same side (a square: its moment m s²/6 about any
    // axis is the box's m (w² + h²)/12), its corners in pairs that the
    // plane sees as one, each pair's forces in that plane through the
    // mass centre, so that nothing turns it out of the plane; its friction
    // in the table's plane acts along x alone, as the box's does. The two
    // models share no code below the contact run: seven coordinates, the
    // norm constraint and eight contacts against three and four. Dropped
    // from 0.05 m, tilted and spinning, drifting: bounces, then bounces
    // on one edge accumulating until its rebounds are too short to
    // resolve. The run ends before that: which rebound is the first too
    // short is judged against the rounding of the gap's value, estimated
    // from the coordinates' sizes (`64 ε Σ |Gᵢⱼ qⱼ|`), which differ
    // between the two models, so the bounces each records before it
    // differ; the time they accumulate at does not (the flights cut off
    // are flown out to it): 0.2483538 s in both, within 2e-9 s, run to
    // 1 s when this was written.
    let (m, s, g, e, mu) = (0.01, 0.016, 9.81, 0.4, 0.5);
    let planar = TumblingBox::new(m, s, s, g, e, mu);
    let die = Die::new(m, s, g, e, mu);
    let (theta, spin) = (0.3, 40.0);
    // The box turns by θ about z (x right, y up); the die by −θ about y
    // (x right, z up), which turns x towards z as the box turns x
    // towards y.
    let turned = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), -theta);
    let (q, qdot) = quaternion::state(&turned, &Vector3::new(0.0, -spin, 0.0));
    let start = (
        [0.0, 0.0, 0.05, q[0], q[1], q[2], q[3]],
        [0.3, 0.0, 0.0, qdot[0], qdot[1], qdot[2], qdot[3]],
    );
    // 24 switches, the last at 0.247628 s; the box's next (0.247735 s)
    // is a bounce of its second bottom corner that the die's pair does
    // not make, in the bounces that accumulate (above).
    let end = 0.2477;
    let samples = times(end, 100);
    let box_run = run(&planar, ([0.0, 0.05, theta], [0.3, 0.0, spin]), &samples).unwrap();
    let die_run = run(&die, start, &samples).unwrap();
    // The die's corners switch in pairs: the same times, once each.
    let distinct = |mut t: Vec<f64>| {
        t.dedup();
        t
    };
    let a = distinct(box_run.switches().iter().map(|s| s.t).collect());
    let b = distinct(die_run.switches().iter().map(|s| s.t).collect());
    assert_eq!(a.len(), b.len(), "{a:?}\n{b:?}");
    let worst_time = a
        .iter()
        .zip(&b)
        .fold(0.0f64, |w, (s, p)| w.max((s - p).abs()));
    // The states at every sample: the centre, and the die's rotation
    // against the box's θ (compared as rotations: the angle between
    // them); the die stays in its plane.
    let (mut worst_state, mut worst_plane, mut worst_norm) = (0.0f64, 0.0f64, 0.0f64);
    for (s, p) in box_run.trajectory().iter().zip(die_run.trajectory().iter()) {
        assert_eq!(s.t, p.t);
        let q = SVector::<f64, 4>::new(p.q[3], p.q[4], p.q[5], p.q[6]);
        let planar_turn = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), -s.q[2]);
        let angle = quaternion::rotation(&q).angle_to(&planar_turn);
        worst_state = worst_state
            .max((s.q[0] - p.q[0]).abs())
            .max((s.q[1] - p.q[2]).abs())
            .max(angle);
        worst_plane = worst_plane
            .max(p.q[1].abs())
            .max(p.q[4].abs().min(p.q[3].abs()).min(0.0));
        worst_plane = worst_plane.max(p.q[4].abs().max(p.q[6].abs()));
        worst_norm = worst_norm.max((q.norm() - 1.0).abs());
        // Never below the table beyond the integration's drift of a
        // closed contact (1e-10 at this tolerance) or a located arrival.
        assert!(die.gaps(p.t, &p.q).min() > -1e-9);
    }
    println!(
        "{} switch times, within {worst_time:.1e} s; states within {worst_state:.1e}; out of the \
         plane {worst_plane:.1e}; |q| − 1 within {worst_norm:.1e}",
        a.len()
    );
    // Each switch is located to the event tolerance on trajectories that
    // agree to the method's 1e-12, which the impacts amplify (a corner
    // striking at a slightly different angle): 1e-9 s is a thousand times
    // that.
    assert!(worst_time < 1e-9, "{worst_time:e} s");
    // The method's error through the impacts, as for the times.
    assert!(worst_state < 1e-9, "{worst_state:e}");
    // Nothing pushes the die out of its plane: rounding only.
    assert!(worst_plane < 1e-12, "{worst_plane:e}");
    // The norm drifts by the method's error between switches, and each
    // switch projects it back.
    assert!(worst_norm < 1e-10, "{worst_norm:e}");
}

lagrangian! {
    /// A pendulum bob in Cartesian coordinates held on its circle by a
    /// constraint (a closed loop's kind: a holonomic constraint the run
    /// holds with a multiplier), striking a wall at `x = −l sin β`.
    struct WalledCartesianPendulum {
        coordinates: x, y;
        parameters: m, l, g, beta, e;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*y;
        constraints: rod: x^2 + y^2 = l^2;
        contacts: wall: x >= -l*sin(beta) { restitution: e };
    }
}

/// A pendulum in Cartesian coordinates (its rod a constraint) swinging
/// against a wall, against the minimal pendulum with the same wall as an
/// event that reverses `θ̇` (`models::PendulumWall`): the wall's normal
/// is along x, the bob's velocity along the circle, and Newton's law on
/// the gap's rate, `ẋ⁺ = −e ẋ⁻`, with the velocity kept on the circle by
/// the rod's impulse, is `θ̇⁺ = −e θ̇⁻`. Released from rest at 1 rad, β =
/// 0.2, e = 0.8: its impacts at the minimal run's times, and each swing's
/// amplitude the closed form's, `cos a⁺ = cos β − e² (cos β − cos a)`
/// (`PendulumWall::amplitude_after`).
#[test]
fn a_pendulum_held_on_its_circle_by_a_constraint_strikes_a_wall_as_the_minimal_one_does() {
    let (m, l, g, beta, e) = (1.0, 1.0, 9.81, 0.2, 0.8);
    let a0 = 1.0f64;
    let walled = WalledCartesianPendulum::new(m, l, g, beta, e);
    let end = 6.0;
    let samples = times(end, 600);
    let cartesian = run(
        &walled,
        ([l * a0.sin(), -l * a0.cos()], [0.0, 0.0]),
        &samples,
    )
    .unwrap();
    let pendulum = Pendulum::new(m, l, g);
    let wall = PendulumWall {
        beta,
        restitution: e,
    };
    let events = Events::new().with(wall.event());
    let minimal = super::tight()
        .integrate_with_events(
            &pendulum,
            0.0,
            Vector1::new(a0),
            Vector1::new(0.0),
            &samples,
            &events,
        )
        .unwrap();
    let impacts: Vec<_> = cartesian
        .switches()
        .iter()
        .filter(|s| s.cause == Cause::Impact)
        .collect();
    let expected: Vec<f64> = minimal.events().iter().map(|ev| ev.t).collect();
    assert_eq!(impacts.len(), expected.len(), "{impacts:?}\n{expected:?}");
    assert!(impacts.len() >= 4);
    let worst_time = impacts
        .iter()
        .zip(&expected)
        .fold(0.0f64, |w, (s, t)| w.max((s.t - t).abs()));
    // Each swing's amplitude from its energy at every sample, `cos a =
    // −(y + |v|²/(2 g))/l` (the apex's height), against the closed form
    // from the one before.
    let amplitude_at = |q: &SVector<f64, 2>, v: &SVector<f64, 2>| {
        (-(q[1] + v.norm_squared() / (2.0 * g)) / l).acos()
    };
    let mut amplitude = a0;
    let mut worst_amplitude = 0.0f64;
    let mut worst_circle = 0.0f64;
    for (k, impact) in impacts.iter().enumerate() {
        let next = impacts.get(k + 1).map_or(end, |s| s.t);
        amplitude = wall.amplitude_after(amplitude);
        for s in cartesian.trajectory().iter() {
            if s.t > impact.t && s.t < next {
                worst_amplitude =
                    worst_amplitude.max((amplitude_at(&s.q, &s.qdot) - amplitude).abs());
            }
        }
    }
    for s in cartesian.trajectory().iter() {
        worst_circle = worst_circle.max((s.q.norm() - l).abs());
        // Never through the wall beyond the drift of a located arrival.
        assert!(walled.gaps(s.t, &s.q)[0] > -1e-9);
    }
    println!(
        "{} impacts within {worst_time:.1e} s of the minimal run's; amplitudes within \
         {worst_amplitude:.1e} rad of the closed form; on the circle within \
         {worst_circle:.1e}",
        impacts.len()
    );
    // Both located to the event tolerance on trajectories within Dop853's
    // 1e-12: 1e-9 s is a thousand times that.
    assert!(worst_time < 1e-9, "{worst_time:e} s");
    // The energy to Dop853's 1e-12 and the impacts' located states,
    // through `acos` (its slope `1/sin a`, below 5 at these amplitudes):
    // 1e-10 rad leaves a factor of ten.
    assert!(worst_amplitude < 1e-10, "{worst_amplitude:e} rad");
    // The constraint's drift between switches (the method's error), and
    // each switch projects it back.
    assert!(worst_circle < 1e-10, "{worst_circle:e}");
}

lagrangian! {
    /// The Chaplygin sleigh (`models::ChaplyginSleigh`: a knife edge at
    /// `a` behind the mass centre that cannot slide sideways, a velocity
    /// constraint) whose mass centre strikes a frictionless wall at `x =
    /// w`.
    struct WalledSleigh {
        coordinates: x, y, theta;
        parameters: m, i, a, w, e;
        kinetic: m/2*(dot(x)^2 + dot(y)^2) + i/2*dot(theta)^2;
        potential: 0;
        constraints: edge: cos(theta)*dot(y) - sin(theta)*dot(x) = a*dot(theta);
        contacts: wall: x <= w { restitution: e };
    }
}

/// The sleigh, a velocity constraint (rolling's kind), striking a wall
/// askew: the impact's impulses, the wall's `Λ` along x and the edge's
/// sideways, leave the edge's constraint held (`A v⁺ = 0`) and reverse
/// the gap's rate by the restitution (`ġ⁺ = −e ġ⁻`). Neither constraint
/// impulse works on the mean velocity that both states satisfy, so the
/// energy changes by `½ (ġ⁺ + ġ⁻) Λ = ½ (1 − e) ġ⁻ Λ` alone: kept where
/// `e = 1`, and otherwise that loss (the energy the switch records).
#[test]
fn a_sleigh_under_a_velocity_constraint_strikes_a_wall_keeping_its_constraint_and_its_energy_law() {
    let (m, i, a, w) = (2.0, 0.3, 0.4, 1.0);
    for e in [1.0, 0.5] {
        let sleigh = WalledSleigh::new(m, i, a, w, e);
        // Heading 0.4 rad off the wall's normal, turning: speed 1 m/s.
        let theta = 0.4f64;
        let (v, omega) = (1.0, 0.8);
        let qdot = [
            v * theta.cos() - a * omega * theta.sin(),
            v * theta.sin() + a * omega * theta.cos(),
            omega,
        ];
        let energy = |qd: &SVector<f64, 3>| {
            m / 2.0 * (qd[0] * qd[0] + qd[1] * qd[1]) + i / 2.0 * qd[2] * qd[2]
        };
        let edge = |q: &SVector<f64, 3>, qd: &SVector<f64, 3>| {
            q[2].cos() * qd[1] - q[2].sin() * qd[0] - a * qd[2]
        };
        let run = run(&sleigh, ([0.0, 0.0, theta], qdot), &times(2.0, 200)).unwrap();
        let impact = run
            .switches()
            .iter()
            .find(|s| s.cause == Cause::Impact)
            .expect("no impact");
        // The switch records the state after the impact. Before it, the
        // same sleigh without the wall (`models::ChaplyginSleigh`) run to
        // the impact's time: its gap's rate `ġ⁻ = −ẋ`.
        let free = super::tight()
            .integrate(
                &ChaplyginSleigh::new(m, i, a),
                0.0,
                SVector::from([0.0, 0.0, theta]),
                SVector::from(qdot),
                &[impact.t],
            )
            .unwrap();
        let before = -free.last().unwrap().qdot[0];
        let after = -impact.qdot[0];
        let e0 = energy(&SVector::from(qdot));
        // No force works between impacts: the energy just before is the
        // start's.
        let lost = e0 - energy(&impact.qdot);
        let law = -0.5 * (after + before) * impact.impulse.0;
        println!(
            "e = {e}: impact at {:.6} s, impulse {:.6}; gap's rate {before:.12} -> {after:.12}; energy \
             lost {lost:.6e} J (law {law:.6e}, recorded {:.6e}); edge's constraint after {:.1e}",
            impact.t,
            impact.impulse.0,
            impact.energy_lost,
            edge(&impact.q, &impact.qdot),
        );
        // Rates of 1 m/s to Dop853's 1e-12 and the impact's location: 1e-9.
        assert!(
            (after + e * before).abs() < 1e-9,
            "e = {e}: {before} -> {after}"
        );
        // Energies of 1 J, likewise.
        assert!((lost - law).abs() < 1e-9, "e = {e}: lost {lost}, law {law}");
        assert!((impact.energy_lost - law).abs() < 1e-9);
        // The constraint held after the impact, to its projection's
        // tolerance.
        for s in run.trajectory().iter() {
            assert!(edge(&s.q, &s.qdot).abs() < 1e-10, "edge slides at {}", s.t);
        }
    }
}
