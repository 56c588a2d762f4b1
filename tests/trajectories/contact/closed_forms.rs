//! Frictionless contacts: a particle leaving a sphere, a ladder leaving a
//! wall, a string going slack and snapping taut, a ball coming to rest.

use lagrange::contact::{Cause, Mode};
use lagrange::models::{BallOnFloor, BobOnString, Ladder, ParticleOnSphere};
use lagrange::nalgebra::Vector2;

use super::{run, times};

#[test]
fn a_particle_leaves_the_sphere_where_cos_theta_is_two_thirds_of_cos_theta0() {
    // Released from rest at θ₀ from the top of a frictionless sphere.
    let sphere = ParticleOnSphere::new(2.0, 9.81, 1.5);
    for theta0 in [0.05f64, 0.4, 1.2] {
        let run = run(&sphere, sphere.at_rest(theta0), &times(2.0, 40)).unwrap();
        let release = run
            .switches()
            .iter()
            .find(|s| s.cause == Cause::Release)
            .expect("it leaves");
        let theta = release.q[0].atan2(release.q[1]);
        // The trajectory's error (1e-12) and the location's (a few ulps of
        // t times θ̇ of a few rad/s) bound the angle's.
        let exact = ParticleOnSphere::release_angle(theta0);
        assert!(
            (theta - exact).abs() < 1e-10,
            "θ₀ = {theta0}: {theta} against {exact}"
        );
        // Then a parabola from the release state, exact for Dop853 up to
        // rounding (a quadratic): the error is the release state's.
        for sample in run.trajectory().iter().filter(|s| s.t > release.t) {
            let s = sample.t - release.t;
            let parabola = Vector2::new(
                release.q[0] + release.qdot[0] * s,
                release.q[1] + release.qdot[1] * s - 9.81 / 2.0 * s * s,
            );
            assert!((sample.q - parabola).norm() < 1e-10, "t = {}", sample.t);
        }
    }
}

#[test]
fn a_ladder_leaves_the_wall_when_its_top_has_fallen_to_two_thirds() {
    let ladder = Ladder::new(5.0, 3.0, 9.81);
    for theta0 in [0.5f64, 1.0, 1.3] {
        let run = run(&ladder, ladder.at_rest(theta0), &times(3.0, 60)).unwrap();
        let release = run
            .switches()
            .iter()
            .find(|s| s.cause == Cause::Release)
            .expect("it leaves");
        assert_eq!(release.name, "wall");
        let exact = Ladder::release_angle(theta0);
        // The height's error is the trajectory's (1e-12), and the location's
        // (ulps of t times the top's speed, about 3 m/s).
        assert!(
            (release.q[2].sin() - exact.sin()).abs() < 1e-10,
            "θ₀ = {theta0}: top at {} of its start, not 2/3",
            release.q[2].sin() / theta0.sin()
        );
        // Until then both contacts push; the wall's force falls to zero.
        for (sample, forces) in run.trajectory().iter().zip(run.forces()) {
            if sample.t < release.t {
                assert!(forces.normal[0] > 0.0 && forces.normal[1] > 0.0);
            }
        }
    }
}

