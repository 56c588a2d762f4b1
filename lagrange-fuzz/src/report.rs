//! What a run found: counts per class, timings, memory, the kinds of
//! findings, and every failing input written out for `--replay`.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use crate::inputs::Input;
use crate::worker::{Class, Outcome};

/// An input worth naming in the summary.
#[derive(Clone, Debug)]
pub struct Noted {
    pub index: u64,
    pub origin: String,
    pub class: Class,
    pub nanos: u64,
    pub peak: Option<usize>,
}

/// The findings of one kind: same class, origin kind and message head.
#[derive(Debug)]
pub struct Kind {
    pub count: usize,
    pub first: u64,
    pub smallest: (usize, u64),
}

pub struct Report {
    pub seed: u64,
    pub out: PathBuf,
    pub max_findings: usize,
    pub counts: BTreeMap<Class, usize>,
    pub nanos: Vec<u64>,
    pub slowest: Vec<Noted>,
    pub peak: Option<Noted>,
    pub kinds: BTreeMap<(Class, String, String), Kind>,
    pub errors: BTreeMap<String, usize>,
    /// Inputs and total time per origin kind.
    pub by_kind: BTreeMap<String, (usize, u64)>,
    pub written: usize,
    pub started: Instant,
    last_progress: Instant,
    pub done: usize,
    pub total: usize,
}

impl Report {
    pub fn new(seed: u64, out: PathBuf, max_findings: usize, total: usize) -> Self {
        Report {
            seed,
            out,
            max_findings,
            counts: BTreeMap::new(),
            nanos: Vec::new(),
            slowest: Vec::new(),
            peak: None,
            kinds: BTreeMap::new(),
            errors: BTreeMap::new(),
            by_kind: BTreeMap::new(),
            written: 0,
            started: Instant::now(),
            last_progress: Instant::now(),
            done: 0,
            total,
        }
    }

    pub fn count(&self, class: &Class) -> usize {
        self.counts.get(class).copied().unwrap_or(0)
    }

    pub fn failures(&self) -> usize {
        Class::ALL
            .iter()
            .filter(|c| c.is_failure())
            .map(|c| self.count(c))
            .sum()
    }

    pub fn record(&mut self, index: u64, input: &Input, o: &Outcome) {
        *self.counts.entry(o.class.clone()).or_default() += 1;
        self.nanos.push(o.nanos);
        self.done += 1;
        let kind = self.by_kind.entry(input.kind().to_string()).or_default();
        kind.0 += 1;
        kind.1 += o.nanos;
        let noted = Noted {
            index,
            origin: input.origin.clone(),
            class: o.class.clone(),
            nanos: o.nanos,
            peak: o.peak,
        };
        self.slowest.push(noted.clone());
        self.slowest
            .sort_by(|a, b| b.nanos.cmp(&a.nanos).then(a.index.cmp(&b.index)));
        self.slowest.truncate(5);
        if o.peak > self.peak.as_ref().and_then(|p| p.peak) {
            self.peak = Some(noted);
        }
        if o.class == Class::CompileError {
            *self.errors.entry(shape(&o.message)).or_default() += 1;
        }
        if o.class.is_failure() {
            let key = (o.class.clone(), input.kind().to_string(), head(&o.message));
            let kind = self.kinds.entry(key).or_insert(Kind {
                count: 0,
                first: index,
                smallest: (usize::MAX, index),
            });
            kind.count += 1;
            if input.text.len() < kind.smallest.0 {
                kind.smallest = (input.text.len(), index);
            }
            self.write_finding(index, input, o);
        }
        if self.last_progress.elapsed().as_secs() >= 10 {
            self.last_progress = Instant::now();
            let secs = self.started.elapsed().as_secs_f64();
            eprintln!(
                "[{secs:.0} s] {}/{} inputs, {:.0}/s, {} expanded, {} compile errors, {} findings",
                self.done,
                self.total,
                self.done as f64 / secs,
                self.count(&Class::Expansion),
                self.count(&Class::CompileError),
                self.failures()
            );
        }
    }

    /// `DIR/<class>-<seed>-<index>.txt`, replayable, and a line in
    /// `DIR/index.tsv` (past `max_findings` files, the line only: the
    /// input is regenerated with `--seed S --show INDEX`).
    pub fn write_finding(&mut self, index: u64, input: &Input, o: &Outcome) {
        if std::fs::create_dir_all(&self.out).is_err() {
            return;
        }
        let name = format!("{}-{}-{index}.txt", o.class.name(), self.seed);
        let one_line = o.message.replace('\n', " ");
        if let Ok(mut f) = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(self.out.join("index.tsv"))
        {
            let _ = writeln!(
                f,
                "{}\t{}\t{index}\t{}\t{}",
                o.class.name(),
                self.seed,
                input.origin,
                one_line
            );
        }
        if self.written >= self.max_findings {
            return;
        }
        self.written += 1;
        let text = format!(
            "// lagrange-fuzz finding: {}\n// seed {}, input {index} ({})\n// {}\n\
             // replay: cargo run --release -p lagrange-fuzz -- --replay FILE\n{}\n",
            o.class.name(),
            self.seed,
            input.origin,
            one_line,
            input.text
        );
        let _ = std::fs::write(self.out.join(name), text);
    }

