//! Coulomb friction: a ball that slides until it rolls, a block that
//! stays put below its friction angle and slides above it, a block on a
//! belt that sticks and slips, Painlevé's rod, a crate on two rough
//! supports whose friction is statically indeterminate; and friction
//! against a given normal force: a torsion pendulum in a loaded bearing, and a
//! braked cart set sliding by an impact elsewhere.

use lagrange::contact::{Cause, ContactError, Mode};
use lagrange::models::{BlockOnBelt, BlockOnIncline, SlidingBall, TorsionBearing};

use super::{run, times};

#[test]
fn a_ball_thrown_sliding_starts_to_roll_at_two_v0_over_seven_mu_g_at_five_sevenths_of_v0() {
    let ball = SlidingBall::new(0.3, 0.05, 9.81, 0.2);
    for v0 in [0.5, 3.0] {
        let t_roll = ball.rolling_time(v0);
        let run = run(&ball, ball.thrown(v0), &times(3.0 * t_roll, 60)).unwrap();
        let start = run.switches()[0];
        assert_eq!(start.to, Mode::Sliding { forward: true });
        let roll = run
            .switches()
            .iter()
            .find(|s| s.cause == Cause::SlideStopped)
            .expect("it rolls");
        assert_eq!(roll.to, Mode::Stuck);
        // The slip velocity is linear in t while it slides (every method
        // exact up to rounding), so the time is the location's (a few ulps)
        // and the speed the trajectory's rounding.
        assert!(
            (roll.t - t_roll).abs() < 1e-10,
            "rolls at {}, closed form {t_roll}",
            roll.t
        );
        let speed = SlidingBall::rolling_speed(v0);
        assert!(
            (roll.qdot[0] - speed).abs() < 1e-10,
            "{} against {speed}",
            roll.qdot[0]
        );
        for ((sample, forces), modes) in run.trajectory().iter().zip(run.forces()).zip(run.modes())
        {
            // N = m g throughout; while it slides friction is −μ N, once it
            // rolls none is needed: the speed stays 5 v₀ / 7.
            assert!((forces.normal[0] - 0.3 * 9.81).abs() < 1e-12);
            if sample.t < roll.t {
                assert_eq!(modes[0], Mode::Sliding { forward: true });
                assert!((forces.friction[0] + 0.2 * 0.3 * 9.81).abs() < 1e-12);
            } else if sample.t > roll.t {
                assert_eq!(modes[0], Mode::Stuck);
                assert!(forces.friction[0].abs() < 1e-12);
                assert!((sample.qdot[0] - speed).abs() < 1e-10);
            }
        }
    }
}

#[test]
fn a_block_below_its_friction_angle_stays_put_and_above_it_slides_at_the_closed_form_rate() {
    // μ_s = 0.5, μ_k = 0.4: the friction angle is atan(0.5) = 26.6°.
    let (m, g) = (1.0, 9.81);
    for degrees in [10.0f64, 20.0, 26.0] {
        let alpha = degrees.to_radians();
        let block = BlockOnIncline::new(m, g, alpha, 0.5, 0.4);
        assert!(block.holds());
        let run = run(&block, ([0.0, 0.0], [0.0, 0.0]), &times(10.0, 100)).unwrap();
        assert_eq!(run.switches().len(), 1, "{:?}", run.switches());
        assert_eq!(run.switches()[0].to, Mode::Stuck);
        for (sample, forces) in run.trajectory().iter().zip(run.forces()) {
            // Stuck: the accelerations are zero to rounding of forces of
            // 10 N, so over 10 s the block moves by no more than rounding.
            assert!(
                sample.q.norm() < 1e-13,
                "moved {} at t = {}",
                sample.q.norm(),
                sample.t
            );
            assert!((forces.normal[0] - m * g * alpha.cos()).abs() < 1e-12);
            // The friction force holds it up the slope.
            assert!((forces.friction[0] + m * g * alpha.sin()).abs() < 1e-12);
        }
    }
    for degrees in [30.0f64, 45.0] {
        let alpha = degrees.to_radians();
        let block = BlockOnIncline::new(m, g, alpha, 0.5, 0.4);
        assert!(!block.holds());
        let run = run(&block, ([0.0, 0.0], [0.0, 0.0]), &times(2.0, 20)).unwrap();
        assert_eq!(run.switches()[0].to, Mode::Sliding { forward: true });
        let a = block.sliding_acceleration();
        for sample in run.trajectory().iter() {
            // x = a t²/2: a quadratic, exact for Dop853 up to rounding.
            assert!((sample.q[0] - a * sample.t * sample.t / 2.0).abs() < 1e-12);
            assert!(sample.q[1].abs() < 1e-12);
        }
    }
}

