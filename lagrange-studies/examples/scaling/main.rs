//! How `lagrangian!` scales: the N-link pendulum chain for N = 1..=20 (25
//! and 30 with `--max 30`), measured on both sides of the macro.
//!
//! `cargo run --release -p lagrange-studies --example scaling`
//!
//! For each N: the engine's expansion time and operation counts (in this
//! process), then a generated crate holding only the model, its
//! `cargo build --release` time, the generated `M` and `f` in ns per call,
//! and the same `M` and `f` by runtime forward-mode AD (num-dual), checked
//! to agree. Prints the table and writes it, with the fitted growth
//! exponents and the project's targets, into the marked section of
//! `BENCHMARKS.md`.
//!
//! Options: `--max N` (largest chain, default 20), `--only 5,10,20` (just
//! these), `--scalar` (the model
//! written out, `theta0, theta1, ...`, instead of the indexed DSL),
//! `--engine-only` (no builds), `--no-ad`, `--no-write` (leave
//! `BENCHMARKS.md` alone), `--optimised-macro` (the model crates build the
//! engine with `opt-level = 3`, as the README recommends; cargo's default
//! for proc macros is 0), `--articulated` (the chain with
//! `#[lagrange(articulated)]` instead of `articulated = false`: its `M`
//! and `f` are formed at run time from the links' parts at every size, as
//! a chain as a user writes it has them from 18 coordinates, and the build
//! is that of the parts; implies `--no-write`), `--timeout S` (per build, default 600).

mod chain;
mod crates;
mod engine;
mod machine;
mod report;

use chain::Form;
use crates::Crates;
use report::{AdStats, BuildStats, Row};
use std::fmt::Write;
use std::path::Path;
use std::time::{Duration, Instant};

struct Options {
    max: usize,
    only: Option<Vec<usize>>,
    form: Form,
    builds: bool,
    ad: bool,
    write: bool,
    optimised_macro: bool,
    articulated: bool,
    timeout: Duration,
}

impl Options {
    fn parse() -> Result<Self, String> {
        let mut o = Options {
            max: 20,
            only: None,
            form: Form::Indexed,
            builds: true,
            ad: true,
            write: true,
            optimised_macro: false,
            articulated: false,
            timeout: Duration::from_secs(600),
        };
        let mut args = std::env::args().skip(1);
        while let Some(a) = args.next() {
            let mut number = |name: &str| -> Result<u64, String> {
                args.next()
                    .and_then(|v| v.parse().ok())
                    .ok_or(format!("{name} needs a number"))
            };
            match a.as_str() {
                "--max" => o.max = number("--max")? as usize,
                "--timeout" => o.timeout = Duration::from_secs(number("--timeout")?),
                "--only" => {
                    let list = args.next().unwrap_or_default();
                    let ns: Result<Vec<usize>, _> = list.split(',').map(str::parse).collect();
                    o.only = Some(ns.map_err(|_| "--only needs a list like 5,10,20")?);
                }
                "--scalar" => o.form = Form::Scalar,
                "--engine-only" => o.builds = false,
                "--no-ad" => o.ad = false,
                "--no-write" => o.write = false,
                "--optimised-macro" => o.optimised_macro = true,
                "--articulated" => o.articulated = true,
                "--help" | "-h" => return Err(
                    "usage: cargo run --release -p lagrange-studies --example scaling -- [--max N | --only N,N,..] \
                         [--scalar] [--engine-only] [--no-ad] [--no-write] [--optimised-macro] \
                         [--articulated] [--timeout S]"
                        .into(),
                ),
                other => return Err(format!("unknown option `{other}` (try --help)")),
            }
        }
        if o.max == 0 {
            return Err("--max must be at least 1".into());
        }
        // BENCHMARKS.md's table is of the generated `M` and `f`.
        if o.articulated {
            o.write = false;
        }
        Ok(o)
    }

    fn chain_lengths(&self) -> Vec<usize> {
        if let Some(only) = &self.only {
            return only.clone();
        }
        (1..=self.max.min(20))
            .chain([25, 30].into_iter().filter(|&n| n <= self.max))
            .collect()
    }

    fn describe(&self) -> String {
        let mut s = String::new();
        if let Some(only) = &self.only {
            let list: Vec<String> = only.iter().map(usize::to_string).collect();
            write!(s, " --only {}", list.join(",")).unwrap();
        } else if self.max != 20 {
            write!(s, " --max {}", self.max).unwrap();
        }
        if self.form == Form::Scalar {
            s.push_str(" --scalar");
        }
        if !self.builds {
            s.push_str(" --engine-only");
        }
        if !self.ad {
            s.push_str(" --no-ad");
        }
        if self.optimised_macro {
            s.push_str(" --optimised-macro");
        }
        if self.articulated {
            s.push_str(" --articulated");
        }
        if s.is_empty() {
            String::new()
        } else {
            format!(" --{s}")
        }
    }
}

