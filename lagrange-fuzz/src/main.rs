//! Fuzzing of the `lagrangian!` engine (`lagrange_engine::expand`), which
//! must answer every input with items or a `compile_error!`: never a panic,
//! a stack overflow, a runaway in time or in memory (issue 10).
//!
//! Inputs are a pure function of `--seed`, their index and the repository's
//! models: generated models
//! ([`generate`]), the repository's own models (extracted by `build.rs`),
//! their mutants ([`mutate`]) and pathological families ([`families`]),
//! mixed as [`inputs`] says. Each runs in a worker process (this binary with
//! `--worker`) on an 8 MiB thread under a memory limit ([`worker`]); the
//! supervisor ([`supervisor`]) kills a worker past the time limit and
//! replaces a dead one, so a stack overflow costs one input, not the run.
//! Outcomes: expansion, compile error, panic, abort, over time, over memory
//! (and, should they occur: malformed output, nondeterministic output,
//! unlexable input). Every finding goes to `--out` (default `findings/` in
//! this crate) as a file that `--replay` runs again.
//!
//! A sample of valid models (every 32nd input that expands, up to
//! `--determinism`, and every repository model) is expanded twice in one
//! process and again in a fresh one: all must give identical bytes.
//!
//! ```text
//! cargo run --release -p lagrange-fuzz -- --inputs 20000 --seed 1 --jobs 2
//! cargo run --release -p lagrange-fuzz -- --replay lagrange-fuzz/findings/panic-1-1234.txt
//! cargo run --release -p lagrange-fuzz -- --seed 1 --show 1234
//! ```
//!
//! The long run, 10⁶ inputs: 650 to 900 inputs/s on the 2-core development
//! machine once the engine stops every runaway at its budget, so 20 to 30
//! minutes (docs/guides/methods.md, "Measured", has the figures):
//!
//! ```text
//! cargo run --release -p lagrange-fuzz -- --inputs 1000000 --seed 1 --jobs 2
//! ```
//!
//! `tests/bounded.rs` runs a few thousand inputs in CI.

mod families;
mod generate;
mod inputs;
mod minimize;
mod mutate;
mod report;
mod rng;
mod supervisor;
mod worker;

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::time::Duration;

use inputs::Input;
use report::Report;
use supervisor::{Limits, Worker};
use worker::Class;

#[global_allocator]
static ALLOC: worker::Counting = worker::Counting;

/// Every this many inputs, one is expanded twice (the determinism sample).
const PROBE_EVERY: u64 = 32;

const USAGE: &str = "\
usage: lagrange-fuzz [--inputs N] [--seed S] [--jobs J] [--timeout-ms T] [--mem-mb M]
                     [--out DIR] [--determinism N] [--max-findings N]
       lagrange-fuzz --replay FILE...   [--timeout-ms T] [--mem-mb M]
       lagrange-fuzz --show INDEX       [--seed S]
       lagrange-fuzz --minimize FILE    [--timeout-ms T] [--mem-mb M]

  --inputs N        inputs to run (10000)
  --seed S          the input stream (1)
  --jobs J          worker processes in parallel (available cores)
  --timeout-ms T    time limit per input (10000)
  --mem-mb M        heap limit per input, MiB (1024)
  --out DIR         where findings go (lagrange-fuzz/findings)
  --determinism N   valid sampled models to re-expand in a fresh process (200; 0: off)
  --max-findings N  finding files to write; index.tsv lists all (1000)
  --replay FILE...  run saved inputs again and print their outcomes
  --show INDEX      print input INDEX of the seed's stream
  --minimize FILE   shrink a finding while it fails the same way; writes FILE.min";

struct Options {
    inputs: u64,
    seed: u64,
    jobs: usize,
    limits: Limits,
    out: PathBuf,
    determinism: usize,
    max_findings: usize,
    replay: Vec<PathBuf>,
    show: Option<u64>,
    minimize: Option<PathBuf>,
    worker: bool,
}

