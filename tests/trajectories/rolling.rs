//! Constraints on the velocities, `A(t, q) q̇ + b(t, q) = 0`, with
//! Lagrange–d'Alembert dynamics: a knife edge (`ChaplyginSleigh`) and a
//! thin disk rolling without slipping (`RollingDisk`), each against its
//! closed form, both from `lagrange::models`.

use lagrange::constraints::{StartError, state_from_body_rates};
use lagrange::models::{ChaplyginSleigh, RollingBall, RollingDisk};
use lagrange::nalgebra::{UnitQuaternion, Vector2, Vector3};
use lagrange::prelude::*;
use lagrange::{InvalidInput, Method};

/// The sleigh's `m`, `i`, `a`, and its start: forward speed `v0`, turning
/// rate `ω0`, from the origin heading along `x`.
const SLEIGH: [f64; 3] = [2.0, 0.3, 0.4];
const V0: f64 = 0.5;
const W0: f64 = 1.5;

fn sleigh() -> ChaplyginSleigh {
    let [m, i, a] = SLEIGH;
    ChaplyginSleigh::new(m, i, a)
}

/// The sleigh's speed and turning rate in closed form
/// (`ChaplyginSleigh::closed_form`: `v` a tanh, `ω` a sech).
fn sleigh_closed_form(t: f64) -> (f64, f64) {
    sleigh().closed_form(V0, W0, t)
}

/// The knife edge against its closed form: speed a tanh, turning rate a
/// sech, to 1e-10 every 0.05 s over 10 s (the turning rate falls from 1.5
/// to 2e-6 rad/s); the multiplier is the edge's sideways force, which
/// turns the body: `a λ = i ω̇` (the force on `θ` is `−Gᵀλ`, G's row
/// `(−sin θ, cos θ, −a)`), so `λ = −i m v ω / J`, to 1e-10 of its largest
/// value; the velocity residual at rounding.
///
/// Bounds: Dop853 at rtol = atol = 1e-13 on a regular motion errs by a
/// few times the tolerance per unit time, ~1e-12 here; the multiplier is
/// a function of the state with derivatives of order one. 1e-10 leaves a
/// margin of about 100.
#[test]
fn the_chaplygin_sleigh_speeds_up_as_a_tanh_and_stops_turning_as_a_sech() {
    let [m, i, a] = SLEIGH;
    let sleigh = sleigh();
    let (q0, v0) = sleigh.state(V0, W0);
    let times: Vec<f64> = (1..=200).map(|k| 0.05 * k as f64).collect();
    let run = Dop853::new()
        .rtol(1e-13)
        .atol(1e-13)
        .integrate(&sleigh, 0.0, q0, v0, &times)
        .unwrap();
    let j = i + m * a * a;
    let lambda_scale = i * m * V0.max(1.0) * W0 / j;
    let energy0 = sleigh.energy(0.0, &q0, &v0);
    let (mut worst_state, mut worst_force, mut worst_energy) = (0.0f64, 0.0f64, 0.0f64);
    for s in &run {
        let v = ChaplyginSleigh::speed(&s.q, &s.qdot);
        let w = s.qdot[2];
        let (v_exact, w_exact) = sleigh_closed_form(s.t);
        worst_state = worst_state
            .max((v - v_exact).abs())
            .max((w - w_exact).abs());
        let lambda = sleigh.multipliers(s.t, &s.q, &s.qdot).unwrap()[0];
        worst_force =
            worst_force.max((lambda + i * m * v_exact * w_exact / j).abs() / lambda_scale);
        worst_energy =
            worst_energy.max((sleigh.energy(s.t, &s.q, &s.qdot) - energy0).abs() / energy0);
        assert!(sleigh.constraint_velocities(s.t, &s.q, &s.qdot)[0].abs() < 1e-14);
    }
    assert!(
        worst_state < 1e-10,
        "speed or turning rate off by {worst_state:e}"
    );
    assert!(worst_force < 1e-10, "edge force off by {worst_force:e}");
    assert!(worst_energy < 1e-10, "energy drifted by {worst_energy:e}");
    let end = run.last().unwrap();
    assert!(end.qdot[2] < 1e-5, "it stops turning: ω = {}", end.qdot[2]);
}

/// The disk's `m`, `r`, `g`.
const DISK: [f64; 3] = [1.5, 0.3, 9.81];

fn disk() -> RollingDisk {
    let [m, r, g] = DISK;
    RollingDisk::new(m, r, g)
}

