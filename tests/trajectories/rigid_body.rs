//! A rigid body in unit quaternions (`lagrange::models::FreeBody`), whose
//! mass matrix is singular by itself and regular on the rates `|q| = 1`
//! allows: the Dzhanibekov effect against Euler's closed form.
//!
//! Torque-free, principal moments `I1 < I2 < I3`, energy `E` and angular
//! momentum `M` with `M² > 2 E I2`: the body rates are (Landau–Lifshitz,
//! Mechanics, §37)
//!
//! ```text
//! Ω1 = A1 cn τ,  Ω2 = A2 sn τ,  Ω3 = A3 dn τ,   τ = λ t,
//! A1² = (2E I3 − M²) / (I1 (I3 − I1)),  A2² = (2E I3 − M²) / (I2 (I3 − I2)),
//! A3² = (M² − 2E I1) / (I3 (I3 − I1)),  λ² = (I3 − I2)(M² − 2E I1) / (I1 I2 I3),
//! k² = (I2 − I1)(2E I3 − M²) / ((I3 − I2)(M² − 2E I1)),
//! ```
//!
//! for a start at `τ = 0`: `Ω2 = 0` and `Ω1, Ω3 > 0` (so that `Ω̇2 > 0`).
//! The rates come back after `4K(k)/λ`, and `Ω2`, the spin about the
//! intermediate axis, reverses (the body flips) every `2K(k)/λ`.

use crate::support::elliptic::jacobi;
use lagrange::models::{FreeBody, quaternion};
use lagrange::nalgebra::{SVector, UnitQuaternion, Vector3};
use lagrange::prelude::*;

/// Principal moments, and the start: rates `(1.7, 0, 1)`, so that
/// `M² − 2 E I2 = 0.11`, near the separatrix of the intermediate axis
/// (`k = 0.98`): the body spins about its middle axis for most of each
/// half-period and flips in about one second.
const INERTIA: [f64; 3] = [1.0, 2.0, 3.0];
const OMEGA0: [f64; 3] = [1.7, 0.0, 1.0];

struct ClosedForm {
    amplitudes: [f64; 3],
    lambda: f64,
    k: f64,
    kp: f64,
}

impl ClosedForm {
    fn new() -> Self {
        let [i1, i2, i3] = INERTIA;
        let [w1, w2, w3] = OMEGA0;
        let two_e = i1 * w1 * w1 + i2 * w2 * w2 + i3 * w3 * w3;
        let m2 = (i1 * w1).powi(2) + (i2 * w2).powi(2) + (i3 * w3).powi(2);
        let (upper, lower) = (two_e * i3 - m2, m2 - two_e * i1);
        let k2 = (i2 - i1) * upper / ((i3 - i2) * lower);
        Self {
            amplitudes: [
                (upper / (i1 * (i3 - i1))).sqrt(),
                (upper / (i2 * (i3 - i2))).sqrt(),
                (lower / (i3 * (i3 - i1))).sqrt(),
            ],
            lambda: ((i3 - i2) * lower / (i1 * i2 * i3)).sqrt(),
            k: k2.sqrt(),
            kp: (1.0 - k2).sqrt(),
        }
    }

    fn rates(&self, t: f64) -> Vector3<f64> {
        let j = jacobi(self.lambda * t, self.k, self.kp);
        let [a1, a2, a3] = self.amplitudes;
        Vector3::new(a1 * j.cn, a2 * j.sn, a3 * j.dn)
    }

    /// `2K(k)/λ`: the time between flips.
    fn half_period(&self) -> f64 {
        2.0 * jacobi(0.0, self.k, self.kp).k_complete / self.lambda
    }
}

fn body() -> FreeBody {
    FreeBody::new(INERTIA[0], INERTIA[1], INERTIA[2])
}

/// A generic starting orientation: the closed form is about the body's
/// rates, which do not depend on it.
fn start() -> (SVector<f64, 4>, SVector<f64, 4>) {
    let rotation = UnitQuaternion::from_euler_angles(0.3, -0.7, 1.1);
    quaternion::state(&rotation, &Vector3::from(OMEGA0))
}

