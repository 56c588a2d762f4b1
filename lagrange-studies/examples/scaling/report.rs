//! The table, the fitted growth exponents and the targets, as markdown;
//! and the marked section of `BENCHMARKS.md` they replace.

use crate::engine::{EngineFailure, EngineStats};
use std::fmt::Write;
use std::time::Duration;

/// One chain length's figures.
pub struct Row {
    pub n: usize,
    pub engine: Result<EngineStats, EngineFailure>,
    /// `None` when builds were not asked for.
    pub build: Option<Result<BuildStats, String>>,
}

pub struct BuildStats {
    /// `cargo check --release` of the same, after touching the model: the
    /// front end (expansion in rustc, type checking) without codegen.
    pub check: Duration,
    /// `cargo build --release` of the model crate (lib and timing binary).
    pub build: Duration,
    /// Generated `mass_matrix_and_forcing`, ns per call.
    pub gen_ns: f64,
    pub ad: Option<AdStats>,
}

pub struct AdStats {
    /// `cargo build --release` of the AD binary alone (the lib is built).
    pub build: Duration,
    /// num-dual's M and f, ns per evaluation.
    pub ns: f64,
    /// The generated code timed in the same process, for the ratio.
    pub gen_ns: f64,
    pub max_rel_diff: f64,
}

impl Row {
    fn engine(&self) -> Option<&EngineStats> {
        self.engine.as_ref().ok()
    }
    fn built(&self) -> Option<&BuildStats> {
        self.build.as_ref().and_then(|b| b.as_ref().ok())
    }
    fn ad(&self) -> Option<&AdStats> {
        self.built().and_then(|b| b.ad.as_ref())
    }
    pub fn ratio(&self) -> Option<f64> {
        self.ad().map(|a| a.ns / a.gen_ns)
    }
}

/// The quantities whose growth is fitted.
struct Quantity {
    name: &'static str,
    value: fn(&Row) -> Option<f64>,
}

const QUANTITIES: &[Quantity] = &[
    Quantity {
        name: "operations, shared (CSE)",
        value: |r| r.engine().map(|e| e.shared.total() as f64),
    },
    Quantity {
        name: "of which M",
        value: |r| r.engine().map(|e| e.shared_mass.total() as f64),
    },
    Quantity {
        name: "of which f",
        value: |r| r.engine().map(|e| e.shared_forcing.total() as f64),
    },
    Quantity {
        name: "operations, tree (no sharing)",
        value: |r| {
            r.engine()
                .map(|e| e.tree.total())
                .filter(|&t| t < u64::MAX)
                .map(|t| t as f64)
        },
    },
    Quantity {
        name: "expression nodes",
        value: |r| r.engine().map(|e| e.nodes as f64),
    },
    Quantity {
        name: "expansion time",
        value: |r| r.engine().map(|e| e.expand.as_secs_f64()),
    },
    Quantity {
        name: "`cargo check --release` time",
        value: |r| r.built().map(|b| b.check.as_secs_f64()),
    },
    Quantity {
        name: "`cargo build --release` time",
        value: |r| r.built().map(|b| b.build.as_secs_f64()),
    },
    Quantity {
        name: "generated M + f, ns per call",
        value: |r| r.built().map(|b| b.gen_ns),
    },
    Quantity {
        name: "AD M + f, ns per call",
        value: |r| r.ad().map(|a| a.ns),
    },
];

/// The log-log slope of a quantity between two chain lengths.
fn slope(rows: &[Row], q: &Quantity, n1: usize, n2: usize) -> Option<f64> {
    let at = |n| rows.iter().find(|r| r.n == n).and_then(q.value);
    let (a, b) = (at(n1)?, at(n2)?);
    (a > 0.0 && b > 0.0).then(|| (b / a).ln() / (n2 as f64 / n1 as f64).ln())
}

/// Doublings (and the one 1.5× step past 20) that the run covers.
fn spans(rows: &[Row]) -> Vec<(usize, usize)> {
    let has = |n| rows.iter().any(|r| r.n == n);
    [(5, 10), (10, 20), (15, 30), (20, 30)]
        .into_iter()
        .filter(|&(a, b)| has(a) && has(b))
        .collect()
}

