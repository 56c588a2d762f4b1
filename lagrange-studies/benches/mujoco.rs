//! lagrange's `Stepper` beside MuJoCo, the engine a robotics user would
//! pick instead, on the N-link chain (point masses m = l = 1 in absolute
//! angles, released from rest at 0.5 rad, 2 s) and on a branched tree in
//! relative angles (2 × B links, the second model, on which nothing was
//! tuned): ns per step of RK4 and of symplectic Euler (MuJoCo: RK4 and its
//! default semi-implicit Euler) at the same step, and the final state's
//! error of each against Dop853 at 1e-13.
//!
//! MuJoCo runs from Python (PyPI `mujoco`, `benches/peers/mujoco_chain.py`)
//! in its own C loop (`mujoco.rollout`, one thread); our side is a scratch
//! crate built here against the checkout (`benches/peers/mujoco/`, release,
//! one codegen unit, the engine optimized) so that the studies' own build
//! never expands the 64-link models. The timings alternate between the two
//! sides, `--reps` rounds (default 5), and the table gives the median of
//! each side and of the per-round ratios. It needs a Python with mujoco
//! and numpy (`LAGRANGE_PEERS_PYTHON`, else `python3`), and says so and
//! skips without one:
//!
//! ```sh
//! python3 -m venv ../peers-venv && ../peers-venv/bin/pip install mujoco numpy
//! LAGRANGE_PEERS_PYTHON=../peers-venv/bin/python cargo bench -p lagrange-studies --bench mujoco
//! ... --bench mujoco -- --chains 2,5,10 --trees 5 --reps 3      # quicker
//! ... --bench mujoco -- --lagrange ../other-checkout            # another tree's runtime
//! ... --bench mujoco -- --engine-only                           # the expansions alone
//! ... --bench mujoco -- --native    # ours with -C target-cpu=native (AVX2, FMA here)
//! ```
//!
//! MuJoCo's wheels are built for AVX (they stop with an illegal instruction
//! on a CPU without it); ours are built for the default x86-64 target, SSE2,
//! two `f64` lanes, unless `--native` builds the scratch crate with
//! `RUSTFLAGS="-C target-cpu=native"` (in its own target directory; the
//! table is then written to `target/peers/mujoco-native.txt`).
//!
//! About 17 minutes on 2 cores with the defaults (chains 2, 5, 10, 20, 40,
//! 64; trees 2 × 5 and 2 × 32), 12 of them building the scratch crate: the
//! 2 × 32 tree's generated code is 14 MB. `--trees 5` leaves it out (about
//! 4 minutes). The build time is printed, and the table is written to
//! `target/peers/mujoco.txt`.
//! Under `cargo test` (no `--bench` argument) it only says what it would do.

#[path = "../examples/support/peers_python.rs"]
mod peers_python;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};
use std::time::Instant;

use serde_json::Value;

struct Options {
    chains: Vec<usize>,
    trees: Vec<usize>,
    reps: usize,
    hs: String,
    lagrange: PathBuf,
    engine_only: bool,
    native: bool,
}

fn list(value: &str) -> Result<Vec<usize>, String> {
    value
        .split(',')
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().map_err(|_| format!("not a size: {s}")))
        .collect()
}

impl Options {
    fn parse(args: &[String], root: &Path) -> Result<Self, String> {
        let mut o = Options {
            chains: vec![2, 5, 10, 20, 40, 64],
            trees: vec![5, 32],
            reps: 5,
            hs: "1e-2,1e-3".into(),
            lagrange: root.to_path_buf(),
            engine_only: false,
            native: false,
        };
        let mut it = args.iter();
        while let Some(flag) = it.next() {
            let mut value = || it.next().ok_or(format!("{flag} needs a value"));
            match flag.as_str() {
                "--chains" => o.chains = list(value()?)?,
                "--trees" => o.trees = list(value()?)?,
                "--reps" => o.reps = value()?.parse().map_err(|_| "--reps: a count")?,
                "--hs" => o.hs = value()?.clone(),
                "--lagrange" => o.lagrange = PathBuf::from(value()?),
                "--engine-only" => o.engine_only = true,
                "--native" => o.native = true,
                other => return Err(format!("unknown option {other}")),
            }
        }
        if o.reps == 0 {
            return Err("--reps: at least 1".into());
        }
        Ok(o)
    }
}