#[test]
fn a_block_on_a_belt_sticks_and_slips_on_its_closed_form_cycle() {
    // Riding the belt from x = 0, it slips at x₁ = μ_s m g / k, slips back
    // harmonically about μ_k m g / k, sticks again at the belt's speed at
    // x₂, and rides to x₁ again: a limit cycle.
    let block = BlockOnBelt::new(1.0, 9.81, 40.0, 0.3, 0.6, 0.4);
    let cycle = block.cycle();
    let run = run(&block, ([0.0, 0.0], [0.3, 0.0]), &times(10.0, 200)).unwrap();
    let switches: Vec<_> = run
        .switches()
        .iter()
        .filter(|s| s.cause != Cause::Start)
        .collect();
    assert!(switches.len() >= 6, "{switches:?}");
    let mut expected_t = cycle.slips_at / 0.3;
    for (k, s) in switches.iter().enumerate() {
        // Alternately: it slips back (the friction needed reached μ_s N)
        // and sticks (the slip velocity reached zero).
        if k % 2 == 0 {
            assert_eq!(
                (s.cause, s.to),
                (Cause::StickLimit, Mode::Sliding { forward: false })
            );
            assert!(
                (s.q[0] - cycle.slips_at).abs() < 1e-10,
                "slips at x = {}",
                s.q[0]
            );
        } else {
            assert_eq!((s.cause, s.to), (Cause::SlideStopped, Mode::Stuck));
            assert!(
                (s.q[0] - cycle.sticks_at).abs() < 1e-10,
                "sticks at x = {}",
                s.q[0]
            );
        }
        // The times: each phase's duration in closed form; the errors of
        // the harmonic phases (1e-12 each) add up over the cycles.
        assert!(
            (s.t - expected_t).abs() < 1e-9,
            "switch {k} at {}, closed form {expected_t}",
            s.t
        );
        expected_t += if k % 2 == 0 {
            cycle.slip_duration
        } else {
            cycle.stick_duration
        };
    }
}

lagrange::lagrangian! {
    /// A uniform rod of half-length `l` (moment of inertia `m l²/3`), its
    /// lower end on a rough floor: centre `(x, y)`, angle `theta` above
    /// the horizontal, the end at `(x − l cos θ, y − l sin θ)`.
    struct PainleveRod {
        coordinates: x, y, theta;
        parameters: m, l, g, mu;
        let end_x = x - l*cos(theta);
        let end_y = y - l*sin(theta);
        kinetic: m/2*(dot(x)^2 + dot(y)^2) + m*l^2/6*dot(theta)^2;
        potential: m*g*y;
        contacts: floor: end_y >= 0 { friction: mu, slip: dot(end_x) };
    }
}

#[test]
fn painleves_rod_sliding_with_too_much_friction_is_a_typed_error_at_its_state() {
    // Sliding towards its foot at 30°: the normal force's own effect on the
    // end's normal acceleration is G M⁻¹ (Gᵀ ∓ μ Tᵀ) = (1 + 3 cos² θ −
    // 3 μ sin θ cos θ)/m, negative for μ > 2.5 here, so gravity's pull
    // down is met by no normal force ≥ 0: no mode is consistent. Below that
    // it slides.
    let (l, theta) = (0.5f64, 30f64.to_radians());
    let start = |v: f64| ([l * theta.cos(), l * theta.sin(), theta], [v, 0.0, 0.0]);
    let rod = PainleveRod::new(1.0, l, 9.81, 3.0);
    let failure = run(&rod, start(-1.0), &[0.1]).unwrap_err();
    match failure.error {
        lagrange::contact::ContactError::NoConsistentMode { t, at_impact, .. } => {
            assert_eq!((t, at_impact), (0.0, false));
        }
        error => panic!("{error}"),
    }
    assert!(
        failure.error.to_string().contains("Painlevé"),
        "{}",
        failure.error
    );
    let rod = PainleveRod::new(1.0, l, 9.81, 1.0);
    let slides = run(&rod, start(-1.0), &[0.1]).unwrap();
    assert_eq!(slides.switches()[0].to, Mode::Sliding { forward: false });
}

