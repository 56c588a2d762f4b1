//! The heavy symmetric top, twice: in unit quaternions
//! (`lagrange::models::HeavyTop`: no chart, `M` regular only on `|q| = 1`) and in Euler angles (z–x–z: precession `φ`,
//! nutation `θ`, spin `ψ`), which lock at the pole `θ = 0` where `φ` and
//! `ψ` turn about the same axis.
//!
//! Pivot at the origin, `z` up, mass centre at `l` along the symmetry axis,
//! moments `A` (about the pivot, across the axis) and `C` (along it). Its
//! invariants are the energy, the angular momentum about the vertical
//! `L_z = p_φ` and about the symmetry axis `L_3 = C ω3 = p_ψ` (Goldstein,
//! Classical Mechanics, §5.7).

use lagrange::models::{EulerTop, HeavyTop, quaternion};
use lagrange::nalgebra::{SVector, UnitQuaternion, Vector3, Vector4};
use lagrange::prelude::*;

/// `A`, `C`, `m`, `g`, `l`: a top a little longer than wide.
const TOP: [f64; 5] = [1.0, 0.5, 1.0, 9.81, 0.2];

fn quaternion_top() -> HeavyTop {
    let [a, c, m, g, l] = TOP;
    HeavyTop::new(a, c, m, g, l)
}

fn euler_top() -> EulerTop {
    let [a, c, m, g, l] = TOP;
    EulerTop::new(a, c, m, g, l)
}

/// The rotation of z–x–z Euler angles: `R_z(φ) R_x(θ) R_z(ψ)`.
fn rotation(phi: f64, theta: f64, psi: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::z_axis(), phi)
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), theta)
        * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), psi)
}

/// The body rates of z–x–z Euler angles and their rates.
fn body_rates(e: &SVector<f64, 3>, rates: &SVector<f64, 3>) -> Vector3<f64> {
    let (theta, psi) = (e[1], e[2]);
    let (phid, thetad, psid) = (rates[0], rates[1], rates[2]);
    Vector3::new(
        phid * theta.sin() * psi.sin() + thetad * psi.cos(),
        phid * theta.sin() * psi.cos() - thetad * psi.sin(),
        phid * theta.cos() + psid,
    )
}

/// The quaternion state of an Euler-angle state.
fn quaternion_state(e: &SVector<f64, 3>, rates: &SVector<f64, 3>) -> (Vector4<f64>, Vector4<f64>) {
    quaternion::state(&rotation(e[0], e[1], e[2]), &body_rates(e, rates))
}

/// Away from the pole the two models are one motion: started from the same
/// state (tilted by 1 rad, spinning at 20 rad/s, precessing slowly), their
/// rotations agree to 1e-10 rad every 0.05 s for 5 s, compared as
/// rotations (the angle of `R_euler⁻¹ R_quaternion`), never as
/// quaternions. Dop853 at rtol = atol = 1e-13 errs by ~1e-12 over these
/// few nutation periods in each model (a regular motion: errors grow
/// linearly), so 1e-10 holds with a margin of about 100.
#[test]
fn the_quaternion_top_is_the_euler_angle_top_away_from_the_pole() {
    let e0 = SVector::<f64, 3>::new(0.0, 1.0, 0.0);
    let rates0 = SVector::<f64, 3>::new(0.3, 0.0, 20.0);
    let (q0, v0) = quaternion_state(&e0, &rates0);
    let times: Vec<f64> = (1..=100).map(|k| 0.05 * k as f64).collect();
    let method = Dop853::new().rtol(1e-13).atol(1e-13);
    let euler = method
        .integrate(&euler_top(), 0.0, e0, rates0, &times)
        .unwrap();
    let quaternion = method
        .integrate(&quaternion_top(), 0.0, q0, v0, &times)
        .unwrap();
    let mut worst = 0.0f64;
    let mut lowest_theta = f64::INFINITY;
    for (e, s) in euler.iter().zip(&quaternion) {
        assert_eq!(e.t, s.t);
        lowest_theta = lowest_theta.min(e.q[1]);
        let re = rotation(e.q[0], e.q[1], e.q[2]);
        let rq = quaternion::rotation(&s.q);
        worst = worst.max((re.inverse() * rq).angle());
    }
    assert!(
        lowest_theta > 0.5,
        "stays away from the pole (θ ≥ {lowest_theta})"
    );
    assert!(worst < 1e-10, "the rotations differ by {worst:e} rad");
}

