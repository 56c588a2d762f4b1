//! Friction in a plane: a slip vector of two components, isotropic
//! Coulomb friction (a disc of friction forces), on a puck pushed across
//! a table, a ball in a unit quaternion thrown with spin and striking the
//! table, and a die thrown onto it that comes to rest.

use lagrange::contact::{Cause, ContactSettings, Mode};
use lagrange::models::{BallOnTable, Die, PushedPuck, PushedRod, quaternion};
use lagrange::nalgebra::{UnitQuaternion, Vector3};
use lagrange::prelude::*;

use super::{run, times};

/// The puck holds while the push is inside the disc of friction, `P <
/// μ m g`, whatever its direction, and breaks away where it reaches it,
/// at `t_b = (μ m g − p0)/rate`: then it slides along the push, `s =
/// rate (t − t_b)³/(6 m)`. The direction is 5.6° from the x axis, the
/// middle of a side of the 32-gon that stands for the disc in the
/// decisions: the breakaway is the disc's (its limit watched exactly
/// between switches), not the polygon's, which would come at `cos(π/32)
/// μ m g`, 0.047 s earlier here.
#[test]
fn a_puck_pushed_across_a_rough_table_breaks_away_at_the_disc_of_friction_in_any_direction() {
    let (m, g, mu, rate) = (1.0, 9.81, 0.5, 0.5);
    let limit = mu * m * g;
    for a in [core::f64::consts::PI / 32.0, 2.0] {
        let p0 = 0.9 * limit;
        let puck = PushedPuck::new(m, g, mu, a, p0, rate);
        let t_b = (limit - p0) / rate;
        let end = t_b + 2.0;
        let run = run(&puck, ([0.0; 3], [0.0; 3]), &times(end, 100)).unwrap();
        let switches: Vec<_> = run.switches().iter().map(|s| (s.cause, s.to)).collect();
        assert_eq!(
            switches,
            [
                (Cause::Start, Mode::Stuck),
                (Cause::StickLimit, Mode::Slipping)
            ]
        );
        let breakaway = &run.switches()[1];
        let last = run.trajectory().last().unwrap();
        let along = rate * (end - t_b).powi(3) / (6.0 * m);
        println!(
            "a = {a}: breaks away {:.1e} s from the closed form, {:.1e} m from it at the end, in {} \
             steps",
            breakaway.t - t_b,
            (last.q[0] - along * a.cos()).hypot(last.q[1] - along * a.sin()),
            run.trajectory().stats().steps_accepted
        );
        // The margin is linear in t while it holds: located to rounding.
        assert!(
            (breakaway.t - t_b).abs() < 1e-9,
            "a = {a}: broke away at {}, closed form {t_b}",
            breakaway.t
        );
        // It sets off along the push, against its friction there.
        let (d0, d1) = breakaway.slip_direction;
        assert!((d0 - a.cos()).abs() < 1e-12 && (d1 - a.sin()).abs() < 1e-12);
        for ((sample, forces), modes) in run.trajectory().iter().zip(run.forces()).zip(run.modes())
        {
            let f = (forces.friction[0], forces.second_friction[0]);
            let size = (f.0 * f.0 + f.1 * f.1).sqrt();
            // Forces of 5 N to rounding: 1e-12.
            assert!((forces.normal[0] - m * g).abs() < 1e-12);
            assert!(size <= mu * forces.normal[0] + 1e-12);
            let s = (sample.t - t_b).max(0.0);
            let along = rate * s.powi(3) / (6.0 * m);
            if sample.t < t_b - 1e-9 {
                assert_eq!(modes[0], Mode::Stuck);
            } else if sample.t > t_b + 1e-9 {
                assert_eq!(modes[0], Mode::Slipping);
                // Sliding friction, μ m g against the slip.
                assert!((size - limit).abs() < 1e-12);
            }
            // Dop853 at 1e-12 over 2 s of a cubic, with the breakaway
            // time's error times the speed (at most 1 m/s): 3.7e-14 m at
            // the end when this was written.
            assert!(
                (sample.q[0] - along * a.cos()).abs() < 1e-9
                    && (sample.q[1] - along * a.sin()).abs() < 1e-9,
                "a = {a}: ({:e}, {:e}) off at {}, closed form {along} along the push",
                sample.q[0] - along * a.cos(),
                sample.q[1] - along * a.sin(),
                sample.t
            );
        }
    }
}

