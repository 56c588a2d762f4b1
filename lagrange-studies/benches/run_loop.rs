//! The run loop's cost, method by method: the time of a whole `integrate`
//! divided by its right-hand side evaluations, on the shared problems, for
//! every explicit method (adaptive at two or three tolerances, fixed-step
//! at one step) and Radau5, beside one evaluation alone (`acceleration`: `M + f`
//! and the solve). What a run adds per evaluation is the difference: the
//! stages' sums, the step-size control, the error norm, the growth guard,
//! the recording. A change to the run loop is measured with this before it
//! lands (BENCHMARKS.md, "The run loop's baseline").
//!
//! ```text
//! cargo bench -p lagrange-studies --bench run_loop                   # the table
//! cargo bench -p lagrange-studies --bench run_loop -- --baseline lagrange-studies/benches/run_loop/baseline.tsv
//! cargo bench -p lagrange-studies --bench run_loop -- --save FILE    # a new baseline
//! lagrange-studies/benches/run_loop/compare.sh REV                   # REV against the work tree, interleaved
//! ```
//!
//! Each row's figure is its best over `--rounds` rounds (15 by default),
//! every round running every row once in turn, so that a slow spell of a
//! shared machine falls on all rows alike. A stored baseline was taken at
//! another time, under another load: it says where to look. Only two builds
//! timed in one run, interleaved (`compare.sh`), settle a change of a few
//! percent; `compare.sh --instructions` adds the instructions per
//! evaluation counted by cachegrind, which no load moves.
//!
//! `--raw` prints one tab-separated line per row (key, evaluations, ns per
//! evaluation); `--only TEXT` keeps the rows whose key contains `TEXT`;
//! `--once` runs each row once untimed (for cachegrind).

use lagrange::dynamics::acceleration;
use lagrange::models::{CartesianPendulum, Chain, DoublePendulum, Kepler};
use lagrange::nalgebra::{SVector, Vector2};
use lagrange::prelude::*;
use std::hint::black_box;
use std::time::Instant;

/// One row: a run of one method on one problem, timed as a whole.
struct Row<'a> {
    key: String,
    /// One run, returning its evaluations (none is run before the rows
    /// are chosen, so that `--only` runs only its own).
    run: Box<dyn FnMut() -> usize + 'a>,
}

/// A run of `method` on `model` from `(q0, q̇0)` to `t_end`, keeping only the
/// final state (as a long run that samples rarely).
fn row<'a, M, L, const N: usize>(
    problem: &str,
    name: &str,
    method: M,
    model: &'a L,
    (q0, qdot0): (SVector<f64, N>, SVector<f64, N>),
    t_end: f64,
) -> Row<'a>
where
    M: Integrator<f64> + 'a,
    L: Lagrangian<N, Scalar = f64>,
{
    let run = move || {
        method
            .integrate(black_box(model), 0.0, q0, qdot0, &[t_end])
            .expect("every row's run succeeds")
            .stats()
            .rhs_evals
    };
    Row {
        key: format!("{problem}|{name}"),
        run: Box::new(run),
    }
}

/// One evaluation alone, on 64 states near `(q0, q̇0)` in turn: its rows
/// count each call as an evaluation.
fn evaluation<'a, L: Lagrangian<N, Scalar = f64>, const N: usize>(
    problem: &str,
    model: &'a L,
    (q0, qdot0): (SVector<f64, N>, SVector<f64, N>),
) -> Row<'a> {
    let states: Vec<_> = (0..64)
        .map(|k| {
            let nudge = 1e-3 * (k as f64).sin();
            (q0.add_scalar(nudge), qdot0.add_scalar(nudge))
        })
        .collect();
    let calls = 20_000 / N.max(1);
    Row {
        key: format!("{problem}|evaluation alone"),
        run: Box::new(move || {
            for k in 0..calls {
                let (q, v) = &states[k & 63];
                black_box(acceleration(model, 0.0, black_box(q), v).ok());
            }
            calls
        }),
    }
}

