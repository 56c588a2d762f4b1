//! The mutator: edits of a model's tokens (delete, duplicate, swap, insert,
//! replace a number by an extreme one, a name by another, an operator by
//! another), of its sections (delete, duplicate, swap, splice one from
//! another model) and of its structure (wrap an atom in parentheses, minus
//! signs, calls or method chains, unwrap a group, stretch a range, repeat a
//! term). Delimiters stay balanced, as rustc guarantees a macro's input.

use crate::families::{INT_ATOMS, INTEGERS};
use crate::rng::Rng;

/// A token and whether whitespace preceded it (kept, so that `..=` and
/// `dot(x)` survive a round trip).
#[derive(Clone, Debug)]
pub struct Tok {
    pub text: String,
    pub space: bool,
}

/// Splits source text into tokens: words (identifiers, keywords, numbers
/// with suffixes and exponents), string literals, `..` and `..=`, and
/// single punctuation. Comments are dropped.
pub fn lex(s: &str) -> Vec<Tok> {
    let c: Vec<char> = s.chars().collect();
    let mut toks = Vec::new();
    let (mut i, mut space) = (0, false);
    let word = |ch: char| ch.is_alphanumeric() || ch == '_';
    while i < c.len() {
        let start = i;
        if c[i].is_whitespace() {
            space = true;
            i += 1;
            continue;
        }
        if c[i] == '/' && c.get(i + 1) == Some(&'/') {
            while i < c.len() && c[i] != '\n' {
                i += 1;
            }
            space = true;
            continue;
        }
        if c[i].is_ascii_digit() {
            while i < c.len() {
                let exponent_sign = (c[i] == '+' || c[i] == '-')
                    && matches!(c[i - 1], 'e' | 'E')
                    && c[start..i]
                        .iter()
                        .all(|ch| ch.is_ascii_digit() || ".eE_".contains(*ch));
                let decimal_point = c[i] == '.' && c.get(i + 1).is_some_and(|d| d.is_ascii_digit());
                if word(c[i]) || exponent_sign || decimal_point {
                    i += 1;
                } else {
                    break;
                }
            }
        } else if word(c[i]) {
            if c[i] == 'r' && c.get(i + 1) == Some(&'#') {
                i += 2;
            }
            while i < c.len() && word(c[i]) {
                i += 1;
            }
        } else if c[i] == '"' {
            i += 1;
            while i < c.len() && c[i] != '"' {
                i += if c[i] == '\\' { 2 } else { 1 };
            }
            i = (i + 1).min(c.len());
        } else if c[i] == '.' && c.get(i + 1) == Some(&'.') {
            i += if c.get(i + 2) == Some(&'=') { 3 } else { 2 };
        } else if c[i] == '\'' && c.get(i + 1).is_some_and(|&ch| word(ch)) {
            i += 1;
            while i < c.len() && word(c[i]) {
                i += 1;
            }
            if c.get(i) == Some(&'\'') {
                i += 1;
            }
        } else if c
            .get(i..i + 2)
            .is_some_and(|p| PAIRS.contains(&p.iter().collect::<String>().as_str()))
        {
            i += 2;
        } else {
            i += 1;
        }
        toks.push(Tok {
            text: c[start..i].iter().collect(),
            space,
        });
        space = false;
    }
    toks
}

/// Punctuation of two characters that must stay joined.
const PAIRS: [&str; 9] = ["::", "->", "=>", "==", "!=", "<=", ">=", "&&", "||"];

/// Back to text, with a space wherever one was, and wherever two tokens
/// brought together by an edit would lex as one (`x` `y`, `/` `/`).
pub fn join(toks: &[Tok]) -> String {
    let mut s = String::new();
    for (k, t) in toks.iter().enumerate() {
        let glued = k > 0 && {
            let prev = toks[k - 1].text.as_str();
            (is_word(prev) && is_word(&t.text))
                || (prev.ends_with('/') && t.text.starts_with(['/', '*']))
                || (prev.ends_with('.') && t.text.starts_with('.'))
        };
        if k > 0 && (t.space || glued) {
            s.push(' ');
        }
        s.push_str(&t.text);
    }
    s
}

fn is_word(s: &str) -> bool {
    s.chars()
        .last()
        .is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '"')
}

