//! Typed errors of events: bad settings before any work, non-finite
//! values naming the event, resets that refuse the state at their event.

use lagrange::Method;
use lagrange::models::Oscillator;
use lagrange_runtime::nalgebra::Vector1;
use lagrange_runtime::prelude::*;
use lagrange_runtime::{InvalidInput, NonFiniteValue};

fn spring() -> Oscillator<f64> {
    Oscillator::new(1.0, 1.0, 0.0)
}

fn x(_: f64, q: &Vector1<f64>, _: &Vector1<f64>) -> f64 {
    q[0]
}

fn run(
    method: Method,
    events: &Events<'_, f64, 1>,
) -> Result<Trajectory<f64, 1>, Box<Failure<f64, 1>>> {
    let (q0, v0) = (Vector1::new(1.0), Vector1::new(0.0));
    method
        .integrator(0.01, 1e-8)
        .integrate_with_events(&spring(), 0.0, q0, v0, &[0.0, 3.0], events)
}

#[test]
fn settings_out_of_range_are_invalid_input_before_any_work() {
    let bad = [
        Events::new()
            .with(Event::new("x", x))
            .time_tolerance(-1e-12),
        Events::new().with(Event::new("x", x)).time_tolerance(0.0),
        Events::new()
            .with(Event::new("x", x))
            .min_separation(f64::NAN),
        Events::new().with(Event::new("x", x)).min_separation(-1.0),
        Events::new().with(Event::new("x", x)).max_step(0.0),
        Events::new()
            .with(Event::new("x", x))
            .max_step(f64::INFINITY),
    ];
    for method in Method::ALL {
        for events in &bad {
            let failure = run(method, events).unwrap_err();
            assert!(
                matches!(
                    failure.error,
                    IntegrationError::InvalidInput(InvalidInput::InvalidEventSetting { .. })
                ),
                "{method:?}: {}",
                failure.error
            );
            assert!(failure.trajectory.is_empty());
        }
    }
    // Zero separation turns the guard off: valid.
    let events = Events::new().with(Event::new("x", x)).min_separation(0.0);
    assert!(run(Method::Dopri5, &events).is_ok());
}

#[test]
fn a_nan_event_function_is_an_error_naming_the_event() {
    for method in Method::ALL {
        // NaN once x falls below 0.5 (t > π/3).
        let broken = Event::new(
            "broken",
            |_, q: &Vector1<f64>, _: &_| {
                if q[0] < 0.5 { f64::NAN } else { q[0] - 2.0 }
            },
        );
        let events = Events::new().with(Event::new("x", x)).with(broken);
        let failure = run(method, &events).unwrap_err();
        let IntegrationError::NonFiniteEvent {
            event, t, value, q, ..
        } = failure.error
        else {
            panic!("{method:?}: {}", failure.error);
        };
        assert_eq!((event, value), ("broken", NonFiniteValue::EventFunction));
        // At the end of the first step past π/3, where it was evaluated.
        let past = t > std::f64::consts::FRAC_PI_3 && q[0] < 0.5;
        assert!(past, "{method:?}: {t}");
        // The sample at t0 was kept.
        assert_eq!(failure.trajectory.len(), 1);
    }
}

#[test]
fn a_reset_to_a_non_finite_state_is_an_error_naming_the_event() {
    for method in Method::ALL {
        let bad_reset = Event::new("x", x).reset(|_, q, _| (*q, Vector1::new(f64::NAN)));
        let failure = run(method, &Events::new().with(bad_reset)).unwrap_err();
        let IntegrationError::NonFiniteEvent { event, value, .. } = failure.error else {
            panic!("{method:?}: {}", failure.error);
        };
        assert_eq!((event, value), ("x", NonFiniteValue::EventReset));
        let message = failure.to_string();
        assert!(message.contains("event `x`"), "{message}");
    }
}

