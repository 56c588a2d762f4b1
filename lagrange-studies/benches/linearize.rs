//! What a linearization costs, three ways, on the 10- and 20-link pendulum
//! chains: exact (the generated residual Jacobians, one `M` factorization
//! and `2N` triangular solves), central differences of the right-hand side
//! (`4N` accelerations, what a model without `#[lagrange(jacobians)]`
//! gets), and forward-mode AD (num-dual) through the whole right-hand side,
//! `M`, `f` and the Cholesky solve, with `2N` derivative directions at
//! once. Prints a table (time per linearization, largest deviation from
//! the exact blocks relative to their largest entry), then criterion's
//! measurements. The chains keep the dense solve (`articulated = false`),
//! as when BENCHMARKS.md's figures were taken; what the recursion over a
//! tree of links does to a right-hand side is `benches/articulated.rs`.
//!
//! `cargo bench -p lagrange-studies --bench linearize`

use std::hint::black_box;
use std::time::Instant;

use criterion::{Criterion, criterion_group};
use lagrange::analysis::linearize;
use lagrange::dynamics::acceleration;
use lagrange::lagrangian;
use lagrange::nalgebra::{SMatrix, SVector};
use lagrange::{Lagrangian, WithLayers};
use num_dual::{DualSVec64, jacobian};

lagrangian! {
    /// The 10-link chain of `src/models/chain.rs`, with exact Jacobians.
    #[lagrange(jacobians, articulated = false)]
    pub struct Chain10 {
        const N = 10;
        coordinates: theta[N];
        parameters: m[N], l[N];
        constants: g = 9.81;
        let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));
        let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));
        kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2));
        potential: sum(i in 0..N, m[i]*g*y[i]);
    }
}

lagrangian! {
    /// The 20-link chain, with exact Jacobians.
    #[lagrange(jacobians, articulated = false)]
    pub struct Chain20 {
        const N = 20;
        coordinates: theta[N];
        parameters: m[N], l[N];
        constants: g = 9.81;
        let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));
        let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));
        kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2));
        potential: sum(i in 0..N, m[i]*g*y[i]);
    }
}

/// A swinging, non-equilibrium state of an `N`-link chain.
fn state<const N: usize>() -> (SVector<f64, N>, SVector<f64, N>) {
    (
        SVector::from_fn(|i, _| 0.4 * (0.7 * i as f64).sin()),
        SVector::from_fn(|i, _| 0.5 * (1.3 * i as f64).cos()),
    )
}

/// `(∂q̈/∂q, ∂q̈/∂q̇)` by forward AD: the model evaluated in dual numbers
/// with `D = 2N` directions, through `acceleration` (Cholesky included).
#[allow(clippy::type_complexity)]
fn ad_blocks<L, const N: usize, const D: usize>(
    model: &L,
    q: &SVector<f64, N>,
    qdot: &SVector<f64, N>,
) -> (SMatrix<f64, N, N>, SMatrix<f64, N, N>)
where
    L: Lagrangian<N, Scalar = DualSVec64<D>>,
{
    let x = SVector::<f64, D>::from_fn(|k, _| if k < N { q[k] } else { qdot[k - N] });
    let (_, j) = jacobian(
        |x: SVector<DualSVec64<D>, D>| {
            let q = SVector::<_, N>::from_fn(|k, _| x[k]);
            let v = SVector::<_, N>::from_fn(|k, _| x[N + k]);
            acceleration(model, DualSVec64::from_re(0.0), &q, &v).expect("a regular chain")
        },
        &x,
    );
    (
        j.fixed_view::<N, N>(0, 0).into_owned(),
        j.fixed_view::<N, N>(0, N).into_owned(),
    )
}

/// Best-of-five mean time of `f` in microseconds.
fn micros(mut f: impl FnMut()) -> f64 {
    let reps = 200;
    (0..5)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..reps {
                f();
            }
            start.elapsed().as_secs_f64() * 1e6 / reps as f64
        })
        .fold(f64::INFINITY, f64::min)
}