fn is_open(s: &str) -> bool {
    matches!(s, "(" | "[" | "{")
}

fn is_close(s: &str) -> bool {
    matches!(s, ")" | "]" | "}")
}

/// Whether every delimiter is closed by its partner.
pub fn balanced(toks: &[Tok]) -> bool {
    let mut stack = Vec::new();
    for t in toks {
        let s = t.text.as_str();
        match s {
            "(" => stack.push(")"),
            "[" => stack.push("]"),
            "{" => stack.push("}"),
            _ if is_close(s) && stack.pop() != Some(s) => return false,
            _ => {}
        }
    }
    stack.is_empty()
}

/// For each delimiter, the index of its partner (in a balanced sequence).
pub fn partners(toks: &[Tok]) -> Vec<Option<usize>> {
    let mut partner = vec![None; toks.len()];
    let mut open = Vec::new();
    for (k, t) in toks.iter().enumerate() {
        if is_open(&t.text) {
            open.push(k);
        } else if is_close(&t.text) {
            if let Some(o) = open.pop() {
                partner[o] = Some(k);
                partner[k] = Some(o);
            }
        }
    }
    partner
}

/// The index of the delimiter closing the one opened at `open`.
fn matching(toks: &[Tok], open: usize) -> Option<usize> {
    let mut depth = 0usize;
    for (k, t) in toks.iter().enumerate().skip(open) {
        if is_open(&t.text) {
            depth += 1;
        } else if is_close(&t.text) {
            depth -= 1;
            if depth == 0 {
                return Some(k);
            }
        }
    }
    None
}

fn tok(text: &str) -> Tok {
    Tok {
        text: text.into(),
        space: true,
    }
}

/// The model's sections: token ranges `start..end` (the `;` included)
/// inside the first brace group.
pub fn sections(toks: &[Tok]) -> Vec<(usize, usize)> {
    let Some(open) = toks.iter().position(|t| t.text == "{") else {
        return Vec::new();
    };
    let close = matching(toks, open).unwrap_or(toks.len());
    let mut out = Vec::new();
    let (mut depth, mut start) = (0usize, open + 1);
    for (k, tok) in toks.iter().enumerate().take(close).skip(open + 1) {
        let t = tok.text.as_str();
        if is_open(t) {
            depth += 1;
        } else if is_close(t) {
            depth = depth.saturating_sub(1);
        } else if t == ";" && depth == 0 {
            out.push((start, k + 1));
            start = k + 1;
        }
    }
    out
}

/// Tokens the mutator inserts (from `sum` on: the words it renames to).
const VOCABULARY: &str = "+ - * / ^ , ; : = . .. ..= in sum dot t let const kinetic potential dissipation forces constraints inputs coordinates parameters constants x N i 0 1 2.5 sin powi atan2 r#type struct # ! _ & budget jacobians parameter_derivatives";

const OPERATORS: [&str; 5] = ["+", "-", "*", "/", "^"];

const NUMBERS: [&str; 10] = [
    "0.0", "1e308", "1e400", "1e-400", "0.5", "1_000", "0x10", "1u8", "2.0f32", "-0.0",
];

/// `base` after one to six random edits; names the edits applied.
pub fn mutate(rng: &mut Rng, base: &str, donor: &str) -> (String, String) {
    let mut toks = lex(base);
    let donor = lex(donor);
    let mut applied = Vec::new();
    let count = 1 + rng.weighted(&[8, 4, 2, 1, 1, 1]);
    for _ in 0..count {
        for _attempt in 0..8 {
            let mut next = toks.clone();
            let name = edit(rng, &mut next, &donor);
            if let Some(name) = name {
                if balanced(&next) && next.len() < 200_000 {
                    toks = next;
                    applied.push(name);
                    break;
                }
            }
        }
    }
    (join(&toks), applied.join("+"))
}

/// Positions of tokens satisfying `f`.
fn positions(toks: &[Tok], f: impl Fn(&str) -> bool) -> Vec<usize> {
    (0..toks.len()).filter(|&k| f(&toks[k].text)).collect()
}

/// An atom at `k` and its extent: a word, with its call or index group.
fn atom_end(toks: &[Tok], k: usize) -> usize {
    match toks.get(k + 1) {
        Some(t) if t.text == "(" || t.text == "[" => matching(toks, k + 1).map_or(k + 1, |c| c + 1),
        _ => k + 1,
    }
}

