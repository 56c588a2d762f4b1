//! The two limits the extremes approach: the light outer bob as a
//! pendulum on a moving support, the heavy one as a single pendulum.

use super::{END, G, chain, heavy_start, light_start, max_distance, reference, sample_times};
use lagrange::models::Pendulum;
use lagrange::nalgebra::{Vector1, Vector2};
use lagrange::prelude::*;

lagrangian! {
    /// The limit `m2/m1 → 0` of the double pendulum: `θ1` a simple pendulum
    /// of length `l1`, unaffected by the outer bob; `θ2` a pendulum of length
    /// `l2` hanging from the moving inner bob (its Euler–Lagrange equation
    /// divided by `m2`, with `θ̈1 = −(g/l1) sin θ1` substituted).
    pub struct LightOuterLimit {
        coordinates: theta1, theta2;
        parameters: l1, l2, g;
        kinetic: (dot(theta1)^2 + dot(theta2)^2)/2;
        potential: -g/l1*cos(theta1);
        forces: theta2 = (g*cos(theta1 - theta2)*sin(theta1)
                          + l1*sin(theta1 - theta2)*dot(theta1)^2 - g*sin(theta2))/l2;
    }
}

/// `m2/m1 = 10⁻⁶`: the inner link is a simple pendulum of length `l1` and
/// the outer one a pendulum on a moving support ([`LightOuterLimit`]), up
/// to `O(μ)`, `μ = m2/(m1 + m2)`: the outer bob's reaction enters the inner
/// equation as `θ̈1 = −(g/l1) sin θ1 − μ (l2/l1)(cos Δ θ̈2 + sin Δ θ̇2²)`.
///
/// Two checks of that claim. The inner deviation is bounded by the forcing
/// it gets: a linear oscillator of frequency at least
/// `ω_min = √(g/l1 · cos θ_max)` driven by at most `μ F` drifts by at most
/// `μ F t / ω_min` (Duhamel's integral), doubled for the frequency's
/// variation along the swing. And the whole state's deviation is first
/// order in `μ`: from `μ = 10⁻⁶` to `10⁻⁵` it grows by 10 within 1 %
/// (the `O(μ²)` term is 10⁻⁵ of it; the references' errors 10⁻⁵).
#[test]
fn light_outer_bob_leaves_the_inner_link_a_simple_pendulum() {
    let (q0, v0) = light_start();
    let limit = Dop853::new()
        .rtol(1e-13)
        .atol(1e-13)
        .integrate(
            &LightOuterLimit::new(1.0, 1.0, G),
            0.0,
            q0,
            v0,
            &sample_times(),
        )
        .unwrap();
    // The limit's θ1 is the simple pendulum of length l1 itself.
    let simple = Dop853::new()
        .rtol(1e-13)
        .atol(1e-13)
        .integrate(
            &Pendulum::new(1.0, 1.0, G),
            0.0,
            Vector1::new(q0[0]),
            Vector1::new(v0[0]),
            &sample_times(),
        )
        .unwrap();
    for (a, b) in limit.iter().zip(simple.iter()) {
        assert!((a.q[0] - b.q[0]).abs() < 1e-10);
    }

    let deviation = |ratio: f64| {
        let model = chain(1.0, ratio);
        let run = reference(&model, (q0, v0));
        let mu = ratio / (1.0 + ratio);
        let inner = run
            .iter()
            .zip(limit.iter())
            .map(|(s, l)| (s.q[0] - l.q[0]).abs().max((s.qdot[0] - l.qdot[0]).abs()))
            .fold(0.0, f64::max);
        (mu, inner, max_distance(&run, &limit))
    };
    let (mu, inner, whole) = deviation(1e-6);
    let (mu10, _, whole10) = deviation(1e-5);

    // The forcing μ F of the inner link, along the limit motion.
    let model = LightOuterLimit::new(1.0, 1.0, G);
    let forcing = limit
        .iter()
        .map(|s| {
            let qdd = model.forcing(s.t, &s.q, &s.qdot); // M = I
            let d = s.q[0] - s.q[1];
            (d.cos() * qdd[1] + d.sin() * s.qdot[1].powi(2)).abs()
        })
        .fold(0.0, f64::max);
    let omega_min = (G * q0[0].cos()).sqrt();
    let bound = 2.0 * mu * forcing * END / omega_min;
    let linearity = (whole10 / mu10) / (whole / mu);
    println!(
        "light outer bob (m2/m1 = 1e-6): θ1 deviates from the simple pendulum by {inner:.2e} \
         = {:.2} μ (Duhamel bound {bound:.2e}); whole state {whole:.2e} = {:.2} μ; \
         deviation(1e-5)/deviation(1e-6) = {:.4} × 10",
        inner / mu,
        whole / mu,
        linearity
    );
    assert!(inner <= bound, "θ1 deviation {inner:e} > {bound:e}");
    assert!(
        (linearity - 1.0).abs() < 0.01,
        "deviation not first order in μ: {linearity}"
    );
}