/// A rod on two rough supports (loads 0.4 and 0.6 of its weight, behind
/// and ahead of its centre of mass), pushed in the table's plane at 30°
/// to its axis, 0.3 ahead of its centre of mass, from 0.9 of its
/// closed-form breakaway push `P_b` (`PushedRod::breakaway_push`, 0.9466
/// μ m g: the push's moment loads the front disc across the rod). While
/// both supports stick, their friction along the rod is not determined;
/// every distribution the run takes must lie inside both discs, and the
/// rod must hold until `t_b = (P_b − p0)/rate`, where no admissible
/// distribution is left, and break away there. Shared in proportion to
/// the loads instead, the friction would leave the front disc 3 % before
/// `P_b` (`PushedRod::proportional_use`).
#[test]
fn a_rod_on_two_rough_supports_holds_inside_both_discs_and_breaks_away_at_the_closed_form_push() {
    let (m, j, a1, a2, c, g, mu, rate) = (1.0, 0.1, 0.6, 0.4, 0.3, 9.81, 0.5, 0.5);
    let a = 30f64.to_radians();
    let p_b = PushedRod::new(m, j, a1, a2, c, g, mu, a, 0.0, rate).breakaway_push();
    let p0 = 0.9 * p_b;
    let rod = PushedRod::new(m, j, a1, a2, c, g, mu, a, p0, rate);
    let t_b = (p_b - p0) / rate;
    // To a little after the breakaway: both supports then slip from rest,
    // their slips turning fastest while they are smallest, and the steps
    // are short (about 4,700 in the first 0.02 s when this was written,
    // against 9 for the 0.93 s it holds).
    let run = run(&rod, ([0.0; 5], [0.0; 5]), &times(t_b + 0.02, 100)).unwrap();
    let switches = run.switches();
    let after: Vec<_> = switches[2..]
        .iter()
        .map(|s| (s.name, s.cause, s.to))
        .collect();
    println!(
        "breaks away at {} ({:.1e} s from the closed form, P_b = {p_b}), {} steps",
        switches[2].t,
        switches[2].t - t_b,
        run.trajectory().stats().steps_accepted
    );
    assert!(
        switches[..2]
            .iter()
            .all(|s| s.cause == Cause::Start && s.to == Mode::Stuck)
    );
    // Both discs are full at the breakaway (the only admissible
    // distribution left), and both supports set off.
    assert_eq!(
        after,
        [
            ("back", Cause::StickLimit, Mode::Slipping),
            ("front", Cause::StickLimit, Mode::Slipping)
        ]
    );
    // The margin is smooth in t while it holds, and located to the event
    // tolerance (rounding of forces of 5 N over the push's rate of 0.5
    // N/s: some 1e-14 s; 4.4e-15 s when this was written).
    assert!(
        (switches[2].t - t_b).abs() < 1e-9,
        "broke away at {}, closed form {t_b}",
        switches[2].t
    );
    let (n_back, n_front) = rod.loads();
    let mut uses = (0.0f64, 0.0f64);
    for (sample, forces) in run.trajectory().iter().zip(run.forces()) {
        if sample.t >= switches[2].t {
            break;
        }
        // At rest: Dop853's steps of 0.1 s while it holds, each of a
        // local error within its atol of 1e-12 (1.3e-12 m when this was
        // written).
        assert!(
            sample.q.norm() < 1e-11,
            "moved by {:e} at {}",
            sample.q.norm(),
            sample.t
        );
        // Normal forces of 4 and 6 N, each support's friction within its
        // disc, to rounding: 1e-12.
        for (i, n) in [n_back, n_front].into_iter().enumerate() {
            assert!((forces.normal[i] - n).abs() < 1e-12);
            let size = forces.friction[i].hypot(forces.second_friction[i]);
            assert!(
                size <= mu * forces.normal[i] + 1e-12,
                "support {i} at {}: friction {size} outside its disc {}",
                sample.t,
                mu * forces.normal[i]
            );
            let u = size / (mu * forces.normal[i]);
            if i == 0 {
                uses.0 = uses.0.max(u)
            } else {
                uses.1 = uses.1.max(u)
            }
        }
    }
    println!("largest uses of the discs while it holds: {uses:?}");
}

