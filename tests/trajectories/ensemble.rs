//! Ensembles in parallel: generated models, their trajectories and a
//! `Stepper` are plain `Send + Sync` values, so a sweep is a rayon
//! `par_iter`, and each member's result is the same on any thread.

use lagrange::models::DoublePendulum;
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;
use rayon::prelude::*;

fn send_sync<T: Send + Sync>() {}

#[test]
fn a_sweep_in_parallel_equals_the_sweep_in_sequence() {
    send_sync::<DoublePendulum<f64>>();
    send_sync::<Trajectory<f64, 2>>();
    send_sync::<Stepper<'static, DoublePendulum<f64>, Dopri5<f64>, 2>>();
    let model = DoublePendulum::unit();
    let angles: Vec<(f64, f64)> = (0..64)
        .map(|k| {
            (
                -3.0 + 6.0 * (k % 8) as f64 / 7.0,
                -3.0 + 6.0 * (k / 8) as f64 / 7.0,
            )
        })
        .collect();
    let end = |&(a, b): &(f64, f64)| {
        let q0 = Vector2::new(a, b);
        let run = Dop853::new()
            .integrate(&model, 0.0, q0, Vector2::zeros(), &[2.0])
            .unwrap();
        run.last().unwrap().q
    };
    let parallel: Vec<Vector2<f64>> = angles.par_iter().map(end).collect();
    let serial: Vec<Vector2<f64>> = angles.iter().map(end).collect();
    assert_eq!(parallel, serial);
}
