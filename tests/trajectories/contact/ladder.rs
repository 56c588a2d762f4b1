//! A ladder against a rough wall on a rough floor: statically
//! indeterminate while it stands (four unknown forces, three equations of
//! equilibrium), so the friction it is held by must move normal load
//! between the contacts; it stands exactly where an admissible
//! distribution of its forces exists, and slips, both ends together, where
//! none remains.

use lagrange::contact::{Cause, ContactTrajectory, Mode};
use lagrange::models::RoughLadder;

use super::{run, times};

/// Checks the samples before `until` (and all of them, when `None`): both
/// ends stuck, the ladder where it started, every force admissible and the
/// ladder in equilibrium under them.
fn assert_standing(
    ladder: &RoughLadder<f64>,
    theta: f64,
    run: &ContactTrajectory<f64, 3, 2>,
    until: Option<f64>,
) {
    let (q0, _) = ladder.at_rest(theta);
    let (s, c) = theta.sin_cos();
    let weight = ladder.m * ladder.g;
    for ((sample, forces), modes) in run.trajectory().iter().zip(run.forces()).zip(run.modes()) {
        if until.is_some_and(|t_b| sample.t >= t_b) {
            continue;
        }
        let t = sample.t;
        assert_eq!(*modes, [Mode::Stuck; 2], "modes at {t}");
        // Both stuck, the accelerations are zero to the rounding of the
        // forces' solve (1e-15 of g), which moves the ladder by about 1e-15
        // g t² over these few seconds: 1e-12 bounds it with room.
        for k in 0..3 {
            assert!(
                (sample.q[k] - q0[k]).abs() < 1e-12,
                "crept: q = {:?}, started at {q0:?}, at {t}",
                sample.q
            );
        }
        let (n, f) = (forces.normal, forces.friction);
        let laws = [ladder.mu_w, ladder.mu_f];
        for i in 0..2 {
            assert!(n[i] >= 0.0, "contact {i} pulls: N = {n:?} at {t}");
            // Inside the cone to rounding: 1e-12 relative.
            assert!(
                f[i].abs() <= laws[i] * n[i] * (1.0 + 1e-12),
                "contact {i} outside its cone at {t}: |F| = {}, μ N = {}",
                f[i].abs(),
                laws[i] * n[i]
            );
        }
        // Equilibrium under gravity and the push, to the rounding of the
        // largest force (1e-12 of it): along x, along y, and the moments
        // (the generalized force on θ over l/2).
        let push = ladder.p0 + ladder.rate * t;
        let (wall, floor) = (0, 1);
        let largest = [n.amax(), f.amax(), weight, push.abs()]
            .into_iter()
            .fold(0.0, f64::max);
        let tolerance = 1e-12 * largest;
        assert!((n[wall] + f[floor] + push).abs() < tolerance, "x at {t}");
        assert!((f[wall] + n[floor] - weight).abs() < tolerance, "y at {t}");
        let moment = -c * n[wall] - s * f[wall] + s * n[floor] + c * f[floor];
        assert!(moment.abs() < tolerance, "moment {moment} at {t}");
    }
}

/// The minimum-norm forces of the standing ladder, unpushed, set the
/// wall's normal force to zero (the least `N_w² + F_w² + N_f² + F_f²`
/// under the equilibrium `N_w = (m g/2 − F_w) tan θ = −F_f`, `N_f = m g −
/// F_w` is at `F_w = m g/2`), friction with no normal force; friction
/// shared in proportion to the cones `μ N` of those normal forces then
/// gives the wall none, and the floor must carry `F_f = m g tan θ / 2`
/// against `N_f = m g`: a use of its cone `tan θ / (2 μ_f)`, outside it
/// for `tan θ > 2 μ_f`, below the classical limit.
fn proportional_floor_use(ladder: &RoughLadder<f64>, theta: f64) -> f64 {
    theta.tan() / (2.0 * ladder.mu_f)
}