fn count(x: u64) -> String {
    if x == u64::MAX {
        "> 1.8e19".into()
    } else if x >= 10_000_000 {
        format!("{:.2e}", x as f64)
    } else {
        x.to_string()
    }
}

fn secs(d: Duration) -> String {
    let s = d.as_secs_f64();
    if s < 0.01 {
        format!("{:.4}", s)
    } else if s < 10.0 {
        format!("{:.3}", s)
    } else {
        format!("{:.1}", s)
    }
}

fn ns(x: f64) -> String {
    if x < 100.0 {
        format!("{x:.1}")
    } else {
        format!("{x:.0}")
    }
}

pub fn table(rows: &[Row]) -> String {
    let mut s = String::new();
    s.push_str(
        "| N | expand (s) | derive (s) | emit (s) | nodes | steps | code (KB) | ops, shared | of which M / f | ops, tree \
         | check (s) | build (s) | M+f (ns) | AD (ns) | AD / generated | AD max rel. diff |\n",
    );
    s.push_str(&"|---:".repeat(16));
    s.push_str("|\n");
    for r in rows {
        write!(s, "| {} ", r.n).unwrap();
        match &r.engine {
            Ok(e) => write!(
                s,
                "| {} | {} | {} | {} | {} | {:.0} | {} | {} / {} | {} ",
                secs(e.expand),
                secs(e.derive),
                secs(e.emit),
                e.nodes,
                count(e.steps),
                e.code_bytes as f64 / 1024.0,
                count(e.shared.total()),
                count(e.shared_mass.total()),
                count(e.shared_forcing.total()),
                count(e.tree.total()),
            )
            .unwrap(),
            Err(f) if f.over_budget => s.push_str(&format!(
                "| over the work budget ({} steps) | | | | | | | | ",
                crate::engine::budget()
            )),
            Err(f) => write!(s, "| error: {} | | | | | | | | ", one_line(&f.message)).unwrap(),
        }
        match &r.build {
            None => s.push_str("| | | | | | |"),
            Some(Err(e)) => write!(s, "| {} | | | | | |", one_line(e)).unwrap(),
            Some(Ok(b)) => {
                write!(
                    s,
                    "| {} | {} | {} ",
                    secs(b.check),
                    secs(b.build),
                    ns(b.gen_ns)
                )
                .unwrap();
                match (&b.ad, r.ratio()) {
                    (Some(a), Some(ratio)) => write!(
                        s,
                        "| {} | {:.0}× | {:.1e} |",
                        ns(a.ns),
                        ratio,
                        a.max_rel_diff
                    )
                    .unwrap(),
                    _ => s.push_str("| | | |"),
                }
            }
        }
        s.push('\n');
    }
    s
}

fn one_line(s: &str) -> String {
    let first = s.lines().next().unwrap_or("");
    first.replace('|', "\\|")
}

pub fn exponents(rows: &[Row]) -> String {
    let spans = spans(rows);
    if spans.is_empty() {
        return "(the run covers no doubling of N to fit over)\n".into();
    }
    let mut s = String::from("| quantity |");
    for (a, b) in &spans {
        write!(s, " {a} → {b} |").unwrap();
    }
    s.push_str("\n|---|");
    s.push_str(&"---:|".repeat(spans.len()));
    s.push('\n');
    for q in QUANTITIES {
        let fits: Vec<Option<f64>> = spans.iter().map(|&(a, b)| slope(rows, q, a, b)).collect();
        if fits.iter().all(Option::is_none) {
            continue;
        }
        write!(s, "| {} |", q.name).unwrap();
        for f in fits {
            match f {
                Some(f) => write!(s, " {f:.2} |").unwrap(),
                None => s.push_str(" |"),
            }
        }
        s.push('\n');
    }
    s
}

/// A target: what was promised, whether the run meets it, and the figure.
struct Target {
    what: String,
    verdict: Option<String>,
    figure: String,
}

