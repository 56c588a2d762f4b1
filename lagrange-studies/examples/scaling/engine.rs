//! The engine's side, outside rustc: how long `lagrangian!`'s expansion
//! takes (with the engine built in release, as this example is), and how
//! many operations the generated `M` and `f` perform.

use lagrange_engine::expr::DEFAULT_BUDGET;
use lagrange_engine::expr::cse::{self, OpCount};
use proc_macro2::TokenStream;
use std::time::{Duration, Instant};

/// What the engine did with one model.
#[derive(Clone, Debug)]
pub struct EngineStats {
    /// `lagrange_engine::expand`, tokens in, tokens out: what the macro runs.
    pub expand: Duration,
    /// `derive`: parse, lower, check, differentiate.
    pub derive: Duration,
    /// `Derived::tokens`: schedule the shared nodes and emit the items.
    pub emit: Duration,
    /// Repetitions behind each median.
    pub reps: usize,
    /// Expression nodes in the pool (each costs the work budget a few steps).
    pub nodes: usize,
    /// Steps of the engine's work budget spent by derive and emit together.
    pub steps: u64,
    /// Operations of `M` (upper triangle) and `f`, as emitted with sharing.
    pub shared: OpCount,
    /// Of which `M` alone (sharing only within `M`).
    pub shared_mass: OpCount,
    /// Of which `f` alone (sharing only within `f`).
    pub shared_forcing: OpCount,
    /// The same without any sharing: what a tree would cost.
    pub tree: OpCount,
    /// Size of the emitted items, as text.
    pub code_bytes: usize,
}

/// The engine's verdict on a model it would not derive.
#[derive(Clone, Debug)]
pub struct EngineFailure {
    pub over_budget: bool,
    pub message: String,
}

/// Median of a few repetitions: five for quick models, fewer once one
/// expansion takes more than about a second.
pub fn measure(source: &str) -> Result<EngineStats, EngineFailure> {
    let tokens: TokenStream = source.parse().expect("generated model source lexes");
    let derived = lagrange_engine::derive(tokens.clone()).map_err(|e| {
        let message = e.to_string();
        EngineFailure {
            over_budget: message.contains("budget"),
            message,
        }
    })?;
    let (shared, tree) = derived.op_counts();
    let n = derived.model.dof();
    // Empty where the recursion solves the model without `M` and `f`
    // derived (`--articulated`): their counts are then zero, and
    // `op_counts` counts the parts.
    let rows = derived.equations.mass.len();
    let mass: Vec<_> = (0..rows)
        .flat_map(|i| (i..n).map(move |j| (i, j)))
        .map(|(i, j)| derived.equations.mass[i][j])
        .collect();
    let shared_mass = cse::shared_ops(&derived.model.pool, &mass);
    let shared_forcing = cse::shared_ops(&derived.model.pool, &derived.equations.forcing);
    let nodes = derived.model.pool.len();
    drop(derived.tokens());
    let steps = derived.model.pool.spent();
    drop(derived);

    let mut expand = Vec::new();
    let mut derive = Vec::new();
    let mut emit = Vec::new();
    let mut code_bytes = 0;
    let mut spent = Duration::ZERO;
    while expand.len() < 5 && (expand.len() < 3 || spent < Duration::from_secs(3)) {
        let input = tokens.clone();
        let start = Instant::now();
        let out = lagrange_engine::expand(input);
        let e = start.elapsed();
        code_bytes = out.to_string().len();
        expand.push(e);

        let input = tokens.clone();
        let start = Instant::now();
        let derived = lagrange_engine::derive(input).expect("derived once already");
        let d = start.elapsed();
        let start = Instant::now();
        let out = derived.tokens();
        let m = start.elapsed();
        drop(out);
        derive.push(d);
        emit.push(m);

        spent += e + d + m;
        if spent > Duration::from_secs(20) {
            break;
        }
    }
    Ok(EngineStats {
        reps: expand.len(),
        expand: median(&mut expand),
        derive: median(&mut derive),
        emit: median(&mut emit),
        nodes,
        steps,
        shared,
        shared_mass,
        shared_forcing,
        tree,
        code_bytes,
    })
}

/// The engine's default work budget, in steps.
pub fn budget() -> u64 {
    DEFAULT_BUDGET
}

pub fn median(xs: &mut [Duration]) -> Duration {
    xs.sort();
    xs[xs.len() / 2]
}