/// Steady circular rolling: for lean `θ`, spin `ω` and heading rate `Ω`
/// held constant, the lean's equation of motion (the other four hold with
/// the contact forces) reads
///
/// ```text
/// 4 g sin θ = 6 Ω ω r cos θ − 5 Ω² r sin θ cos θ,
/// ```
///
/// the classical relation of a thin disk (Routh, Advanced Rigid Dynamics,
/// §244; derived here from this Lagrangian with SymPy, independently of
/// the macro): `g tan θ = (1 + I_a / m r²) Ω v − …` with `v = r ω`. Given
/// `θ` and `ω`, `Ω` is its smaller root, and the contact point runs round
/// a circle of radius `R = r |ω / Ω|`.
///
/// Started on it (lean 0.5 rad, spin −6 rad/s), the disk stays on it: the
/// lean stays at `θ` to 1e-9 rad and the contact point on its circle to
/// 1e-9 of the radius over 10 s (3.7 turns), and the energy is kept to
/// 1e-11 relative (the rolling constraints do no work). Dop853 at 1e-13
/// errs by ~1e-12 per unit time, and this steady motion is stable, so the
/// errors grow at most linearly: 1e-9 leaves a margin of ~100 (measured:
/// the lean 7e-15, the circle 7e-13, the energy 4e-14). A wrong `Ω` would
/// show at once: the lean would oscillate about the true steady lean by
/// the difference.
#[test]
fn a_disk_rolls_round_the_circle_its_lean_spin_and_precession_say() {
    let [_, r, g] = DISK;
    let (theta, omega) = (0.5f64, -6.0f64);
    let model = disk();
    let big_omega = model.steady_precession(theta, omega);
    let (s, c) = theta.sin_cos();
    let residual =
        4.0 * g * s - 6.0 * big_omega * omega * r * c + 5.0 * big_omega.powi(2) * r * s * c;
    assert!(residual.abs() < 1e-12 * g, "the root: {residual:e}");
    let radius = r * (omega / big_omega).abs();
    let (q0, v0) = model.state(theta, 0.0, big_omega, omega);
    // The contact point starts at the origin moving along x at −r ω and
    // turning at Ω: the circle's centre is R to the left or right.
    let turning_left = (-r * omega) * big_omega > 0.0;
    let centre = Vector3::new(0.0, if turning_left { radius } else { -radius }, 0.0);
    let times: Vec<f64> = (1..=200).map(|k| 0.05 * k as f64).collect();
    let run = Dop853::new()
        .rtol(1e-13)
        .atol(1e-13)
        .integrate(&model, 0.0, q0, v0, &times)
        .unwrap();
    let energy0 = model.energy(0.0, &q0, &v0);
    let (mut worst_lean, mut worst_circle, mut worst_energy) = (0.0f64, 0.0f64, 0.0f64);
    for s in &run {
        worst_lean = worst_lean.max((s.q[3] - theta).abs());
        let contact = Vector3::new(s.q[0], s.q[1], 0.0);
        worst_circle = worst_circle.max(((contact - centre).norm() - radius).abs() / radius);
        worst_energy =
            worst_energy.max((model.energy(s.t, &s.q, &s.qdot) - energy0).abs() / energy0.abs());
    }
    let turns = (big_omega * 10.0).abs() / std::f64::consts::TAU;
    assert!(turns > 2.0, "{turns} turns");
    assert!(worst_lean < 1e-9, "the lean wandered by {worst_lean:e}");
    assert!(
        worst_circle < 1e-9,
        "the contact point left its circle by {worst_circle:e}"
    );
    assert!(worst_energy < 1e-11, "energy drifted by {worst_energy:e}");
}

/// The largest lean over 20 s of a disk rolling upright at speed `v`,
/// nudged by a lean rate of 1e-3 rad/s.
fn largest_lean(v: f64) -> f64 {
    let r = DISK[1];
    let (q0, v0) = disk().state(0.0, 1e-3, 0.0, -v / r);
    let times: Vec<f64> = (1..=400).map(|k| 0.05 * k as f64).collect();
    let run = Dop853::new()
        .rtol(1e-10)
        .atol(1e-12)
        .integrate(&disk(), 0.0, q0, v0, &times);
    // A disk that falls over ends its run lying down, where the rolling
    // model's contact breaks down: what was recorded up to then counts.
    let trajectory = match run {
        Ok(t) => t,
        Err(failure) => failure.trajectory,
    };
    trajectory.iter().map(|s| s.q[3].abs()).fold(0.0, f64::max)
}