fn parse_args(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        inputs: 10_000,
        seed: 1,
        jobs: std::thread::available_parallelism().map_or(1, |n| n.get()),
        limits: Limits {
            timeout: Duration::from_secs(10),
            mem_mb: 1024,
        },
        out: PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/findings")),
        determinism: 200,
        max_findings: 1000,
        replay: Vec::new(),
        show: None,
        minimize: None,
        worker: false,
    };
    let mut it = args.iter();
    while let Some(flag) = it.next() {
        let mut value = || {
            it.next()
                .ok_or_else(|| format!("{flag} needs a value"))
                .cloned()
        };
        let number = |v: String| {
            v.replace('_', "")
                .parse::<u64>()
                .map_err(|_| format!("{flag}: `{v}` is not a number"))
        };
        match flag.as_str() {
            "--inputs" => o.inputs = number(value()?)?,
            "--seed" => o.seed = number(value()?)?,
            "--jobs" => o.jobs = number(value()?)?.max(1) as usize,
            "--timeout-ms" => o.limits.timeout = Duration::from_millis(number(value()?)?),
            "--mem-mb" => o.limits.mem_mb = number(value()?)? as usize,
            "--out" => o.out = PathBuf::from(value()?),
            "--determinism" => o.determinism = number(value()?)? as usize,
            "--max-findings" => o.max_findings = number(value()?)? as usize,
            "--show" => o.show = Some(number(value()?)?),
            "--minimize" => o.minimize = Some(PathBuf::from(value()?)),
            "--worker" => o.worker = true,
            "--replay" => {
                let rest = it.as_slice();
                let files = rest.iter().take_while(|a| !a.starts_with("--")).count();
                o.replay.extend(rest[..files].iter().map(PathBuf::from));
                it = rest[files..].iter();
                if o.replay.is_empty() {
                    return Err("--replay needs files".into());
                }
            }
            "-h" | "--help" => return Err(String::new()),
            other => return Err(format!("unknown argument `{other}`")),
        }
    }
    Ok(o)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let o = match parse_args(&args) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("{e}\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    if o.worker {
        worker::run(o.limits.mem_mb);
        return ExitCode::SUCCESS;
    }
    if let Some(index) = o.show {
        let input = inputs::input(o.seed, index);
        let mut out = std::io::stdout().lock();
        let _ = writeln!(
            out,
            "// seed {}, input {index}: {}\n{}",
            o.seed, input.origin, input.text
        );
        return ExitCode::SUCCESS;
    }
    if !o.replay.is_empty() {
        return replay(&o);
    }
    if let Some(path) = &o.minimize {
        return minimize(&o, path);
    }
    fuzz(&o)
}

