//! `--minimize FILE`: the smallest input found that fails the same way, by
//! removing ever smaller runs of tokens (delta debugging, one pass per run
//! length) while the delimiters stay balanced and the outcome keeps its class
//! and, for a panic, its location.

use crate::mutate::{Tok, balanced, join, lex, partners, sections};
use crate::supervisor::Worker;
use crate::worker::{Class, Outcome};

/// What must stay the same: the class, and a panic's `file:line:col`.
fn signature(o: &Outcome) -> (Class, String) {
    let place = match o.class {
        Class::Panic => o.message.lines().next().unwrap_or("").to_string(),
        Class::Abort if o.message.contains("overflowed its stack") => "stack overflow".into(),
        _ => String::new(),
    };
    (o.class.clone(), place)
}

/// The minimized text and the number of worker runs it took; `None` if `text`
/// does not fail at all.
pub fn minimize(worker: &mut Worker, text: &str, max_runs: usize) -> Option<(String, usize)> {
    let first = worker.run(text, false);
    if !first.class.is_failure() {
        return None;
    }
    let target = signature(&first);
    let mut toks: Vec<Tok> = lex(text);
    let mut runs = 1;
    // Rounds until one removes nothing: whole sections, then runs of half
    // the input, a quarter, ... down to single tokens.
    let mut progress = true;
    while progress && runs < max_runs {
        progress = false;
        // `kinetic: ..;` is rarely a run of 2^k tokens at a multiple of 2^k.
        let mut k = 0;
        while let Some(&(start, end)) = sections(&toks).get(k) {
            if runs >= max_runs {
                break;
            }
            let candidate = without(&toks, start, end);
            runs += 1;
            if signature(&worker.run(&join(&candidate), false)) == target {
                toks = candidate;
                progress = true;
            } else {
                k += 1;
            }
        }
        let mut chunk = (toks.len() / 2).max(1);
        loop {
            let mut start = 0;
            while start < toks.len() && runs < max_runs {
                let end = (start + chunk).min(toks.len());
                let candidate = without(&toks, start, end);
                if !candidate.is_empty() && balanced(&candidate) {
                    runs += 1;
                    if signature(&worker.run(&join(&candidate), false)) == target {
                        toks = candidate;
                        progress = true;
                        continue;
                    }
                }
                // Short runs at every offset: `/ 2` and `* x` are pairs.
                start += if chunk <= 4 { 1 } else { chunk };
            }
            if chunk == 1 || runs >= max_runs {
                break;
            }
            chunk = if chunk <= 4 { chunk - 1 } else { chunk / 2 };
        }
    }
    Some((join(&toks), runs))
}

/// `toks` without `start..end` and without the partners of the delimiters
/// in that run: `sin(` out of `sin(sin(x))` takes its `)` along.
fn without(toks: &[Tok], start: usize, end: usize) -> Vec<Tok> {
    let partner = partners(toks);
    let mut drop = vec![false; toks.len()];
    for k in start..end {
        drop[k] = true;
        if let Some(p) = partner[k] {
            drop[p] = true;
        }
    }
    toks.iter()
        .zip(drop)
        .filter(|(_, d)| !d)
        .map(|(t, _)| t.clone())
        .collect()
}
