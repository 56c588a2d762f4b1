//! Ensembles in SIMD lanes against scalar steppers: the throughput of one
//! core on many states of one model, the double pendulum and the 5-link
//! chain (`lagrange::models`), in `f64` and `f32`, with RK4 and symplectic
//! Euler at a fixed step.
//!
//! Each round steps 64 states (a grid of starts, the same parameters)
//! through 60 frames of 1/60 s at `h = 1e-3` (17 steps a frame): once as
//! 64 scalar `Stepper`s, once as `Ensemble`s of 2, 4 or 8 lanes. Their
//! results are the same bits lane by lane (`tests/trajectories/ensemble.rs`);
//! the table is the time per state and step, and the scalar time over the
//! ensemble's: medians over interleaved rounds, with their range.
//!
//! On an x86-64 CPU with AVX2 the default build steps the ensembles in
//! code compiled for AVX2, chosen at run time (its scalar runs stay SSE2);
//! built for the CPU, everything is, the scalar runs too:
//!
//! ```text
//! cargo bench -p lagrange-studies --bench ensemble
//! RUSTFLAGS="-C target-cpu=native" cargo bench -p lagrange-studies --bench ensemble --target-dir target/native
//! ```
//!
//! `-- --rounds R` sets the rounds (default 7). `-- --adaptive`: the
//! adaptive ensemble (`AdaptiveEnsemble`, Dormand–Prince with one step
//! shared by four `f64` lanes) against scalar `Dopri5` steppers at
//! `rtol = atol = 1e-8`, the same grid and frames, with the steps the
//! sharing costs.

use std::hint::black_box;
use std::time::Instant;

use lagrange::ensemble::{
    AdaptiveEnsemble, AutoF32x4, AutoF32x8, AutoF64x2, AutoF64x4, Ensemble, LaneModel,
};
use lagrange::models::{Chain, DoublePendulum};
use lagrange::nalgebra::{RealField, SVector, SimdRealField, SimdValue, convert, zero};
use lagrange::prelude::*;
use lagrange::{LaneStep, StepMethod};

const STATES: usize = 64;
const FRAMES: usize = 60;
const HZ: f64 = 60.0;
const H: f64 = 1e-3;

/// A start of the grid: state `i` of `STATES`, every angle between −1.2
/// and 1.2 rad, at rest.
fn start<S: RealField + Copy, const N: usize>(i: usize) -> (SVector<S, N>, SVector<S, N>) {
    let q = SVector::from_fn(|k, _| {
        let x = ((i * (2 * k + 3) + k) % STATES) as f64 / STATES as f64;
        convert(-1.2 + 2.4 * x)
    });
    (q, SVector::zeros())
}

fn frame<S: RealField + Copy>(k: usize) -> S {
    convert(k as f64 / HZ)
}

/// Seconds for `STATES` scalar steppers through every frame.
fn scalar<L, M, const N: usize>(model: L, method: M) -> f64
where
    L: Lagrangian<N> + Copy,
    M: StepMethod<L::Scalar> + Copy,
{
    let clock = Instant::now();
    for i in 0..STATES {
        let (q0, qdot0) = start(i);
        let mut stepper = Stepper::new(model, method, zero(), q0, qdot0).unwrap();
        for k in 1..=FRAMES {
            stepper.advance_to(frame(k)).unwrap();
        }
        black_box(stepper.q());
    }
    clock.elapsed().as_secs_f64()
}

/// Seconds for the same states in ensembles of the model's lanes.
fn lanes<L, M, const N: usize>(model: L, method: M) -> f64
where
    L: LaneModel<N> + Copy,
    M: LaneStep<<L::Lanes as SimdValue>::Element> + Copy,
{
    let width = L::Lanes::LANES;
    let clock = Instant::now();
    for group in 0..STATES / width {
        let (q0, qdot0): (Vec<_>, Vec<_>) = (0..width).map(|j| start(group * width + j)).unzip();
        let mut ensemble = Ensemble::new(model, method, zero(), &q0, &qdot0).unwrap();
        for k in 1..=FRAMES {
            ensemble.advance_to(frame(k)).unwrap();
        }
        black_box(ensemble.lanes());
    }
    clock.elapsed().as_secs_f64()
}

