//! Identification (`lagrange::identify`): the damped double pendulum of
//! `tests/models/parameter_derivatives.rs` recorded for 10 s at 100 Hz by
//! Radau5 with noise of known size on both angles, fitted by Dop853 over
//! its sensitivities from a start 20 % off: the second mass, both lengths
//! and both dampers (the first mass given: it fixes the scale, see the
//! last test).

use crate::models::parameter_derivatives::{DampedDoublePendulum, FromScalars};
use lagrange::identify::{FitError, FitSettings, Measurements, fit};
use lagrange::nalgebra::SVector;
use lagrange::prelude::*;
use lagrange::sensitivity::Direction;
use lagrange::{Dop853, Radau5};
use rand::{Rng, SeedableRng, rngs::StdRng};

/// m1, m2, l1, l2, g, c1, c2.
const TRUTH: [f64; 7] = [1.0, 0.8, 1.1, 0.9, 9.81, 0.3, 0.2];
const NOISE: f64 = 1e-3;

fn start() -> (SVector<f64, 2>, SVector<f64, 2>) {
    (SVector::from([1.0, -0.5]), SVector::from([0.0, 0.3]))
}

/// The recorded angles: Radau5 at 1e-12 (an error far below the noise),
/// plus independent Gaussian noise of standard deviation `NOISE` (Box–
/// Muller from a seeded generator).
fn recorded(seed: u64) -> Measurements<2> {
    recorded_from(&TRUTH, seed)
}

/// [`recorded`] from other parameters (m1, m2, l1, l2, g, c1, c2), built
/// by the unchecked `new`, so that they may lie outside the model's
/// domains.
fn recorded_from(parameters: &[f64; 7], seed: u64) -> Measurements<2> {
    let times: Vec<f64> = (1..=1000).map(|i| i as f64 / 100.0).collect();
    let truth = DampedDoublePendulum::from_scalars(parameters);
    let (q0, v0) = start();
    let run = Radau5::new()
        .rtol(1e-12)
        .atol(1e-12)
        .integrate(&truth, 0.0, q0, v0, &times)
        .unwrap();
    let mut rng = StdRng::seed_from_u64(seed);
    let mut gauss = move || {
        let (u, v): (f64, f64) = (rng.gen_range(f64::EPSILON..1.0), rng.gen_range(0.0..1.0));
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    };
    let noisy = run
        .positions()
        .iter()
        .map(|q| q.map(|x| x + NOISE * gauss()))
        .collect();
    Measurements::positions(times, noisy)
}

/// Each of `m2, l1, l2, c1, c2` (the fits' directions, in that order)
/// within 4 standard errors of the truth: a true value outside them has
/// probability 6e-5 under the fit's own (linear, Gaussian) model; a biased
/// fit (a wrong sensitivity, a wrong σ̂) lands far outside.
fn within_four_standard_errors(values: &[f64], errors: &[f64], names: [&str; 5]) {
    for (j, k) in [1, 2, 3, 5, 6].into_iter().enumerate() {
        let (value, error) = (values[j], errors[j]);
        assert!(
            (value - TRUTH[k]).abs() < 4.0 * error,
            "{}: {value} ± {error}, truth {}",
            names[j],
            TRUTH[k]
        );
    }
}

#[test]
fn a_noisy_recording_gives_back_the_parameters_within_their_standard_errors() {
    let data = recorded(7);
    let names = ["m2", "l1", "l2", "c1", "c2"];
    let directions = names;
    // Every fitted parameter 20 % off (up or down) at the start.
    let mut guess = TRUTH;
    for (k, sign) in [(1, 1.2), (2, 0.8), (3, 1.2), (5, 0.8), (6, 1.2)] {
        guess[k] *= sign;
    }
    let method = Dop853::new().rtol(1e-10).atol(1e-10);
    let fitted = fit(
        DampedDoublePendulum::from_scalars(&guess),
        &method,
        directions,
        0.0,
        start(),
        &data,
        &FitSettings::default(),
    )
    .unwrap();
    assert_eq!(fitted.names, names.map(String::from));
    for (j, k) in [1, 2, 3, 5, 6].into_iter().enumerate() {
        // 4 standard errors: a true value outside them has probability
        // 6e-5 under the fit's own (linear, Gaussian) model; a biased fit
        // (a wrong sensitivity, a wrong σ̂) lands far outside.
        let (value, error) = (fitted.values[j], fitted.standard_errors[j]);
        assert!(
            (value - TRUTH[k]).abs() < 4.0 * error,
            "{}: {value} ± {error}, truth {}",
            names[j],
            TRUTH[k]
        );
        // The data determine each to better than a percent.
        assert!(error < 1e-2 * TRUTH[k], "{}: ± {error}", names[j]);
    }
    // σ̂ from 2000 residuals estimates the noise to about 1/√4000 = 1.6 %
    // (one standard deviation); 10 % allows six.
    assert!(
        (fitted.sigma / NOISE - 1.0).abs() < 0.1,
        "σ̂ = {}",
        fitted.sigma
    );
    assert_eq!(fitted.model.m1, TRUTH[0], "the given mass is kept");
    assert_eq!(fitted.fitted.len(), 1000);
}

