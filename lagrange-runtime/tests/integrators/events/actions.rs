//! What each action does to a run, for every method: a recorded event
//! leaves the run untouched, a stop ends it, a reset restarts it.

use std::f64::consts::PI;

use lagrange::Method;
use lagrange::models::{CartesianPendulum, Oscillator, Pendulum};
use lagrange_runtime::nalgebra::{Vector1, Vector2};
use lagrange_runtime::prelude::*;

fn spring() -> Oscillator<f64> {
    Oscillator::new(1.0, 1.0, 0.0)
}

fn x(_: f64, q: &Vector1<f64>, _: &Vector1<f64>) -> f64 {
    q[0]
}

/// `x = cos t`, from x = 1 at rest.
fn start() -> (Vector1<f64>, Vector1<f64>) {
    (Vector1::new(1.0), Vector1::new(0.0))
}

fn every_tenth_to(end: f64) -> Vec<f64> {
    (0..=(end * 10.0).round() as usize)
        .map(|i| 0.1 * i as f64)
        .collect()
}

/// The methods at their everyday settings: fixed steps of 0.01, adaptive
/// at 1e-10.
fn method(method: Method) -> lagrange::AnyIntegrator<f64> {
    method.integrator(0.01, 1e-10)
}

#[test]
fn a_recorded_event_leaves_samples_and_steps_unchanged() {
    let times = every_tenth_to(10.0);
    let (q0, v0) = start();
    for m in Method::ALL {
        let plain = method(m).integrate(&spring(), 0.0, q0, v0, &times).unwrap();
        let events = Events::new().with(Event::new("x = 0", x));
        let watched = method(m)
            .integrate_with_events(&spring(), 0.0, q0, v0, &times, &events)
            .unwrap();
        // Samples to the bit, and the steps: only the evaluations grow.
        assert_eq!(plain.positions(), watched.positions(), "{m:?}");
        assert_eq!(plain.velocities(), watched.velocities(), "{m:?}");
        assert_eq!(
            plain.stats().steps_accepted,
            watched.stats().steps_accepted,
            "{m:?}"
        );
        assert_eq!(plain.stats().event_evals, 0);
        assert!(watched.stats().event_evals > watched.stats().steps_accepted);
        // The zeros π/2 + kπ before t = 10: three; Euler's O(h) phase
        // error over 10 s is ~0.05, the others' far less.
        let zeros = watched.events();
        assert_eq!(zeros.len(), 3, "{m:?}");
        for (k, zero) in zeros.iter().enumerate() {
            let exact = PI / 2.0 + k as f64 * PI;
            assert!((zero.t - exact).abs() < 0.1, "{m:?}: {}", zero.t);
            assert!(zero.after.is_none());
        }
        assert!(watched.stopped().is_none());
    }
}

#[test]
fn a_stop_ends_the_trajectory_at_the_event() {
    let times = every_tenth_to(10.0);
    let (q0, v0) = start();
    for m in Method::ALL {
        let plain = method(m).integrate(&spring(), 0.0, q0, v0, &times).unwrap();
        // x falling through −0.5, first at t = 2π/3.
        let below = Event::new("x = -1/2", |_, q: &Vector1<f64>, _: &_| q[0] + 0.5)
            .falling()
            .stop();
        let events = Events::new().with(below);
        let stopped = method(m)
            .integrate_with_events(&spring(), 0.0, q0, v0, &times, &events)
            .unwrap();
        let stop = stopped.stopped().expect("stopped");
        assert!((stop.t - 2.0 * PI / 3.0).abs() < 0.05, "{m:?}: {}", stop.t);
        assert_eq!(stopped.events().len(), 1);
        // Samples up to the stop only (t = 2.0 < 2.094 < 2.1), the same as
        // without the event, bit for bit where they come from the same
        // steps (all, but those inside the stopping step of an adaptive
        // method, which come from its dense output either way).
        assert_eq!(stopped.len(), 21, "{m:?}");
        assert_eq!(stopped.times(), &times[..21]);
        assert_eq!(&plain.positions()[..21], stopped.positions(), "{m:?}");
    }
}

#[test]
fn a_reset_restarts_every_method_from_the_new_state() {
    // A wall at x = 0: x falling through 0 is reflected, ẋ → −ẋ, so the
    // motion is |cos t| (perfectly elastic).
    let times = every_tenth_to(6.0);
    let (q0, v0) = start();
    for m in Method::ALL {
        let wall = Event::new("wall", x)
            .falling()
            .reset(|_, q, qdot| (*q, -qdot));
        let events = Events::new().with(wall);
        let run = method(m)
            .integrate_with_events(&spring(), 0.0, q0, v0, &times, &events)
            .unwrap();
        // Impacts at π/2 and 3π/2 (the second by 6 s), each reversing
        // the velocity it met.
        let impacts = run.events();
        assert_eq!(impacts.len(), 2, "{m:?}");
        for impact in impacts {
            let (q_after, v_after) = impact.after.unwrap();
            assert_eq!((q_after, v_after), (impact.q, -impact.qdot));
            assert!(v_after[0] > 0.0);
        }
        // Every sample, before and after the impacts, on |cos t|: to the
        // method's accuracy at h = 0.01 over 6 s: Euler's O(h) ~0.03, the
        // second-order ones' h² t / 12 ~ 5e-5, the others' below 1e-7.
        let tolerance = match m.order() {
            1 => 0.05,
            2 => 1e-4,
            _ => 1e-6,
        };
        for s in &run {
            assert!(s.q[0] >= -1e-9, "{m:?} at {}: {}", s.t, s.q[0]);
            let error = (s.q[0] - s.t.cos().abs()).abs();
            assert!(error < tolerance, "{m:?} at {}: {error:e}", s.t);
        }
    }
}

