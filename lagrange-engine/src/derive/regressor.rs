//! The regressor: `M q̈ − f = Y(t, q, q̇, q̈) π + r₀(t, q, q̇, q̈)`, for a
//! model written with `#[lagrange(regressor(p, ..))]`, `π` the products of
//! the listed parameters that occur (the lumped parameters), grouped into
//! base parameters, and `r₀` the terms free of them.
//!
//! The residual is a polynomial in the listed parameters wherever they
//! enter only as masses, inertias, damping, stiffness or lengths times
//! those: its Taylor coefficients at zero are exact, each a mixed partial
//! derivative (`∂^α r / ∂p^α / α!`) with the listed parameters then set to
//! zero. A parameter in a sine, a root or a denominator makes the
//! derivatives go on forever: past [`MAX_DEGREE`] it is refused, on the
//! parameter's token.
//!
//! Base parameters: a column that is a constant multiple of an earlier
//! one (the chain's `m_k l_i l_j` for every `k` past `i` and `j`) is
//! merged into it, its product added to the earlier one's with that
//! factor (`(m2 + m3) l1 l2`). The multiples are found by evaluating the
//! columns at generic states and parameter values (deterministic ones);
//! any other dependence among the columns that remain is refused, naming
//! the lumped parameter the others determine.

use super::{Equations, ExprMatrix};
use crate::expr::{ExprId, Pool, SymId};
use crate::model::Model;
use proc_macro2::Span;
use std::collections::HashMap;

/// Products of more listed parameters than this are taken for a
/// parameter the residual is not polynomial in.
pub const MAX_DEGREE: usize = 6;

/// The regressor of a model.
pub struct Regressor {
    /// Each lumped parameter's name, as its products read
    /// (`m[1]*l[0]*l[1] + m[2]*l[0]*l[1]`).
    pub names: Vec<String>,
    /// `Y`, `N × K` row-major.
    pub columns: ExprMatrix,
    /// `r₀`, the terms free of the listed parameters.
    pub offset: Vec<ExprId>,
    /// Each lumped parameter as an expression of the parameters.
    pub parameters: Vec<ExprId>,
}

/// A monomial: the listed parameters' indices, sorted, with repetition.
type Monomial = Vec<usize>;

