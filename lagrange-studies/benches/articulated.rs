//! What the recursion over a tree of links (`lagrange::linalg::articulated`)
//! does to one right-hand side, against the dense solve of the same model:
//! `lagrange::dynamics::acceleration` (the generated code and the solve) on
//! the N-link chain in absolute angles, N = 4 to 16, and on the branched
//! tree of `models::Tree` (ten links in relative angles), each model twice
//! from the same source, `#[lagrange(articulated)]` and
//! `#[lagrange(articulated = false)]`. The table says where the recursion
//! starts to pay: `FROM_COORDINATES` in `lagrange-engine/src/derive/articulated.rs`,
//! from which a model gets it without asking. (The chain up to 64 links and
//! a 2 × 32 tree, beside MuJoCo: `benches/mujoco.rs`.)
//!
//! `cargo bench -p lagrange-studies --bench articulated [-- --rounds R]`
//! (under `cargo test` it only says so). Calls on 64 fixed states, which
//! the processor overlaps (throughput); each timing the best of `R` rounds
//! (15 by default), the rounds interleaving every timing, so that a slow
//! spell of a shared machine falls on all of them alike.

use lagrange::Lagrangian;
use lagrange::dynamics::acceleration;
use lagrange::lagrangian;
use lagrange::nalgebra::SVector;
use std::hint::black_box;
use std::time::Instant;

/// The chain of `$n` links in absolute angles, with the options `$opt`.
macro_rules! chain {
    ($name:ident, $n:tt, $($opt:tt)*) => {
        lagrangian! {
            #[lagrange($($opt)*)]
            pub struct $name {
                const N = $n;
                coordinates: theta[N];
                parameters: m[N], l[N];
                constants: g = 9.81;
                let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));
                let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));
                kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2));
                potential: sum(i in 0..N, m[i]*g*y[i]);
            }
        }
    };
}

chain!(Chain4, 4, articulated);
chain!(Dense4, 4, articulated = false);
chain!(Chain6, 6, articulated);
chain!(Dense6, 6, articulated = false);
chain!(Chain8, 8, articulated);
chain!(Dense8, 8, articulated = false);
chain!(Chain10, 10, articulated);
chain!(Dense10, 10, articulated = false);
chain!(Chain12, 12, articulated);
chain!(Dense12, 12, articulated = false);
chain!(Chain16, 16, articulated);
chain!(Dense16, 16, articulated = false);

lagrangian! {
    /// `models::Tree`, with the dense solve.
    #[lagrange(articulated = false)]
    pub struct DenseTree {
        const B = 5;
        coordinates: phi[B], psi[B];
        parameters: m, l, g;
        let ta[i in 0..B] = sum(j in 0..=i, phi[j]);
        let tb[i in 0..B] = ta[0] + sum(j in 0..=i, psi[j]);
        let xa[i in 0..B] = l*sum(j in 0..=i, sin(ta[j]));
        let ya[i in 0..B] = -l*sum(j in 0..=i, cos(ta[j]));
        let xb[i in 0..B] = xa[0] + l*sum(j in 0..=i, sin(tb[j]));
        let yb[i in 0..B] = ya[0] - l*sum(j in 0..=i, cos(tb[j]));
        kinetic: m/2*sum(i in 0..B, dot(xa[i])^2 + dot(ya[i])^2 + dot(xb[i])^2 + dot(yb[i])^2);
        potential: m*g*sum(i in 0..B, ya[i] + yb[i]);
    }
}

/// 64 states spread over the circle and over ±3 rad/s.
fn states<const N: usize>() -> Vec<(SVector<f64, N>, SVector<f64, N>)> {
    (0..64)
        .map(|k| {
            let q = SVector::from_fn(|i, _| 3.0 * ((7 * i + 13 * k) as f64 * 0.37).sin());
            let v = SVector::from_fn(|i, _| 3.0 * ((5 * i + 11 * k) as f64 * 0.61).cos());
            (q, v)
        })
        .collect()
}

/// ns per right-hand side of `model` over `states`, one pass.
fn per_call<L: Lagrangian<N, Scalar = f64>, const N: usize>(
    model: &L,
    states: &[(SVector<f64, N>, SVector<f64, N>)],
) -> f64 {
    let passes = 200;
    let start = Instant::now();
    for _ in 0..passes {
        for (q, v) in states {
            let a = acceleration(black_box(model), 0.0, black_box(q), black_box(v));
            black_box(a.expect("a regular chain"));
        }
    }
    start.elapsed().as_secs_f64() * 1e9 / (passes * states.len()) as f64
}

/// One row: the recursion's and the dense solve's best over `rounds`
/// interleaved rounds.
fn row<A, D, const N: usize>(name: &str, fast: &A, dense: &D, rounds: usize) -> String
where
    A: Lagrangian<N, Scalar = f64>,
    D: Lagrangian<N, Scalar = f64>,
{
    assert!(A::SOLVES_ACCELERATIONS && !D::SOLVES_ACCELERATIONS);
    let states = states::<N>();
    let (mut a, mut d) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..rounds {
        a = a.min(per_call(fast, &states));
        d = d.min(per_call(dense, &states));
    }
    format!("| {name} | {N} | {a:.0} | {d:.0} | {:.2} |", a / d)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if !args.iter().any(|a| a == "--bench") {
        println!(
            "articulated: a benchmark; run it with `cargo bench -p lagrange-studies --bench articulated`"
        );
        return;
    }
    let rounds = args
        .iter()
        .position(|a| a == "--rounds")
        .and_then(|k| args.get(k + 1)?.parse().ok())
        .unwrap_or(15);
    let m = |i: usize| 1.0 + 0.1 * i as f64;
    let l = |i: usize| 1.0 - 0.02 * i as f64;
    macro_rules! chains {
        ($(($fast:ident, $dense:ident, $n:literal)),*) => {
            vec![$(row(
                concat!("chain ", $n),
                &$fast::new(std::array::from_fn(m), std::array::from_fn(l)),
                &$dense::new(std::array::from_fn(m), std::array::from_fn(l)),
                rounds,
            )),*]
        };
    }
    let mut rows = chains!(
        (Chain4, Dense4, 4),
        (Chain6, Dense6, 6),
        (Chain8, Dense8, 8),
        (Chain10, Dense10, 10),
        (Chain12, Dense12, 12),
        (Chain16, Dense16, 16)
    );
    rows.push(row(
        "tree 2 × 5",
        &lagrange::models::Tree::unit(),
        &DenseTree::new(1.0, 1.0, 9.81),
        rounds,
    ));
    println!(
        "One right-hand side (`dynamics::acceleration`), ns, best of {rounds} interleaved rounds:\n"
    );
    println!("| model | N | recursion | dense solve | ratio |");
    println!("|---|---:|---:|---:|---:|");
    for r in rows {
        println!("{r}");
    }
}