fn edit(rng: &mut Rng, toks: &mut Vec<Tok>, donor: &[Tok]) -> Option<&'static str> {
    if toks.is_empty() {
        return None;
    }
    let plain = positions(toks, |t| !is_open(t) && !is_close(t));
    let words = positions(toks, |t| {
        t.starts_with(|c: char| c.is_alphanumeric() || c == '_')
    });
    let k = rng.below(toks.len());
    Some(
        match rng.weighted(&[6, 3, 3, 5, 7, 5, 4, 3, 2, 2, 3, 4, 2, 2, 2, 1]) {
            0 => {
                toks.remove(*pick(rng, &plain)?);
                "delete"
            }
            1 => {
                let p = *pick(rng, &plain)?;
                let copy = toks[p].clone();
                toks.insert(
                    p + 1,
                    Tok {
                        space: true,
                        ..copy
                    },
                );
                "duplicate"
            }
            2 => {
                let p = *pick(rng, &plain)?;
                if p + 1 >= toks.len() || is_open(&toks[p + 1].text) || is_close(&toks[p + 1].text)
                {
                    return None;
                }
                toks.swap(p, p + 1);
                "swap"
            }
            3 => {
                let v = *rng.pick(&VOCABULARY.split(' ').collect::<Vec<_>>());
                if rng.chance(0.15) {
                    let (open, close) = *rng.pick(&[("(", ")"), ("[", "]"), ("{", "}")]);
                    toks.insert(k, tok(close));
                    toks.insert(k, tok(open));
                } else {
                    toks.insert(k, tok(v));
                }
                "insert"
            }
            4 => {
                let numbers = positions(toks, |t| t.starts_with(|c: char| c.is_ascii_digit()));
                let p = match pick(rng, &numbers) {
                    Some(&p) => p,
                    None => *pick(rng, &words)?,
                };
                let n = match rng.below(4) {
                    0 | 1 => {
                        let sign = if rng.chance(0.3) { "-" } else { "" };
                        format!("{sign}{}", rng.pick(&INTEGERS))
                    }
                    2 => format!("({})", rng.pick(&INT_ATOMS)),
                    _ => rng.pick(&NUMBERS).to_string(),
                };
                toks.splice(
                    p..p + 1,
                    lex(&n).into_iter().map(|t| Tok { space: true, ..t }),
                );
                "number"
            }
            5 => {
                let p = *pick(rng, &words)?;
                let other = if rng.chance(0.7) {
                    toks[*pick(rng, &words)?].text.clone()
                } else {
                    let words: Vec<&str> = VOCABULARY.split(" ").skip(13).collect();
                    rng.pick(&words).to_string()
                };
                toks[p] = tok(&other);
                "rename"
            }
            6 => {
                let ops = positions(toks, |t| OPERATORS.contains(&t));
                let p = *pick(rng, &ops)?;
                let op = *rng.pick(&OPERATORS);
                toks[p] = tok(op);
                "operator"
            }
            7 => {
                let s = sections(toks);
                let (a, b) = *pick(rng, &s)?;
                toks.drain(a..b);
                "drop-section"
            }
            8 => {
                let s = sections(toks);
                let (a, b) = *pick(rng, &s)?;
                let copy: Vec<Tok> = toks[a..b].to_vec();
                let at = pick(rng, &s)?.0;
                toks.splice(at..at, copy);
                "copy-section"
            }
            9 => {
                let s = sections(toks);
                let (x, y) = (*pick(rng, &s)?, *pick(rng, &s)?);
                let (first, second) = if x.0 < y.0 { (x, y) } else { (y, x) };
                if first.1 > second.0 {
                    return None;
                }
                let a: Vec<Tok> = toks[first.0..first.1].to_vec();
                let b: Vec<Tok> = toks[second.0..second.1].to_vec();
                toks.splice(second.0..second.1, a);
                toks.splice(first.0..first.1, b);
                "swap-sections"
            }
            10 => {
                let s = sections(donor);
                let (a, b) = *pick(rng, &s)?;
                let at = pick(rng, &sections(toks))?.0;
                toks.splice(at..at, donor[a..b].iter().cloned());
                "splice"
            }
            11 => {
                let p = *pick(rng, &words)?;
                wrap(rng, toks, p);
                "wrap"
            }
            12 => {
                // Rarely the model's body itself, which leaves little to test.
                let opens = positions(toks, is_open);
                let body = toks.iter().position(|t| t.text == "{");
                let p = *pick(rng, &opens)?;
                if Some(p) == body && rng.chance(0.9) {
                    return None;
                }
                let c = matching(toks, p)?;
                if rng.chance(0.5) {
                    toks.drain(p + 1..c);
                } else {
                    toks.remove(c);
                    toks.remove(p);
                }
                "unwrap"
            }
            13 => {
                let ranges = positions(toks, |t| t == ".." || t == "..=");
                let p = *pick(rng, &ranges)?;
                if p == 0 || p + 1 >= toks.len() {
                    return None;
                }
                let side = if rng.chance(0.5) { p - 1 } else { p + 1 };
                toks[side] = tok(&format!(
                    "{}{}",
                    if rng.chance(0.3) { "-" } else { "" },
                    rng.pick(&INTEGERS)
                ));
                "range"
            }
            14 => {
                // A term repeated: a moderately long flat sum or product.
                let p = *pick(rng, &words)?;
                let end = atom_end(toks, p);
                let term: Vec<Tok> = toks[p..end].to_vec();
                let op = *rng.pick(&["+", "*", "-"]);
                let mut extra = Vec::new();
                for _ in 0..rng.log_size(300) {
                    extra.push(tok(op));
                    extra.extend(term.iter().cloned());
                }
                toks.splice(end..end, extra);
                "repeat"
            }
            _ => {
                let p = *pick(rng, &words)?;
                toks.insert(p, tok("#"));
                "hash"
            }
        },
    )
}