/// Dop853 at rtol = atol = 1e-14 over ten flips (≈ 62 s), with the
/// default drift control (the state projected onto `|q| = 1` and its
/// tangent after every step).
fn run(times: &[f64], events: &Events<f64, 4>) -> Trajectory<f64, 4> {
    let (q0, v0) = start();
    Dop853::new()
        .rtol(1e-14)
        .atol(1e-14)
        .integrate_with_events(&body(), 0.0, q0, v0, times, events)
        .unwrap()
}

/// The rates against the closed form to 1e-9 relative (of `|Ω|`), every
/// 0.05 s over ten flips; `|q| = 1` to rounding, and the angular momentum
/// in space (a rotation applied to `I Ω`, so the same for `q` and `−q`)
/// constant to 1e-9 relative.
///
/// Bounds: the error is a phase error, growing linearly: a perturbation of
/// the rates near the separatrix grows during each flip and shrinks back,
/// staying within about `1/k'² ≈ 27` of its size, and Dop853 at 1e-14
/// adds about the tolerance per unit time, so the global error is about
/// `1e-14 · 27 · 61 ≈ 2e-11` at the end (3e-11 measured); 1e-9 leaves a
/// margin of 30. The momentum errs by the same local errors without the
/// phase's growth (5e-13 measured). `|q| − 1` is what the projection
/// leaves: a few rounding errors of the four squares, 4 ε ≈ 1e-15.
#[test]
fn an_asymmetric_body_near_its_intermediate_axis_flips_as_euler_says() {
    let exact = ClosedForm::new();
    let end = 10.0 * exact.half_period();
    let times: Vec<f64> = (1..)
        .map(|k| 0.05 * k as f64)
        .take_while(|&t| t <= end)
        .collect();
    let trajectory = run(&times, &Events::new());
    let body = body();
    let (q0, v0) = start();
    let momentum0 = body.angular_momentum(&q0, &v0);
    let scale = Vector3::from(OMEGA0).norm();
    let (mut worst_rate, mut worst_norm, mut worst_momentum) = (0.0f64, 0.0f64, 0.0f64);
    for s in &trajectory {
        let rates = quaternion::body_rates(&s.q, &s.qdot);
        worst_rate = worst_rate.max((rates - exact.rates(s.t)).norm() / scale);
        worst_norm = worst_norm.max((s.q.norm() - 1.0).abs());
        let momentum = body.angular_momentum(&s.q, &s.qdot);
        worst_momentum = worst_momentum.max((momentum - momentum0).norm() / momentum0.norm());
    }
    assert_eq!(trajectory.len(), times.len());
    assert!(
        worst_rate < 1e-9,
        "body rates off the closed form by {worst_rate:e}"
    );
    assert!(worst_norm < 4.0 * f64::EPSILON, "|q| − 1 = {worst_norm:e}");
    assert!(
        worst_momentum < 1e-9,
        "angular momentum drifted by {worst_momentum:e}"
    );
}

/// Each reversal of `Ω2` located as an event, at `n · 2K/λ` to 1e-9
/// relative, and the rates back at their start after each `4K/λ`.
///
/// The event time errs by the state's error over `|Ω̇2|` there, which is
/// largest mid-flip (about `A2 λ` ≈ 1.7 /s²): ~2e-11 s at the end (see the
/// test above), plus the location tolerance (a few ulps of `t`), so 1e-9
/// relative holds with a wide margin (6e-13 measured).
#[test]
fn the_body_flips_every_2k_over_lambda_and_its_rates_return_every_4k() {
    let exact = ClosedForm::new();
    let half = exact.half_period();
    let flips = 10;
    let end = (flips as f64 + 0.5) * half;
    let omega2 = Event::new("flip", |_t, q: &SVector<f64, 4>, qdot: &SVector<f64, 4>| {
        quaternion::body_rates(q, qdot)[1]
    });
    let trajectory = run(&[end], &Events::new().with(omega2));
    let crossings: Vec<_> = trajectory.events().iter().collect();
    assert_eq!(crossings.len(), flips, "one reversal of Ω2 per half-period");
    for (n, e) in crossings.iter().enumerate() {
        let expected = (n + 1) as f64 * half;
        assert!(
            (e.t - expected).abs() < 1e-9 * expected,
            "flip {n}: t = {}, closed form {expected} (off by {:e})",
            e.t,
            e.t - expected
        );
        if n % 2 == 1 {
            // After a whole period 4K/λ: the rates of the start.
            let rates = quaternion::body_rates(&e.q, &e.qdot);
            let off = (rates - Vector3::from(OMEGA0)).norm() / Vector3::from(OMEGA0).norm();
            assert!(
                off < 1e-9,
                "rates after period {}: off by {off:e}",
                n / 2 + 1
            );
        }
    }
}