/// A uniform ball thrown along a table, spinning about a horizontal axis,
/// released touching it: its lowest point slips at `s₀ = v₀ + ω₀ × (0,
/// 0, −r)`, friction `μ m g` against it slows the slip at `(7/2) μ g`
/// along its own direction (which therefore never turns), so it rolls
/// from `t* = 2 |s₀| / (7 μ g)` on, at `v₀ − μ g t* ŝ₀`: along the throw,
/// with backspin ω₀ about −y, `(5 v₀ − 2 r ω₀)/7`, coming back when
/// `2 r ω₀ > 5 v₀`. Thrown askew (the spin's axis not across the throw),
/// the slip has both components.
#[test]
fn a_ball_thrown_with_spin_rolls_from_the_closed_form_time_at_the_closed_form_velocity() {
    let (m, r, g, mu) = (0.2, 0.1, 9.81, 0.3);
    let ball = BallOnTable::new(m, r, g, mu, 0.0);
    let throws = [
        // Backspin: it rolls on forwards, then comes back.
        (Vector3::new(3.0, 0.0, 0.0), Vector3::new(0.0, -20.0, 0.0)),
        (Vector3::new(3.0, 0.0, 0.0), Vector3::new(0.0, -100.0, 0.0)),
        // Askew, with some spin about the vertical (which friction at a
        // point does not touch).
        (Vector3::new(2.0, 1.0, 0.0), Vector3::new(15.0, -10.0, 4.0)),
    ];
    for (v0, w0) in throws {
        let (q, qdot) = quaternion::state(&UnitQuaternion::identity(), &w0);
        let start = (
            [0.0, 0.0, r, q[0], q[1], q[2], q[3]],
            [v0[0], v0[1], 0.0, qdot[0], qdot[1], qdot[2], qdot[3]],
        );
        let s0 = v0 + w0.cross(&Vector3::new(0.0, 0.0, -r));
        let t_roll = 2.0 * s0.norm() / (7.0 * mu * g);
        let v_roll = v0 - s0.normalize() * (mu * g * t_roll);
        let run = run(&ball, start, &times(2.0 * t_roll, 50)).unwrap();
        let causes: Vec<_> = run.switches().iter().map(|s| (s.cause, s.to)).collect();
        assert_eq!(
            causes,
            [
                (Cause::Start, Mode::Slipping),
                (Cause::SlideStopped, Mode::Stuck)
            ],
            "{v0:?}, {w0:?}"
        );
        let rolls = &run.switches()[1];
        // Located where the slip, linear in t, passes zero: to rounding,
        // on the trajectory's error (Dop853 at 1e-12).
        assert!(
            (rolls.t - t_roll).abs() < 1e-9,
            "rolls at {}, closed form {t_roll}",
            rolls.t
        );
        let end = run.trajectory().last().unwrap();
        let v = Vector3::new(end.qdot[0], end.qdot[1], end.qdot[2]);
        assert!(
            (v - v_roll).norm() < 1e-9,
            "{v:?} against the closed form {v_roll:?}"
        );
        // Rolling: its lowest point at rest, its spin the rolling one.
        let w = quaternion::rotation(&end.q.fixed_rows::<4>(3).into_owned())
            * quaternion::body_rates(
                &end.q.fixed_rows::<4>(3).into_owned(),
                &end.qdot.fixed_rows::<4>(3).into_owned(),
            );
        let low = v + w.cross(&Vector3::new(0.0, 0.0, -r));
        assert!(low.norm() < 1e-9, "the lowest point slips at {low:?}");
        println!(
            "v0 = {v0:?}, ω0 = {w0:?}: rolls at {:.12} s ({:.1e} from the closed form), at {:?}",
            rolls.t,
            rolls.t - t_roll,
            v
        );
    }
}