/// Without an input, scaling every mass and damper by one factor scales
/// `M` and `f` alike and leaves the motion unchanged: fitting `m1`, `m2`,
/// `c1` and `c2` together is refused, and the combination named is that
/// scaling (equal relative changes, each 1/2 of a unit vector of four).
#[test]
fn masses_and_dampers_together_are_reported_not_identifiable() {
    let data = recorded(7);
    let directions = ["m1", "m2", "c1", "c2"];
    let error = fit(
        DampedDoublePendulum::from_scalars(&TRUTH),
        &Dop853::new().rtol(1e-10).atol(1e-10),
        directions,
        0.0,
        start(),
        &data,
        &FitSettings::default(),
    )
    .unwrap_err();
    let FitError::NotIdentifiable { combination, ratio } = &error else {
        panic!("{error}");
    };
    // The symmetry is exact, so the ratio is at the level of rounding
    // (measured: 8e-16), far below the 1e-7 at which a fit is refused.
    assert!(*ratio < 1e-8, "{ratio:e}");
    for (name, share) in combination {
        assert!((share - 0.5).abs() < 1e-6, "{name}: {share}");
    }
    assert!(error.to_string().contains("m1 +0.500"), "{error}");
}

#[test]
fn bad_measurements_are_refused_with_the_reason() {
    let model = DampedDoublePendulum::from_scalars(&TRUTH);
    let method = Dop853::new();
    let try_fit = |data: &Measurements<2>| {
        fit(
            model,
            &method,
            ["m2"],
            0.0,
            start(),
            data,
            &FitSettings::default(),
        )
        .unwrap_err()
        .to_string()
    };
    let q = SVector::<f64, 2>::zeros();
    let short = Measurements::positions(vec![0.1, 0.2], vec![q]);
    assert!(try_fit(&short).contains("2 times but 1 positions"));
    let backwards = Measurements::positions(vec![0.2, 0.1], vec![q, q]);
    assert!(try_fit(&backwards).contains("times decrease at sample 1"));
    let early = Measurements::positions(vec![-0.1, 0.1], vec![q, q]);
    assert!(try_fit(&early).contains("time 0 is -0.1"));
    let blind = Measurements::positions(vec![0.1, 0.2], vec![q, q]).observing([false, false]);
    assert!(try_fit(&blind).contains("observe no coordinate"));
    let nan = Measurements::positions(vec![0.1, 0.2], vec![q, SVector::from([f64::NAN, 0.0])]);
    assert!(try_fit(&nan).contains("sample 1 (t = 0.2)"));
    // One measured angle is enough samples for one parameter.
    let one = Measurements::positions(vec![0.1], vec![q]).observing([true, false]);
    assert!(try_fit(&one).contains("1 residuals for 1 directions"));
}

lagrangian! {
    /// A damped pendulum driven by a torque at its pivot; without its
    /// exact Jacobians, so that its sensitivities take the differences.
    #[lagrange(parameter_derivatives)]
    pub struct DrivenPendulum {
        coordinates: theta;
        parameters: m > 0, l > 0, c >= 0;
        inputs: tau;
        constants: g = 9.81;
        kinetic: m/2*l^2*dot(theta)^2;
        potential: -m*g*l*cos(theta);
        dissipation: c/2*dot(theta)^2;
        forces: theta = tau;
    }
}

/// The torque recorded at 100 Hz, replayed by linear interpolation.
fn torque_at(recorded: &[f64], t: f64) -> f64 {
    let x = (t * 100.0).clamp(0.0, (recorded.len() - 1) as f64);
    let i = (x.floor() as usize).min(recorded.len() - 2);
    recorded[i] + (x - i as f64) * (recorded[i + 1] - recorded[i])
}