fn pendulum<S: SimdRealField + Copy>() -> DoublePendulum<S>
where
    S::Element: RealField + Copy,
{
    let c = |x: f64| S::splat(convert(x));
    DoublePendulum::new(c(1.0), c(1.0), c(1.0), c(1.0), c(9.81))
}

fn chain<S: SimdRealField + Copy>() -> Chain<S>
where
    S::Element: RealField + Copy,
{
    let c = |x: f64| S::splat(convert(x));
    Chain::new([c(1.0); 5], [c(1.0); 5])
}

/// One row: the scalar run and the ensemble's, interleaved over `rounds`.
struct Row {
    name: String,
    scalar: Vec<f64>,
    lanes: Vec<f64>,
}

fn median(mut x: Vec<f64>) -> f64 {
    x.sort_by(f64::total_cmp);
    x[x.len() / 2]
}

/// What a step shared by the lanes would cost an adaptive method: the
/// steps Dop853 (rtol = atol = 1e-9) takes for each state of the grid
/// over the same second, alone; in groups of `width` lanes sharing a step,
/// each group takes at least its largest count, for the sum of the
/// counts' work. Returns (min, median, max steps, the share of the lanes'
/// steps that are a state's own).
fn shared_step_share<L: Lagrangian<N, Scalar = f64> + Copy, const N: usize>(
    model: L,
    width: usize,
) -> (usize, usize, usize, f64) {
    let method = Dop853::new().rtol(1e-9).atol(1e-9);
    let counts: Vec<usize> = (0..STATES)
        .map(|i| {
            let (q0, qdot0) = start(i);
            let mut stepper = Stepper::new(model, method, 0.0, q0, qdot0).unwrap();
            stepper.advance_to(1.0).unwrap();
            stepper.stats().steps_accepted + stepper.stats().steps_rejected
        })
        .collect();
    let own: usize = counts.iter().sum();
    let shared: usize = counts
        .chunks(width)
        .map(|g| g.len() * g.iter().max().unwrap())
        .sum();
    let mut sorted = counts.clone();
    sorted.sort_unstable();
    (
        sorted[0],
        sorted[STATES / 2],
        sorted[STATES - 1],
        own as f64 / shared as f64,
    )
}

/// Seconds for `STATES` scalar `Dopri5` steppers through every frame, and
/// their steps (accepted and rejected), at `rtol = atol = tol`.
fn scalar_adaptive<L, const N: usize>(model: L, tol: f64) -> (f64, usize)
where
    L: Lagrangian<N, Scalar = f64> + Copy,
{
    let method = Dopri5::new().rtol(tol).atol(tol);
    let clock = Instant::now();
    let mut steps = 0;
    for i in 0..STATES {
        let (q0, qdot0) = start(i);
        let mut stepper = Stepper::new(model, method, 0.0, q0, qdot0).unwrap();
        for k in 1..=FRAMES {
            stepper.advance_to(frame(k)).unwrap();
        }
        steps += stepper.stats().steps_accepted + stepper.stats().steps_rejected;
        black_box(stepper.q());
    }
    (clock.elapsed().as_secs_f64(), steps)
}

/// The same states in adaptive ensembles of four `f64` lanes, one step
/// shared by the lanes: seconds, and the steps of every lane together.
fn lanes_adaptive<L, const N: usize>(model: L, tol: f64) -> (f64, usize)
where
    L: LaneModel<N, Lanes = AutoF64x4> + Copy,
{
    let method = Dopri5::new().rtol(tol).atol(tol);
    let width = 4;
    let clock = Instant::now();
    let mut steps = 0;
    for group in 0..STATES / width {
        let (q0, qdot0): (Vec<_>, Vec<_>) = (0..width).map(|j| start(group * width + j)).unzip();
        let mut ensemble = AdaptiveEnsemble::new(model, method, 0.0, &q0, &qdot0).unwrap();
        for k in 1..=FRAMES {
            ensemble.advance_to(frame(k)).unwrap();
        }
        steps += width * (ensemble.stats().steps_accepted + ensemble.stats().steps_rejected);
        black_box(ensemble.q(0));
    }
    (clock.elapsed().as_secs_f64(), steps)
}

