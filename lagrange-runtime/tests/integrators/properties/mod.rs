//! Properties of every method on any input: random parameters, initial
//! states, times, step sizes and tolerances, finite or not, end in a typed
//! error or a finite trajectory at exactly the requested times; never a
//! panic, never a NaN or an infinity in a returned sample, never a hang
//! (each run's work is bounded by its step budget). Beside them, the
//! reproducers of what such inputs once did instead.
//!
//! The runs are deterministic: a fixed seed, a fixed number of cases, no
//! regression files. `cargo test -p lagrange-runtime --test integrators --
//! properties:: --nocapture` prints how the outcomes were spread.
//!
//! The hand-written models are in `models.rs`, the random inputs in
//! `strategies.rs`, the reproducers in `reproducers.rs`.

use std::collections::BTreeMap;

use lagrange::Method;
use lagrange_runtime::IntegrationResult;
use lagrange_runtime::prelude::*;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestRng, TestRunner};

use models::{CartPendulum, DampedSpring, Pendulum};
use strategies::{coordinate, parameter, settings, times};

mod models;
mod reproducers;
mod strategies;

// ---------------------------------------------------------------------------
// Every method, in one list: a new method is tested here by adding a line.

/// Each method's settings, from one random draw: the fixed-step ones read
/// `h`, the adaptive ones `rtol` and `atol`; all get `max_steps`.
#[derive(Debug, Clone, Copy)]
struct Settings {
    h: f64,
    rtol: f64,
    atol: f64,
    max_steps: usize,
}

/// One method of `Method::ALL` (the one list of every integrator), with the
/// settings applied.
fn run<L: Lagrangian<N, Scalar = f64>, const N: usize>(
    method: Method,
    s: Settings,
    model: &L,
    (t0, q0, v0): (f64, [f64; N], [f64; N]),
    times: &[f64],
) -> IntegrationResult<f64, N> {
    method
        .with_step(s.h)
        .tolerances(s.rtol, s.atol)
        .max_steps(s.max_steps)
        .integrate(model, t0, q0.into(), v0.into(), times)
}

// ---------------------------------------------------------------------------
// The property.

/// What a run may return: a trajectory at exactly `times`, all finite; or a
/// typed failure whose samples are a finite prefix of `times` (none for
/// invalid input), within the budget. Returns the outcome's name.
fn check<const N: usize>(
    method: Method,
    s: Settings,
    times: &[f64],
    result: IntegrationResult<f64, N>,
) -> Result<String, TestCaseError> {
    let (trajectory, outcome) = match &result {
        Ok(trajectory) => (trajectory, "Ok".to_string()),
        Err(failure) => {
            // The message is part of the error: it must format.
            let message = failure.to_string();
            prop_assert!(!message.is_empty());
            let name = format!("{:?}", failure.error);
            let name = name.split([' ', '(', '{']).next().unwrap_or("").to_string();
            let name = match &failure.error {
                IntegrationError::InvalidInput(invalid) => {
                    prop_assert!(failure.trajectory.is_empty(), "{method:?}: {message}");
                    let which = format!("{invalid:?}");
                    format!(
                        "InvalidInput::{}",
                        which.split([' ', '{']).next().unwrap_or("")
                    )
                }
                _ => name,
            };
            (&failure.trajectory, name)
        }
    };
    let kept = trajectory.times();
    prop_assert!(kept.len() <= times.len(), "{method:?}: {outcome}");
    prop_assert!(kept == &times[..kept.len()], "{method:?}: {outcome}");
    if result.is_ok() {
        prop_assert_eq!(kept.len(), times.len(), "{:?}", method);
    }
    for sample in trajectory {
        let finite = sample
            .q
            .iter()
            .chain(sample.qdot.iter())
            .all(|x| x.is_finite());
        prop_assert!(finite, "{method:?}, {outcome}: sample {sample:?}");
    }
    let stats = trajectory.stats();
    let attempts = stats.steps_accepted + stats.steps_rejected;
    prop_assert!(attempts <= s.max_steps, "{method:?}: {attempts} attempts");
    Ok(outcome)
}

/// Runs every method on `cases` random inputs for the model that `model`
/// draws, and prints how the outcomes were spread.
fn every_method_on<L, const N: usize>(
    name: &str,
    seed: u8,
    cases: u32,
    model: impl Strategy<Value = L>,
) where
    L: Lagrangian<N, Scalar = f64> + std::fmt::Debug,
{
    let config = Config {
        cases,
        failure_persistence: None,
        max_shrink_iters: 256,
        ..Config::default()
    };
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[seed; 32]);
    let mut runner = TestRunner::new_with_rng(config, rng);
    let state = prop::array::uniform(coordinate());
    let inputs = (
        model,
        settings(),
        times(),
        state,
        prop::array::uniform(coordinate()),
    );
    let outcomes = std::cell::RefCell::new(BTreeMap::<String, usize>::new());
    let result = runner.run(&inputs, |(model, s, (t0, times), q0, v0)| {
        for method in Method::ALL {
            let result = run(method, s, &model, (t0, q0, v0), &times);
            let outcome = check(method, s, &times, result)?;
            *outcomes.borrow_mut().entry(outcome).or_default() += 1;
        }
        Ok(())
    });
    if let Err(failure) = result {
        panic!("{name}: {failure}");
    }
    println!(
        "{name}: {cases} cases × {} methods: {:?}",
        Method::ALL.len(),
        outcomes.borrow()
    );
}

// 1000 cases per model, every method (`Method::ALL`, 12) each: 36 000 runs.
const CASES: u32 = 1000;

#[test]
fn every_method_on_a_random_pendulum_gives_a_typed_error_or_finite_samples() {
    let model = (parameter(), parameter(), parameter()).prop_map(|(m, l, g)| Pendulum { m, l, g });
    every_method_on("pendulum", 1, CASES, model);
}

#[test]
fn every_method_on_a_random_cart_pendulum_gives_a_typed_error_or_finite_samples() {
    let model = (parameter(), parameter(), parameter(), parameter())
        .prop_map(|(mc, m, l, g)| CartPendulum { mc, m, l, g });
    every_method_on("cart pendulum", 2, CASES, model);
}

#[test]
fn every_method_on_a_random_damped_spring_gives_a_typed_error_or_finite_samples() {
    let model =
        (parameter(), parameter(), parameter()).prop_map(|(m, k, c)| DampedSpring { m, k, c });
    every_method_on("damped spring", 3, CASES, model);
}