/// With a recorded torque the mass and the damping are no longer tied:
/// `m l² θ̈ = −m g l sin θ − c θ̇ + τ` changes with `m` and `c` scaled
/// together, since `τ` is not. The torque replayed through a controller
/// (as it was when the motion was recorded) gives `m`, `l` and `c` back;
/// the same motion without it is refused.
#[test]
fn a_recorded_input_separates_what_the_free_motion_cannot() {
    let recorded: Vec<f64> = (0..=1000)
        .map(|i| {
            let t = i as f64 / 100.0;
            0.5 * (1.7 * t).sin() + 0.3 * (4.1 * t).sin()
        })
        .collect();
    let torque = |t: f64, _: &SVector<f64, 1>, _: &SVector<f64, 1>| {
        SVector::<f64, 1>::from([torque_at(&recorded, t)])
    };
    let truth = DrivenPendulum::new(1.3, 0.6, 0.15);
    let (q0, v0) = (SVector::from([0.2]), SVector::from([0.0]));
    let times: Vec<f64> = (1..=1000).map(|i| i as f64 / 100.0).collect();
    let mut rng = StdRng::seed_from_u64(3);
    let mut gauss = move || {
        let (u, v): (f64, f64) = (rng.gen_range(f64::EPSILON..1.0), rng.gen_range(0.0..1.0));
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    };
    let run = Radau5::new()
        .rtol(1e-12)
        .atol(1e-12)
        .integrate(&truth.with_controller(torque), 0.0, q0, v0, &times)
        .unwrap();
    let noisy = run
        .positions()
        .iter()
        .map(|q| q.map(|x| x + NOISE * gauss()))
        .collect();
    let data = Measurements::positions(times, noisy);
    let directions = [
        Direction::Parameter(0),
        Direction::Parameter(1),
        Direction::Parameter(2),
    ];
    let method = Dop853::new().rtol(1e-10).atol(1e-10);
    let guess = DrivenPendulum::new(1.3 * 0.8, 0.6 * 1.2, 0.15 * 1.2);
    let fitted = fit(
        guess.with_controller(torque),
        &method,
        directions,
        0.0,
        (q0, v0),
        &data,
        &FitSettings::default(),
    )
    .unwrap();
    for (j, truth) in [1.3, 0.6, 0.15].into_iter().enumerate() {
        // 4 standard errors, as for the double pendulum above.
        let (value, error) = (fitted.values[j], fitted.standard_errors[j]);
        assert!(
            (value - truth).abs() < 4.0 * error,
            "{j}: {value} ± {error}"
        );
        assert!(error < 2e-2 * truth, "{j}: ± {error}");
    }
    // The free motion, from the same start with no torque: `m` and `c`
    // move together.
    let free = guess.with_inputs(&SVector::<f64, 1>::zeros());
    let error = fit(
        free,
        &method,
        [Direction::Parameter(0), Direction::Parameter(2)],
        0.0,
        (q0, v0),
        &data,
        &FitSettings::default(),
    )
    .unwrap_err();
    assert!(matches!(error, FitError::NotIdentifiable { .. }), "{error}");
}

/// The second bob's Cartesian position (the model's `let`s `x2` and
/// `y2`) measured at 800 irregular times instead of the angles: the same
/// parameters come back within their standard errors, and a `let` the
/// model does not name is refused.
#[test]
fn named_lets_at_irregular_times_fit_as_well() {
    let mut rng = StdRng::seed_from_u64(11);
    let mut times: Vec<f64> = (0..800).map(|_| rng.gen_range(0.01..10.0)).collect();
    times.sort_by(f64::total_cmp);
    let truth = DampedDoublePendulum::from_scalars(&TRUTH);
    let (q0, v0) = start();
    let run = Radau5::new()
        .rtol(1e-12)
        .atol(1e-12)
        .integrate(&truth, 0.0, q0, v0, &times)
        .unwrap();
    let mut gauss = move || {
        let (u, v): (f64, f64) = (rng.gen_range(f64::EPSILON..1.0), rng.gen_range(0.0..1.0));
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    };
    let values: Vec<Vec<f64>> = run
        .iter()
        .map(|s| {
            let lets = truth.lets(s.t, &s.q, &s.qdot);
            // x1, y1, x2, y2: the second bob's.
            vec![lets[2] + NOISE * gauss(), lets[3] + NOISE * gauss()]
        })
        .collect();
    let data = Measurements::lets(times, &["x2", "y2"], values);
    let names = ["m2", "l1", "l2", "c1", "c2"];
    let mut guess = TRUTH;
    for (k, factor) in [(1, 1.2), (2, 0.8), (3, 1.2), (5, 0.8), (6, 1.2)] {
        guess[k] *= factor;
    }
    let method = Dop853::new().rtol(1e-10).atol(1e-10);
    let fitted = fit(
        DampedDoublePendulum::from_scalars(&guess),
        &method,
        names,
        0.0,
        start(),
        &data,
        &FitSettings::default(),
    )
    .unwrap();
    within_four_standard_errors(
        fitted.values.as_slice(),
        fitted.standard_errors.as_slice(),
        names,
    );
    // σ̂ from 1600 residuals: 1/√3200 = 1.8 % per standard deviation.
    assert!(
        (fitted.sigma / NOISE - 1.0).abs() < 0.1,
        "σ̂ = {}",
        fitted.sigma
    );

    let wrong = Measurements::lets(vec![0.1, 0.2], &["x3"], vec![vec![0.0], vec![0.0]]);
    let error = fit(
        DampedDoublePendulum::from_scalars(&TRUTH),
        &method,
        ["m2"],
        0.0,
        start(),
        &wrong,
        &FitSettings::default(),
    )
    .unwrap_err();
    assert!(
        error
            .to_string()
            .contains("`x3`, which is not a `let` of the model (it names: x1, y1, x2, y2)"),
        "{error}"
    );
}

