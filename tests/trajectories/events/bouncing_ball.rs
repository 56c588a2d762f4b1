//! The ball dropped from 1 m with restitution 0.9: its bounce times against
//! the closed form, and the Zeno limit where they accumulate.

use lagrange::EventRecord;
use lagrange::Method;
use lagrange::models::BouncingBall;
use lagrange::nalgebra::Vector1;
use lagrange::prelude::*;

const HEIGHT: f64 = 1.0;
const RESTITUTION: f64 = 0.9;
/// Fixed-step methods' step; the adaptive ones run at their defaults.
const H: f64 = 1e-3;

fn ball() -> BouncingBall<f64> {
    BouncingBall::new(1.0, 9.81)
}

/// Dropped from rest, watched until long after the bounces accumulate:
/// the trajectory, and how it ended if it did not reach 20 s.
fn drop(method: Method, h: f64) -> (Trajectory<f64, 1>, Option<IntegrationError<f64, 1>>) {
    let events = Events::new().with(BouncingBall::floor(RESTITUTION));
    let (q0, v0) = (Vector1::new(HEIGHT), Vector1::new(0.0));
    let run = method
        .with_step(h)
        .integrate_with_events(&ball(), 0.0, q0, v0, &[20.0], &events);
    match run {
        Ok(trajectory) => (trajectory, None),
        Err(failure) => (failure.trajectory, Some(failure.error)),
    }
}

/// Free fall is quadratic in `t`; the Euler methods are the only ones not
/// exact on it.
fn exact_on_free_fall(method: Method) -> bool {
    !matches!(method, Method::ExplicitEuler | Method::SymplecticEuler)
}

/// The worst relative error of the first 20 bounce times, and the bounces.
fn first_twenty(method: Method, h: f64) -> (f64, Vec<EventRecord<f64, 1>>) {
    let exact = ball().bounce_times(HEIGHT, RESTITUTION, 20);
    let (trajectory, _) = drop(method, h);
    let bounces = trajectory.events();
    assert!(bounces.len() >= 20, "{method:?}: {} bounces", bounces.len());
    let worst = bounces
        .iter()
        .zip(&exact)
        .map(|(bounce, t)| ((bounce.t - t) / t).abs())
        .fold(0.0, f64::max);
    (worst, bounces[..20].to_vec())
}

#[test]
fn first_twenty_bounces_match_the_closed_form() {
    println!("method             worst relative error of the first 20 bounce times");
    for method in Method::ALL {
        let (worst, bounces) = first_twenty(method, H);
        println!("{:<18} {worst:.1e}", method.id());
        for bounce in &bounces {
            // At the floor: to rounding, or to the Euler step's O(h²) in z.
            assert!(bounce.q[0].abs() < 1e-5, "{method:?}: z = {}", bounce.q[0]);
            let (_, v_after) = bounce.after.expect("a reset");
            assert_eq!(v_after[0], -RESTITUTION * bounce.qdot[0]);
        }
        if exact_on_free_fall(method) {
            // These methods reproduce a quadratic motion exactly, and so do
            // their interpolants (dense output of order 3 or more, or the
            // cubic Hermite one), so the times carry only rounding and the
            // time tolerance, 4 ε t: a few 1e-14 over 20 bounces, each of
            // whose velocity comes from the previous one.
            assert!(worst < 1e-12, "{method:?}: {worst:e}");
        } else {
            // First order: the errors (2.9e-2 for explicit Euler, which
            // gains energy on every flight) halve with h.
            let (finer, _) = first_twenty(method, H / 2.0);
            let ratio = worst / finer;
            println!("{:<18} {finer:.1e} at h / 2: ratio {ratio:.2}", "");
            assert!(
                (1.7..2.3).contains(&ratio),
                "{method:?}: {worst:e} / {finer:e}"
            );
        }
    }
}

#[test]
fn the_bounces_accumulate_into_a_zeno_stop_near_the_rest_time() {
    let ball = ball();
    let rest = ball.rest_time(HEIGHT, RESTITUTION);
    println!("method             bounces  t_zeno               t_inf - t_zeno  min separation");
    // Not the Euler methods: explicit Euler gains energy on each flight
    // (its z overshoots by g h t / 2), and at h = 1e-3 the gain balances
    // the restitution's loss at flights of ~19 steps: it bounces forever,
    // a fixed cycle, not a Zeno run. Symplectic Euler is first order too.
    for method in Method::ALL.into_iter().filter(|&m| exact_on_free_fall(m)) {
        let (trajectory, error) = drop(method, H);
        let Some(IntegrationError::Zeno {
            t,
            gaps,
            min_separation,
            q,
            ..
        }) = error
        else {
            panic!("{method:?}: {error:?}");
        };
        let bounces = trajectory.events().len();
        println!(
            "{:<18} {bounces:>7}  {t:.15}  {:.3e}       {min_separation:.1e}",
            method.id(),
            rest - t
        );
        assert_eq!(gaps, 3);
        assert!(q[0].abs() < 1e-6, "{method:?}: z = {}", q[0]);
        // The separation: 1000 time tolerances (4 ε t, t ≈ 8.6) for the
        // adaptive methods, four steps for the fixed-step ones.
        let expected = if method.is_adaptive() {
            4000.0 * f64::EPSILON * t
        } else {
            4.0 * H
        };
        assert!(
            (min_separation - expected).abs() <= 1e-12 * expected,
            "{method:?}"
        );
        // The gaps shrink by e: after a gap δ shorter than the separation,
        // the bounces left take Σ_{j≥1} δ eʲ = δ e / (1 − e) = 9 δ, so the
        // stop comes at most 9 separations before t∞, and after it but
        // for the bounce times' own errors (rounding, a few 1e-12 over the
        // ~245 bounces).
        let slack = 1e-11;
        let before_rest = rest - t;
        assert!(
            before_rest > -slack && before_rest < 9.0 * min_separation + slack,
            "{method:?}: t∞ − t = {before_rest:e}"
        );
        // No sample after the stop: the only one asked for is at 20 s.
        assert!(trajectory.is_empty());
    }
}