/// Upright rolling is stable above `v² = g r / 3` and not below. About
/// upright rolling at spin `ω0` (`v = r |ω0|`), this Lagrangian linearized
/// (with SymPy, as above) gives `ψ̇ = 2 ω0 θ` and
/// `5 r θ̈ = (4 g − 12 ω0² r) θ`: a growing mode exactly when
/// `v² < g r / 3` (the classical thin-disk threshold; Neimark & Fufaev,
/// ch. 3). 10 % either side of it, `|s|² = 0.08 g / r` ≈ 2.6 /s²: above,
/// the lean oscillates at 1.6 rad/s with the nudge's amplitude over that
/// frequency, ≈ 6e-4 rad (6.2e-4 measured), bounded here by 1e-2; below,
/// it grows at 1.6 /s until the nonlinear terms take over (the disk then
/// circles, leaning, rather than falling: 0.35 rad measured), bounded below
/// by 0.1, a hundred times what it reaches when stable.
#[test]
fn upright_rolling_is_stable_above_v_squared_gr_over_3_and_not_below() {
    let [_, r, g] = DISK;
    let critical = (g * r / 3.0).sqrt();
    let above = largest_lean(1.1f64.sqrt() * critical);
    let below = largest_lean(0.9f64.sqrt() * critical);
    assert!(
        above < 1e-2,
        "above the critical speed the lean reached {above}"
    );
    assert!(
        below > 0.1,
        "below the critical speed the lean reached only {below}"
    );
}

/// A rolling ball started the way a user has it, from its orientation and
/// body rates, by `constraints::state_from_body_rates`: the centre's
/// velocity comes from the rolling constraints. It equals the hand-made
/// start of `RollingBall::state` (space rates `ω = R ω_body`) to
/// rounding: both are a few quaternion products of order-1 values, some
/// ulps each, so 1e-14; every constraint holds to the rounding the
/// integrators accept (100 ε of its terms). The runs from the two starts
/// (Dop853 at 1e-12 for 2 s, each within 1e-9 of the closed form as in
/// the model's doctest) agree to 1e-10, where two runs of the same method
/// from states a rounding apart can differ by the tolerance's order times
/// a few steps' worth of different step sizes.
#[test]
fn a_rolling_ball_started_from_its_body_rates_matches_the_hand_made_start() {
    let ball = RollingBall::new(1.0, 0.1);
    let rotation = UnitQuaternion::from_euler_angles(0.3, -0.7, 1.1);
    let (velocity, spin) = (Vector2::new(0.3, -0.2), 1.5);
    let body = rotation.inverse() * ball.angular_velocity(&velocity, spin);
    let (q0, v0) = state_from_body_rates(
        &ball,
        0.0,
        &[("x", 0.0), ("y", 0.0)],
        &[],
        ["w", "a", "b", "c"],
        &rotation,
        &body,
    )
    .expect("a unit quaternion and body rates determine the rolling state");
    let (q_hand, v_hand) = ball.state(&rotation, &velocity, spin);
    assert!((q0 - q_hand).amax() < 1e-14, "{q0} against {q_hand}");
    assert!((v0 - v_hand).amax() < 1e-14, "{v0} against {v_hand}");
    let tolerance = 100.0 * f64::EPSILON;
    assert!(ball.constraints(0.0, &q0).amax() < tolerance);
    assert!(ball.constraint_velocities(0.0, &q0, &v0).amax() < tolerance * v0.amax());
    let ends: Vec<_> = [(q0, v0), (q_hand, v_hand)]
        .into_iter()
        .map(|(q, v)| {
            let run = Dop853::new()
                .rtol(1e-12)
                .atol(1e-12)
                .integrate(&ball, 0.0, q, v, &[2.0])
                .expect("the ball rolls");
            let end = run.last().unwrap();
            (end.q, end.qdot)
        })
        .collect();
    let exact = ball.rotation_at(&rotation, &velocity, spin, 2.0);
    assert!(RollingBall::rotation(&ends[0].0).angle_to(&exact) < 1e-9);
    assert!((ends[0].0 - ends[1].0).amax() < 1e-10);
    assert!((ends[0].1 - ends[1].1).amax() < 1e-10);
    // A quaternion that is not of unit norm cannot be held on `unit`.
    let err = lagrange::constraints::consistent_start(
        &ball,
        0.0,
        &(q_hand * 1.01),
        &v_hand,
        &["w", "a", "b", "c"],
        &["w", "a", "b", "c"],
    )
    .unwrap_err();
    assert!(
        matches!(
            err,
            StartError::NotConverged {
                constraint: "unit",
                ..
            }
        ),
        "{err}"
    );
}