fn fuzz(o: &Options) -> ExitCode {
    let report = Mutex::new(Report::new(
        o.seed,
        o.out.clone(),
        o.max_findings,
        o.inputs as usize,
    ));
    let next = AtomicU64::new(0);
    let starts = AtomicUsize::new(0);
    let probes: Mutex<Vec<(u64, Input, u128)>> = Mutex::new(Vec::new());
    std::thread::scope(|s| {
        for _ in 0..o.jobs {
            s.spawn(|| {
                let mut worker = Worker::new(o.limits);
                loop {
                    let index = next.fetch_add(1, Ordering::Relaxed);
                    if index >= o.inputs {
                        break;
                    }
                    let input = inputs::input(o.seed, index);
                    let probe = index % PROBE_EVERY == 0;
                    let outcome = worker.run(&input.text, probe);
                    if let (true, Class::Expansion, Some(h)) = (probe, &outcome.class, outcome.hash)
                    {
                        probes.lock().unwrap().push((index, input.clone(), h));
                    }
                    report.lock().unwrap().record(index, &input, &outcome);
                }
                starts.fetch_add(worker.starts, Ordering::Relaxed);
            });
        }
    });
    let mut report = report.into_inner().unwrap();
    let mut probes = probes.into_inner().unwrap();
    probes.sort_by_key(|p| p.0);
    probes.truncate(o.determinism);
    let determinism = determinism(o, probes, &mut report);
    let header = format!(
        "lagrange-fuzz: seed {}, {} inputs, {} jobs, limits {} ms and {} MiB per input, {} MiB stack; {} worker processes",
        o.seed,
        o.inputs,
        o.jobs,
        o.limits.timeout.as_millis(),
        o.limits.mem_mb,
        worker::STACK >> 20,
        starts.into_inner()
    );
    let (own, workers) = (usage(libc::RUSAGE_SELF), usage(libc::RUSAGE_CHILDREN));
    let header = format!(
        "{header}\n  cpu: workers {:.1} s, supervisor {:.1} s; largest worker resident set {:.0} MiB",
        workers.0,
        own.0,
        workers.1 as f64 / 1024.0
    );
    print!("{}", report.summary(&header, &determinism));
    if report.failures() > 0 {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// CPU seconds (user + system) and peak resident set (KiB) of this process
/// or of its reaped children (for children: the largest one's).
fn usage(who: libc::c_int) -> (f64, i64) {
    // SAFETY: getrusage fills the zeroed struct it is given.
    let mut u: libc::rusage = unsafe { std::mem::zeroed() };
    unsafe { libc::getrusage(who, &mut u) };
    let secs = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
    (secs(u.ru_utime) + secs(u.ru_stime), u.ru_maxrss)
}

/// The sampled valid models (hashed in the run) and every repository model
/// (hashed now, in a fresh process, each expanded twice there) expanded
/// again in another fresh process: identical bytes, or a finding.
fn determinism(o: &Options, probes: Vec<(u64, Input, u128)>, report: &mut Report) -> String {
    if o.determinism == 0 {
        return "determinism: not checked (--determinism 0)".into();
    }
    let sampled = probes.len();
    let mut sample: Vec<(u64, Input, Option<u128>)> = probes
        .into_iter()
        .map(|(i, input, h)| (i, input, Some(h)))
        .collect();
    let mut first = Worker::new(o.limits);
    for (k, text) in inputs::CORPUS.iter().enumerate() {
        let input = Input {
            text: text.to_string(),
            origin: format!("corpus {k}"),
        };
        let outcome = first.run(text, true);
        if outcome.class.is_failure() {
            report.write_finding(k as u64, &input, &outcome);
            *report.counts.entry(outcome.class).or_default() += 1;
        } else {
            sample.push((k as u64, input, outcome.hash));
        }
    }
    drop(first);
    let mut second = Worker::new(o.limits);
    let (mut same, mut differ) = (0, 0);
    for (index, input, hash) in &sample {
        let outcome = second.run(&input.text, true);
        if outcome.hash.is_some() && outcome.hash == *hash {
            same += 1;
        } else {
            differ += 1;
            let mut o = outcome.clone();
            o.message = format!(
                "expanded to different bytes in two processes ({})",
                outcome.message
            );
            o.class = Class::Nondeterministic;
            report.write_finding(*index, input, &o);
            *report.counts.entry(Class::Nondeterministic).or_default() += 1;
        }
    }
    format!(
        "determinism: {same} of {} models ({sampled} sampled valid inputs, {} repository models) \
         gave identical bytes twice in one process and again in another; {differ} differed",
        sample.len(),
        sample.len() - sampled
    )
}

fn replay(o: &Options) -> ExitCode {
    let mut worker = Worker::new(o.limits);
    let mut failing = 0;
    for path in &o.replay {
        let text = match std::fs::read_to_string(path) {
            Ok(t) => t,
            Err(e) => {
                eprintln!("{}: {e}", path.display());
                failing += 1;
                continue;
            }
        };
        let outcome = worker.run(&text, false);
        if outcome.class.is_failure() {
            failing += 1;
        }
        let peak = outcome.peak.map_or(String::new(), |p| {
            format!(", peak heap {:.1} MiB", p as f64 / (1 << 20) as f64)
        });
        println!(
            "{}: {} in {:.1} ms{peak}\n  {}",
            path.display(),
            outcome.class.name(),
            outcome.nanos as f64 / 1e6,
            outcome.message.replace('\n', "\n  ")
        );
    }
    if failing > 0 {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

fn minimize(o: &Options, path: &std::path::Path) -> ExitCode {
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("{}: {e}", path.display());
            return ExitCode::from(2);
        }
    };
    let mut worker = Worker::new(o.limits);
    match minimize::minimize(&mut worker, &text, 5000) {
        None => {
            println!("{}: does not fail", path.display());
            ExitCode::SUCCESS
        }
        Some((small, runs)) => {
            let out = path.with_extension("min");
            let outcome = worker.run(&small, false);
            println!(
                "{}: {} bytes after {runs} runs, {} in {:.1} ms: {}\n{small}",
                out.display(),
                small.len(),
                outcome.class.name(),
                outcome.nanos as f64 / 1e6,
                outcome.message.lines().next().unwrap_or("")
            );
            let _ = std::fs::write(&out, format!("{small}\n"));
            ExitCode::FAILURE
        }
    }
}