/// A controller whose torque turns NaN at `t = 0.5` is blamed as what it
/// is, the inputs, whether the pendulum runs alone or with its
/// sensitivities (as `identify::fit` runs it when it replays a recorded
/// input): before issue 45 the sensitivities mapped the solve's errors
/// themselves and called the NaN a non-finite forcing.
#[test]
fn a_controllers_nan_is_blamed_on_the_inputs_alone_and_with_sensitivities() {
    use lagrange::sensitivity::Sensitivity;
    use lagrange::{IntegrationError, NonFiniteValue};
    let torque = |t: f64, _: &SVector<f64, 1>, _: &SVector<f64, 1>| {
        SVector::<f64, 1>::from([if t < 0.5 { 0.1 } else { f64::NAN }])
    };
    let model = DrivenPendulum::new(1.3, 0.6, 0.15).with_controller(torque);
    let (q0, v0) = (SVector::from([0.2]), SVector::from([0.0]));
    let method = Dop853::new().rtol(1e-10).atol(1e-10);
    let alone = method.integrate(&model, 0.0, q0, v0, &[1.0]).unwrap_err();
    assert!(
        matches!(
            alone.error,
            IntegrationError::NonFiniteState { t, value: NonFiniteValue::Inputs, .. } if t >= 0.5
        ),
        "alone: {}",
        alone.error
    );
    let sensitivity = Sensitivity::new(model, [Direction::Parameter(0)]).unwrap();
    let (x0, xdot0) = sensitivity.initial_state(&q0, &v0);
    let with = method
        .integrate(&sensitivity, 0.0, x0, xdot0, &[1.0])
        .unwrap_err();
    assert!(
        matches!(
            with.error,
            IntegrationError::NonFiniteState { t, value: NonFiniteValue::Inputs, .. } if t >= 0.5
        ),
        "with sensitivities: {}",
        with.error
    );
}

/// Inputs set to NaN after the sensitivities were built (through
/// `model_mut`) are refused before any work, as for the model alone: the
/// sensitivities pass their model's inputs on to the run's checks (before
/// issue 45 they had none, and the run failed at its first evaluation).
#[test]
fn inputs_unset_behind_the_sensitivities_are_refused_as_for_the_model_alone() {
    use lagrange::sensitivity::Sensitivity;
    use lagrange::{IntegrationError, InvalidInput};
    let nan = SVector::<f64, 1>::from([f64::NAN]);
    let model = DrivenPendulum::new(1.3, 0.6, 0.15).with_inputs(&SVector::from([0.1]));
    let (q0, v0) = (SVector::from([0.2]), SVector::from([0.0]));
    let method = Dop853::new().rtol(1e-10).atol(1e-10);
    fn refused<const N: usize>(error: &IntegrationError<f64, N>) -> bool {
        matches!(
            error,
            IntegrationError::InvalidInput(InvalidInput::InputsNotSet { inputs }) if *inputs == ["tau"]
        )
    }
    let alone = method
        .integrate(&model.with_inputs(&nan), 0.0, q0, v0, &[1.0])
        .unwrap_err();
    assert!(refused(&alone.error), "alone: {}", alone.error);
    let mut sensitivity = Sensitivity::new(model, [Direction::Parameter(0)]).unwrap();
    sensitivity.model_mut().set_inputs(&nan);
    let (x0, xdot0) = sensitivity.initial_state(&q0, &v0);
    let with = method
        .integrate(&sensitivity, 0.0, x0, xdot0, &[1.0])
        .unwrap_err();
    assert!(refused(&with.error), "with sensitivities: {}", with.error);
    assert!(with.trajectory.is_empty());
}