/// Every method that integrates `q̈` through the constraints takes a model
/// with both a singular `M` made regular by a constraint and velocity
/// constraints: a solid ball rolling on a plane, in unit quaternions
/// (`RollingBall`). Free of forces but the contact's, it rolls in a
/// straight line at constant speed with a constant angular velocity
/// `ω = (−v_y/r, v_x/r, spin)`, so its rotation is `exp(t ω) R(0)`:
/// compared as rotations (the angle between them), never as quaternions.
/// The variational integrator refuses it for its velocity constraints,
/// with a typed error before any work, and so does it the sleigh's alone
/// (a singular `M` alone it takes: `rigid_body.rs`); so do the analyses on
/// the constraint manifold.
///
/// Bounds over 1 s, `|ω|` = 3.9 rad/s: a fixed-step method of order `p` at
/// `h = 1e-3` errs by at most about `(h |ω|)^p |ω| t` on a rotation at that
/// rate, the bound used (1e-11 where rounding is the floor); measured:
/// explicit and symplectic Euler 1.6e-3 rad against 1.5e-2, implicit
/// midpoint 1.2e-6 against 5.9e-5, RK4 and Gauss–Legendre 5e-13 and below.
/// An adaptive one at 1e-8 errs by a few times the tolerance per unit
/// time, bounded by 1e-7 (Dopri5, Tsit5, Dop853, Radau5: 1.4e-9 to
/// 6.4e-9). The centre's position is tied to the rotation by the
/// constraints, so its error is `r` times the same.
#[test]
fn every_method_but_the_variational_one_takes_a_ball_rolling_in_quaternions() {
    let ball = RollingBall::new(1.0, 0.1);
    let rotation = UnitQuaternion::from_euler_angles(0.3, -0.7, 1.1);
    let (velocity, spin) = (Vector2::new(0.3, -0.2), 1.5);
    let (q0, v0) = ball.state(&rotation, &velocity, spin);
    let rate = ball.angular_velocity(&velocity, spin).norm();
    let exact = ball.rotation_at(&rotation, &velocity, spin, 1.0);
    for method in Method::ALL {
        let run = method
            .integrator(1e-3, 1e-8)
            .integrate(&ball, 0.0, q0, v0, &[1.0]);
        if method == Method::Variational {
            let error = run.unwrap_err().error;
            assert!(
                matches!(
                    error,
                    IntegrationError::InvalidInput(InvalidInput::VelocityConstraints { .. })
                ),
                "{error}"
            );
            continue;
        }
        let run = run.unwrap_or_else(|e| panic!("{method:?}: {}", e.error));
        let end = run.last().unwrap();
        let bound = if method.is_adaptive() {
            1e-7
        } else {
            ((1e-3 * rate).powi(method.order() as i32) * rate).max(1e-11)
        };
        let angle = RollingBall::rotation(&end.q).angle_to(&exact);
        assert!(
            angle < bound,
            "{method:?}: rotation off by {angle:e} rad, bound {bound:e}"
        );
        let centre = (Vector2::new(end.q[0], end.q[1]) - velocity).norm();
        assert!(
            centre < ball.r * bound + 1e-12,
            "{method:?}: centre off by {centre:e}"
        );
        assert!(
            (end.q.fixed_rows::<4>(2).norm() - 1.0).abs() < 1e-14,
            "{method:?}: |q|"
        );
    }
    // Velocity constraints alone are refused by the variational
    // integrator too (a singular `M` alone is not: `rigid_body.rs`), and
    // the manifold's linearization refuses them.
    let sleigh = sleigh();
    let (q, v) = sleigh.state(V0, W0);
    let error = Variational::new(1e-3)
        .integrate(&sleigh, 0.0, q, v, &[1.0])
        .unwrap_err()
        .error;
    assert!(
        matches!(
            error,
            IntegrationError::InvalidInput(InvalidInput::VelocityConstraints { .. })
        ),
        "{error}"
    );
    let (q, v) = sleigh.state(V0, W0);
    let error = lagrange::analysis::linearize_on_manifold(&sleigh, 0.0, &q, &v).unwrap_err();
    assert!(
        matches!(
            error,
            lagrange::analysis::AnalysisError::VelocityConstraints { .. }
        ),
        "{error}"
    );
}

