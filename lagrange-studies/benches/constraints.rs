//! What a constraint costs: one right-hand side (`M`, `f`, `G`, `γ` and the
//! saddle-point solve) of a constrained model against the same mechanism in
//! minimal coordinates (`M`, `f` and the `N × N` solve), and the operation
//! counts of the generated `G` and `γ` beside those of `M` and `f`.
//!
//! `cargo bench -p lagrange-studies --bench constraints`

use criterion::{Criterion, criterion_group};
use lagrange::dynamics::acceleration;
use lagrange::models::{CartesianPendulum, FourBar, Pendulum, SliderCrank};
use lagrange::nalgebra::{Vector1, Vector3};
use std::hint::black_box;

fn right_hand_sides(c: &mut Criterion) {
    let mut group = c.benchmark_group("constrained_rhs");

    // The pendulum: x, y with one rod against θ alone.
    let cartesian = CartesianPendulum::new(1.0, 1.0, 9.81);
    let theta = Pendulum::new(1.0, 1.0, 9.81);
    let (q, v) = cartesian.state(0.7, 1.3);
    let (qt, vt) = (Vector1::new(0.7), Vector1::new(1.3));
    // Same motion first: θ̈ from both, x = l sin θ ⇒ ẍ = l (cos θ θ̈ − sin θ θ̇²).
    let a = acceleration(&cartesian, 0.0, &q, &v).unwrap();
    let at = acceleration(&theta, 0.0, &qt, &vt).unwrap()[0];
    let want = 0.7f64.cos() * at - 0.7f64.sin() * 1.3 * 1.3;
    assert!((a[0] - want).abs() < 1e-12, "{} vs {want}", a[0]);
    group.bench_function("pendulum/cartesian_x_y_rod", |b| {
        b.iter(|| acceleration(&cartesian, black_box(0.0), black_box(&q), black_box(&v)))
    });
    group.bench_function("pendulum/minimal_theta", |b| {
        b.iter(|| acceleration(&theta, black_box(0.0), black_box(&qt), black_box(&vt)))
    });

    // The slider-crank: three coordinates and two loop constraints against
    // the crank angle alone.
    let crank = SliderCrank::engine();
    let minimal = crank.minimal();
    let (q, v) = crank.state(0.4, 20.0);
    let (qm, vm) = (Vector1::new(0.4), Vector1::new(20.0));
    let a = acceleration(&crank, 0.0, &q, &v).unwrap()[0];
    let am = acceleration(&minimal, 0.0, &qm, &vm).unwrap()[0];
    assert!((a - am).abs() < 1e-9 * am.abs().max(1.0), "{a} vs {am}");
    group.bench_function("slider_crank/redundant_3_coordinates_2_constraints", |b| {
        b.iter(|| acceleration(&crank, black_box(0.0), black_box(&q), black_box(&v)))
    });
    group.bench_function("slider_crank/minimal_crank_angle", |b| {
        b.iter(|| acceleration(&minimal, black_box(0.0), black_box(&qm), black_box(&vm)))
    });

    // The four-bar: three angles and two loop constraints against the
    // crank angle alone, the loop eliminated by hand (`MinimalFourBar`).
    let four_bar = FourBar::crank_rocker();
    let minimal = four_bar.minimal();
    let (q, v): (Vector3<f64>, Vector3<f64>) = four_bar.state(0.8, 12.0).unwrap();
    let (qm, vm) = (Vector1::new(0.8), Vector1::new(12.0));
    let a = acceleration(&four_bar, 0.0, &q, &v).unwrap()[0];
    let am = acceleration(&minimal, 0.0, &qm, &vm).unwrap()[0];
    assert!((a - am).abs() < 1e-9 * am.abs().max(1.0), "{a} vs {am}");
    group.bench_function("four_bar/redundant_3_coordinates_2_constraints", |b| {
        b.iter(|| acceleration(&four_bar, black_box(0.0), black_box(&q), black_box(&v)))
    });
    group.bench_function("four_bar/minimal_crank_angle", |b| {
        b.iter(|| acceleration(&minimal, black_box(0.0), black_box(&qm), black_box(&vm)))
    });
    group.finish();
}

criterion_group!(benches, right_hand_sides);

fn main() {
    op_counts::print();
    benches();
    Criterion::default().configure_from_args().final_summary();
}

/// The operation counts of the generated code, from the engine run on the
/// models' own source files (`src/models/`), as the macro runs it.
mod op_counts {
    use lagrange_engine::expr::cse;

    const SOURCES: [&str; 4] = [
        include_str!("../../src/models/cartesian_pendulum.rs"),
        include_str!("../../src/models/pendulum.rs"),
        include_str!("../../src/models/slider_crank.rs"),
        include_str!("../../src/models/four_bar.rs"),
    ];

    pub fn print() {
        println!("Operations of the generated code (after sharing; arithmetic + calls):");
        println!(
            "{:<20} {:>3} {:>3} {:>10} {:>10} {:>16}",
            "model", "N", "C", "M + f", "G + gamma", "M + f + G + gamma"
        );
        for source in SOURCES {
            let file = source.parse().expect("a model file lexes");
            for tokens in lagrange_engine::invocations(file) {
                let derived = lagrange_engine::derive(tokens).expect("a shared model derives");
                let name = derived.model.name.to_string();
                let (mf, _) = derived.op_counts();
                let together = derived.equations.constraints.as_ref().map(|c| {
                    let n = derived.model.dof();
                    let mut roots: Vec<_> = (0..n)
                        .flat_map(|i| (i..n).map(move |j| (i, j)))
                        .map(|(i, j)| derived.equations.mass[i][j])
                        .collect();
                    roots.extend(&derived.equations.forcing);
                    roots.extend(c.jacobian.iter().flatten());
                    roots.extend(&c.bias);
                    (c.values.len(), cse::shared_ops(&derived.model.pool, &roots))
                });
                let g = derived.constraint_op_counts().map(|(shared, _)| shared);
                println!(
                    "{:<20} {:>3} {:>3} {:>10} {:>10} {:>16}",
                    name,
                    derived.model.dof(),
                    together.map_or(0, |(c, _)| c),
                    mf.total(),
                    g.map_or("-".into(), |g| g.total().to_string()),
                    together.map_or("-".into(), |(_, all)| all.total().to_string()),
                );
            }
        }
        println!();
    }
}