/// The lengths are declared positive (`parameters: .., l1 > 0, ..`): a
/// fit started at a negative length, a mirrored pendulum that moves as the
/// true one only where `l1` flips sign with the angle, is refused before
/// any run, naming the parameter and its value, as the checked
/// constructors refuse it.
#[test]
fn a_fit_started_outside_a_parameters_domain_is_refused_naming_it() {
    use lagrange::ParameterError;
    use lagrange::models::DampedDoublePendulumParameters;
    let data = recorded(7);
    let mut guess = TRUTH;
    guess[2] = -0.3;
    let error = fit(
        DampedDoublePendulum::from_scalars(&guess),
        &Dop853::new().rtol(1e-10).atol(1e-10),
        ["m2", "l1", "l2", "c1", "c2"],
        0.0,
        start(),
        &data,
        &FitSettings::default(),
    )
    .unwrap_err();
    let FitError::OutsideDomain(ParameterError { name, value, .. }) = error else {
        panic!("{error}");
    };
    assert_eq!((name, value), ("l1", -0.3));
    assert_eq!(
        error.to_string(),
        "the fit cannot start there: parameter `l1` is -0.3, outside its domain `l1 > 0`"
    );
    let [m1, m2, l1, l2, g, c1, c2] = guess;
    let refused = DampedDoublePendulum::try_new(m1, m2, l1, l2, g, c1, c2).unwrap_err();
    assert_eq!((refused.name, refused.value), ("l1", -0.3));
    let by_name = DampedDoublePendulum::from_parameters(DampedDoublePendulumParameters {
        m1,
        m2,
        l1: 1.1,
        l2,
        g,
        c1: -0.1,
        c2,
    })
    .unwrap_err();
    assert_eq!(
        by_name.to_string(),
        "parameter `c1` is -0.1, outside its domain `c1 >= 0`"
    );
}

/// From a start inside the domains but far off (both lengths a tenth of
/// the truth), the fit converges to the true values within their standard
/// errors and ends inside its domains. Whether a step of this fit was
/// projected is not observed here.
#[test]
fn a_fit_from_far_inside_the_domain_stays_inside_and_converges() {
    let data = recorded(7);
    let mut guess = TRUTH;
    for (k, value) in [(1, 0.96), (2, 0.11), (3, 0.09), (5, 0.24), (6, 0.24)] {
        guess[k] = value;
    }
    let names = ["m2", "l1", "l2", "c1", "c2"];
    let fitted = fit(
        DampedDoublePendulum::from_scalars(&guess),
        &Dop853::new().rtol(1e-10).atol(1e-10),
        names,
        0.0,
        start(),
        &data,
        &FitSettings::default(),
    )
    .unwrap();
    within_four_standard_errors(
        fitted.values.as_slice(),
        fitted.standard_errors.as_slice(),
        names,
    );
    fitted.model.check_parameters().unwrap();
}

/// A fit whose least-squares minimum lies outside a closed domain ends on
/// its bound, exactly. The recording is of a pendulum pumped at its first
/// joint (`c1 = −0.05`, built by the unchecked `new`: a negative damper, a
/// motor feeding energy in), which the model's domain `c1 >= 0` does not
/// admit. Fitted alone from `c1 = 0.3`, the unconstrained minimum is
/// `−0.05` within its standard error (about 1e-4 at this noise, far from
/// zero): each step towards it is projected onto `c1 = 0`, where the fit
/// stops, inside the domain. Without the projection it would return about
/// −0.05, and with a reparametrization (`c1 = exp(u)`) it could never
/// reach zero.
#[test]
fn a_fit_whose_minimum_lies_outside_a_closed_domain_stops_on_its_bound() {
    let mut pumped = TRUTH;
    pumped[5] = -0.05;
    let data = recorded_from(&pumped, 11);
    let fitted = fit(
        DampedDoublePendulum::from_scalars(&TRUTH),
        &Dop853::new().rtol(1e-10).atol(1e-10),
        ["c1"],
        0.0,
        start(),
        &data,
        &FitSettings::default(),
    )
    .unwrap();
    assert_eq!(fitted.values[0], 0.0, "c1 ended at {}", fitted.values[0]);
    fitted.model.check_parameters().unwrap();
}