/// The largest energy error, the largest drift of the angular momentum in
/// space (relative), the largest `||q| − 1|` and the flip times' largest
/// error against the closed form, of the variational integrator at step
/// `h` over ten flips (61.2 s).
fn variational(h: f64) -> (f64, f64, f64, f64) {
    let exact = ClosedForm::new();
    let half = exact.half_period();
    let body = body();
    let (q0, v0) = start();
    let omega2 = Event::new("flip", |_t, q: &SVector<f64, 4>, qdot: &SVector<f64, 4>| {
        quaternion::body_rates(q, qdot)[1]
    });
    let times: Vec<f64> = (1..=612).map(|k| 0.1 * k as f64).collect();
    let run = Variational::new(h)
        .integrate_with_events(&body, 0.0, q0, v0, &times, &Events::new().with(omega2))
        .unwrap_or_else(|e| panic!("h = {h}: {}", e.error));
    let energy = |q: &SVector<f64, 4>, v: &SVector<f64, 4>| body.kinetic_energy(0.0, q, v);
    let (e0, l0) = (energy(&q0, &v0), body.angular_momentum(&q0, &v0));
    let (mut de, mut dl, mut unit) = (0.0f64, 0.0f64, 0.0f64);
    for s in run.iter() {
        de = de.max((energy(&s.q, &s.qdot) - e0).abs() / e0);
        dl = dl.max((body.angular_momentum(&s.q, &s.qdot) - l0).norm() / l0.norm());
        unit = unit.max((s.q.norm() - 1.0).abs());
    }
    let flips = run
        .events()
        .iter()
        .enumerate()
        .map(|(n, e)| (e.t - (n + 1) as f64 * half).abs())
        .fold(0.0, f64::max);
    assert_eq!(run.events().len(), 10, "h = {h}: ten flips");
    (de, dl, unit, flips)
}

/// The tumbling body by a symplectic method at a fixed step: the
/// variational integrator (midpoint rule, RATTLE on `|q| = 1`) at
/// h = 0.02, 0.01 and 0.005 over ten flips (61.2 s), 3,060 to 12,240
/// steps. The angular momentum in space is the momentum of a symmetry
/// (rotations of space), kept by the discrete Noether theorem to the
/// Newton tolerance: 1e-12 relative, a few hundred roundings (1.6e-14 to
/// 2.6e-14 measured). The energy error is bounded, 1e-12 here: it stays at
/// rounding on this torque-free body (2.6e-14 measured at every `h`), so
/// its order in `h` is checked on the heavy top instead
/// (`heavy_top.rs`). `|q| = 1` to the constraint's Newton tolerance
/// (1e-14). The flips come at Euler's times within the method's phase
/// error, second order: halving `h` divides it by 4 (3.5 to 4.5 allowed).
#[test]
fn the_variational_integrator_keeps_the_angular_momentum_and_flips_at_second_order() {
    let results: Vec<(f64, (f64, f64, f64, f64))> = [0.02, 0.01, 0.005]
        .iter()
        .map(|&h| (h, variational(h)))
        .collect();
    for &(h, (de, dl, unit, flips)) in &results {
        println!(
            "h = {h}: energy error {de:.2e}, angular momentum {dl:.1e}, ||q| − 1| {unit:.1e}, flip times off by {flips:.2e} s"
        );
        assert!(dl < 1e-12, "h = {h}: angular momentum drifts by {dl:e}");
        assert!(de < 1e-12, "h = {h}: energy off by {de:e}");
        assert!(unit < 1e-14, "h = {h}: |q| off by {unit:e}");
    }
    for pair in results.windows(2) {
        let phase = pair[0].1.3 / pair[1].1.3;
        assert!(
            (3.5..4.5).contains(&phase),
            "flip time error ratio {phase} between h = {} and {}",
            pair[0].0,
            pair[1].0
        );
    }
}