/// A ball striking the table at `u` with its lowest point slipping at
/// `s`: the plastic impulse stops both where friction can, `|P_t| =
/// (2/7) m |s| ≤ μ m u` (the ball's lowest point has an effective mass of
/// `2 m / 7` along the table), and Poisson's law scales it by `1 + e`:
/// it leaves at `e u`, slipping at `−e s`. Where friction cannot, the
/// plastic friction impulse is at the limit of the 32-gon that stands for
/// the disc in impacts, between `cos(π/32) μ m u` and `μ m u`, against
/// the slip. No impact gains energy.
#[test]
fn a_spinning_ball_striking_the_table_rebounds_as_poissons_law_says_and_never_gains_energy() {
    let (m, r, g, mu, e) = (0.2, 0.1, 9.81, 0.3, 0.6);
    let ball = BallOnTable::new(m, r, g, mu, e);
    let u = 2.0;
    // Slips at 0.7 m/s (sticks: 0.2 < 0.6) and at 4 m/s (slips: 1.14 >
    // 0.6), each in a direction off the polygon's vertices and sides.
    for (s, sticks) in [(0.7, true), (4.0, false)] {
        for angle in [0.3f64, core::f64::consts::PI / 32.0] {
            let slip = Vector3::new(angle.cos(), angle.sin(), 0.0) * s;
            // No spin, moving at the slip: its lowest point slips at it.
            let (q, qdot) = quaternion::state(&UnitQuaternion::identity(), &Vector3::zeros());
            let start = (
                [0.0, 0.0, r, q[0], q[1], q[2], q[3]],
                [slip[0], slip[1], -u, qdot[0], qdot[1], qdot[2], qdot[3]],
            );
            let run = run(&ball, start, &[1e-3]).unwrap();
            let impact = &run.switches()[0];
            assert_eq!(impact.cause, Cause::Impact);
            let (p_n, p_t) = (
                impact.impulse.0,
                (impact.impulse.1 * impact.impulse.1
                    + impact.second_impulse * impact.second_impulse)
                    .sqrt(),
            );
            // The impulses of one solve, of size 1: rounding.
            assert!((p_n - (1.0 + e) * m * u).abs() < 1e-12);
            let w = quaternion::rotation(&impact.q.fixed_rows::<4>(3).into_owned())
                * quaternion::body_rates(
                    &impact.q.fixed_rows::<4>(3).into_owned(),
                    &impact.qdot.fixed_rows::<4>(3).into_owned(),
                );
            let v = Vector3::new(impact.qdot[0], impact.qdot[1], impact.qdot[2]);
            // The lowest point's velocity along the table.
            let mut after = v + w.cross(&Vector3::new(0.0, 0.0, -r));
            after[2] = 0.0;
            assert!((v[2] - e * u).abs() < 1e-12);
            if sticks {
                assert!((p_t - (1.0 + e) * 2.0 / 7.0 * m * s).abs() < 1e-12);
                assert!((after + slip * e).norm() < 1e-12, "{after:?}");
            } else {
                let limit = (1.0 + e) * mu * m * u;
                let polygon = (core::f64::consts::PI / 32.0).cos();
                assert!(p_t <= limit * (1.0 + 1e-12) && p_t >= polygon * limit * (1.0 - 1e-12));
                println!(
                    "slipping impact at {angle:.3} rad: friction impulse {:.6} of the disc's",
                    p_t / limit
                );
            }
            assert!(impact.energy_lost >= 0.0);
        }
    }
}