fn targets(rows: &[Row]) -> Vec<Target> {
    let row = |n| rows.iter().find(|r| r.n == n);
    let expand = |n| row(n).and_then(Row::engine).map(|e| e.expand.as_secs_f64());
    let mut out = Vec::new();
    for (n, limit) in [(10, 0.1), (20, 1.0)] {
        let t = expand(n);
        out.push(Target {
            what: format!("{n}-link chain expands in < {limit} s"),
            verdict: t.map(|t| verdict_text(t < limit)),
            figure: t.map_or("not measured".into(), |t| format!("{t:.3} s")),
        });
    }
    let ops = &QUANTITIES[0];
    let fit = slope(rows, ops, 10, 20).or_else(|| slope(rows, ops, 5, 10));
    out.push(Target {
        what: "operation count grows no faster than ~N² (fitted exponent ≤ 2.2)".into(),
        verdict: fit.map(|f| verdict_text(f <= 2.2)),
        figure: match (slope(rows, ops, 5, 10), slope(rows, ops, 10, 20)) {
            (Some(a), Some(b)) => format!("exponent {a:.2} (5 → 10), {b:.2} (10 → 20)"),
            (Some(a), None) => format!("exponent {a:.2} (5 → 10)"),
            (None, Some(b)) => format!("exponent {b:.2} (10 → 20)"),
            (None, None) => "not measured".into(),
        },
    });
    let build = row(20).and_then(Row::built).map(|b| b.build.as_secs_f64());
    out.push(Target {
        what: "20-link chain: `cargo build --release` of its crate in < 60 s".into(),
        verdict: build.map(|b| verdict_text(b < 60.0)),
        figure: build.map_or("not measured".into(), |b| format!("{b:.1} s")),
    });
    let ratios: Vec<(usize, f64)> = rows
        .iter()
        .filter_map(|r| r.ratio().map(|x| (r.n, x)))
        .collect();
    out.push(ad_target(&ratios));
    out
}

fn ad_target(ratios: &[(usize, f64)]) -> Target {
    let worst = |from: usize| {
        ratios
            .iter()
            .copied()
            .filter(|&(n, _)| n >= from)
            .min_by(|a, b| a.1.total_cmp(&b.1))
    };
    // One link is a Hessian in 2 variables, which AD does cheaply: the target
    // is about chains, so N = 1 is shown but judged apart.
    let (verdict, judged) = match (worst(1), worst(2)) {
        (Some((n, x)), _) if x >= 10.0 => (Some("met".to_string()), Some((n, x))),
        (Some((1, one)), Some(rest)) if rest.1 >= 10.0 => (
            Some(format!("met for N ≥ 2 (N = 1: {one:.0}×)")),
            Some(rest),
        ),
        (Some(w), _) => (Some(verdict_text(false)), Some(w)),
        (None, _) => (None, None),
    };
    Target {
        what: "generated M + f many times (≥ 10×) faster than runtime AD, at every N".into(),
        verdict,
        figure: match (judged, ratios.last()) {
            (Some((n, x)), Some(&(last_n, last))) => {
                format!("{x:.0}× at worst (N = {n}), {last:.0}× at N = {last_n}")
            }
            _ => "not measured".into(),
        },
    }
}

fn verdict_text(met: bool) -> String {
    if met { "met" } else { "**missed**" }.into()
}

pub fn targets_table(rows: &[Row]) -> String {
    let mut s = String::from("| target | met? | figure |\n|---|---|---|\n");
    for t in targets(rows) {
        let verdict = t.verdict.as_deref().unwrap_or("not measured");
        writeln!(s, "| {} | {} | {} |", t.what, verdict, t.figure).unwrap();
    }
    s
}

pub const START: &str = "<!-- scaling:start (written by `cargo run --release -p lagrange-studies --example scaling`) -->";
pub const END: &str = "<!-- scaling:end -->";

/// Replaces the marked section of `text` (or appends one) with `section`.
pub fn splice(text: &str, section: &str) -> String {
    let block = format!("{START}\n{section}{END}\n");
    match (text.find(START), text.find(END)) {
        (Some(a), Some(b)) if a < b => {
            format!(
                "{}{}{}",
                &text[..a],
                block,
                &text[b + END.len()..].trim_start_matches('\n')
            )
        }
        _ if text.trim().is_empty() => format!("# Benchmarks\n\n{block}"),
        _ => format!("{}\n\n{block}", text.trim_end()),
    }
}