/// The adaptive explicit methods at `1e-8`, `1e-10`, `1e-12` (Bs3 at
/// `1e-6` and `1e-8`), the fixed-step explicit ones at `h`, Radau5 at
/// `1e-8`, and the evaluation alone, on one problem.
fn rows<'a, L: Lagrangian<N, Scalar = f64>, const N: usize>(
    problem: &str,
    model: &'a L,
    start: (SVector<f64, N>, SVector<f64, N>),
    t_end: f64,
    h: f64,
) -> Vec<Row<'a>> {
    let mut rows = vec![evaluation(problem, model, start)];
    for tol in [1e-8, 1e-10, 1e-12] {
        let budget = 10_000_000;
        let dopri5 = Dopri5::new().rtol(tol).atol(tol).max_steps(budget);
        let tsit5 = Tsit5::new().rtol(tol).atol(tol).max_steps(budget);
        let dop853 = Dop853::new().rtol(tol).atol(tol).max_steps(budget);
        rows.push(row(
            problem,
            &format!("Dopri5 {tol:e}"),
            dopri5,
            model,
            start,
            t_end,
        ));
        rows.push(row(
            problem,
            &format!("Tsit5 {tol:e}"),
            tsit5,
            model,
            start,
            t_end,
        ));
        rows.push(row(
            problem,
            &format!("Dop853 {tol:e}"),
            dop853,
            model,
            start,
            t_end,
        ));
    }
    // The third-order pair at the loose tolerances it is for.
    for tol in [1e-6, 1e-8] {
        let bs3 = Bs3::new().rtol(tol).atol(tol).max_steps(10_000_000);
        rows.push(row(
            problem,
            &format!("Bs3 {tol:e}"),
            bs3,
            model,
            start,
            t_end,
        ));
    }
    let radau5 = Radau5::new().rtol(1e-8).atol(1e-8);
    rows.push(row(problem, "Radau5 1e-8", radau5, model, start, t_end));
    let name = |method: &str| format!("{method} h={h:e}");
    let euler = ExplicitEuler::new(h).max_steps(10_000_000);
    let symplectic = SymplecticEuler::new(h).max_steps(10_000_000);
    let rk4 = Rk4::new(h).max_steps(10_000_000);
    rows.push(row(
        problem,
        &name("ExplicitEuler"),
        euler,
        model,
        start,
        t_end,
    ));
    rows.push(row(
        problem,
        &name("SymplecticEuler"),
        symplectic,
        model,
        start,
        t_end,
    ));
    rows.push(row(problem, &name("Rk4"), rk4, model, start, t_end));
    rows
}

/// `(ns per evaluation, evaluations)` of a stored table, by key.
fn read_table(path: &str) -> std::collections::BTreeMap<String, (f64, usize)> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split('\t').collect();
            let evals = f[1].parse().expect("evaluations");
            (
                f[0].to_string(),
                (f[2].parse().expect("ns per evaluation"), evals),
            )
        })
        .collect()
}

