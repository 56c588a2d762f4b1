//! The observer (`Events::observe`) on every method: called once per
//! accepted step, it stops the run cleanly where it says, the samples
//! before that time the same as a run without it, later ones absent.

use std::ops::ControlFlow;
use std::sync::atomic::{AtomicUsize, Ordering};

use lagrange::Method;
use lagrange::models::DoublePendulum;
use lagrange::prelude::*;

#[test]
fn an_observer_sees_every_step_and_stops_every_method_cleanly() {
    let (model, q0, v0) = DoublePendulum::<f64>::regular();
    let times: Vec<f64> = (1..=40).map(|k| 0.25 * k as f64).collect();
    for method in Method::ALL {
        let integrator = method.integrator(1e-2, 1e-9);
        let calls = AtomicUsize::new(0);
        let watching = Events::new().observe(|_t, _q, _qdot| {
            calls.fetch_add(1, Ordering::Relaxed);
            ControlFlow::Continue(())
        });
        let full = integrator
            .integrate_with_events(&model, 0.0, q0, v0, &times, &watching)
            .unwrap();
        // Once per accepted step.
        assert_eq!(
            calls.load(Ordering::Relaxed),
            full.stats().steps_accepted,
            "{method:?}"
        );
        assert_eq!(full.interrupted(), None);

        let stopping = Events::new().observe(|t, _q, _qdot| {
            if t > 4.1 {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        });
        let cut = integrator
            .integrate_with_events(&model, 0.0, q0, v0, &times, &stopping)
            .unwrap();
        let at = cut.interrupted().expect("the observer stopped the run");
        assert!(at > 4.1, "{method:?}: {at}");
        // Every sample up to the stop, none after, each the very sample of
        // the run that was not stopped (the same steps up to there).
        let kept = times.iter().filter(|&&t| t <= at).count();
        assert_eq!(cut.len(), kept, "{method:?}");
        for (a, b) in cut.iter().zip(full.iter()) {
            assert_eq!((a.t, a.q, a.qdot), (b.t, b.q, b.qdot), "{method:?}");
        }
    }
}