fn main() -> ExitCode {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let benching = args.iter().any(|a| a == "--bench");
    args.retain(|a| a != "--bench");
    let studies = Path::new(env!("CARGO_MANIFEST_DIR"));
    let peers = studies.join("benches/peers");
    let root = studies
        .parent()
        .expect("lagrange-studies sits in the repository");
    if !benching {
        println!("mujoco: run with `cargo bench -p lagrange-studies --bench mujoco`");
        return ExitCode::SUCCESS;
    }
    let options = match Options::parse(&args, root) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("mujoco: {e}");
            return ExitCode::FAILURE;
        }
    };
    // The expansions alone need no Python.
    let python = match peers_python::importing("mujoco, numpy") {
        Ok(python) => Some(python),
        Err(_) if options.engine_only => None,
        Err(why) => {
            println!("mujoco: skipped: {why}");
            return ExitCode::SUCCESS;
        }
    };
    match run(&options, python.as_deref(), &peers, root) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("mujoco: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The scratch crate's `src/models.rs`: one model per size and `cases`,
/// which runs `reference` or `time` on each; and each model's name and
/// source, for the engine's figures.
fn models(options: &Options, peers: &Path) -> Result<(String, Vec<(String, String)>), String> {
    let read = |name: &str| {
        std::fs::read_to_string(peers.join("mujoco").join(name)).map_err(|e| format!("{name}: {e}"))
    };
    let (chain, tree) = (read("chain.rs.in")?, read("tree.rs.in")?);
    let mut text = String::from(
        "// Written by benches/mujoco.rs.\nuse lagrange::lagrangian;\nuse super::{reference, time};\n\n",
    );
    let mut cases = String::new();
    let mut sources = Vec::new();
    for &n in &options.chains {
        let source = chain.replace("@N@", &n.to_string());
        text += &source;
        sources.push((format!("chain {n}"), source));
        let model = format!("Chain{n}::new([1.0; {n}], [1.0; {n}])");
        let _ = writeln!(
            cases,
            "    parts.push(if reference_mode {{ reference(\"chain {n}\", {model}, true, hs) }} else {{ time(\"chain {n}\", {model}, true) }});"
        );
    }
    for &b in &options.trees {
        let source = tree.replace("@B@", &b.to_string());
        text += &source;
        sources.push((format!("tree 2x{b}"), source));
        let model = format!("Tree{b}::<f64>::new()");
        let _ = writeln!(
            cases,
            "    parts.push(if reference_mode {{ reference(\"tree 2x{b}\", {model}, false, hs) }} else {{ time(\"tree 2x{b}\", {model}, false) }});"
        );
    }
    let _ = write!(
        text,
        "\npub fn cases(reference_mode: bool, hs: &[f64]) -> Vec<String> {{\n    let mut parts = Vec::new();\n{cases}    parts\n}}\n"
    );
    Ok((text, sources))
}

/// The engine on one model's source, as `lagrangian!` runs it inside
/// rustc (but built here with the bench's optimizations): seconds to
/// expand, arithmetic operations of `M` and `f` as emitted (shared
/// subexpressions once), and the emitted code's size in kB.
fn engine(source: &str) -> Result<(f64, u64, usize), String> {
    let open = source
        .find("lagrangian! {")
        .ok_or("no lagrangian! in the template")?;
    let close = source.rfind('}').ok_or("no closing brace")?;
    let body = &source[open + "lagrangian! {".len()..close];
    let tokens: proc_macro2::TokenStream = body.parse().map_err(|e| format!("{e}"))?;
    let clock = Instant::now();
    let code = lagrange_engine::expand(tokens.clone()).to_string();
    let seconds = clock.elapsed().as_secs_f64();
    let derived = lagrange_engine::derive(tokens).map_err(|e| e.to_string())?;
    let (shared, _) = derived.op_counts();
    Ok((seconds, shared.total(), code.len() / 1000))
}

fn output(command: &mut Command) -> Result<String, String> {
    let out = command
        .output()
        .map_err(|e| format!("could not run {command:?}: {e}"))?;
    if !out.status.success() {
        return Err(format!(
            "{command:?} failed ({}):\n{}",
            out.status,
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    String::from_utf8(out.stdout).map_err(|e| e.to_string())
}

fn json(text: &str) -> Result<Value, String> {
    serde_json::from_str(text).map_err(|e| format!("not JSON ({e}): {text}"))
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 {
        values[n / 2]
    } else {
        (values[n / 2 - 1] + values[n / 2]) / 2.0
    }
}

fn run(options: &Options, python: Option<&str>, peers: &Path, root: &Path) -> Result<(), String> {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("target"));
    let work = target.join("peers/mujoco");
    std::fs::create_dir_all(work.join("src")).map_err(|e| e.to_string())?;
    let lagrange = options
        .lagrange
        .canonicalize()
        .map_err(|e| format!("--lagrange {}: {e}", options.lagrange.display()))?;
    let manifest = std::fs::read_to_string(peers.join("mujoco/Cargo.toml.in"))
        .map_err(|e| e.to_string())?
        .replace("@LAGRANGE@", &lagrange.display().to_string());
    let write = |path: PathBuf, text: &str| {
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))
    };
    write(work.join("Cargo.toml"), &manifest)?;
    std::fs::copy(peers.join("mujoco/main.rs"), work.join("src/main.rs"))
        .map_err(|e| e.to_string())?;
    let (text, sources) = models(options, peers)?;
    write(work.join("src/models.rs"), &text)?;
    let mut expansions = String::from(
        "The engine on each model (`lagrange_engine::expand`, built with the bench's optimizations, one run):\n\n\
         | model | expand (s) | ops of M and f, shared | code (kB) |\n|---|---:|---:|---:|\n",
    );
    for (name, source) in &sources {
        let (seconds, ops, kb) = engine(source)?;
        println!("mujoco: {name} expands in {seconds:.2} s ({ops} operations, {kb} kB)");
        let _ = writeln!(expansions, "| {name} | {seconds:.2} | {ops} | {kb} |");
    }

    let Some(python) = python.filter(|_| !options.engine_only) else {
        print!("\n{expansions}");
        return Ok(());
    };
    println!(
        "mujoco: building the models against {} in {}",
        lagrange.display(),
        work.display()
    );
    let clock = Instant::now();
    let mut cargo = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()));
    let scratch_target = work.join(if options.native {
        "target-native"
    } else {
        "target"
    });
    cargo
        .args(["build", "--release", "--quiet"])
        .current_dir(&work)
        .env("CARGO_TARGET_DIR", &scratch_target);
    if options.native {
        cargo.env("RUSTFLAGS", "-C target-cpu=native");
    }
    let status = cargo.status().map_err(|e| e.to_string())?;
    if !status.success() {
        return Err(format!("building the scratch crate failed ({status})"));
    }
    let build = clock.elapsed().as_secs_f64();
    println!("mujoco: built in {build:.0} s (cargo build --release, this process's load)");
    let ours = scratch_target.join("release/chain-vs-mujoco");

    let reference_text = output(Command::new(&ours).args(["reference", "--hs", &options.hs]))?;
    let reference_path = work.join("reference.json");
    write(reference_path.clone(), &reference_text)?;
    let reference = json(&reference_text)?;
    let script = peers.join("mujoco_chain.py");
    let theirs_errors = json(&output(
        Command::new(python)
            .arg(&script)
            .arg("errors")
            .arg(&reference_path),
    )?)?;

    let mut rounds: Vec<(Value, Value)> = Vec::new();
    for round in 1..=options.reps {
        println!("mujoco: timing, round {round} of {}", options.reps);
        let ours_time = json(&output(Command::new(&ours).arg("time"))?)?;
        let theirs_time = json(&output(
            Command::new(python)
                .arg(&script)
                .arg("time")
                .arg(&reference_path),
        )?)?;
        rounds.push((ours_time, theirs_time));
    }

    let version = theirs_errors["mujoco"].as_str().unwrap_or("?");
    let h_timed = reference["h_timed"].as_f64().unwrap_or(f64::NAN);
    let mut table = format!(
        "lagrange's Stepper beside MuJoCo {version} (mujoco.rollout, one thread): ns per step at h = {h_timed}, \
         medians of {} interleaved rounds (ratio: the median of the rounds' ratios, ours / MuJoCo); \
         ours built for {}\n\n",
        options.reps,
        if options.native {
            "-C target-cpu=native"
        } else {
            "the default target"
        }
    );
    table += "| model | N | method | ours ns/step | MuJoCo ns/step | ratio |\n|---|---:|---|---:|---:|---:|\n";
    // In the order of the options (the JSON objects are sorted by name).
    let names: Vec<&String> = sources.iter().map(|(name, _)| name).collect();
    for &name in &names {
        let n = reference[name]["n"].as_u64().unwrap_or(0);
        for (method, theirs) in [("RK4", "RK4"), ("SymplecticEuler", "Euler")] {
            let take = |side: usize| -> Vec<f64> {
                rounds
                    .iter()
                    .map(|r| if side == 0 { &r.0 } else { &r.1 })
                    .filter_map(|v| v[name.as_str()][method].as_f64())
                    .collect()
            };
            let (a, b) = (take(0), take(1));
            let ratios = a.iter().zip(&b).map(|(x, y)| x / y).collect();
            let _ = writeln!(
                table,
                "| {name} | {n} | {method} / {theirs} | {:.0} | {:.0} | {:.3} |",
                median(a),
                median(b),
                median(ratios)
            );
        }
    }
    table += "\nThe final state's error against Dop853 at 1e-13 (max over q and q̇; the chain's in absolute angles):\n\n";
    table += "| model | h | method | ours | MuJoCo |\n|---|---:|---|---:|---:|\n";
    for &name in &names {
        let ours_rows = reference[name]["ours"]
            .as_array()
            .cloned()
            .unwrap_or_default();
        let theirs_rows = theirs_errors[name.as_str()]
            .as_array()
            .cloned()
            .unwrap_or_default();
        for (o, t) in ours_rows.iter().zip(&theirs_rows) {
            let _ = writeln!(
                table,
                "| {name} | {} | {} | {:.2e} | {:.2e} |",
                o["h"],
                o["method"].as_str().unwrap_or("?"),
                o["error"].as_f64().unwrap_or(f64::NAN),
                t["error"].as_f64().unwrap_or(f64::NAN)
            );
        }
    }
    let _ = writeln!(
        table,
        "\nThe scratch crate (every model above) built in {build:.0} s."
    );
    print!("\n{table}");
    let out = target.join(if options.native {
        "peers/mujoco-native.txt"
    } else {
        "peers/mujoco.txt"
    });
    write(out.clone(), &table)?;
    println!("\nmujoco: written to {}", out.display());
    Ok(())
}