/// Largest deviation of `(a, b)` from `(a0, b0)`, relative to the largest
/// entry of the exact blocks.
fn deviation<const N: usize>(
    (a, b): (SMatrix<f64, N, N>, SMatrix<f64, N, N>),
    (a0, b0): (SMatrix<f64, N, N>, SMatrix<f64, N, N>),
) -> f64 {
    (a - a0).amax().max((b - b0).amax()) / a0.amax().max(b0.amax())
}

/// One table row per method for the `N`-link chain, `exact` and `dual` the
/// same chain in `f64` and in dual numbers.
fn rows<E, A, const N: usize, const D: usize>(exact: &E, dual: &A)
where
    E: Lagrangian<N, Scalar = f64> + Copy,
    A: Lagrangian<N, Scalar = DualSVec64<D>>,
{
    let (q, v) = state::<N>();
    let lin = linearize(exact, 0.0, &q, &v).unwrap();
    let reference = (lin.dqddot_dq, lin.dqddot_dqdot);
    let numeric = exact.without_jacobians();
    let fd = linearize(&numeric, 0.0, &q, &v).unwrap();
    let ad = ad_blocks(dual, &q, &v);
    let t_exact = micros(|| {
        black_box(linearize(exact, 0.0, black_box(&q), black_box(&v)).unwrap());
    });
    let t_fd = micros(|| {
        black_box(linearize(&numeric, 0.0, black_box(&q), black_box(&v)).unwrap());
    });
    let t_ad = micros(|| {
        black_box(ad_blocks(dual, black_box(&q), black_box(&v)));
    });
    println!("| {N} | exact (residual Jacobians) | {t_exact:.1} | 0 (reference) |");
    println!(
        "| {N} | central differences, 4N = {} right-hand sides | {t_fd:.1} | {:.1e} |",
        4 * N,
        deviation((fd.dqddot_dq, fd.dqddot_dqdot), reference)
    );
    println!(
        "| {N} | forward AD (num-dual, {D} directions) | {t_ad:.1} | {:.1e} |",
        deviation(ad, reference)
    );
}

fn m_l<const N: usize>() -> ([f64; N], [f64; N]) {
    ([1.0 / N as f64; N], [1.0 / N as f64; N])
}

fn dual<const N: usize, const D: usize>(a: [f64; N]) -> [DualSVec64<D>; N] {
    a.map(DualSVec64::from_re)
}

fn table() {
    println!("| links | method | µs per linearization | max deviation from exact / max entry |");
    println!("|---|---|---|---|");
    let (m, l) = m_l::<10>();
    rows::<_, _, 10, 20>(&Chain10::new(m, l), &Chain10::new(dual(m), dual(l)));
    let (m, l) = m_l::<20>();
    rows::<_, _, 20, 40>(&Chain20::new(m, l), &Chain20::new(dual(m), dual(l)));
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("linearize");
    let (m, l) = m_l::<10>();
    let chain10 = Chain10::new(m, l);
    let (q10, v10) = state::<10>();
    group.bench_function("chain10/exact", |b| {
        b.iter(|| linearize(&chain10, 0.0, black_box(&q10), black_box(&v10)).unwrap())
    });
    let numeric10 = chain10.without_jacobians();
    group.bench_function("chain10/central_differences", |b| {
        b.iter(|| linearize(&numeric10, 0.0, black_box(&q10), black_box(&v10)).unwrap())
    });
    let (m, l) = m_l::<20>();
    let chain20 = Chain20::new(m, l);
    let (q20, v20) = state::<20>();
    group.bench_function("chain20/exact", |b| {
        b.iter(|| linearize(&chain20, 0.0, black_box(&q20), black_box(&v20)).unwrap())
    });
    let numeric20 = chain20.without_jacobians();
    group.bench_function("chain20/central_differences", |b| {
        b.iter(|| linearize(&numeric20, 0.0, black_box(&q20), black_box(&v20)).unwrap())
    });
    let dual20 = Chain20::new(dual::<20, 40>(m), dual(l));
    group.bench_function("chain20/forward_ad", |b| {
        b.iter(|| ad_blocks(&dual20, black_box(&q20), black_box(&v20)))
    });
    group.finish();
}

criterion_group!(benches, bench);

fn main() {
    table();
    benches();
    Criterion::default().configure_from_args().final_summary();
}