/// Derives the regressor if the model asks for one, into `eq.regressor`.
pub fn regressor(model: &mut Model, eq: &mut Equations) -> syn::Result<()> {
    let Some(listed) = model.options.regressor.clone() else {
        return Ok(());
    };
    // The listed fields' scalars, with the token each is named by.
    let mut unknowns: Vec<(SymId, Span)> = Vec::new();
    for name in &listed {
        let scalars: Vec<SymId> = model
            .parameters
            .iter()
            .zip(&model.symbols.parameters)
            .filter(|(p, _)| p.name == *name)
            .map(|(_, &s)| s)
            .collect();
        if scalars.is_empty() {
            let known: Vec<String> = model.fields.iter().map(|f| f.name.to_string()).collect();
            return Err(syn::Error::new(
                name.span(),
                format!(
                    "`{name}` is not a parameter: `regressor(...)` lists parameters (here: {})",
                    if known.is_empty() {
                        "none".to_string()
                    } else {
                        known.join(", ")
                    }
                ),
            ));
        }
        unknowns.extend(scalars.into_iter().map(|s| (s, name.span())));
    }
    let syms: Vec<SymId> = unknowns.iter().map(|(s, _)| *s).collect();
    let unknown_names: Vec<String> = syms
        .iter()
        .map(|&s| model.parameters[param_index(model, s)].to_string())
        .collect();
    let pool = &mut model.pool;
    let n = eq.forcing.len();
    // r = M q̈ − f.
    let residual: Vec<ExprId> = (0..n)
        .map(|i| {
            let mut terms: Vec<ExprId> = (0..n)
                .map(|j| {
                    let a = pool.sym(model.symbols.accelerations[j]);
                    pool.mul2(eq.mass[i][j], a)
                })
                .collect();
            terms.push(pool.neg(eq.forcing[i]));
            pool.add(&terms)
        })
        .collect();
    // Every monomial's Taylor coefficient, depth first, each monomial once
    // (its indices non-decreasing).
    let mut coefficients: Vec<(Monomial, Vec<ExprId>)> = Vec::new();
    let mut work: Vec<(Monomial, Vec<ExprId>)> = vec![(Vec::new(), residual)];
    while let Some((monomial, exprs)) = work.pop() {
        if pool.exhausted() {
            return Ok(());
        }
        let from = monomial.last().copied().unwrap_or(0);
        for k in from..syms.len() {
            if !exprs.iter().any(|&e| pool.depends_on(e, syms[k])) {
                continue;
            }
            if monomial.len() == MAX_DEGREE {
                return Err(syn::Error::new(
                    unknowns[k].1,
                    format!(
                        "the equations are not a polynomial in `{}` (it appears in a \
                         function, a root or a denominator): a regressor writes M q̈ − f \
                         linearly in products of the parameters it lists; leave it out \
                         of `regressor(...)` to treat it as known",
                        unknown_names[k]
                    ),
                ));
            }
            let derivative: Vec<ExprId> = exprs.iter().map(|&e| pool.diff(e, syms[k])).collect();
            let mut next = monomial.clone();
            next.push(k);
            work.push((next, derivative));
        }
        // The coefficient: the derivative at zero over α!.
        let at_zero = pool.at_zero(&exprs, &syms);
        if at_zero.iter().all(|&e| e == Pool::ZERO) {
            continue;
        }
        let factorial = multiplicity_factorial(&monomial);
        let scaled: Vec<ExprId> = at_zero
            .into_iter()
            .map(|e| {
                let inverse = pool.num(1.0 / factorial);
                let e = pool.mul2(inverse, e);
                pool.factored(e)
            })
            .collect();
        coefficients.push((monomial, scaled));
    }
    // Offset first (the empty monomial), then by degree and indices.
    coefficients.sort_by(|a, b| (a.0.len(), &a.0).cmp(&(b.0.len(), &b.0)));
    let offset = match coefficients.first() {
        Some((m, _)) if m.is_empty() => coefficients.remove(0).1,
        _ => vec![Pool::ZERO; n],
    };
    if coefficients.is_empty() {
        return Err(syn::Error::new(
            unknowns[0].1,
            "the equations do not depend on the parameters `regressor(...)` lists",
        ));
    }
    let groups = group(model, &coefficients).map_err(|dependent| {
        let monomial = &coefficients[dependent].0;
        let name = name_of(&unknown_names, monomial, 1.0);
        syn::Error::new(
            unknowns[monomial[0]].1,
            format!(
                "the equations see `{name}` only in combination with the products of \
                 the parameters before it: its column of the regressor is a sum of \
                 theirs with factors that are not constants, so no data can tell \
                 them apart; leave one of its parameters out of `regressor(...)`"
            ),
        )
    })?;
    if model.pool.exhausted() {
        return Ok(());
    }
    let texts: Vec<String> = groups
        .iter()
        .map(|group| {
            group
                .iter()
                .map(|&(member, factor)| name_of(&unknown_names, &coefficients[member].0, factor))
                .collect::<Vec<_>>()
                .join(" + ")
        })
        .collect();
    let pool = &mut model.pool;
    let mut columns = vec![Vec::new(); n];
    let mut parameters = Vec::new();
    for group in &groups {
        let (first, _) = group[0];
        for (i, row) in columns.iter_mut().enumerate() {
            row.push(coefficients[first].1[i]);
        }
        let mut terms = Vec::new();
        for &(member, factor) in group {
            let monomial = &coefficients[member].0;
            let mut factors = vec![pool.num(factor)];
            factors.extend(monomial.iter().map(|&k| pool.sym(syms[k])));
            terms.push(pool.mul(&factors));
        }
        parameters.push(pool.add(&terms));
    }
    let names = texts;
    eq.regressor = Some(Regressor {
        names,
        columns,
        offset,
        parameters,
    });
    Ok(())
}

fn param_index(model: &Model, s: SymId) -> usize {
    model
        .symbols
        .parameters
        .iter()
        .position(|&p| p == s)
        .expect("a listed scalar is a parameter")
}

/// `α!`: the product of the factorials of each index's multiplicity.
fn multiplicity_factorial(monomial: &Monomial) -> f64 {
    let mut out = 1.0;
    let mut run = 1.0;
    for w in monomial.windows(2) {
        if w[0] == w[1] {
            run += 1.0;
            out *= run;
        } else {
            run = 1.0;
        }
    }
    out
}

/// `2*m[1]*l[0]^2`, from the listed scalars' names.
fn name_of(names: &[String], monomial: &Monomial, factor: f64) -> String {
    let mut parts = Vec::new();
    if factor != 1.0 {
        parts.push(format!("{factor}"));
    }
    let mut i = 0;
    while i < monomial.len() {
        let k = monomial[i];
        let power = monomial[i..].iter().take_while(|&&x| x == k).count();
        let name = &names[k];
        parts.push(if power == 1 {
            name.clone()
        } else {
            format!("{name}^{power}")
        });
        i += power;
    }
    parts.join("*")
}