#[test]
fn a_torsion_pendulum_in_a_loaded_bearing_loses_two_d_per_swing_and_sticks_where_static_friction_holds()
 {
    // Friction in a joint, against a given normal force (the bearing's
    // load): no gap, no reaction. ω = √(κ/I) = 2, d = μ_k F r / κ = 0.015,
    // static friction holds the spring within μ_s F r / κ = 0.02: from rest
    // at 0.205 it turns at 0.205, −0.175, 0.145, −0.115, 0.085, −0.055,
    // 0.025 and sticks at 0.005 (the last swing stays on one side).
    let bearing = TorsionBearing::new(0.5, 2.0, 1.0, 0.1, 0.4, 0.3);
    // A negative load is no normal force: refused before any work.
    let pulling = TorsionBearing::new(0.5, 2.0, -1.0, 0.1, 0.4, 0.3);
    let refused = run(&pulling, ([0.205], [0.0]), &[1.0]).unwrap_err();
    assert!(
        matches!(
            refused.error,
            ContactError::InvalidSetting {
                setting: "normal",
                ..
            }
        ),
        "{refused}"
    );
    // The equations' text lists the given normal force and the slip
    // velocity (and a gap where a contact has one).
    let text = TorsionBearing::<f64>::EQUATIONS;
    assert!(text.contains("N[bearing] = load"), "{text}");
    assert!(text.contains("v_t[bearing] = "), "{text}");
    assert!(SlidingBall::<f64>::EQUATIONS.contains("g[table] = "));
    let swings = bearing.swings(0.205);
    assert_eq!(swings.len(), 7);
    let stop = swings.last().unwrap();
    let end = stop.start + 2.0 * core::f64::consts::FRAC_PI_2;
    let run = run(&bearing, ([0.205], [0.0]), &times(end + 3.0, 140)).unwrap();
    // The start: at rest, the spring's torque beyond static friction's.
    assert_eq!(run.switches()[0].to, Mode::Sliding { forward: false });
    let turns: Vec<_> = run
        .switches()
        .iter()
        .filter(|s| s.cause == Cause::SlideStopped)
        .collect();
    assert_eq!(turns.len(), swings.len(), "{:?}", run.switches());
    for (k, (turn, swing)) in turns.iter().zip(&swings).enumerate() {
        // Each turning point where and when the closed form puts it: the
        // slip velocity crosses zero with the acceleration κ |θ| / I away
        // from zero, so the location is a few ulps of t; the angle is the
        // trajectory's (Dop853 at 1e-12 over 12 s: about 1e-12).
        let t_turn = swing.start + core::f64::consts::FRAC_PI_2;
        assert!(
            (turn.t - t_turn).abs() < 1e-10,
            "turn {k}: {} against {t_turn}",
            turn.t
        );
        assert!(
            (turn.q[0] - swing.to).abs() < 1e-10,
            "turn {k}: {} against {}",
            turn.q[0],
            swing.to
        );
        let expected = if k + 1 == swings.len() {
            Mode::Stuck
        } else {
            Mode::Sliding {
                forward: swing.to < 0.0,
            }
        };
        assert_eq!(turn.to, expected, "turn {k}");
    }
    for ((sample, forces), modes) in run.trajectory().iter().zip(run.forces()).zip(run.modes()) {
        // The normal force is the load throughout.
        assert_eq!(forces.normal[0], 1.0);
        let swing = swings.iter().rev().find(|s| s.start <= sample.t);
        match swing {
            Some(swing) if sample.t < swing.start + core::f64::consts::FRAC_PI_2 => {
                // Sliding: harmonic about the friction's balance point, the
                // friction force μ_k F against the slip.
                let theta = bearing.angle(swing, sample.t);
                assert!((sample.q[0] - theta).abs() < 1e-10, "t = {}", sample.t);
                assert!(matches!(modes[0], Mode::Sliding { .. }));
                assert!((forces.friction[0].abs() - 0.3).abs() < 1e-15);
            }
            _ => {
                // Stuck at 0.005 for good: the friction force holds the
                // spring's torque, F r = κ θ, within μ_s F.
                assert_eq!(modes[0], Mode::Stuck);
                assert!((sample.q[0] - 0.005).abs() < 1e-10);
                assert!(sample.qdot[0].abs() < 1e-12);
                assert!((forces.friction[0] * 0.1 - 2.0 * sample.q[0]).abs() < 1e-12);
            }
        }
    }
}