/// The start of the motion through the pole: tilted by 0.5 rad, spinning at
/// `ω3 = 5` with `L_z = L_3` (`φ̇ = p (1 − cos θ) / (A sin² θ)`, `p = C ω3`),
/// and a nutation rate of −2 rad/s: in Euler angles and in quaternions, and
/// `p`.
#[allow(clippy::type_complexity)]
fn through_the_pole() -> (
    (SVector<f64, 3>, SVector<f64, 3>),
    (Vector4<f64>, Vector4<f64>),
    f64,
) {
    let [a, c, ..] = TOP;
    let theta0 = 0.5f64;
    let omega3 = 5.0;
    let p = c * omega3;
    let phid = p * (1.0 - theta0.cos()) / (a * theta0.sin().powi(2));
    let e0 = SVector::<f64, 3>::new(0.0, theta0, 0.0);
    let rates0 = SVector::<f64, 3>::new(phid, -2.0, omega3 - phid * theta0.cos());
    ((e0, rates0), quaternion_state(&e0, &rates0), p)
}

/// Through the pole: with `L_z = L_3` the symmetry axis swings straight
/// through the vertical (`θ = 0`), where `φ̇` and `ψ̇` of the Euler angles
/// are not determined by the motion alone (`M` singular there). Started
/// at `θ = 0.5` rad moving towards the vertical at 2 rad/s with spin
/// `ω3 = 5` rad/s and `φ̇` chosen so that `p_φ = p_ψ`.
///
/// The quaternion top passes through it, again and again over 10 s, its
/// energy, `L_z` and `L_3` kept to 1e-9 relative (Dop853 at 1e-12: a few
/// hundred steps, each erring by ~1e-13, growing linearly), and `|q| = 1`
/// to rounding. The Euler-angle top, from the same state, is recorded as it
/// fails: at the first pass (t ≈ 0.25 s) its `M` is nearly singular and
/// its `φ̇`, `ψ̇` swing wildly, and Dop853 spends its whole budget of
/// 100 000 steps there (`TooManySteps` at θ ≈ 6e-7 rad, measured), the
/// samples before returned.
#[test]
fn the_quaternion_top_swings_through_the_pole_where_euler_angles_fail() {
    let ((e0, rates0), (q0, v0), p) = through_the_pole();
    let times: Vec<f64> = (1..=1000).map(|k| 0.01 * k as f64).collect();

    let top = quaternion_top();
    let start = top.invariants(&q0, &v0);
    assert!(
        (start[1] - start[2]).abs() < 1e-14 * p,
        "L_z = L_3: {start:?}"
    );
    let run = Dop853::new()
        .rtol(1e-12)
        .atol(1e-12)
        .integrate(&top, 0.0, q0, v0, &times)
        .unwrap();
    let mut worst = [0.0f64; 3];
    let (mut highest, mut passes, mut was_near) = (0.0f64, 0, false);
    for s in &run {
        let now = top.invariants(&s.q, &s.qdot);
        for k in 0..3 {
            worst[k] = worst[k].max((now[k] - start[k]).abs() / start[k].abs());
        }
        assert!((s.q.norm() - 1.0).abs() < 4.0 * f64::EPSILON);
        let axis = HeavyTop::axis(&s.q);
        highest = highest.max(axis[2]);
        let near = axis[2] > 0.999;
        passes += (near && !was_near) as usize;
        was_near = near;
    }
    assert!(
        worst.iter().all(|&w| w < 1e-9),
        "invariants drifted: {worst:?}"
    );
    assert!(
        highest > 1.0 - 1e-6,
        "the axis reached within {:e} of the vertical",
        1.0 - highest
    );
    assert!(passes >= 3, "through the pole {passes} times");

    let euler =
        Dop853::new()
            .rtol(1e-12)
            .atol(1e-12)
            .integrate(&euler_top(), 0.0, e0, rates0, &times);
    let failure = euler.expect_err("the Euler-angle top should fail at the pole");
    let reached = failure.trajectory.last().map_or(0.0, |s| s.t);
    assert!(reached < 1.0, "stopped at the first pass, t = {reached}");
    assert!(
        matches!(
            failure.error,
            IntegrationError::TooManySteps { .. } | IntegrationError::SingularMassMatrix { .. }
        ),
        "{}",
        failure.error
    );
}

