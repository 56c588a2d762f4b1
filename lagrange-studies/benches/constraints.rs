//! What a constraint costs: one right-hand side (`M`, `f`, `G`, `γ` and the
//! saddle-point solve) of a constrained model against the same mechanism in
//! minimal coordinates (`M`, `f` and the `N × N` solve), and the operation
//! counts of the generated `G` and `γ` beside those of `M` and `f`.
//!
//! `cargo bench -p lagrange-studies --bench constraints`

use criterion::{Criterion, criterion_group};
use lagrange::Lagrangian;
use lagrange::dynamics::acceleration;
use lagrange::models::{CartesianPendulum, FourBar, Pendulum, SliderCrank};
use lagrange::nalgebra::{SVector, Vector1, Vector3};
use std::hint::black_box;

/// One right-hand side of `model` at `(0, q, v)`, its result kept from the
/// optimizer by `std::hint::black_box` and nothing handed back to
/// criterion: criterion 0.5's own `black_box` (without its nightly
/// `real_blackbox` feature) reads what a routine returns byte by byte
/// through volatile loads, about a hundred of them for this `Result` with
/// its error variant, which took longer than the Cartesian pendulum's whole
/// right-hand side and grew with `N`, not with the work measured.
#[inline(always)]
fn one_rhs<L: Lagrangian<N, Scalar = f64>, const N: usize>(
    model: &L,
    q: &SVector<f64, N>,
    v: &SVector<f64, N>,
) {
    let _ = black_box(acceleration(
        model,
        black_box(0.0),
        black_box(q),
        black_box(v),
    ));
}

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
        b.iter(|| one_rhs(&cartesian, &q, &v))
    });
    group.bench_function("pendulum/minimal_theta", |b| {
        b.iter(|| one_rhs(&theta, &qt, &vt))
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
        b.iter(|| one_rhs(&crank, &q, &v))
    });
    group.bench_function("slider_crank/minimal_crank_angle", |b| {
        b.iter(|| one_rhs(&minimal, &qm, &vm))
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
        b.iter(|| one_rhs(&four_bar, &q, &v))
    });
    group.bench_function("four_bar/minimal_crank_angle", |b| {
        b.iter(|| one_rhs(&minimal, &qm, &vm))
    });
    group.finish();
}

criterion_group!(benches, right_hand_sides);

fn main() {
    op_counts::print();
    benches();
    Criterion::default().configure_from_args().final_summary();
    if std::env::args().any(|a| a == "--bench") {
        plain_loops::print();
    }
}

/// The same right-hand sides in a plain loop, one `#[inline(never)]` loop
/// per model: criterion's loop around a closure is one harness, and the
/// ratio of two short right-hand sides depends on the harness (how much of
/// the call overlaps the next, what is inlined where). Ten batches of each
/// model, the two of a pair interleaved; the best batch and the median.
mod plain_loops {
    use super::*;
    use std::time::Instant;

    const CALLS: u32 = 1_000_000;
    const BATCHES: usize = 10;

    #[inline(never)]
    fn batch<L: Lagrangian<N, Scalar = f64>, const N: usize>(
        model: &L,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
    ) -> f64 {
        let start = Instant::now();
        for _ in 0..CALLS {
            one_rhs(model, q, v);
        }
        start.elapsed().as_secs_f64() * 1e9 / f64::from(CALLS)
    }

    fn pair<A, B, const N: usize, const M: usize>(
        name: &str,
        (a, qa, va): (&A, SVector<f64, N>, SVector<f64, N>),
        (b, qb, vb): (&B, SVector<f64, M>, SVector<f64, M>),
    ) where
        A: Lagrangian<N, Scalar = f64>,
        B: Lagrangian<M, Scalar = f64>,
    {
        let (mut ta, mut tb) = (Vec::new(), Vec::new());
        for _ in 0..BATCHES {
            ta.push(batch(a, &qa, &va));
            tb.push(batch(b, &qb, &vb));
        }
        let best = |t: &[f64]| t.iter().copied().fold(f64::INFINITY, f64::min);
        let median = |t: &mut Vec<f64>| {
            t.sort_by(f64::total_cmp);
            t[t.len() / 2]
        };
        let (ba, bb) = (best(&ta), best(&tb));
        let (ma, mb) = (median(&mut ta), median(&mut tb));
        println!(
            "{name:<14} {ba:>10.1} {bb:>10.1} {:>10.2} {ma:>12.1} {mb:>12.1} {:>12.2}",
            ba / bb,
            ma / mb
        );
    }

    pub fn print() {
        println!();
        println!("Plain loops, ns per right-hand side ({BATCHES} batches of {CALLS} calls each):");
        println!(
            "{:<14} {:>10} {:>10} {:>10} {:>12} {:>12} {:>12}",
            "model", "best con.", "best min.", "ratio", "median con.", "median min.", "ratio"
        );
        let cartesian = CartesianPendulum::new(1.0, 1.0, 9.81);
        let (q, v) = cartesian.state(0.7, 1.3);
        let theta = Pendulum::new(1.0, 1.0, 9.81);
        let (qt, vt) = (Vector1::new(0.7), Vector1::new(1.3));
        pair("pendulum", (&cartesian, q, v), (&theta, qt, vt));
        let crank = SliderCrank::engine();
        let (q, v) = crank.state(0.4, 20.0);
        let (qm, vm) = (Vector1::new(0.4), Vector1::new(20.0));
        pair("slider_crank", (&crank, q, v), (&crank.minimal(), qm, vm));
        let four_bar = FourBar::crank_rocker();
        let (q, v): (Vector3<f64>, Vector3<f64>) = four_bar.state(0.8, 12.0).unwrap();
        let (qm, vm) = (Vector1::new(0.8), Vector1::new(12.0));
        pair("four_bar", (&four_bar, q, v), (&four_bar.minimal(), qm, vm));
    }
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