lagrange::lagrangian! {
    /// A cart of mass `mc` on rails, held by a brake pressed with the given
    /// force `fb` (friction `mu`), carrying a pendulum (a bob of mass `m` on
    /// a rod of length `l`) that strikes a stop at `theta = -limit` with
    /// restitution `e`.
    struct BrakedCart {
        coordinates: x, theta;
        parameters: mc, m, l, g, e, fb, mu, limit;
        let bob_x = x + l*sin(theta);
        let bob_y = -l*cos(theta);
        kinetic: mc/2*dot(x)^2 + m/2*(dot(bob_x)^2 + dot(bob_y)^2);
        potential: m*g*bob_y;
        contacts: stop: theta >= -limit { restitution: e },
                  brake: { normal: fb, friction: mu, slip: dot(x) };
    }
}

#[test]
fn an_impact_elsewhere_sets_a_braked_cart_sliding_with_the_momentum_the_impact_gives_it() {
    // The brake (50 N at most) holds the cart while the pendulum swings
    // down from rest at 0.5 rad (its pull on the cart stays below 15 N):
    // θ̇⁻² = 2 g/l (cos θ_s − cos θ₀) at the stop, θ_s = −0.2. The stop's
    // impulse acts on θ alone, so the cart's horizontal momentum
    // (mc + m) ẋ + m l cos θ θ̇ is kept through the impact, and the brake,
    // a finite force, gives no impulse: from ẋ⁻ = 0 and θ̇⁺ = −e θ̇⁻, the
    // cart leaves at ẋ⁺ = (1 + e) m l cos θ_s θ̇⁻ / (mc + m), sliding.
    let cart = BrakedCart::new(2.0, 1.0, 1.0, 9.81, 0.5, 100.0, 0.5, 0.2);
    let run = run(&cart, ([0.0, 0.5], [0.0, 0.0]), &times(1.0, 20)).unwrap();
    assert_eq!(
        run.switches()[0].to,
        Mode::Stuck,
        "the brake holds at the start"
    );
    let impact = run
        .switches()
        .iter()
        .find(|s| s.cause == Cause::Impact)
        .expect("the pendulum strikes the stop");
    let (theta_s, e) = (-0.2f64, 0.5);
    let before = -(2.0 * 9.81 * (theta_s.cos() - 0.5f64.cos())).sqrt();
    let brake = run
        .switches()
        .iter()
        .find(|s| s.contact == 1 && s.t == impact.t)
        .expect("the brake switches at the impact");
    let cart_after = (1.0 + e) * theta_s.cos() * before / 3.0;
    assert_eq!(
        (brake.from, brake.to),
        (Mode::Stuck, Mode::Sliding { forward: false })
    );
    // The angle is the stop's to the location tolerance; the velocities are
    // the trajectory's (Dop853 at 1e-12 over half a second: about 1e-12).
    assert!((impact.q[1] - theta_s).abs() < 1e-10);
    assert!(
        (impact.qdot[1] + e * before).abs() < 1e-9,
        "θ̇⁺ = {}, −e θ̇⁻ = {}",
        impact.qdot[1],
        -e * before
    );
    assert!(
        (impact.qdot[0] - cart_after).abs() < 1e-9,
        "ẋ⁺ = {}, closed form {cart_after}",
        impact.qdot[0]
    );
}