/// The commit this bench was built from, as `git` tells it, `+` where the
/// work tree differs from it.
fn commit() -> String {
    let git = |args: &[&str]| {
        std::process::Command::new("git")
            .args(args)
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
    };
    match git(&["rev-parse", "--short", "HEAD"]) {
        Some(head) => {
            let dirty = git(&["status", "--porcelain", "--untracked-files=no"])
                .is_some_and(|s| !s.is_empty());
            format!("{head}{}", if dirty { "+" } else { "" })
        }
        None => "unknown".to_string(),
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if !args.iter().any(|a| a == "--bench") {
        println!("run_loop: run with `cargo bench -p lagrange-studies --bench run_loop`");
        return;
    }
    let value = |flag: &str| {
        args.iter().position(|a| a == flag).map(|i| {
            args.get(i + 1)
                .unwrap_or_else(|| panic!("{flag} takes a value"))
                .clone()
        })
    };
    // Cargo runs a bench in its package's folder: a relative path is taken
    // from the repository's root, where the commands are typed.
    let from_root = |path: String| {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        root.join(path).to_string_lossy().into_owned()
    };
    let rounds: usize = value("--rounds").map_or(15, |r| r.parse().expect("--rounds N"));
    let (raw, once) = (
        args.iter().any(|a| a == "--raw"),
        args.iter().any(|a| a == "--once"),
    );
    let only = value("--only");

    // The seed problem (the double pendulum from (2, 2.5) at rest, chaotic),
    // the 5-link chain, an orbit of eccentricity 0.5 (`M = I`: the loop's
    // share is largest), and a constrained model (the saddle-point solve
    // and the drift control after every step).
    let pendulum = DoublePendulum::unit();
    let chain = Chain::new([1.0; 5], [1.0; 5]);
    let kepler = Kepler::new(1.0);
    let rod = CartesianPendulum::new(1.0, 1.0, 9.81);
    let mut all = Vec::new();
    let seed = (Vector2::new(2.0, 2.5), Vector2::zeros());
    all.extend(rows("double pendulum", &pendulum, seed, 10.0, 1e-3));
    let bent = (SVector::from([0.5, 1.0, 1.5, 2.0, 2.5]), SVector::zeros());
    all.extend(rows("chain 5", &chain, bent, 10.0, 1e-3));
    all.extend(rows(
        "kepler e=0.5",
        &kepler,
        kepler.pericentre(0.5),
        20.0,
        1e-3,
    ));
    all.extend(rows(
        "cartesian pendulum",
        &rod,
        rod.state(1.0, 0.0),
        10.0,
        1e-3,
    ));
    all.retain(|r| only.as_ref().is_none_or(|o| r.key.contains(o.as_str())));

    if once {
        for row in &mut all {
            println!("{}\t{}", row.key, (row.run)());
        }
        return;
    }
    // Each row's evaluations, from a first run that also warms it.
    let evals: Vec<usize> = all.iter_mut().map(|row| (row.run)()).collect();
    let mut best = vec![f64::INFINITY; all.len()];
    for _ in 0..rounds {
        for ((row, best), &evals) in all.iter_mut().zip(&mut best).zip(&evals) {
            let start = Instant::now();
            (row.run)();
            let ns = start.elapsed().as_secs_f64() * 1e9 / evals as f64;
            *best = best.min(ns);
        }
    }
    let table: Vec<(String, usize, f64)> = all
        .iter()
        .zip(&best)
        .zip(&evals)
        .map(|((r, &ns), &evals)| (r.key.clone(), evals, ns))
        .collect();
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    let header = format!(
        "# run_loop at {}, best of {rounds} interleaved rounds, load average {}",
        commit(),
        load.split_whitespace()
            .take(3)
            .collect::<Vec<_>>()
            .join(" ")
    );
    if let Some(path) = value("--save").map(from_root) {
        let mut text = format!("{header}\n# key\tevaluations\tns per evaluation\n");
        for (key, evals, ns) in &table {
            text += &format!("{key}\t{evals}\t{ns:.2}\n");
        }
        std::fs::write(&path, text).unwrap_or_else(|e| panic!("{path}: {e}"));
    }
    if raw {
        for (key, evals, ns) in &table {
            println!("{key}\t{evals}\t{ns:.3}");
        }
        return;
    }
    let baseline = value("--baseline")
        .map(from_root)
        .map(|p| (read_table(&p), p));
    println!("{header}");
    if let Some((_, path)) = &baseline {
        let first = std::fs::read_to_string(path).unwrap_or_default();
        println!("baseline {path}: {}", first.lines().next().unwrap_or(""));
    }
    println!();
    // Each run against its problem's evaluation alone, in this run and in
    // the baseline's: a machine slower for a while slows both alike, so
    // this ratio moves less with the load than the times do.
    let alone = |problem: &str, get: &dyn Fn(&str) -> Option<f64>| {
        get(&format!("{problem}|evaluation alone"))
    };
    let here = |key: &str| table.iter().find(|r| r.0 == key).map(|r| r.2);
    let there = |key: &str| baseline.as_ref().and_then(|(b, _)| b.get(key)).map(|b| b.0);
    println!(
        "| problem | method | evaluations | ns per evaluation | ÷ evaluation alone | baseline (ns) | ratio | ratio of the ÷ |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|---:|");
    for (key, evals, ns) in &table {
        let (problem, method) = key.split_once('|').expect("problem|method");
        let per = alone(problem, &here).map(|a| ns / a);
        let (base, ratio, relative) = match baseline.as_ref().and_then(|(b, _)| b.get(key)) {
            // A run whose evaluations moved is not the same work.
            Some(&(base, base_evals)) if base_evals == *evals => {
                let base_per = alone(problem, &there).map(|a| base / a);
                let relative = match (per, base_per) {
                    (Some(per), Some(base_per)) => format!("{:.3}", per / base_per),
                    _ => "-".to_string(),
                };
                (format!("{base:.1}"), format!("{:.3}", ns / base), relative)
            }
            Some(&(_, base_evals)) => (
                format!("{base_evals} evaluations"),
                "-".to_string(),
                "-".to_string(),
            ),
            None => ("-".to_string(), "-".to_string(), "-".to_string()),
        };
        let per = per.map_or("-".to_string(), |p| format!("{p:.2}"));
        println!(
            "| {problem} | {method} | {evals} | {ns:.1} | {per} | {base} | {ratio} | {relative} |"
        );
    }
}