/// The columns grouped into base parameters: each group its first member
/// (the column kept) and the others that are constant multiples of it,
/// each with its factor (1 for the first). Any other dependence is the
/// error: the index of the first column the ones before it determine.
fn group(
    model: &Model,
    coefficients: &[(Monomial, Vec<ExprId>)],
) -> Result<Vec<Vec<(usize, f64)>>, usize> {
    // Each column at generic values of every symbol: SplitMix64 from a
    // fixed seed, so that the same model always groups the same way.
    const SAMPLES: usize = 12;
    let mut state: u64 = 0x0005_EED0_F1A6_4A4E;
    let mut uniform = move |lo: f64, hi: f64| {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        let u = ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * u
    };
    // The evaluations, paid for before they are made; the comparisons as
    // they go (a comparison of two columns is a few float operations per
    // entry, some thirty of which cost what one step of the budget does).
    let (k, n) = (
        coefficients.len() as u64,
        model.symbols.coordinates.len() as u64,
    );
    let len = n.saturating_mul(SAMPLES as u64);
    model.pool.charge(k.saturating_mul(len));
    if model.pool.exhausted() {
        return Ok(Vec::new());
    }
    let s = &model.symbols;
    let mut vectors: Vec<Vec<f64>> = vec![Vec::new(); coefficients.len()];
    // The parameters are drawn once: the question is whether a model with
    // given kinematics (the parameters not listed) can tell its lumped
    // parameters apart over all its motions.
    let parameters: Vec<f64> = s.parameters.iter().map(|_| uniform(0.5, 2.0)).collect();
    for _ in 0..SAMPLES {
        let mut values = vec![0.0; s.count()];
        values[s.time.0 as usize] = uniform(0.0, 10.0);
        for &q in &s.coordinates {
            values[q.0 as usize] = uniform(-3.0, 3.0);
        }
        for &v in s.velocities.iter().chain(&s.accelerations) {
            values[v.0 as usize] = uniform(-2.0, 2.0);
        }
        for (&p, &value) in s.parameters.iter().zip(&parameters) {
            values[p.0 as usize] = value;
        }
        for &u in &s.inputs {
            values[u.0 as usize] = uniform(-1.0, 1.0);
        }
        let mut memo = HashMap::new();
        for (vector, (_, column)) in vectors.iter_mut().zip(coefficients) {
            vector.extend(
                column
                    .iter()
                    .map(|&e| model.pool.eval_memo(e, &values, &mut memo)),
            );
        }
    }
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    // Constant multiples of an earlier column, with a rational factor.
    let mut groups: Vec<Vec<(usize, f64)>> = Vec::new();
    'column: for (k, v) in vectors.iter().enumerate() {
        model
            .pool
            .charge((groups.len() as u64).saturating_mul(len / 32 + 1));
        if model.pool.exhausted() {
            return Ok(Vec::new());
        }
        for group in groups.iter_mut() {
            let first = &vectors[group[0].0];
            let c = dot(v, first) / dot(first, first);
            let off: Vec<f64> = v.iter().zip(first).map(|(a, b)| a - c * b).collect();
            if norm(&off) <= 1e-9 * norm(v) {
                if let Some(c) = rational(c) {
                    group.push((k, c));
                    continue 'column;
                }
            }
        }
        groups.push(vec![(k, 1.0)]);
    }
    // Any other dependence: Gram–Schmidt over the kept columns.
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for group in &groups {
        let v = &vectors[group[0].0];
        let mut w = v.clone();
        for _ in 0..2 {
            for b in &basis {
                let c = dot(&w, b);
                w.iter_mut().zip(b).for_each(|(x, y)| *x -= c * y);
            }
        }
        let size = norm(&w);
        if size <= 1e-9 * norm(v) {
            return Err(group[0].0);
        }
        basis.push(w.iter().map(|x| x / size).collect());
    }
    Ok(groups)
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `c` as a fraction with a denominator up to 12, if it is one to
/// rounding.
fn rational(c: f64) -> Option<f64> {
    (1..=12).find_map(|d| {
        let n = (c * d as f64).round();
        ((c - n / d as f64).abs() <= 1e-9 * c.abs().max(1.0)).then(|| n / d as f64)
    })
}