/// `m2/m1 = 10⁶`: the chain stays straight and swings as a simple pendulum
/// of length `l1 + l2`. The light joint sags by an angle `~m1/m2` (its
/// weight against the tension), the chain's inertia and effective length
/// differ by relative `O(m1/m2)`, and the straight release starts a kink
/// vibration of amplitude `O(m1/m2)`; so both angles follow the pendulum to
/// `O(m1/m2)`. The angular *velocities* follow it only to `O(√(m1/m2))`:
/// the kink's frequency is `O(√(m2/m1))`, its rate amplitude the product.
/// Checked by the scaling from `m1/m2 = 10⁻⁶` to `10⁻⁵`: the angle deviation
/// grows ×10 and the velocity deviation ×√10, each within 5 % (the maxima
/// are read off samples at unrelated phases of the vibration, whose
/// frequency changes by √10 between the runs), and the angle deviation is
/// `O(1) · m1/m2` (below 10 m1/m2).
#[test]
fn heavy_outer_bob_makes_the_chain_a_pendulum_of_length_l1_plus_l2() {
    let (q0, v0) = heavy_start();
    let straight = Dop853::new()
        .rtol(1e-13)
        .atol(1e-13)
        .integrate(
            &Pendulum::new(1.0, 2.0, G),
            0.0,
            Vector1::new(q0[0]),
            Vector1::new(v0[0]),
            &sample_times(),
        )
        .unwrap();
    let worst = |chain: &[Vector2<f64>], single: &[Vector1<f64>]| {
        chain
            .iter()
            .zip(single)
            .map(|(c, p)| (c - Vector2::repeat(p[0])).amax())
            .fold(0.0, f64::max)
    };
    let deviation = |light: f64| {
        let run = reference(&chain(light, 1.0), (q0, v0));
        let angles = worst(run.positions(), straight.positions());
        let rates = worst(run.velocities(), straight.velocities());
        let kink = run
            .positions()
            .iter()
            .map(|q| (q[0] - q[1]).abs())
            .fold(0.0, f64::max);
        (angles, rates, kink, run.stats())
    };
    let (angles, rates, kink, stats) = deviation(1e-6);
    let (angles10, rates10, _, _) = deviation(1e-5);
    let angle_scaling = angles10 / angles / 10.0;
    let rate_scaling = rates10 / rates / 10f64.sqrt();
    println!(
        "heavy outer bob (m2/m1 = 1e6): angles deviate from the pendulum of length l1 + l2 by \
         {angles:.2e} = {:.2} m1/m2 (kink up to {kink:.1e}), rates by {rates:.2e} = {:.2} \
         √(m1/m2); from m1/m2 = 1e-6 to 1e-5 they grow {angle_scaling:.3} × 10 and \
         {rate_scaling:.3} × √10; the reference needed {} steps ({} rejected) for 5 s",
        angles / 1e-6,
        rates / 1e-3,
        stats.steps_accepted,
        stats.steps_rejected
    );
    assert!(
        (angle_scaling - 1.0).abs() < 0.05,
        "angle deviation not first order in m1/m2: {angle_scaling}"
    );
    assert!(
        (rate_scaling - 1.0).abs() < 0.05,
        "rate deviation not of order √(m1/m2): {rate_scaling}"
    );
    assert!(angles < 10.0 * 1e-6, "angle deviation {angles:e}");
}