fn pick<'a, T>(rng: &mut Rng, items: &'a [T]) -> Option<&'a T> {
    (!items.is_empty()).then(|| rng.pick(items))
}

/// Wraps the atom at `p` in up to 64 layers of one kind: parentheses,
/// minus signs, a function, a method, a power.
fn wrap(rng: &mut Rng, toks: &mut Vec<Tok>, p: usize) {
    let end = atom_end(toks, p);
    let layers = rng.log_size(64);
    let (before, after): (Vec<&str>, Vec<&str>) = match rng.below(5) {
        0 => (vec!["("], vec![")"]),
        1 => (vec!["-"], vec![]),
        2 => (
            vec![*rng.pick(&["sin", "exp", "ln", "sqrt", "dot"]), "("],
            vec![")"],
        ),
        3 => (vec![], vec![".", *rng.pick(&["cos", "tanh"]), "(", ")"]),
        _ => (vec!["("], vec!["^", "2", ")"]),
    };
    for _ in 0..layers {
        for (offset, t) in after.iter().enumerate() {
            toks.insert(end + offset, tok(t));
        }
    }
    for _ in 0..layers {
        for t in before.iter().rev() {
            toks.insert(p, tok(t));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lexing_and_joining_keep_ranges_calls_and_numbers() {
        let src = "let x[i in 0..=N] = sum(j in 1..i, 2.5e-3*dot(q[j])^2); // note";
        let toks = lex(src);
        let texts: Vec<&str> = toks.iter().map(|t| t.text.as_str()).collect();
        assert!(texts.contains(&"..=") && texts.contains(&"..") && texts.contains(&"2.5e-3"));
        assert!(!texts.iter().any(|t| t.contains("note")));
        assert_eq!(join(&toks), src.trim_end_matches(" // note"));
    }

    #[test]
    fn mutants_stay_balanced_and_lex_as_rust_tokens() {
        let base = "pub struct M { const N = 2; coordinates: q[N]; parameters: m; \
                    let y[i in 0..N] = sum(j in 0..=i, sin(q[j])); \
                    kinetic: sum(i in 0..N, m/2*dot(y[i])^2); potential: -y[1]; }";
        for index in 0..500 {
            let mut rng = Rng::for_input(3, index);
            let (mutant, ops) = mutate(&mut rng, base, base);
            assert!(balanced(&lex(&mutant)), "{ops}: {mutant}");
            assert!(
                mutant.parse::<proc_macro2::TokenStream>().is_ok(),
                "{ops}: {mutant}"
            );
        }
    }
}