    /// The summary table and the machine-readable `result` line.
    pub fn summary(&self, header: &str, determinism: &str) -> String {
        let mut s = String::new();
        let total = self.done.max(1) as f64;
        let secs = self.started.elapsed().as_secs_f64();
        let _ = writeln!(s, "{header}");
        let _ = writeln!(s, "  {:<18} {:>9} {:>7}", "class", "inputs", "share");
        for c in Class::ALL {
            let n = self.count(&c);
            let mark = if c.is_failure() && n > 0 { "  <-" } else { "" };
            let share = 100.0 * n as f64 / total;
            let _ = writeln!(s, "  {:<18} {n:>9} {share:>6.2}%{mark}", c.name());
        }
        let mut sorted = self.nanos.clone();
        sorted.sort_unstable();
        let at = |q: f64| {
            sorted
                .get(((sorted.len() as f64 - 1.0) * q) as usize)
                .copied()
        };
        let ms = |n: Option<u64>| n.map_or(0.0, |n| n as f64 / 1e6);
        let _ = writeln!(
            s,
            "  {} inputs in {secs:.1} s: {:.0} inputs/s; per input median {:.2} ms, p99 {:.1} ms, max {:.0} ms",
            self.done,
            self.done as f64 / secs.max(1e-9),
            ms(at(0.5)),
            ms(at(0.99)),
            ms(at(1.0))
        );
        if let Some(p) = &self.peak {
            let _ = writeln!(
                s,
                "  peak heap of one input: {:.1} MiB (input {}, {})",
                p.peak.unwrap_or(0) as f64 / (1 << 20) as f64,
                p.index,
                p.origin
            );
        }
        let mut kinds: Vec<(&String, &(usize, u64))> = self.by_kind.iter().collect();
        kinds.sort_by(|a, b| b.1.1.cmp(&a.1.1).then(a.0.cmp(b.0)));
        let line: Vec<String> = kinds
            .iter()
            .map(|(k, (n, t))| format!("{k} {n} in {:.1} s", *t as f64 / 1e9))
            .collect();
        let _ = writeln!(s, "  time by origin: {}", line.join(", "));
        let _ = writeln!(s, "  slowest:");
        for n in &self.slowest {
            let _ = writeln!(
                s,
                "    input {:>8} {:>9.1} ms  {:<14} {}",
                n.index,
                n.nanos as f64 / 1e6,
                n.class.name(),
                clip(&n.origin, 70)
            );
        }
        let _ = writeln!(s, "  {determinism}");
        let mut errors: Vec<(&String, &usize)> = self.errors.iter().collect();
        errors.sort_by(|a, b| b.1.cmp(a.1).then(a.0.cmp(b.0)));
        let _ = writeln!(
            s,
            "  compile errors: {} distinct messages (by shape); most frequent:",
            errors.len()
        );
        for (m, n) in errors.iter().take(8) {
            let _ = writeln!(s, "    {n:>8}  {}", clip(m, 90));
        }
        if !self.kinds.is_empty() {
            let _ = writeln!(s, "  findings by kind (class, origin, message):");
            for ((class, kind, head), k) in &self.kinds {
                let _ = writeln!(
                    s,
                    "    {:>6}  {} {kind}: {} (first input {}, smallest {} with {} bytes)",
                    k.count,
                    class.name(),
                    clip(head, 80),
                    k.first,
                    k.smallest.1,
                    k.smallest.0
                );
            }
            let _ = writeln!(
                s,
                "  findings written: {} files in {} (index.tsv lists all {})",
                self.written,
                self.out.display(),
                self.failures()
            );
        }
        let counts: Vec<String> = Class::ALL
            .iter()
            .map(|c| format!("{}={}", c.name(), self.count(c)))
            .collect();
        let _ = writeln!(s, "result {}", counts.join(" "));
        s
    }
}

/// What findings are grouped by: a panic's location and message, a stack
/// overflow as such (not its thread's id), a death's signal.
fn head(message: &str) -> String {
    if message.contains("has overflowed its stack") {
        return "stack overflow".into();
    }
    clip(&message.replace('\n', " "), 120)
}

/// A compile error's message with names and numbers blanked: its shape.
fn shape(message: &str) -> String {
    let mut out = String::new();
    let mut in_code = false;
    for c in message.trim_matches('"').chars() {
        if c == '`' {
            in_code = !in_code;
            if in_code {
                out.push_str("`_`");
            }
        } else if !in_code && c.is_ascii_digit() {
            if !out.ends_with('#') {
                out.push('#');
            }
        } else if !in_code {
            out.push(c);
        }
    }
    out
}

fn clip(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        s.to_string()
    } else {
        let cut: String = s.chars().take(n).collect();
        format!("{cut}…")
    }
}