#[test]
fn a_string_whirled_too_slowly_goes_slack_and_snaps_taut_with_the_energy_accounted_for() {
    // 2 g l < v₀² < 5 g l at the bottom: the string goes slack above the
    // horizontal, the bob flies on a parabola inside the circle, and the
    // string snaps taut plastically, taking the bob's radial kinetic energy.
    let bob = BobOnString::new(0.5, 9.81, 1.2);
    let v0 = (3.5f64 * 9.81 * 1.2).sqrt();
    let run = run(&bob, bob.whirled(v0), &times(3.0, 300)).unwrap();
    let switches = run.switches();
    let slack = switches
        .iter()
        .find(|s| s.cause == Cause::Release)
        .expect("slack");
    let phi = slack.q[0].atan2(-slack.q[1]);
    // The angle from the bottom: the trajectory's error (1e-12) and the
    // location's (ulps of t times φ̇ of a few rad/s).
    assert!(
        (phi - bob.slack_angle(v0)).abs() < 1e-10,
        "slack at {phi}, closed form {}",
        bob.slack_angle(v0)
    );
    // The free flight in closed form: r(s) = r_s + v_s s − g s²/2 e_y; it
    // comes back to |r| = l where the first root of |r(s)|² − l² > 0 lies,
    // found by bisection on the closed form to rounding.
    let (r, v) = (slack.q, slack.qdot);
    let at = |s: f64| Vector2::new(r[0] + v[0] * s, r[1] + v[1] * s - 9.81 / 2.0 * s * s);
    let outside = |s: f64| at(s).norm() > 1.2;
    let mut lo = 1e-3;
    while !outside(lo + 1e-3) {
        lo += 1e-3;
    }
    let mut hi = lo + 1e-3;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if outside(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let taut = switches
        .iter()
        .find(|s| s.cause == Cause::Impact && s.t > slack.t)
        .expect("it snaps taut");
    assert_eq!(taut.to, Mode::Closed, "a plastic snap keeps it taut");
    // The time: the location on an exact parabola, to the release state's
    // error.
    assert!(
        (taut.t - (slack.t + hi)).abs() < 1e-10,
        "taut at {}, closed form {}",
        taut.t,
        slack.t + hi
    );
    // The energy lost is the radial part of the kinetic energy, m/2 (r̂·v)²,
    // and the total energy drops by exactly that (accounted, to rounding of
    // energies of about 10 J).
    let s = taut.t - slack.t;
    let (rt, vt) = (at(s), v - Vector2::new(0.0, 9.81 * s));
    let radial = vt.dot(&rt) / rt.norm();
    let expected = 0.5 * 0.5 * radial * radial;
    assert!(
        (taut.energy_lost - expected).abs() < 1e-9 * expected.max(1.0),
        "{} against {expected}",
        taut.energy_lost
    );
    let (before, after) = run
        .trajectory()
        .iter()
        .map(|x| (x.t, bob.energy(x.t, &x.q, &x.qdot)))
        .fold((None, None), |(b, a), (t, e)| {
            if t < taut.t {
                (Some(e), a)
            } else {
                (b, a.or(Some(e)))
            }
        });
    let drop = before.unwrap() - after.unwrap();
    assert!(
        (drop - taut.energy_lost).abs() < 1e-9,
        "energy fell by {drop}, the impact took {}",
        taut.energy_lost
    );
}

#[test]
fn a_ball_with_restitution_one_half_settles_at_the_accumulation_time_then_rests_with_n_equal_to_mg()
{
    // Released from rest at 1 m: flights 2 t₁ eᵏ sum to t₁ (1 + e)/(1 − e).
    let ball = BallOnFloor::new(2.0, 9.81, 0.5);
    let run = run(&ball, ([0.0, 1.0], [0.0, 0.0]), &times(3.0, 30)).unwrap();
    let rest = run.switches().last().expect("switches");
    assert_eq!((rest.cause, rest.to), (Cause::Settled, Mode::Closed));
    // Cut off where a flight would be shorter than the shortest flight
    // (1e-10 s): the flights left out add up to at most 1e-10 / (1 − e),
    // and each bounce time carries the location's few ulps.
    assert!(
        (rest.t - ball.rest_time(1.0)).abs() < 1e-9,
        "rests at {}, closed form {}",
        rest.t,
        ball.rest_time(1.0)
    );
    let bounces = run
        .switches()
        .iter()
        .filter(|s| s.cause == Cause::Impact)
        .count();
    assert!(bounces > 20, "{bounces} bounces before it settles");
    for (sample, forces) in run.trajectory().iter().zip(run.forces()) {
        if sample.t > rest.t {
            // At rest: N = m g to rounding, and it stays on the floor.
            assert!(
                (forces.normal[0] - 2.0 * 9.81).abs() < 1e-12,
                "N = {}",
                forces.normal[0]
            );
            assert!(sample.q[1].abs() < 1e-12 && sample.qdot[1].abs() < 1e-12);
        }
    }
    // Every impact takes energy: (1 − e²) of the kinetic energy before it.
    for impact in run.switches().iter().filter(|s| s.cause == Cause::Impact) {
        assert!(impact.energy_lost > 0.0);
    }
}

lagrange::lagrangian! {
    /// A ball of mass `m` above a floor at height `h`, bouncing with
    /// restitution `e` under gravity `g`: `BallOnFloor` with the floor
    /// moved off the origin.
    struct BallAboveFloor {
        coordinates: x, y;
        parameters: m, g, e, h;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*y;
        contacts: floor: y >= h { restitution: e };
    }
}

/// Where the floor is, and the units the ball is written in, are no
/// physics: released from rest 1 m above the floor, the ball comes to rest
/// at `t₁ (1 + e)/(1 − e)` whether the floor is at 0, 0.1, 1 or 1000 m,
/// and in millimetres. (Before its rebounds were flown out to their
/// accumulation, the floor at 0.1 m rested 2.7e-8 s early, at 1000 m
/// microseconds.)
#[test]
fn a_ball_comes_to_rest_at_the_accumulation_time_wherever_the_floor_is_and_in_any_units() {
    let e = 0.5f64;
    for (h, unit) in [
        (0.0f64, 1.0f64),
        (0.1, 1.0),
        (1.0, 1.0),
        (1000.0, 1.0),
        (0.1, 1e3),
        (1.0, 1e3),
    ] {
        let g = 9.81 * unit;
        let ball = BallAboveFloor::new(2.0, g, e, h * unit);
        let closed = (2.0 * unit / g).sqrt() * (1.0 + e) / (1.0 - e);
        let run = run(
            &ball,
            ([0.0, (h + 1.0) * unit], [0.0, 0.0]),
            &times(3.0, 30),
        )
        .unwrap();
        let rest = run.switches().last().expect("switches");
        assert_eq!((rest.cause, rest.to), (Cause::Settled, Mode::Closed));
        println!(
            "floor at {h} m, unit {unit}: rests {:.2e} s from the closed form after {} switches",
            rest.t - closed,
            run.switches().len()
        );
        // Each bounce is located to the rounding of the height, ulp(h),
        // over its speed, down to the cut's (the apex at 64 ε h: 1e-7 m/s
        // at 0.1 m, 1e-5 m/s at 1000 m), and the flights cut off are
        // summed exactly at a constant acceleration; the cut at the
        // velocity tolerance (1e-9 m/s, at h = 0) leaves out at most
        // 2 · 1e-9 / (g (1 − e)) = 4e-10 s. Measured: 1.6e-10 to 6.3e-10 s
        // within 1 m of the origin, 2.0e-8 s at 1000 m (ulp 1.1e-13 m).
        let bound = if h > 1.0 { 1e-7 } else { 1e-9 };
        assert!(
            (rest.t - closed).abs() < bound,
            "floor at {h} m, unit {unit}: rests at {}, closed form {closed}",
            rest.t
        );
    }
}