lagrange::lagrangian! {
    /// A uniform crate of mass `m`, width `w` and height `h` (moment of
    /// inertia `m (w² + h²)/12`) standing on its two bottom corners on a
    /// rough floor (`mu`, static and kinetic alike), pushed along the floor
    /// at its centre by `P = p0 + rate t`.
    struct PushedCrate {
        coordinates: x, y, theta;
        parameters: m, w, h, g, mu, p0, rate;
        let b = vector(x, y, 0) + rotate_z(theta, vector(-w/2, -h/2, 0));
        let f = vector(x, y, 0) + rotate_z(theta, vector(w/2, -h/2, 0));
        kinetic: m/2*(dot(x)^2 + dot(y)^2) + m*(w^2 + h^2)/24*dot(theta)^2;
        potential: m*g*y;
        forces: x = p0 + rate*t;
        contacts:
            back: b[1] >= 0 { friction: mu, slip: dot(b[0]) },
            front: f[1] >= 0 { friction: mu, slip: dot(f[0]) };
    }
}

/// The crate on two rough supports: while both corners stick, the
/// friction they share is statically indeterminate (only its sum is
/// fixed), and every share must lie inside its corner's cone. The push
/// loads the front corner more (`N_front − N_back = P h / w`), so an even
/// share leaves the back corner's cone first, at `P = μ m g / (1 + μ h /
/// w)`; an admissible share exists until `P = μ m g`, where the crate
/// breaks away, both corners sliding, and then `m ẍ = P − μ m g` (the
/// normal forces still sum to `m g`: it neither lifts nor tips while `P <
/// m g w / h`), so `x = rate (t − t_b)³ / (6 m)` from the breakaway time
/// `t_b = (μ m g − p0) / rate`. The same from a push that starts at zero.
#[test]
fn a_crate_on_two_rough_supports_breaks_away_at_mu_m_g_with_every_share_inside_its_cone() {
    let (m, w, h, g, mu, rate) = (1.0, 1.0, 0.5, 9.81, 0.5, 0.5);
    let limit = mu * m * g;
    for p0 in [0.9 * limit, 0.0] {
        let model = PushedCrate::new(m, w, h, g, mu, p0, rate);
        let t_b = (limit - p0) / rate;
        let end = t_b + 2.0;
        let run = run(&model, ([0.0, h / 2.0, 0.0], [0.0; 3]), &times(end, 200)).unwrap();
        let breakaway = run
            .switches()
            .iter()
            .find(|s| s.cause == Cause::StickLimit)
            .unwrap_or_else(|| panic!("no breakaway: {:#?}", run.switches()));
        // The margins are linear in t while it sticks, so the event is
        // located to rounding; Dop853 at 1e-12 bounds the rest.
        assert!(
            (breakaway.t - t_b).abs() < 1e-9,
            "p0 = {p0}: broke away at {}, closed form {t_b}",
            breakaway.t
        );
        let after: Vec<_> = run
            .switches()
            .iter()
            .filter(|s| s.t > breakaway.t)
            .collect();
        assert!(
            after.is_empty(),
            "p0 = {p0}: switches after the breakaway: {after:?}"
        );
        for ((sample, forces), modes) in run.trajectory().iter().zip(run.forces()).zip(run.modes())
        {
            let (n, f) = (forces.normal, forces.friction);
            // Forces of 10 N to rounding: 1e-12.
            assert!(
                ((n[0] + n[1]) - m * g).abs() < 1e-12,
                "{n:?} at {}",
                sample.t
            );
            if sample.t < t_b - 1e-9 {
                assert_eq!(*modes, [Mode::Stuck; 2], "p0 = {p0} at {}", sample.t);
                for i in 0..2 {
                    assert!(
                        f[i].abs() <= mu * n[i] + 1e-12,
                        "p0 = {p0}, t = {}: corner {i} carries {} of its cone's {}",
                        sample.t,
                        f[i].abs(),
                        mu * n[i]
                    );
                }
                assert!(
                    sample.q[0].abs() < 1e-12,
                    "crept {} by {}",
                    sample.q[0],
                    sample.t
                );
            } else if sample.t > t_b + 1e-9 {
                assert_eq!(*modes, [Mode::Sliding { forward: true }; 2]);
                let s = sample.t - t_b;
                let x = rate * s.powi(3) / (6.0 * m);
                // Dop853's global error at 1e-12 over 2 s of a cubic
                // (its error estimate exact for it to rounding), with the
                // breakaway time's error times the speed (at most 1 m/s).
                assert!(
                    (sample.q[0] - x).abs() < 1e-9,
                    "p0 = {p0}: x = {} at {}, closed form {x}",
                    sample.q[0],
                    sample.t
                );
            }
        }
    }
}
