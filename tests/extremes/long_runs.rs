//! Numerical stability at the extremes: long runs. Ten times the steps must
//! cost no allocation and no byte more, for every integrator, and the only
//! memory that grows with the run is the samples the caller asked for.
//!
//! A global allocator counts this thread's allocations, the bytes they
//! request, and the peak of the bytes live at once; tests run on their own
//! threads, so the harness does not disturb the counts, and nothing is
//! printed inside a measured call.
//!
//! The figures (for STABILITY.md):
//! `cargo test --release --test suite -- extremes::long_runs:: --nocapture` (a few
//! seconds). Every integrator at 10⁶ steps (about twenty seconds) is
//! ignored in CI:
//! `cargo test --release --test suite -- extremes::long_runs:: --ignored --nocapture`.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::f64::consts::PI;
use std::time::Instant;

use lagrange::IntegrationResult;
use lagrange::Method;
use lagrange::models::Kepler;
use lagrange::nalgebra::{SVector, Vector2};
use lagrange::prelude::*;

struct CountingAllocator;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
    static BYTES: Cell<usize> = const { Cell::new(0) };
    /// Bytes allocated and not yet freed by this thread (negative if it
    /// frees another thread's memory).
    static LIVE: Cell<isize> = const { Cell::new(0) };
    static PEAK: Cell<isize> = const { Cell::new(0) };
}

/// Records an allocation of `new` bytes that replaces one of `old`.
fn count(new: usize, old: usize) {
    // `try_with`: the slots may be gone while the thread shuts down.
    let _ = ALLOCATIONS.try_with(|n| n.set(n.get() + 1));
    let _ = BYTES.try_with(|n| n.set(n.get() + new));
    let _ = LIVE.try_with(|live| {
        live.set(live.get() + new as isize - old as isize);
        let _ = PEAK.try_with(|peak| peak.set(peak.get().max(live.get())));
    });
}

// SAFETY: forwards every call to the system allocator unchanged.
unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count(layout.size(), 0);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        let _ = LIVE.try_with(|live| live.set(live.get() - layout.size() as isize));
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count(new_size, layout.size());
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

/// What one call cost in memory.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Usage {
    allocations: usize,
    bytes: usize,
    /// The most bytes live at once during the call beyond those live before
    /// it (the returned trajectory included).
    peak: isize,
}

fn measure<R>(run: impl FnOnce() -> R) -> (R, Usage) {
    let (allocations, bytes, live) = (
        ALLOCATIONS.with(Cell::get),
        BYTES.with(Cell::get),
        LIVE.with(Cell::get),
    );
    PEAK.with(|peak| peak.set(live));
    let result = run();
    let usage = Usage {
        allocations: ALLOCATIONS.with(Cell::get) - allocations,
        bytes: BYTES.with(Cell::get) - bytes,
        peak: PEAK.with(Cell::get) - live,
    };
    (result, usage)
}

const PERIOD: f64 = 2.0 * PI;

/// Fixed steps: T/200, so an orbit is 200 steps and 50 orbits are 10⁴.
const H: f64 = PERIOD / 200.0;

/// An e = 0.6 orbit from pericentre: the pericentre passages make the
/// adaptive methods change their step and reject some.
fn start() -> (Vector2<f64>, Vector2<f64>) {
    Kepler::new(1.0).pericentre(0.6)
}

const MAX_STEPS: usize = 10_000_000;

/// Every method, with the model whose Jacobians it uses: the ones that use
/// Jacobians twice, exact and by finite differences.
fn all() -> Vec<(Method, bool)> {
    Method::ALL
        .into_iter()
        .flat_map(|method| {
            let differenced = method.uses_jacobians().then_some((method, false));
            std::iter::once((method, true)).chain(differenced)
        })
        .collect()
}

/// Tolerances that give the adaptive methods about 200 steps per orbit,
/// like the fixed-step ones (DOP853 about 90 even at 1e-13), and a budget
/// above the 10⁵ steps they default to.
fn integrate<L: Lagrangian<2, Scalar = f64>>(
    method: Method,
    model: &L,
    times: &[f64],
) -> IntegrationResult<f64, 2> {
    let (q0, v0) = start();
    let tol = if method == Method::Dop853 {
        1e-13
    } else {
        1e-10
    };
    let integrator = method.integrator(H, tol);
    let integrator = if method.is_adaptive() {
        integrator.max_steps(MAX_STEPS)
    } else {
        integrator
    };
    integrator.integrate(model, 0.0, q0, v0, times)
}

/// One measured run over `orbits` periods with `samples` equally spaced
/// samples.
struct Run {
    trajectory: Trajectory<f64, 2>,
    usage: Usage,
    seconds: f64,
}

impl Run {
    fn steps(&self) -> usize {
        let stats = self.trajectory.stats();
        stats.steps_accepted + stats.steps_rejected
    }
}