/// A die thrown spinning onto the table bounces, tumbles and comes to
/// rest: no corner below the table beyond the location tolerance, no
/// energy gained (impacts and friction only take it), and at rest on a
/// face its normal forces hold its weight and it does not creep. Its four
/// corners on the table share a load that is not determined: the pivoting
/// that decides them loads two, diagonal, and the decision keeps the other
/// two touching, without force there, so that the forces between switches
/// (the smallest that hold it) share the weight among the four (left
/// open, the die turned about the diagonal through them, unwatched, by 9
/// mm in 1.3 s, before the decision kept them).
#[test]
fn a_die_thrown_spinning_onto_the_table_comes_to_rest_without_creeping() {
    let (m, s, g, e, mu) = (0.01, 0.016, 9.81, 0.3, 0.4);
    let die = Die::new(m, s, g, e, mu);
    let turned = UnitQuaternion::from_euler_angles(0.5, 0.3, 0.2);
    let (q, qdot) = quaternion::state(&turned, &Vector3::new(8.0, -5.0, 12.0));
    // Thrown from 10 cm, drifting at 0.5 m/s, spinning at 15 rad/s.
    let start = (
        [0.0, 0.0, 0.1, q[0], q[1], q[2], q[3]],
        [0.5, 0.2, 0.0, qdot[0], qdot[1], qdot[2], qdot[3]],
    );
    // Dop853 at 1e-13: at rest, what the die creeps in steps of seconds is
    // the method's error (below).
    let run = lagrange::contact::integrate(
        &Dop853::new().rtol(1e-13).atol(1e-13),
        &die,
        0.0,
        start.0.into(),
        start.1.into(),
        &times(12.0, 1200),
        ContactSettings::default(),
    )
    .unwrap();
    let impacts = run
        .switches()
        .iter()
        .filter(|s| s.cause == Cause::Impact)
        .count();
    let e0 = die.energy(0.0, &start.0.into(), &start.1.into());
    let mut previous = e0;
    let mut deepest = 0.0f64;
    for sample in run.trajectory().iter() {
        deepest = deepest.min(die.gaps(sample.t, &sample.q).min());
        // Ten times Dop853's 1e-13 of the energy (0.011 J at the start).
        let energy = die.energy(sample.t, &sample.q, &sample.qdot);
        assert!(
            energy <= previous + 1e-12 * e0,
            "energy rose by {:e} at {}",
            energy - previous,
            sample.t
        );
        previous = energy;
    }
    assert!(run.switches().iter().all(|s| s.energy_lost >= 0.0));
    // A corner's drift while closed (1e-10 at this tolerance), or a located
    // arrival.
    assert!(deepest > -1e-9, "a corner {deepest} below the table");
    // At rest for 10 s from 2 s on: its weight held (forces of 0.1 N, to
    // rounding), and no corner moving along the table by more than
    // 1e-12 m (no creep; the quaternion's norm is no motion: it drifts by
    // the method's error, and each switch projects it back).
    let rest: Vec<_> = run
        .trajectory()
        .iter()
        .zip(run.forces())
        .filter(|(s, _)| s.t >= 2.0)
        .collect();
    let first = die.corners(&rest[0].0.q);
    let mut creep = 0.0f64;
    for (sample, forces) in &rest {
        assert!((forces.normal.sum() - m * g).abs() < 1e-12 * m * g);
        for (now, then) in die.corners(&sample.q).iter().zip(&first) {
            creep = creep.max((now.xy() - then.xy()).norm());
        }
    }
    println!(
        "{impacts} impacts, {} switches, {} steps; deepest corner {deepest:.1e} m; energy {e0:.6} J \
         → {previous:.3e} J; at rest on {} corners, creeping {creep:.1e} m in 10 s",
        run.switches().len(),
        run.trajectory().stats().steps_accepted,
        rest[0].1.normal.iter().filter(|&&n| n > 1e-9).count()
    );
    assert!(impacts >= 3);
    // Stuck, its accelerations are rounding (about 1e-15 of g), and what
    // it creeps is the method's error over its steps of seconds at rest,
    // which falls with the tolerance: 1.4e-12 m in 10 s at 1e-12, 7.9e-13
    // at 1e-13, 2.4e-13 at 1e-14 when this was written.
    assert!(creep < 1e-12, "crept {creep:e}");
}
