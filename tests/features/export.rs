//! Trajectories out of Rust: CSV (feature `csv`) read back to the same
//! numbers, with the model's names in the header and a constrained model's
//! multipliers.

use lagrange::export::write_csv;
use lagrange::models::{CartesianPendulum, DoublePendulum};
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;

/// The CSV text as a header and rows of numbers.
fn read(bytes: Vec<u8>) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = String::from_utf8(bytes).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

#[test]
fn a_trajectory_as_csv_reads_back_to_the_same_numbers() {
    let (model, q0, v0) = DoublePendulum::regular();
    let times: Vec<f64> = (0..=20).map(|k| 0.1 * k as f64).collect();
    let run = Dop853::new()
        .integrate(&model, 0.0, q0, v0, &times)
        .unwrap();
    let mut out = Vec::new();
    write_csv(&model, &run, &mut out).unwrap();
    let (header, rows) = read(out);
    assert_eq!(
        header,
        [
            "t",
            "theta1",
            "theta2",
            "theta1_dot",
            "theta2_dot",
            "energy"
        ]
    );
    assert_eq!(rows.len(), run.len());
    for (row, s) in rows.iter().zip(run.iter()) {
        // Shortest round-trip formatting: the very same f64 values.
        let expected = [
            s.t,
            s.q[0],
            s.q[1],
            s.qdot[0],
            s.qdot[1],
            model.energy(s.t, &s.q, &s.qdot),
        ];
        assert_eq!(row.as_slice(), expected.as_slice());
    }
}

#[test]
fn a_constrained_trajectory_as_csv_carries_its_multipliers() {
    let pendulum = CartesianPendulum::new(1.3, 0.7, 9.81);
    let (q0, v0) = pendulum.state(1.0, 0.0);
    let times: Vec<f64> = (0..=10).map(|k| 0.2 * k as f64).collect();
    let run = Dop853::new()
        .rtol(1e-12)
        .atol(1e-12)
        .integrate(&pendulum, 0.0, q0, v0, &times)
        .unwrap();
    let mut out = Vec::new();
    write_csv(&pendulum, &run, &mut out).unwrap();
    let (header, rows) = read(out);
    assert_eq!(
        header,
        ["t", "x", "y", "x_dot", "y_dot", "energy", "lambda_rod"]
    );
    for row in rows {
        let (q, v) = (Vector2::new(row[1], row[2]), Vector2::new(row[3], row[4]));
        // φ = x² + y² − l²: the rod force on the bob is −2 λ (x, y), a
        // tension of 2 l λ, equal to m (g cos θ + l θ̇²) at any state on the
        // circle; the saddle-point solve is exact to rounding (1e-12 of m g).
        let tension = 2.0 * pendulum.l * row[6];
        let err = (tension - pendulum.tension(&q, &v)).abs();
        assert!(
            err < 1e-12 * pendulum.m * pendulum.g,
            "t = {}: {err}",
            row[0]
        );
    }
}

/// A run with events: each event a row among the samples, in time order,
/// named in the `event` column (the bouncing ball's bounces).
#[test]
fn events_are_rows_of_the_csv() {
    use lagrange::models::BouncingBall;
    use lagrange::nalgebra::Vector1;
    let ball = BouncingBall::new(1.0, 9.81);
    let events = Events::new().with(BouncingBall::floor(0.9));
    let times: Vec<f64> = (0..=20).map(|k| 0.1 * k as f64).collect();
    let run = Dopri5::new()
        .integrate_with_events(
            &ball,
            0.0,
            Vector1::new(1.0),
            Vector1::new(0.0),
            &times,
            &events,
        )
        .unwrap();
    let mut out = Vec::new();
    write_csv(&ball, &run, &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("t,z,z_dot,energy,event"));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), run.len() + run.events().len());
    let bounces: Vec<&Vec<&str>> = rows.iter().filter(|r| r[4] == "floor").collect();
    assert_eq!(bounces.len(), run.events().len());
    for (row, event) in bounces.iter().zip(run.events()) {
        assert_eq!(row[0].parse::<f64>().unwrap(), event.t);
    }
    // In time order.
    let t: Vec<f64> = rows.iter().map(|r| r[0].parse().unwrap()).collect();
    assert!(t.windows(2).all(|w| w[0] <= w[1]));
}