fn run(method: Method, exact_jacobians: bool, orbits: usize, samples: usize) -> Run {
    let span = orbits as f64 * PERIOD;
    let times: Vec<f64> = (1..=samples)
        .map(|k| span * k as f64 / samples as f64)
        .collect();
    let clock = Instant::now();
    let (trajectory, usage) = if exact_jacobians {
        measure(|| integrate(method, &Kepler::new(1.0), &times))
    } else {
        measure(|| integrate(method, &Kepler::new(1.0).without_jacobians(), &times))
    };
    let seconds = clock.elapsed().as_secs_f64();
    let trajectory = trajectory.unwrap_or_else(|f| panic!("{method:?}: {}", f.error));
    assert_eq!(trajectory.len(), samples, "{method:?}");
    Run {
        trajectory,
        usage,
        seconds,
    }
}

fn name(method: Method, exact_jacobians: bool) -> String {
    match (method.uses_jacobians(), exact_jacobians) {
        (true, true) => format!("{method:?} (exact J)"),
        (true, false) => format!("{method:?} (FD J)"),
        _ => format!("{method:?}"),
    }
}

/// Runs `method` over `short` and `long` orbits with the same 100 samples
/// and checks that the long run, with ≥ 9× the steps, allocates exactly as
/// often, as many bytes, and peaks at the same live memory. A single
/// allocation per step, per Jacobian, per rejected step or per Newton
/// iteration would show as thousands.
fn assert_same_memory_for_more_steps(method: Method, exact: bool, short: usize, long: usize) {
    let samples = 100;
    let a = run(method, exact, short, samples);
    let b = run(method, exact, long, samples);
    let label = name(method, exact);
    println!(
        "{label:<26} steps {:>8} → {:>8}: allocations {:>2} → {:>2}, bytes {:>5} → {:>5}, \
         peak {:>5} → {:>5}; {:.3} s ({:.0} ns/step)",
        a.steps(),
        b.steps(),
        a.usage.allocations,
        b.usage.allocations,
        a.usage.bytes,
        b.usage.bytes,
        a.usage.peak,
        b.usage.peak,
        b.seconds,
        b.seconds * 1e9 / b.steps() as f64,
    );
    assert!(
        b.steps() >= 9 * a.steps(),
        "{label}: {} → {} steps",
        a.steps(),
        b.steps()
    );
    if !method.is_adaptive() {
        assert_eq!(a.steps(), 200 * short, "{label}");
        assert_eq!(b.steps(), 200 * long, "{label}");
    }
    assert_eq!(a.usage, b.usage, "{label}");
}

/// Every integrator, 10⁴ steps against 10⁵ (50 and 500 orbits of 200
/// steps; the adaptive ones at tolerances giving about as many, DOP853
/// half), the same 100 samples: the same allocations, bytes and peak memory.
#[test]
fn no_integrator_allocates_per_step() {
    for (method, exact) in all() {
        assert_same_memory_for_more_steps(method, exact, 50, 500);
    }
}

/// The explicit methods at 10⁶ steps (5000 orbits) against 10⁴: still the
/// same allocations. RK4 costs four right-hand sides per step, about 70 ns
/// each here (M, f and the 2 × 2 solve), so 10⁶ steps take about 0.3 s
/// (measured 0.28 s on an idle core): cheap enough for CI.
#[test]
fn a_million_explicit_steps_allocate_no_more_than_ten_thousand() {
    for method in [Method::ExplicitEuler, Method::SymplecticEuler, Method::Rk4] {
        assert_same_memory_for_more_steps(method, true, 50, 5000);
    }
}

/// Every integrator at 10⁶ steps (or, adaptive, about as many) against 10⁴.
#[test]
#[ignore = "10⁶ steps of every integrator, about twenty seconds; run with --ignored"]
fn no_integrator_allocates_per_step_over_a_million_steps() {
    for (method, exact) in all() {
        assert_same_memory_for_more_steps(method, exact, 50, 5000);
    }
}

/// Memory is the requested samples and nothing else: ten times the samples
/// over the same 10⁴ steps cost the same number of allocations (the sample
/// storage is reserved once, never regrown), and exactly the bytes of the
/// extra samples, `t`, `q` and `q̇` each (8 + 16 + 16 = 40 bytes), more, in
/// the bytes requested and in the peak.
#[test]
fn memory_grows_with_the_requested_samples_only() {
    let per_sample = std::mem::size_of::<f64>() + 2 * std::mem::size_of::<SVector<f64, 2>>();
    for (method, exact) in all() {
        let (few, many) = (100, 1000);
        let a = run(method, exact, 50, few);
        let b = run(method, exact, 50, many);
        let label = name(method, exact);
        let extra = (many - few) * per_sample;
        println!(
            "{label:<26} samples {few} → {many}: allocations {} → {}, bytes {} → {} (+{}), \
             peak {} → {}",
            a.usage.allocations,
            b.usage.allocations,
            a.usage.bytes,
            b.usage.bytes,
            b.usage.bytes - a.usage.bytes,
            a.usage.peak,
            b.usage.peak,
        );
        assert_eq!(a.usage.allocations, b.usage.allocations, "{label}");
        assert_eq!(b.usage.bytes, a.usage.bytes + extra, "{label}");
        assert_eq!(b.usage.peak, a.usage.peak + extra as isize, "{label}");
    }
}
