//! Contacts on a model with constraints of its own: a body in a unit
//! quaternion touching the floor, its norm constraint held with the
//! contacts.

use lagrange::models::{Die, TumblingBox, quaternion};
use lagrange::nalgebra::{SVector, UnitQuaternion, Vector3};

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