/// The adaptive ensemble against scalar `Dopri5` steppers (`--adaptive`):
/// time per state over the second, the scalar's over the lanes', and the
/// steps the shared step costs over the states' own.
fn adaptive(rounds: usize) {
    type Run = Box<dyn Fn() -> (f64, usize)>;
    let tol = 1e-8;
    let cases: Vec<(&str, Run, Run)> = vec![
        (
            "double pendulum",
            Box::new(move || scalar_adaptive(pendulum::<f64>(), tol)),
            Box::new(move || lanes_adaptive(pendulum::<AutoF64x4>(), tol)),
        ),
        (
            "5-link chain",
            Box::new(move || scalar_adaptive(chain::<f64>(), tol)),
            Box::new(move || lanes_adaptive(chain::<AutoF64x4>(), tol)),
        ),
    ];
    println!(
        "Dopri5 at rtol = atol = {tol:e}, {STATES} states through {FRAMES} frames of 1/{HZ} s: \
         scalar steppers against adaptive ensembles of four f64 lanes sharing a step; \
         µs per state, medians of {rounds} interleaved rounds (range of the ratio)\n"
    );
    println!("| model | scalar | lanes | scalar / lanes | steps, lanes / scalar |");
    println!("|---|---:|---:|---:|---:|");
    for (name, run_scalar, run_lanes) in &cases {
        let (mut s, mut l) = (Vec::new(), Vec::new());
        let (mut steps_scalar, mut steps_lanes) = (0, 0);
        for round in 0..=rounds {
            let ((ts, ns), (tl, nl)) = if round % 2 == 0 {
                let a = run_scalar();
                (a, run_lanes())
            } else {
                let b = run_lanes();
                (run_scalar(), b)
            };
            if round > 0 {
                s.push(ts);
                l.push(tl);
            }
            (steps_scalar, steps_lanes) = (ns, nl);
        }
        let ratios: Vec<f64> = s.iter().zip(&l).map(|(a, b)| a / b).collect();
        let (lo, hi) = ratios
            .iter()
            .fold((f64::INFINITY, 0.0_f64), |(lo, hi), &r| {
                (lo.min(r), hi.max(r))
            });
        let per = 1e6 / STATES as f64;
        println!(
            "| {name} | {:.1} | {:.1} | {:.2} ({lo:.2}–{hi:.2}) | {:.2} |",
            median(s) * per,
            median(l) * per,
            median(ratios),
            steps_lanes as f64 / steps_scalar as f64
        );
    }
}