/// The linearization about upright straight rolling, reduced to the lean,
/// its rate and the heading rate (`x`, `y`, the heading and the spin angle
/// are ignorable, the spin rate constant to first order), against the
/// closed form above: `θ̈ = (4g / 5r) θ − (6 ω0 / 5) ψ̇`, `ψ̈ = 2 ω0 θ̇`, so
/// `A = [[0, 1, 0], [4g/5r, 0, −6ω0/5], [0, 2ω0, 0]]`, eigenvalues `0` and
/// `±√((4g − 12 ω0² r) / 5r)`.
///
/// Bounds: the derivatives are central differences of the constrained
/// acceleration, relative error `≈ ε^(2/3)` ≈ 4e-11 times the size of the
/// second derivatives (of order `g/r`, 30 /s²): 1e-7 absolute leaves a
/// margin of about 30 (1.7e-9 measured at 0.99). The growing eigenvalue
/// at 0.99 of the critical `v² = g r / 3` is `√(0.04 g / 5r)` ≈ 0.51 /s,
/// and at 1.01 the real parts are zero: both far from the 1e-6 allowed.
#[test]
fn upright_rolling_linearized_is_the_closed_form_and_changes_stability_at_v_squared_gr_over_3() {
    let [_, r, g] = DISK;
    let model = disk();
    for ratio in [0.5, 0.99, 1.01, 2.0] {
        let v = (ratio * g * r / 3.0f64).sqrt();
        let omega0 = -v / r;
        let (q, qdot) = model.state(0.0, 0.0, 0.0, omega0);
        let lin = lagrange::analysis::linearize_steady_motion(
            &model,
            0.0,
            &q,
            &qdot,
            &["theta"],
            &["theta", "psi"],
        )
        .unwrap();
        assert_eq!(lin.states, ["theta", "dot(theta)", "dot(psi)"]);
        let expected = lagrange::nalgebra::Matrix3::new(
            0.0,
            1.0,
            0.0,
            4.0 * g / (5.0 * r),
            0.0,
            -6.0 * omega0 / 5.0,
            0.0,
            2.0 * omega0,
            0.0,
        );
        for i in 0..3 {
            for j in 0..3 {
                let off = (lin.state_matrix[(i, j)] - expected[(i, j)]).abs();
                assert!(
                    off < 1e-7,
                    "v²/(gr/3) = {ratio}: A[{i},{j}] off by {off:e}\n{}",
                    lin.state_matrix
                );
            }
        }
        let s2 = (4.0 * g - 12.0 * omega0 * omega0 * r) / (5.0 * r);
        let growth = lin
            .eigenvalues()
            .iter()
            .map(|s| s.re)
            .fold(f64::MIN, f64::max);
        if ratio < 1.0 {
            assert!(
                (growth - s2.sqrt()).abs() < 1e-6,
                "{ratio}: growth {growth}, closed form {}",
                s2.sqrt()
            );
        } else {
            assert!(growth.abs() < 1e-6, "{ratio}: stable, yet growth {growth}");
        }
    }
}

/// The sleigh running straight: its turning rate decays at `m a v0 / J`
/// (from `J ω̇ = −m a v ω`), the one state that matters; the position, the
/// heading and the forward speed drop out. Bound as above: central
/// differences of a rate of order one.
#[test]
fn the_sleigh_running_straight_linearized_damps_its_turning_at_m_a_v_over_j() {
    let [m, i, a] = SLEIGH;
    let sleigh = sleigh();
    let (q, qdot) = sleigh.state(V0, 0.0);
    let lin = lagrange::analysis::linearize_steady_motion(&sleigh, 0.0, &q, &qdot, &[], &["theta"])
        .unwrap();
    let expected = -m * a * V0 / (i + m * a * a);
    assert!(
        (lin.state_matrix[(0, 0)] - expected).abs() < 1e-8,
        "{} against {expected}",
        lin.state_matrix
    );
    // Leaving out a state that matters is an error, not a wrong answer:
    // the disk's lean rate is driven by the heading rate.
    let [_, r, g] = DISK;
    let disk = disk();
    let (q, qdot) = disk.state(0.0, 0.0, 0.0, -(g * r).sqrt() / r);
    let error =
        lagrange::analysis::linearize_steady_motion(&disk, 0.0, &q, &qdot, &["theta"], &["theta"])
            .unwrap_err();
    assert!(
        matches!(
            error,
            lagrange::analysis::AnalysisError::NotReducible { .. }
        ),
        "{error}"
    );
    // And a motion that is not steady in a kept state is refused.
    let (q, qdot) = disk.state(0.2, 0.1, 0.0, -6.0);
    let error = lagrange::analysis::linearize_steady_motion(
        &disk,
        0.0,
        &q,
        &qdot,
        &["theta"],
        &["theta", "psi"],
    )
    .unwrap_err();
    assert!(
        matches!(error, lagrange::analysis::AnalysisError::NotSteady { .. }),
        "{error}"
    );
}
