//! What one 60 Hz frame of the 5-link chain (`lagrange::models::Chain`)
//! costs, in `f32` and `f64`, advanced by a `Stepper` against one
//! `integrate` call per frame (which validates, allocates a trajectory,
//! and for an adaptive method evaluates a fresh first slope and guesses an
//! initial step every frame). Rk4 with one step per frame and Dopri5 at its
//! default tolerance. Prints a table (best-of-five mean over 600 frames,
//! right-hand sides per frame), then criterion's measurements.
//!
//! `cargo bench -p lagrange-studies --bench frame`

use std::hint::black_box;
use std::time::Instant;

use criterion::{Criterion, criterion_group};
use lagrange::StepMethod;
use lagrange::models::Chain;
use lagrange::nalgebra::{RealField, SVector, convert};
use lagrange::prelude::*;

const N: usize = Chain::<f64>::DOF;
const HZ: f64 = 60.0;
const FRAMES: usize = 600;

fn chain<S: RealField + Copy>() -> (Chain<S>, SVector<S, N>) {
    let c = |x: f64| -> S { convert(x) };
    let model = Chain::new([c(0.2); N], [c(0.2); N]);
    let bent = SVector::from([1.6, 1.4, 1.2, 1.0, 0.8].map(c));
    (model, bent)
}

fn frame_time<S: RealField + Copy>(k: usize) -> S {
    convert(k as f64 / HZ)
}

/// `FRAMES` frames in a stepper: (µs per frame, rhs per frame).
fn stepper<S, M>(method: M) -> (f64, f64)
where
    S: RealField + Copy,
    M: StepMethod<S> + Copy,
{
    best_of_five(|| {
        let start = Instant::now();
        let evals = stepped::<S, M>(method);
        (start.elapsed().as_secs_f64(), evals)
    })
}

/// `FRAMES` frames of the chain from its release in a stepper; the
/// right-hand sides it took.
fn stepped<S: RealField + Copy, M: StepMethod<S>>(method: M) -> usize {
    let (model, q0) = chain::<S>();
    let mut stepper = Stepper::new(model, method, S::zero(), q0, SVector::zeros()).unwrap();
    for k in 1..=FRAMES {
        stepper.advance_to(frame_time(k)).unwrap();
        black_box(stepper.q());
    }
    stepper.stats().rhs_evals
}

/// `FRAMES` frames, one `integrate` call each.
fn per_frame<S, I>(method: I) -> (f64, f64)
where
    S: RealField + Copy,
    I: Integrator<S>,
{
    best_of_five(|| {
        let start = Instant::now();
        let evals = called::<S, I>(&method);
        (start.elapsed().as_secs_f64(), evals)
    })
}

/// `FRAMES` frames of the chain from its release, one `integrate` call
/// each; the right-hand sides they took.
fn called<S: RealField + Copy, I: Integrator<S>>(method: &I) -> usize {
    let (model, q0) = chain::<S>();
    let (mut q, mut v, mut evals) = (q0, SVector::zeros(), 0);
    for k in 1..=FRAMES {
        let (t0, t1) = (frame_time(k - 1), frame_time(k));
        let run = method.integrate(&model, t0, q, v, &[t1]).unwrap();
        let end = run.last().unwrap();
        (q, v, evals) = (end.q, end.qdot, evals + run.stats().rhs_evals);
        black_box(&q);
    }
    evals
}

fn best_of_five(mut run: impl FnMut() -> (f64, usize)) -> (f64, f64) {
    let mut best = (f64::INFINITY, 0);
    for _ in 0..5 {
        let (seconds, evals) = run();
        if seconds < best.0 {
            best = (seconds, evals);
        }
    }
    (best.0 * 1e6 / FRAMES as f64, best.1 as f64 / FRAMES as f64)
}

fn row(what: &str, (stepped, stepped_evals): (f64, f64), (called, called_evals): (f64, f64)) {
    println!(
        "| {what} | {stepped:.2} | {stepped_evals:.1} | {called:.2} | {called_evals:.1} | {:.2} |",
        called / stepped
    );
}

fn table() {
    println!("5-link chain, {FRAMES} frames at {HZ} Hz:");
    println!(
        "| method, scalar | Stepper µs/frame | rhs/frame | integrate per frame µs/frame | rhs/frame | ratio |"
    );
    println!("|---|---:|---:|---:|---:|---:|");
    let h = 1.0 / HZ;
    row(
        "Rk4 h = 1/60, f32",
        stepper(Rk4::new(h as f32)),
        per_frame(Rk4::new(h as f32)),
    );
    row(
        "Rk4 h = 1/60, f64",
        stepper(Rk4::new(h)),
        per_frame(Rk4::new(h)),
    );
    row(
        "Dopri5 default tol, f32",
        stepper(Dopri5::<f32>::new()),
        per_frame(Dopri5::<f32>::new()),
    );
    row(
        "Dopri5 default tol, f64",
        stepper(Dopri5::<f64>::new()),
        per_frame(Dopri5::<f64>::new()),
    );
}

/// Criterion measures runs of `FRAMES` frames from the release, each from
/// a fresh stepper (its construction included, 1/600 of it per frame): a
/// stepper advanced without end would run an `f32` clock past the point
/// where a frame no longer changes it.
fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("frame");
    group.bench_function("chain5/f32/dopri5/stepper_600_frames", |b| {
        b.iter(|| stepped::<f32, _>(Dopri5::new()))
    });
    group.bench_function("chain5/f64/dopri5/stepper_600_frames", |b| {
        b.iter(|| stepped::<f64, _>(Dopri5::new()))
    });
    group.bench_function("chain5/f64/dopri5/integrate_per_frame_600_frames", |b| {
        b.iter(|| called::<f64, _>(&Dopri5::new()))
    });
    group.finish();
}

criterion_group!(benches, bench);

fn main() {
    table();
    benches();
    Criterion::default().configure_from_args().final_summary();
}
