//! `lagrange::trig` against the platform's `sin_cos`: ns per angle when
//! `K` angles are computed together, as the generated code does with
//! `sin_cos_array` for a model with `K` angles.
//!
//! `cargo bench -p lagrange-studies --bench trig` (under `cargo test` it only says so). Best of
//! five repetitions of 200,000 calls on 64 varying states, one process; a
//! quick table, not criterion's statistics.

use lagrange::trig;
use std::hint::black_box;
use std::time::Instant;

/// Best ns per call of `f` over the 64 states.
fn best_ns<const K: usize>(
    states: &[[f64; K]],
    f: impl Fn(&[f64; K]) -> ([f64; K], [f64; K]),
) -> f64 {
    let calls = 200_000;
    (0..5)
        .map(|_| {
            let start = Instant::now();
            let mut acc = 0.0;
            for it in 0..calls {
                let (s, c) = f(black_box(&states[it & 63]));
                acc += s[it % K] + c[it % K];
            }
            black_box(acc);
            start.elapsed().as_secs_f64() * 1e9 / calls as f64
        })
        .fold(f64::INFINITY, f64::min)
}

#[inline(never)]
fn kernel<const K: usize>(x: &[f64; K]) -> ([f64; K], [f64; K]) {
    trig::sin_cos_array(*x)
}

#[inline(never)]
fn platform<const K: usize>(x: &[f64; K]) -> ([f64; K], [f64; K]) {
    let sc = x.map(f64::sin_cos);
    (sc.map(|(s, _)| s), sc.map(|(_, c)| c))
}

fn row<const K: usize>() {
    // The angles of the peers benchmark's states (0.3 + 0.9 sin(..)).
    let states: Vec<[f64; K]> = (0..64)
        .map(|k| core::array::from_fn(|i| 0.3 + 0.9 * (1.7 * i as f64 + k as f64).sin()))
        .collect();
    let ours = best_ns(&states, kernel::<K>) / K as f64;
    let theirs = best_ns(&states, platform::<K>) / K as f64;
    println!("| {K} | {ours:.2} | {theirs:.2} | {:.2} |", ours / theirs);
}

fn main() {
    if !std::env::args().any(|a| a == "--bench") {
        println!("trig: run with `cargo bench -p lagrange-studies --bench trig`");
        return;
    }
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!("load average at the start: {}", load.trim());
    println!();
    println!(
        "| angles K | lagrange::trig, ns per angle | platform sin_cos, ns per angle | ratio |"
    );
    println!("|---:|---:|---:|---:|");
    row::<1>();
    row::<2>();
    row::<5>();
    row::<10>();
    row::<14>();
    row::<20>();
    row::<21>();
    row::<30>();
}