#[test]
fn an_event_at_the_start_is_not_triggered() {
    // x = 0 at t0, moving up: the next crossing, falling at π, is the
    // first one reported.
    let (q0, v0) = (Vector1::new(0.0), Vector1::new(1.0));
    for m in Method::ALL {
        let events = Events::new().with(Event::new("x = 0", x));
        let run = method(m)
            .integrate_with_events(&spring(), 0.0, q0, v0, &[4.0], &events)
            .unwrap();
        let first = run.events()[0].t;
        assert!((first - PI).abs() < 0.05, "{m:?}: {first}");
        assert_eq!(run.events().len(), 1, "{m:?}");
    }
}

#[test]
fn an_excursion_inside_one_step_is_found_with_or_without_a_step_bound() {
    // x = −sin t rises above 0.99 only within ±acos(0.99) = ±0.1415 of
    // t = 3π/2 = 4.712: inside one step of 0.5, from 4.5 to 5.0, whose
    // ends are both below. The rate of g along the step's interpolant
    // shows the maximum between them.
    let high = || Event::new("x = 0.99", |_, q: &Vector1<f64>, _: &_| q[0] - 0.99);
    let (q0, v0) = (Vector1::new(0.0), Vector1::new(-1.0));
    let rk4 = Rk4::new(0.5);
    let times = [5.0];
    let half_width = 0.99f64.acos();
    let events = Events::new().with(high());
    let coarse = rk4
        .integrate_with_events(&spring(), 0.0, q0, v0, &times, &events)
        .unwrap();
    let found: Vec<f64> = coarse.events().iter().map(|e| e.t).collect();
    assert_eq!(found.len(), 2, "{found:?}");
    // RK4 at h = 0.5 errs by ~h⁴/120 ≈ 5e-4 per unit of time in x, and
    // its Hermite interpolant by h⁴/384 ≈ 2e-4: ~2e-3 in x by t = 4.7,
    // over |ẋ| = 0.14 at these crossings, ~2e-2 in t.
    for (t, exact) in found.iter().zip([-half_width, half_width]) {
        assert!((t - (1.5 * PI + exact)).abs() < 2e-2, "{found:?}");
    }
    assert!(
        found[0] > 4.5 && found[1] < 5.0,
        "both inside the step: {found:?}"
    );
    let events = Events::new().with(high()).max_step(0.05);
    let bounded = rk4
        .integrate_with_events(&spring(), 0.0, q0, v0, &times, &events)
        .unwrap();
    let found: Vec<f64> = bounded.events().iter().map(|e| e.t).collect();
    assert_eq!(found.len(), 2);
    // RK4 at 0.05 with the Hermite interpolant: errors ~1e-6 in x, over
    // |ẋ| = 0.14 at these crossings, ~1e-5 in t.
    assert!(
        (found[0] - (1.5 * PI - half_width)).abs() < 1e-4,
        "{found:?}"
    );
    assert!(
        (found[1] - (1.5 * PI + half_width)).abs() < 1e-4,
        "{found:?}"
    );
    assert_eq!(bounded.stats().steps_accepted, 100);
}

#[test]
fn a_constrained_model_s_event_state_is_on_its_constraint() {
    // The bob in x, y on its rod, and the same pendulum in θ: x = 0 is
    // θ = 0, the bottom, at the same times.
    let cartesian = CartesianPendulum::new(1.0, 1.0, 9.81);
    let (q0, v0) = cartesian.state(1.0, 0.0);
    let bottom = Event::new("x = 0", |_, q: &Vector2<f64>, _: &Vector2<f64>| q[0]);
    let events = Events::new().with(bottom);
    let dop853 = Dop853::new().rtol(1e-12).atol(1e-12);
    let run = dop853
        .integrate_with_events(&cartesian, 0.0, q0, v0, &[5.0], &events)
        .unwrap();
    let events = Events::new().with(Event::new("theta = 0", x));
    let angle = dop853
        .integrate_with_events(
            &Pendulum::new(1.0, 1.0, 9.81),
            0.0,
            Vector1::new(1.0),
            Vector1::new(0.0),
            &[5.0],
            &events,
        )
        .unwrap();
    assert_eq!(run.events().len(), angle.events().len());
    for (bob, theta) in run.events().iter().zip(angle.events()) {
        // Both at 1e-12: the time errors are ~1e-11 (tolerance times
        // the few periods), the constraint kept to rounding by the
        // projection of every state from dense output.
        assert!((bob.t - theta.t).abs() < 1e-9, "{} vs {}", bob.t, theta.t);
        let residual = bob.q.norm_squared() - 1.0;
        assert!(residual.abs() < 1e-12, "{residual:e}");
    }
}