fn main() {
    let options = match Options::parse() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(2);
        }
    };
    if let Err(e) = run(&options) {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

fn run(options: &Options) -> Result<(), String> {
    // The repository's root, one above this crate.
    let repo = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."));
    let started = Instant::now();
    let date = machine::now_utc();
    let load_start = machine::load_average();
    let machine = machine::Machine::probe();
    println!(
        "{} cores, {}; load {load_start}; model in {}",
        machine.cores,
        machine.cpu,
        options.form.name()
    );

    println!("\nengine (expansion outside rustc, median of up to 5):");
    let mut rows: Vec<Row> = Vec::new();
    for n in options.chain_lengths() {
        let engine = engine::measure(&chain::model_body(n, options.form, options.articulated));
        match &engine {
            Ok(e) => println!(
                "  N = {n:>2}: expand {:>9.4} s (derive {:.4} s, emit {:.4} s; {} runs), {} nodes, \
                 {} steps, {} ops shared, {} as a tree",
                e.expand.as_secs_f64(),
                e.derive.as_secs_f64(),
                e.emit.as_secs_f64(),
                e.reps,
                e.nodes,
                e.steps,
                e.shared.total(),
                e.tree.total()
            ),
            Err(f) => println!("  N = {n:>2}: {}", f.message),
        }
        rows.push(Row {
            n,
            engine,
            build: None,
        });
    }

    let mut cold = None;
    if options.builds {
        let crates = Crates::new(repo, options.timeout, options.optimised_macro);
        println!("\nwarm-up: the dependencies, built once into target/scaling/target ...");
        let was_cold = !crates.target_exists();
        let first = crates
            .write(1, options.form, options.articulated)
            .map_err(|e| e.to_string())?;
        let t = crates.build(&first, &[])?;
        crates.check(&first, &[])?;
        let what = if was_cold {
            "cold, dependencies included"
        } else {
            "target directory reused: only what changed was rebuilt"
        };
        println!("  warm-up build: {:.1} s ({what})", t.as_secs_f64());
        cold = was_cold.then_some(t);

        println!("\nper chain (build: lib + timing binary, after touching the model):");
        // The builds take minutes: a bar on the terminal (stderr; hidden
        // when it is not a terminal), the lines above it.
        let bar = indicatif::ProgressBar::new(rows.len() as u64).with_style(
            indicatif::ProgressStyle::with_template(
                "  {bar:40} {pos}/{len} chains built, {elapsed}",
            )
            .expect("a valid template"),
        );
        for row in rows.iter_mut() {
            bar.inc(1);
            if row.engine.is_err() {
                row.build = Some(Err("not built: the engine refuses the model".into()));
                continue;
            }
            let result = build_and_time(&crates, row.n, options);
            bar.suspend(|| match &result {
                Ok(b) => {
                    print!(
                        "  N = {:>2}: check {:>6.2} s, build {:>6.2} s, M+f {:>9.1} ns",
                        row.n,
                        b.check.as_secs_f64(),
                        b.build.as_secs_f64(),
                        b.gen_ns
                    );
                    if let Some(a) = &b.ad {
                        print!(
                            "; AD {:>10.1} ns ({:.0}×, max rel. diff {:.1e}; AD binary built in {:.1} s)",
                            a.ns,
                            a.ns / a.gen_ns,
                            a.max_rel_diff,
                            a.build.as_secs_f64()
                        );
                    }
                    println!();
                }
                Err(e) => println!("  N = {:>2}: {e}", row.n),
            });
            // A disagreement between AD and the generated code is a bug:
            // stop here, loudly, rather than print a table around it.
            if let Err(e) = &result {
                if e.contains("disagree") {
                    return Err(e.clone());
                }
            }
            row.build = Some(result);
        }
        bar.finish_and_clear();
    }

    let load_end = machine::load_average();
    let minutes = started.elapsed().as_secs_f64() / 60.0;
    let table = report::table(&rows);
    println!("\n{table}");

    let mut section = String::new();
    writeln!(section, "## Scaling: the N-link pendulum chain\n").unwrap();
    writeln!(
        section,
        "Written by `cargo run --release -p lagrange-studies --example scaling{}` on {date}, in {minutes:.1} min.\n",
        options.describe()
    )
    .unwrap();
    writeln!(
        section,
        "- Machine: {}, {} cores (`nproc`), {:.0} GiB; {}.",
        machine.cpu, machine.cores, machine.memory_gib, machine.rustc
    )
    .unwrap();
    writeln!(
        section,
        "- Load average (1 / 5 / 15 min): {load_start} at the start, {load_end} at the end. \
         The machine may be shared: timings are medians (engine) or bests (evaluation), \
         build times single runs."
    )
    .unwrap();
    writeln!(
        section,
        "- Model: N point masses on massless rods, angles from the vertical; source in {}.\n",
        options.form.name()
    )
    .unwrap();
    section.push_str(COLUMNS);
    if let Some(t) = cold {
        writeln!(
            section,
            "\nThe warm-up build (cold: all dependencies of a model crate, and N = 1): {:.1} s.",
            t.as_secs_f64()
        )
        .unwrap();
    }
    writeln!(section, "\n{table}").unwrap();
    writeln!(
        section,
        "### Growth exponents\n\nThe log-log slope between two chain lengths: 2 means the \
         quantity grows like N².\n\n{}",
        report::exponents(&rows)
    )
    .unwrap();
    writeln!(section, "### Targets\n\n{}", report::targets_table(&rows)).unwrap();

    if options.write {
        let path = repo.join("BENCHMARKS.md");
        let old = std::fs::read_to_string(&path).unwrap_or_default();
        std::fs::write(&path, report::splice(&old, &section)).map_err(|e| e.to_string())?;
        println!("wrote {}", path.display());
    }
    print!("{}", report::targets_table(&rows));
    Ok(())
}

/// Builds the crate for `n`, runs its timing binary, then (unless `--no-ad`)
/// builds and runs the AD comparison.
fn build_and_time(crates: &Crates, n: usize, options: &Options) -> Result<BuildStats, String> {
    let krate = crates
        .write(n, options.form, options.articulated)
        .map_err(|e| e.to_string())?;
    let check = crates.check(&krate, &[krate.eval_bin()])?;
    crates.touch(&krate).map_err(|e| e.to_string())?;
    let build = crates.build(&krate, &[krate.eval_bin()])?;
    // The best of several processes: on this kind of machine one process
    // can run a steady 2× slower than the next, however long it is timed.
    let mut gen_ns = f64::INFINITY;
    for _ in 0..EVAL_PROCESSES {
        let values = crates.run(&krate.eval_bin())?;
        gen_ns = gen_ns.min(get(&values, "gen_ns")?);
    }
    let ad = if options.ad {
        let build = crates.build(&krate, &[krate.ad_bin()])?;
        let mut ad = AdStats {
            build,
            ns: f64::INFINITY,
            gen_ns: f64::INFINITY,
            max_rel_diff: 0.0,
        };
        for _ in 0..AD_PROCESSES {
            let v = crates.run(&krate.ad_bin())?;
            ad.ns = ad.ns.min(get(&v, "ad_ns")?);
            ad.gen_ns = ad.gen_ns.min(get(&v, "gen_ns")?);
            ad.max_rel_diff = ad.max_rel_diff.max(get(&v, "max_rel_diff")?);
        }
        Some(ad)
    } else {
        None
    };
    Ok(BuildStats {
        check,
        build,
        gen_ns,
        ad,
    })
}

const EVAL_PROCESSES: usize = 5;
const AD_PROCESSES: usize = 3;

fn get(values: &std::collections::HashMap<String, f64>, key: &str) -> Result<f64, String> {
    values
        .get(key)
        .copied()
        .ok_or(format!("the generated binary printed no `{key}`"))
}

const COLUMNS: &str = "\
Columns:

- **expand**: `lagrange_engine::expand` on the model's tokens, outside rustc, the engine \
built in release (median of up to 5 runs). **derive** (parse, lower, check, differentiate) \
and **emit** (`Derived::tokens`: schedule the shared nodes, write the items) are the same \
work split in two.
- **nodes**: expression nodes in the engine's hash-consed pool. **steps**: the engine's work \
budget spent by derive and emit together (the default budget is 50,000,000 steps). **code**: \
the emitted items as text.
- **ops, shared**: arithmetic operations and function calls of `M` (upper triangle) and `f` \
as emitted, every shared subexpression computed once (`Derived::op_counts`). **of which \
M / f**: the same for `M` alone and `f` alone (each with its own sharing, so the two add up to \
a little more than the total). **ops, tree**: the same expressions evaluated as trees, \
without any sharing.
- **build**: wall time of `cargo build --release` of a crate holding only the model (its lib) \
and a small timing binary, after touching the model, its dependencies already built: macro \
expansion inside rustc, type checking and codegen of the generated code. Cargo builds proc \
macros without optimisation by default (`build-override`), so the expansion inside rustc is \
slower than the **expand** column, unless the crate sets \
`[profile.release.package.lagrange-engine] opt-level = 3` (`--optimised-macro`). **check**: \
`cargo check --release` of the same, after touching the model: the front end alone (expansion \
and type checking); build − check is roughly codegen.
- **M+f**: the generated `mass_matrix_and_forcing(t, &q, &qdot)` for `f64`, ns per call: \
the best of 5 processes, each the best of 40 batches of about 5 ms (on this virtual machine \
one process can run a steady 2× slower than the next).
- **AD**: the same `M` and `f` by runtime forward-mode AD (num-dual 0.15): one Hessian of \
L(q, q̇) = T − V over (q, q̇) with `Dual2SVec64<2N>`, then M = ∂²L/∂q̇², \
f = ∂L/∂q − (∂²L/∂q̇∂q) q̇; best of 3 processes. **AD / generated**: AD time over the \
generated code's, both timed in the AD binary's processes, their batches interleaved. **AD max rel. diff**: max |AD − generated| / max |generated| over \
the entries of M and f at four states (the run stops if it exceeds 1e-10).
";