/// Serde (feature `serde`): a failed run, its error and the samples before
/// it, through JSON and back, equal; an error naming a constraint too.
#[test]
fn failures_and_trajectories_round_trip_through_serde() {
    use lagrange::{Failure, IntegrationError, InvalidInput};
    let (model, q0, v0) = DoublePendulum::regular();
    let times: Vec<f64> = (0..=40).map(|k| 0.25 * k as f64).collect();
    // A step budget too small for 10 s: `TooManySteps`, with samples.
    let failure = Dopri5::new()
        .max_steps(40)
        .integrate(&model, 0.0, q0, v0, &times)
        .unwrap_err();
    assert!(matches!(
        failure.error,
        IntegrationError::TooManySteps { .. }
    ));
    assert!(!failure.trajectory.is_empty());
    let json = serde_json::to_string(&*failure).unwrap();
    let back: Failure<f64, 2> = serde_json::from_str(&json).unwrap();
    assert_eq!(back, *failure);
    assert_eq!(back.trajectory.stats(), failure.trajectory.stats());

    // A refused start names the constraint it violates.
    let pendulum = CartesianPendulum::new(1.0, 1.0, 9.81);
    let strict = pendulum.with_initial_conditions(InitialConditions::Reject);
    let (q, v) = pendulum.state(0.5, 0.0);
    let refused = Dopri5::new()
        .integrate(&strict, 0.0, q * 1.01, v, &[1.0])
        .unwrap_err();
    let json = serde_json::to_string(&refused.error).unwrap();
    assert!(json.contains("\"rod\""), "{json}");
    let back: IntegrationError<f64, 2> = serde_json::from_str(&json).unwrap();
    assert_eq!(back, refused.error);
    assert!(matches!(
        back,
        IntegrationError::InvalidInput(InvalidInput::InconsistentInitialConditions {
            constraint: "rod",
            ..
        })
    ));
}

lagrange::lagrangian! {
    /// A scene's model whose parameters load from a file: a chain with a
    /// motor torque at its pivot as an input.
    #[lagrange(serde)]
    pub struct SceneChain {
        const N = 3;
        coordinates: theta[N];
        parameters: m[N], l[N], g;
        inputs: torque;
        let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));
        let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));
        kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2));
        potential: sum(i in 0..N, m[i]*g*y[i]);
        forces: theta[0] = torque;
    }
}

/// `#[lagrange(serde)]`: a model's parameters written to and read from
/// JSON (a scene file); its control inputs are not stored and come back
/// unset, which the integrators refuse until they are set.
#[test]
fn a_models_parameters_load_from_a_file() {
    let json = r#"{ "m": [1.0, 0.5, 0.25], "l": [0.4, 0.3, 0.2], "g": 9.81 }"#;
    let chain: SceneChain = serde_json::from_str(json).unwrap();
    assert_eq!(chain.m, [1.0, 0.5, 0.25]);
    assert_eq!((chain.l, chain.g), ([0.4, 0.3, 0.2], 9.81));
    assert!(chain.torque.is_nan(), "inputs come back unset");
    let q0 = lagrange::nalgebra::SVector::<f64, 3>::new(0.3, 0.2, 0.1);
    let v0 = lagrange::nalgebra::SVector::zeros();
    assert!(
        Dopri5::new()
            .integrate(&chain, 0.0, q0, v0, &[1.0])
            .is_err()
    );

    let driven = chain.with_inputs(&lagrange::nalgebra::Vector1::new(0.5));
    let written = serde_json::to_string(&driven).unwrap();
    assert!(!written.contains("torque"), "{written}");
    let back: SceneChain = serde_json::from_str(&written).unwrap();
    assert_eq!((back.m, back.l, back.g), (chain.m, chain.l, chain.g));
}
