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
