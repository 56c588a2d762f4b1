//! The generated double pendulum `M + f` against a hand-written,
//! hand-optimised version of the same equations.
//!
//! `cargo bench -p lagrange-studies --bench double_pendulum`

use criterion::{Criterion, criterion_group, criterion_main};
use lagrange::models::DoublePendulum;
use lagrange::nalgebra::{Matrix2, Vector2};
use std::hint::black_box;

/// The textbook equations written by hand: one `sin_cos` of the angle
/// difference, one `sin` per angle, shared products computed once.
#[inline]
fn hand_written(
    p: &DoublePendulum,
    q: &Vector2<f64>,
    qd: &Vector2<f64>,
) -> (Matrix2<f64>, Vector2<f64>) {
    let (s, c) = (q[0] - q[1]).sin_cos();
    let m12 = p.m2 * p.l1 * p.l2;
    let mc = m12 * c;
    let total = p.m1 + p.m2;
    let m = Matrix2::new(total * p.l1 * p.l1, mc, mc, p.m2 * p.l2 * p.l2);
    let f = Vector2::new(
        -m12 * qd[1] * qd[1] * s - total * p.g * p.l1 * q[0].sin(),
        m12 * qd[0] * qd[0] * s - p.m2 * p.g * p.l2 * q[1].sin(),
    );
    (m, f)
}

fn bench(c: &mut Criterion) {
    let p = DoublePendulum::new(1.0, 1.5, 1.0, 0.8, 9.81);
    let q = Vector2::new(2.0, 2.5);
    let qd = Vector2::new(-0.3, 0.7);
    // Same answer first: the comparison is only fair between equal results.
    let (mg, fg) = p.mass_matrix_and_forcing(0.0, &q, &qd);
    let (mh, fh) = hand_written(&p, &q, &qd);
    assert!((mg - mh).norm() < 1e-12 && (fg - fh).norm() < 1e-12);

    let mut group = c.benchmark_group("double_pendulum_mass_matrix_and_forcing");
    group.bench_function("generated", |b| {
        b.iter(|| p.mass_matrix_and_forcing(black_box(0.0), black_box(&q), black_box(&qd)))
    });
    group.bench_function("hand_written", |b| {
        b.iter(|| hand_written(black_box(&p), black_box(&q), black_box(&qd)))
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