/// The largest relative errors of the energy, `L_z` and `L_3` of the
/// variational integrator at step `h` on the motion through the pole
/// (10 s), and the energy's over the first 5 s alone.
fn variational_through_the_pole(h: f64) -> ([f64; 3], f64) {
    let (_, (q0, v0), _) = through_the_pole();
    let times: Vec<f64> = (1..=1000).map(|k| 0.01 * k as f64).collect();
    let top = quaternion_top();
    let start = top.invariants(&q0, &v0);
    let run = Variational::new(h)
        .integrate(&top, 0.0, q0, v0, &times)
        .unwrap_or_else(|e| panic!("h = {h}: {}", e.error));
    let mut worst = [0.0f64; 3];
    let mut first_half = 0.0f64;
    for s in run.iter() {
        let now = top.invariants(&s.q, &s.qdot);
        for k in 0..3 {
            worst[k] = worst[k].max((now[k] - start[k]).abs() / start[k].abs());
        }
        if s.t <= 5.0 {
            first_half = worst[0];
        }
    }
    (worst, first_half)
}

/// The top through the pole by the variational integrator at fixed steps
/// h = 0.002, 0.001, 0.0005 over 10 s (5,000 to 20,000 steps), in
/// quaternions (`M` regular only on `|q| = 1`). `L_z` and `L_3` are the
/// momenta of symmetries (rotations about the vertical in space, about the
/// axis in the body): kept by the discrete Noether theorem to the Newton
/// tolerance, 1e-12 relative (3e-14 to 6e-14 measured). The energy error
/// is bounded (a symplectic step: over the second 5 s no larger than twice
/// its largest over the first, no drift) and second order: halving `h`
/// divides its largest value by 4 (3.5 to 4.5 allowed; 4.00 measured,
/// while from h = 0.004 the ratio is still 2.8).
#[test]
fn the_variational_integrator_keeps_the_tops_momenta_and_its_energy_at_second_order() {
    let results: Vec<(f64, ([f64; 3], f64))> = [0.002, 0.001, 0.0005]
        .iter()
        .map(|&h| (h, variational_through_the_pole(h)))
        .collect();
    for (h, ([energy, lz, l3], first_half)) in &results {
        println!(
            "h = {h}: energy {energy:.3e} ({first_half:.3e} over the first 5 s), L_z {lz:.1e}, L_3 {l3:.1e}"
        );
        assert!(
            *lz < 1e-12 && *l3 < 1e-12,
            "h = {h}: L_z {lz:e}, L_3 {l3:e}"
        );
        assert!(
            *energy <= 2.0 * first_half,
            "h = {h}: the energy error grows, {first_half:e} → {energy:e}"
        );
    }
    for pair in results.windows(2) {
        let ratio = pair[0].1.0[0] / pair[1].1.0[0];
        assert!(
            (3.5..4.5).contains(&ratio),
            "energy error ratio {ratio} between h = {} and {}",
            pair[0].0,
            pair[1].0
        );
    }
}