/// A uniform ladder released from rest at an angle `θ` from the wall
/// stands iff `tan θ ≤ 2 μ_f / (1 − μ_f μ_w)` (`μ_f μ_w < 1`; see
/// [`RoughLadder::holds`]): here 4/3. At `tan θ = 1.2`, and within 1e-6
/// of the limit below it, it stands, its forces inside both cones, though
/// the proportional share would put the floor's outside; within 1e-6
/// above the limit and at `tan θ = 1.5` no admissible distribution
/// exists, and it slips from the start, both ends together.
#[test]
fn a_rough_ladder_stands_iff_tan_theta_is_at_most_two_mu_f_over_one_minus_mu_f_mu_w() {
    let ladder = RoughLadder::<f64>::new(10.0, 4.0, 9.81, 0.5, 0.5, 0.0, 0.0);
    let limit = 2.0 * ladder.mu_f / (1.0 - ladder.mu_f * ladder.mu_w);
    assert!((limit - 4.0 / 3.0).abs() < 1e-15);
    for tan in [1.2, limit * (1.0 - 1e-6), limit * (1.0 + 1e-6), 1.5] {
        let theta = f64::atan(tan);
        let run = run(&ladder, ladder.at_rest(theta), &times(2.0, 40)).unwrap();
        if ladder.holds(theta) {
            assert!(
                proportional_floor_use(&ladder, theta) > 1.1,
                "the proportional share is inadmissible here"
            );
            assert_eq!(
                run.switches().len(),
                2,
                "tan θ = {tan}: {:#?}",
                run.switches()
            );
            assert_standing(&ladder, theta, &run, None);
        } else {
            let start: Vec<_> = run.switches().iter().take(2).map(|s| s.to).collect();
            assert_eq!(
                start,
                [
                    Mode::Sliding { forward: false },
                    Mode::Sliding { forward: true }
                ],
                "tan θ = {tan}: the top slides down, the foot out"
            );
            let last = run.trajectory().last().unwrap();
            // Far beyond the creep of a standing ladder (1e-12).
            assert!(last.q[2] > theta + 1e-9, "it falls: θ = {}", last.q[2]);
        }
    }
}

/// The ladder standing at `tan θ = 0.88` (`μ_w = μ_f = 0.4`: below the
/// limit 0.952, above `2 μ_f`, so the proportional share is inadmissible
/// from the start), pushed at its centre by a force growing slowly from
/// `p0` (zero, or 90 % of the way to the limit): away from the wall, it
/// slips, its foot out and its top down, where `P` reaches
/// [`RoughLadder::slipping_push`]; towards the wall, its foot in and its
/// top up, at [`RoughLadder::climbing_push`]. Both ends leave their cones
/// at the same switch, and the breakaway does not depend on the load's
/// history (from zero, or from near the limit).
#[test]
fn a_rough_ladder_pushed_slowly_slips_where_both_ends_reach_their_limits_together() {
    let (m, l, g, mu): (f64, f64, f64, f64) = (10.0, 4.0, 9.81, 0.4);
    let theta = f64::atan(0.88);
    let plain = RoughLadder::new(m, l, g, mu, mu, 0.0, 0.0);
    assert!(plain.holds(theta) && proportional_floor_use(&plain, theta) > 1.0);
    let away = plain.slipping_push(theta);
    let towards = plain.climbing_push(theta).expect("it can be pushed up");
    assert!(away > 0.0 && towards < 0.0);
    // (limit, load rate, the modes it slips into: wall, floor)
    let cases = [
        (
            away,
            1.0,
            [
                Mode::Sliding { forward: false },
                Mode::Sliding { forward: true },
            ],
        ),
        (
            towards,
            -300.0,
            [
                Mode::Sliding { forward: true },
                Mode::Sliding { forward: false },
            ],
        ),
    ];
    for (limit, rate, slides) in cases {
        for p0 in [0.0, 0.9 * limit] {
            let ladder = RoughLadder::new(m, l, g, mu, mu, p0, rate);
            let t_b = (limit - p0) / rate;
            let end = t_b + 0.05;
            let run = run(&ladder, ladder.at_rest(theta), &times(end, 100)).unwrap();
            let breakaway: Vec<_> = run
                .switches()
                .iter()
                .filter(|s| s.cause != Cause::Start)
                .collect();
            assert!(!breakaway.is_empty(), "P = {limit}: it does not slip");
            let first = breakaway[0];
            // While it stands the state is its start, exact to rounding,
            // and only the push changes: the margins are continuous in it
            // (the least use of the cones, by bisection to rounding), so
            // the event is located to the rounding of the margins over
            // their rate, well within 1e-9 s.
            assert!(
                (first.t - t_b).abs() < 1e-9,
                "p0 = {p0}: slipped at {}, closed form {t_b}: {breakaway:#?}",
                first.t
            );
            assert_eq!(first.cause, Cause::StickLimit);
            let at_once: Vec<_> = breakaway.iter().filter(|s| s.t == first.t).collect();
            assert_eq!(at_once.len(), 2, "both ends at once: {breakaway:#?}");
            for s in at_once {
                assert_eq!(s.to, slides[s.contact], "{s:?}");
            }
            assert_standing(&ladder, theta, &run, Some(first.t));
        }
    }
}
