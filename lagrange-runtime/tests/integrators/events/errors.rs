//! Typed errors of events: bad settings before any work, non-finite
//! values naming the event.

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