/// Nanoseconds per state for `M` and `f` alone: four scalar evaluations
/// against one on four lanes (`--parts`).
fn parts() {
    fn time(mut f: impl FnMut(usize)) -> f64 {
        let reps = 200_000;
        let clock = Instant::now();
        for i in 0..reps {
            f(i);
        }
        clock.elapsed().as_secs_f64() / reps as f64 * 1e9
    }
    let p64 = pendulum::<f64>();
    let p4 = pendulum::<AutoF64x4>();
    let c64 = chain::<f64>();
    let c4 = chain::<AutoF64x4>();
    let c8 = chain::<AutoF32x8>();
    let c32 = chain::<f32>();
    let q2: Vec<(SVector<f64, 2>, SVector<f64, 2>)> = (0..4).map(start).collect();
    let q5: Vec<(SVector<f64, 5>, SVector<f64, 5>)> = (0..4).map(start).collect();
    let q5f: Vec<(SVector<f32, 5>, SVector<f32, 5>)> = (0..8).map(start).collect();
    let lanes4 = |x: &[SVector<f64, 5>]| {
        SVector::<AutoF64x4, 5>::from_fn(|i, _| AutoF64x4::new(x[0][i], x[1][i], x[2][i], x[3][i]))
    };
    let q5l = lanes4(&q5.iter().map(|s| s.0).collect::<Vec<_>>());
    let q2l = SVector::<AutoF64x4, 2>::from_fn(|i, _| {
        AutoF64x4::new(q2[0].0[i], q2[1].0[i], q2[2].0[i], q2[3].0[i])
    });
    let q5fl = SVector::<AutoF32x8, 5>::from_fn(|i, _| {
        let mut v = AutoF32x8::splat(0.0);
        for (j, s) in q5f.iter().enumerate() {
            v.replace(j, s.0[i]);
        }
        v
    });
    let z = |_| 0.0;
    println!("M and f alone, ns per state:");
    println!(
        "  pendulum f64 scalar {:.1}",
        time(|i| {
            black_box(p64.mass_matrix_and_forcing(z(i), black_box(&q2[i % 4].0), &q2[0].1));
        })
    );
    println!(
        "  pendulum f64 x4     {:.1}",
        time(|_| {
            black_box(p4.mass_matrix_and_forcing(AutoF64x4::splat(0.0), black_box(&q2l), &q2l));
        }) / 4.0
    );
    println!(
        "  chain f64 scalar    {:.1}",
        time(|i| {
            black_box(c64.mass_matrix_and_forcing(z(i), black_box(&q5[i % 4].0), &q5[0].1));
        })
    );
    println!(
        "  chain f64 x4        {:.1}",
        time(|_| {
            black_box(c4.mass_matrix_and_forcing(AutoF64x4::splat(0.0), black_box(&q5l), &q5l));
        }) / 4.0
    );
    println!(
        "  chain f32 scalar    {:.1}",
        time(|i| {
            black_box(c32.mass_matrix_and_forcing(0.0, black_box(&q5f[i % 8].0), &q5f[0].1));
        })
    );
    println!(
        "  chain f32 x8        {:.1}",
        time(|_| {
            black_box(c8.mass_matrix_and_forcing(AutoF32x8::splat(0.0), black_box(&q5fl), &q5fl));
        }) / 8.0
    );
    let angles: [f64; 5] = core::array::from_fn(|i| q5[0].0[i]);
    let angles4: [AutoF64x4; 5] = core::array::from_fn(|i| q5l[i]);
    println!("sines and cosines of 5 angles, ns per state:");
    println!(
        "  f64 scalar          {:.1}",
        time(|_| {
            black_box(lagrange::trig::sin_cos_array(black_box(angles)));
        })
    );
    println!(
        "  f64 x4              {:.1}",
        time(|_| {
            black_box(lagrange::trig::sin_cos_array(black_box(angles4)));
        }) / 4.0
    );
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.iter().any(|a| a == "--parts") {
        parts();
        return;
    }
    let rounds = args
        .iter()
        .position(|a| a == "--rounds")
        .and_then(|i| args.get(i + 1)?.parse().ok())
        .unwrap_or(7);
    if args.iter().any(|a| a == "--adaptive") {
        adaptive(rounds);
        return;
    }
    let h64 = H;
    let h32 = H as f32;
    let steps = (STATES * FRAMES * 17) as f64;
    type Case = (String, Box<dyn Fn() -> f64>, Box<dyn Fn() -> f64>);
    let cases: Vec<Case> = vec![
        (
            "double pendulum, RK4, f64 × 2".into(),
            Box::new(move || scalar(pendulum::<f64>(), Rk4::new(h64))),
            Box::new(move || lanes(pendulum::<AutoF64x2>(), Rk4::new(h64))),
        ),
        (
            "double pendulum, RK4, f64 × 4".into(),
            Box::new(move || scalar(pendulum::<f64>(), Rk4::new(h64))),
            Box::new(move || lanes(pendulum::<AutoF64x4>(), Rk4::new(h64))),
        ),
        (
            "double pendulum, RK4, f32 × 4".into(),
            Box::new(move || scalar(pendulum::<f32>(), Rk4::new(h32))),
            Box::new(move || lanes(pendulum::<AutoF32x4>(), Rk4::new(h32))),
        ),
        (
            "double pendulum, RK4, f32 × 8".into(),
            Box::new(move || scalar(pendulum::<f32>(), Rk4::new(h32))),
            Box::new(move || lanes(pendulum::<AutoF32x8>(), Rk4::new(h32))),
        ),
        (
            "double pendulum, symplectic Euler, f64 × 4".into(),
            Box::new(move || scalar(pendulum::<f64>(), SymplecticEuler::new(h64))),
            Box::new(move || lanes(pendulum::<AutoF64x4>(), SymplecticEuler::new(h64))),
        ),
        (
            "double pendulum, symplectic Euler, f32 × 8".into(),
            Box::new(move || scalar(pendulum::<f32>(), SymplecticEuler::new(h32))),
            Box::new(move || lanes(pendulum::<AutoF32x8>(), SymplecticEuler::new(h32))),
        ),
        (
            "5-link chain, RK4, f64 × 2".into(),
            Box::new(move || scalar(chain::<f64>(), Rk4::new(h64))),
            Box::new(move || lanes(chain::<AutoF64x2>(), Rk4::new(h64))),
        ),
        (
            "5-link chain, RK4, f64 × 4".into(),
            Box::new(move || scalar(chain::<f64>(), Rk4::new(h64))),
            Box::new(move || lanes(chain::<AutoF64x4>(), Rk4::new(h64))),
        ),
        (
            "5-link chain, RK4, f32 × 4".into(),
            Box::new(move || scalar(chain::<f32>(), Rk4::new(h32))),
            Box::new(move || lanes(chain::<AutoF32x4>(), Rk4::new(h32))),
        ),
        (
            "5-link chain, RK4, f32 × 8".into(),
            Box::new(move || scalar(chain::<f32>(), Rk4::new(h32))),
            Box::new(move || lanes(chain::<AutoF32x8>(), Rk4::new(h32))),
        ),
        (
            "5-link chain, symplectic Euler, f64 × 4".into(),
            Box::new(move || scalar(chain::<f64>(), SymplecticEuler::new(h64))),
            Box::new(move || lanes(chain::<AutoF64x4>(), SymplecticEuler::new(h64))),
        ),
        (
            "5-link chain, symplectic Euler, f32 × 8".into(),
            Box::new(move || scalar(chain::<f32>(), SymplecticEuler::new(h32))),
            Box::new(move || lanes(chain::<AutoF32x8>(), SymplecticEuler::new(h32))),
        ),
    ];
    let mut rows: Vec<Row> = cases
        .iter()
        .map(|(name, _, _)| Row {
            name: name.clone(),
            scalar: vec![],
            lanes: vec![],
        })
        .collect();
    // A warm-up round, then the rounds, every case in turn within each.
    for round in 0..=rounds {
        for ((_, run_scalar, run_lanes), row) in cases.iter().zip(&mut rows) {
            let (s, l) = if round % 2 == 0 {
                let s = run_scalar();
                (s, run_lanes())
            } else {
                let l = run_lanes();
                (run_scalar(), l)
            };
            if round > 0 {
                row.scalar.push(s);
                row.lanes.push(l);
            }
        }
    }
    let features: Vec<&str> = [
        ("sse2", cfg!(target_feature = "sse2")),
        ("avx", cfg!(target_feature = "avx")),
        ("avx2", cfg!(target_feature = "avx2")),
        ("fma", cfg!(target_feature = "fma")),
        ("avx512f", cfg!(target_feature = "avx512f")),
    ]
    .into_iter()
    .filter_map(|(name, on)| on.then_some(name))
    .collect();
    println!(
        "{STATES} states × {FRAMES} frames × 17 steps of h = {H}; {rounds} interleaved rounds; target features: {}",
        features.join(", ")
    );
    println!();
    println!(
        "| model, method, lanes | scalar ns/state-step | lanes ns/state-step | throughput × (median) | range |"
    );
    println!("|---|---:|---:|---:|---|");
    for row in rows {
        let ratios: Vec<f64> = row
            .scalar
            .iter()
            .zip(&row.lanes)
            .map(|(s, l)| s / l)
            .collect();
        let lo = ratios.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = ratios.iter().copied().fold(0.0, f64::max);
        println!(
            "| {} | {:.1} | {:.1} | {:.2} | {:.2}–{:.2} |",
            row.name,
            median(row.scalar) / steps * 1e9,
            median(row.lanes) / steps * 1e9,
            median(ratios),
            lo,
            hi
        );
    }

    println!();
    println!(
        "Adaptive methods, a step shared by four lanes: Dop853 at rtol = atol = 1e-9 over the same second, steps per state alone (min, median, max) and the share of a group's lane-steps that are a state's own"
    );
    println!();
    println!("| model | min | median | max | own share, groups of 4 |");
    println!("|---|---:|---:|---:|---:|");
    for (name, (min, med, max, share)) in [
        ("double pendulum", shared_step_share(pendulum::<f64>(), 4)),
        ("5-link chain", shared_step_share(chain::<f64>(), 4)),
    ] {
        println!("| {name} | {min} | {med} | {max} | {share:.2} |");
    }
}