#[test]
fn a_reset_that_refuses_ends_the_run_with_its_reason_at_the_event_and_the_trajectory_so_far() {
    // The spring x = cos t (released from 1 at rest) first crosses x = 0
    // falling at π/2, with velocity −1: the reset refuses there, in its
    // own words.
    let refuse = |t: f64, _: &Vector1<f64>, qd: &Vector1<f64>| {
        Err(lagrange_runtime::ResetFailure::refused(format!(
            "no reflection at t = {t:.3} with velocity {:.3}",
            qd[0]
        )))
    };
    let expected_t = std::f64::consts::FRAC_PI_2;
    for method in Method::ALL {
        let events = Events::new().with(Event::new("x", x).falling().try_reset(refuse));
        let (q0, v0) = (Vector1::new(1.0), Vector1::new(0.0));
        let failure = method
            .integrator(0.01, 1e-8)
            .integrate_with_events(&spring(), 0.0, q0, v0, &[0.0, 1.0, 3.0], &events)
            .unwrap_err();
        let IntegrationError::ResetFailed {
            event,
            t,
            q,
            qdot,
            ref reason,
        } = failure.error
        else {
            panic!("{method:?}: {}", failure.error);
        };
        assert_eq!(event, "x");
        // Located on each method's own trajectory: the first-order methods
        // at h = 0.01 are O(h) off the cosine by π/2 (symplectic Euler's
        // crossing comes 4.8e-3 early, explicit Euler's 8e-5 late), the
        // others within 1e-7; 1e-2 holds for all.
        assert!((t - expected_t).abs() < 1e-2, "{method:?}: {t}");
        assert!(q[0].abs() < 1e-9, "{method:?}: {q}");
        assert!((qdot[0] + 1.0).abs() < 1e-2, "{method:?}: {qdot}");
        assert_eq!(
            **reason,
            lagrange_runtime::ResetFailure::refused(format!(
                "no reflection at t = {t:.3} with velocity {:.3}",
                qdot[0]
            ))
        );
        assert!(
            failure.to_string().contains("event `x`: its reset failed"),
            "{failure}"
        );
        // The samples before the event were kept: t = 0 and t = 1.
        assert_eq!(failure.trajectory.len(), 2, "{method:?}");
    }
}

#[test]
fn a_stepper_whose_reset_refuses_stops_at_the_event_with_its_reason() {
    let events = Events::new().with(
        Event::new("x", x)
            .falling()
            .try_reset(|_, _, _| Err(lagrange_runtime::ResetFailure::refused("never"))),
    );
    let (q0, v0) = (Vector1::new(1.0), Vector1::new(0.0));
    let mut stepper = Stepper::new(spring(), Rk4::new(0.01), 0.0, q0, v0)
        .unwrap()
        .with_events(&events)
        .unwrap();
    let error = (1..=120)
        .find_map(|frame| stepper.advance_to(frame as f64 / 60.0).err())
        .expect("the reset refuses at π/2");
    let IntegrationError::ResetFailed { event, t, .. } = error else {
        panic!("{error}");
    };
    // RK4 at h = 0.01 locates the crossing to its interpolant's error.
    assert_eq!(event, "x");
    assert!((t - std::f64::consts::FRAC_PI_2).abs() < 1e-6, "{t}");
}

/// A reset that keeps a count as data of the run (`Events::keeping`,
/// `Event::try_reset_keeping`) refuses the spring's third falling crossing
/// of `x = 0` (at `π/2 + 4π`, where `x = cos t`) in every run of the same
/// events, by every method: each run counts from the start value, and the
/// reset's changes reach the next crossing. A count kept in the closure
/// instead (an atomic, the only way before) is shared by the runs: the
/// second run refuses at its first crossing.
#[test]
fn data_kept_by_a_reset_is_each_runs_own() {
    let count = |seen: &mut usize, _: f64, q: &Vector1<f64>, qd: &Vector1<f64>| {
        *seen += 1;
        if *seen == 3 {
            return Err(lagrange_runtime::ResetFailure::refused("a third crossing"));
        }
        Ok((*q, *qd))
    };
    let third = std::f64::consts::FRAC_PI_2 + 4.0 * std::f64::consts::PI;
    let keeping = Events::new().keeping(0usize).with(
        Event::keeping("x", |_: &usize, t, q, qd| x(t, q, qd))
            .falling()
            .try_reset_keeping(count),
    );
    let (q0, v0) = (Vector1::new(1.0), Vector1::new(0.0));
    for method in Method::ALL {
        for _ in 0..2 {
            let failure = method
                .integrator(0.01, 1e-8)
                .integrate_with_events(&spring(), 0.0, q0, v0, &[30.0], &keeping)
                .unwrap_err();
            let IntegrationError::ResetFailed { t, .. } = failure.error else {
                panic!("{method:?}: {}", failure.error);
            };
            // As above: the first-order methods' crossings are O(h) off the
            // cosine's, by a few 1e-2 over two more periods; 0.1 holds.
            assert!((t - third).abs() < 0.1, "{method:?}: {t}");
            assert_eq!(failure.trajectory.events().len(), 2, "{method:?}");
        }
    }

    let shared = std::sync::atomic::AtomicUsize::new(0);
    let in_closure = Events::new().with(Event::new("x", x).falling().try_reset(
        |_, q: &Vector1<f64>, qd: &Vector1<f64>| {
            if shared.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1 >= 3 {
                return Err(lagrange_runtime::ResetFailure::refused("a third crossing"));
            }
            Ok((*q, *qd))
        },
    ));
    let crossings = |events: &Events<'_, f64, 1>| {
        let failure = Method::Dopri5
            .with_tolerance(1e-8)
            .integrate_with_events(&spring(), 0.0, q0, v0, &[30.0], events)
            .unwrap_err();
        failure.trajectory.events().len()
    };
    assert_eq!(crossings(&in_closure), 2);
    assert_eq!(crossings(&in_closure), 0);
}
