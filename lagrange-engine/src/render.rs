//! A readable rendering of the derived equations, for docs and debugging:
//! the shared subexpressions first (`e0 = ...`), then each entry of `M` and
//! `f`, for a constrained model of `φ`, `G` and `γ`, and for a model with
//! inputs of `∂f/∂u`. Velocities read `dot(x)`, as in the model.
//!
//! The same equations as LaTeX ([`render_latex`]): one `aligned` block,
//! `\dot{\theta}_{1}` for velocities, Greek names as letters, a trailing
//! number as a subscript, `\frac` for divisions, `\sin`.

use crate::derive::Equations;
use crate::derive::articulated::Articulated;
use crate::expr::cse::dag_uses;
use crate::expr::{ExprId, Node, Pool};
use crate::model::{Model, SymKind};
use std::collections::HashMap;
use std::fmt::Write;

struct Renderer<'a> {
    model: &'a Model,
    names: HashMap<ExprId, String>,
    /// LaTeX rather than plain text.
    latex: bool,
}

/// Greek letters LaTeX names, lower and upper case.
const GREEK: &[&str] = &[
    "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa",
    "lambda", "mu", "nu", "xi", "pi", "rho", "sigma", "tau", "upsilon", "phi", "chi", "psi",
    "omega", "Gamma", "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Upsilon", "Phi", "Psi",
    "Omega",
];

/// A model's name in LaTeX: `theta1` → `\theta_{1}`, `x[2]` → `x_{2}`,
/// `m_cart` → `m_{cart}`, a Greek name as its letter, a longer name
/// upright (`\mathrm{force}`).
fn latex_name(name: &str) -> String {
    let (stem, sub) = if let Some((stem, rest)) = name.split_once('[') {
        (
            stem.to_string(),
            Some(rest.trim_end_matches(']').to_string()),
        )
    } else if let Some((stem, rest)) = name.split_once('_') {
        (stem.to_string(), Some(rest.to_string()))
    } else {
        let digits = name.len() - name.trim_end_matches(|c: char| c.is_ascii_digit()).len();
        if digits > 0 && digits < name.len() {
            let (stem, sub) = name.split_at(name.len() - digits);
            (stem.to_string(), Some(sub.to_string()))
        } else {
            (name.to_string(), None)
        }
    };
    let stem = if GREEK.contains(&stem.as_str()) {
        format!("\\{stem}")
    } else if stem.chars().count() > 1 {
        format!("\\mathrm{{{stem}}}")
    } else {
        stem
    };
    match sub {
        Some(sub) => format!("{stem}_{{{}}}", sub.replace('_', "\\_")),
        None => stem,
    }
}

impl Renderer<'_> {
    fn pool(&self) -> &Pool {
        &self.model.pool
    }

    /// `prec`: 0 sum, 1 product, 2 power base / atom.
    fn text(&self, id: ExprId, prec: u8) -> String {
        if let Some(n) = self.names.get(&id) {
            return n.clone();
        }
        let (s, p) = self.inline(id);
        match (p < prec, self.latex) {
            (false, _) => s,
            (true, false) => format!("({s})"),
            (true, true) => format!("\\left({s}\\right)"),
        }
    }

    fn inline(&self, id: ExprId) -> (String, u8) {
        let pool = self.pool();
        match pool.node(id) {
            Node::Num(bits) => {
                let v = f64::from_bits(*bits);
                (format!("{v}"), if v < 0.0 { 0 } else { 2 })
            }
            Node::Sym(s) if self.latex => {
                let m = self.model;
                let name = match m.symbols.kind(*s) {
                    SymKind::Time => "t".to_string(),
                    SymKind::Coordinate(i) => latex_name(&m.coordinates[i].to_string()),
                    SymKind::Velocity(i) => dotted("dot", &m.coordinates[i].to_string()),
                    SymKind::Parameter(k) => latex_name(&m.parameters[k].to_string()),
                    SymKind::Acceleration(i) => dotted("ddot", &m.coordinates[i].to_string()),
                    SymKind::Input(k) => latex_name(&m.inputs[k].to_string()),
                };
                (name, 2)
            }
            Node::Sym(s) => {
                let m = self.model;
                let name = match m.symbols.kind(*s) {
                    SymKind::Time => "t".to_string(),
                    SymKind::Coordinate(i) => m.coordinates[i].to_string(),
                    SymKind::Velocity(i) => format!("dot({})", m.coordinates[i]),
                    SymKind::Parameter(k) => m.parameters[k].to_string(),
                    SymKind::Acceleration(i) => format!("ddot({})", m.coordinates[i]),
                    SymKind::Input(k) => m.inputs[k].to_string(),
                };
                (name, 2)
            }
            Node::Add(xs) => {
                let mut out = String::new();
                for (k, &x) in xs.iter().enumerate() {
                    let (c, rest) = self.split(x);
                    let term = self.product(c.abs(), &rest);
                    match (k, c < 0.0) {
                        (0, false) => out.push_str(&term),
                        (0, true) => write!(out, "-{term}").unwrap(),
                        (_, false) => write!(out, " + {term}").unwrap(),
                        (_, true) => write!(out, " - {term}").unwrap(),
                    }
                }
                (out, 0)
            }
            Node::Mul(_) => {
                let (c, rest) = self.split(id);
                let term = self.product(c.abs(), &rest);
                if c < 0.0 {
                    (format!("-{term}"), 0)
                } else {
                    (term, 1)
                }
            }
            // The base is written once: writing it twice per level would
            // take 2^depth time on nested roots.
            Node::Pow(b, e) if self.latex => match pool.as_num(*e) {
                Some(0.5) => (format!("\\sqrt{{{}}}", self.text(*b, 0)), 2),
                Some(v) if v < 0.0 => {
                    let (c, rest) = self.split(id);
                    (self.product(c.abs(), &rest), 1)
                }
                _ => (format!("{}^{{{}}}", self.text(*b, 2), self.text(*e, 0)), 1),
            },
            Node::Func(f, a) if self.latex => (
                format!("\\{}\\left({}\\right)", f.name(), self.text(*a, 0)),
                2,
            ),
            Node::Atan2(y, x) if self.latex => (
                format!(
                    "\\operatorname{{atan2}}\\left({}, {}\\right)",
                    self.text(*y, 0),
                    self.text(*x, 0)
                ),
                2,
            ),
            Node::Pow(b, e) => match pool.as_num(*e) {
                Some(0.5) => (format!("sqrt({})", self.text(*b, 0)), 2),
                Some(v) if v < 0.0 => (format!("{}^({v})", self.text(*b, 2)), 1),
                _ => (format!("{}^{}", self.text(*b, 2), self.text(*e, 2)), 1),
            },
            Node::Func(f, a) => (format!("{}({})", f.name(), self.text(*a, 0)), 2),
            Node::Atan2(y, x) => (
                format!("atan2({}, {})", self.text(*y, 0), self.text(*x, 0)),
                2,
            ),
        }
    }

    fn split(&self, id: ExprId) -> (f64, Vec<ExprId>) {
        let pool = self.pool();
        match pool.node(id) {
            Node::Mul(xs) => match pool.as_num(xs[0]) {
                Some(c) => (c, xs[1..].to_vec()),
                None => (1.0, xs.to_vec()),
            },
            Node::Num(bits) => (f64::from_bits(*bits), Vec::new()),
            _ => (1.0, vec![id]),
        }
    }

    fn product(&self, mag: f64, factors: &[ExprId]) -> String {
        if self.latex {
            return self.latex_product(mag, factors);
        }
        let mut parts: Vec<String> = Vec::new();
        if mag != 1.0 || factors.is_empty() {
            parts.push(format!("{mag}"));
        }
        let mut denom: Vec<String> = Vec::new();
        for &f in factors {
            if !self.names.contains_key(&f) {
                if let Node::Pow(b, e) = self.pool().node(f) {
                    if let Some(v) = self.pool().as_num(*e).filter(|v| *v < 0.0) {
                        let base = self.text(*b, 2);
                        denom.push(if v == -1.0 {
                            base
                        } else {
                            format!("{base}^{}", -v)
                        });
                        continue;
                    }
                }
            }
            parts.push(self.text(f, 1));
        }
        if parts.is_empty() {
            parts.push("1".into());
        }
        let mut out = parts.join("*");
        match denom.len() {
            0 => {}
            1 => write!(out, "/{}", denom[0]).unwrap(),
            _ => write!(out, "/({})", denom.join("*")).unwrap(),
        }
        out
    }
}

impl Renderer<'_> {
    /// `\\frac{numerator}{denominator}`, factors side by side (`\\,`).
    fn latex_product(&self, mag: f64, factors: &[ExprId]) -> String {
        let mut numerator: Vec<String> = Vec::new();
        if mag != 1.0 || factors.is_empty() {
            numerator.push(format!("{mag}"));
        }
        let mut denominator: Vec<String> = Vec::new();
        for &f in factors {
            if !self.names.contains_key(&f) {
                if let Node::Pow(b, e) = self.pool().node(f) {
                    if let Some(v) = self.pool().as_num(*e).filter(|v| *v < 0.0) {
                        let base = self.text(*b, 2);
                        denominator.push(if v == -1.0 {
                            base
                        } else {
                            format!("{base}^{{{}}}", -v)
                        });
                        continue;
                    }
                }
            }
            numerator.push(self.text(f, 1));
        }
        let top = if numerator.is_empty() {
            "1".to_string()
        } else {
            numerator.join(" \\, ")
        };
        if denominator.is_empty() {
            top
        } else {
            format!("\\frac{{{top}}}{{{}}}", denominator.join(" \\, "))
        }
    }
}

/// `\\dot{x}` (or `\\ddot`) of a coordinate, its subscript outside.
fn dotted(accent: &str, name: &str) -> String {
    let latex = latex_name(name);
    match latex.split_once('_') {
        Some((stem, sub)) => format!("\\{accent}{{{stem}}}_{sub}"),
        None => format!("\\{accent}{{{latex}}}"),
    }
}

/// The roots the text shows beyond `M` and `f`: `φ`, `G` row by row, `γ`
/// (none for a model without constraints).
pub fn constraint_roots(eq: &Equations) -> Vec<ExprId> {
    let Some(c) = &eq.constraints else {
        return Vec::new();
    };
    let mut roots = c.values.clone();
    roots.extend(c.jacobian.iter().flatten());
    roots.extend(&c.bias);
    roots
}

/// The contacts' gaps, slip velocities and given normal forces, each where
/// the contact has one (none for a model without contacts).
pub fn contact_roots(model: &Model, eq: &Equations) -> Vec<ExprId> {
    let Some(ce) = &eq.contacts else {
        return Vec::new();
    };
    let mut roots = Vec::new();
    for (i, contact) in model.contacts.iter().enumerate() {
        match contact.normal {
            Some(normal) => roots.push(normal),
            None => roots.push(ce.gaps.values[i]),
        }
        if contact.slip.is_some() {
            roots.push(ce.slips.velocities[i]);
        }
        if let (Some(_), Some(second)) = (contact.second_slip, &ce.second_slips) {
            roots.push(second.velocities[i]);
        }
    }
    roots
}

/// The entries of `∂f/∂u` row by row (none for a model without inputs).
pub fn input_roots(eq: &Equations) -> Vec<ExprId> {
    eq.input_jacobian
        .iter()
        .flatten()
        .flatten()
        .copied()
        .collect()
}

/// The equations as plain text, as `EQUATIONS` holds them: the same entries
/// as [`render_latex`].
pub fn render(model: &Model, eq: &Equations) -> String {
    render_with(model, eq, false)
}

/// The equations as LaTeX: one `aligned` block, shared subexpressions
/// `e_{k}` first, then `M`, `f`, and `φ`, `G`, `γ`, the contacts' gaps
/// `g`, slip velocities `v_t` and given normal forces `N`, or `∂f/∂u`
/// where the model has them; the same entries as [`render`].
pub fn render_latex(model: &Model, eq: &Equations) -> String {
    render_with(model, eq, true)
}

/// Every root the text shows, in its order: `M`'s upper triangle and `f`,
/// then the constraints', contacts' and inputs' terms; for a model solved
/// by the recursion without `M` and `f` ([`Equations::mass`] empty), its
/// parts instead: its joints' nonzero axes, bends, masses and inertias,
/// and every coordinate's other forces.
pub fn text_roots(model: &Model, eq: &Equations) -> Vec<ExprId> {
    if let Some(parts) = parts_only(model, eq) {
        return part_roots(model, parts)
            .into_iter()
            .map(|(_, id)| id)
            .collect();
    }
    let n = model.dof();
    let mut roots = Vec::new();
    for i in 0..n {
        for j in i..n {
            roots.push(eq.mass[i][j]);
        }
    }
    roots.extend(&eq.forcing);
    roots.extend(constraint_roots(eq));
    roots.extend(contact_roots(model, eq));
    roots.extend(input_roots(eq));
    roots
}

/// The parts of a model solved by the recursion whose `M` and `f` were
/// never derived; `None` for every other model.
fn parts_only<'a>(model: &Model, eq: &'a Equations) -> Option<&'a Articulated> {
    (eq.mass.len() != model.dof()).then_some(eq.articulated.as_ref())?
}

/// Which part an entry of the text is.
#[derive(Clone, Copy)]
enum Part {
    /// A joint's axis `u` along an axis.
    Axis(usize, usize),
    /// Its bend `∂u/∂φ`.
    Bend(usize, usize),
    /// The mass on its end along an axis.
    Mass(usize, usize),
    /// Its own inertia.
    Inertia(usize),
    /// A coordinate's generalized force other than `T`'s.
    Force(usize),
}

/// The parts' nonzero axes, bends, masses and inertias joint by joint,
/// then every coordinate's force: the entries of the text of a model
/// solved by the recursion (its size `O(N)` entries, against `M`'s
/// `N(N+1)/2`).
fn part_roots(model: &Model, a: &Articulated) -> Vec<(Part, ExprId)> {
    let (n, d) = (model.dof(), a.axes);
    let at = |block: usize, j: usize, k: usize| a.roots[block * n * d + j * d + k];
    let mut out = Vec::new();
    for j in 0..n {
        for k in 0..d {
            out.push((Part::Axis(j, k), at(0, j, k)));
        }
        for k in 0..d {
            out.push((Part::Bend(j, k), at(1, j, k)));
        }
        for k in 0..d {
            out.push((Part::Mass(j, k), at(2, j, k)));
        }
        out.push((Part::Inertia(j), a.roots[3 * n * d + j]));
    }
    for i in 0..n {
        out.push((Part::Force(i), a.roots[3 * n * d + n + i]));
    }
    out.retain(|&(part, id)| matches!(part, Part::Force(_)) || id != Pool::ZERO);
    out
}

fn render_with(model: &Model, eq: &Equations, latex: bool) -> String {
    let n = model.dof();
    let roots = text_roots(model, eq);
    let (order, uses) = dag_uses(&model.pool, &roots);
    let mut r = Renderer {
        model,
        names: HashMap::new(),
        latex,
    };
    let mut out = String::new();
    let mut k = 0;
    // Plain: `lhs = rhs` lines. LaTeX: `lhs &= rhs \\` rows of one block.
    let line = |out: &mut String, lhs: String, rhs: String| {
        if latex {
            writeln!(out, "{lhs} &= {rhs} \\\\").unwrap();
        } else {
            writeln!(out, "{lhs} = {rhs}").unwrap();
        }
    };
    if latex {
        out.push_str("\\begin{aligned}\n");
    }
    for &id in &order {
        // Name only what is shared by more than one user; powers expanded
        // into products in code need no name in text.
        if uses[id.index()] > 1 && !matches!(model.pool.node(id), Node::Num(_) | Node::Sym(_)) {
            let (s, _) = r.inline(id);
            let name = if latex {
                format!("e_{{{k}}}")
            } else {
                format!("e{k}")
            };
            k += 1;
            line(&mut out, name.clone(), s);
            r.names.insert(id, name);
        }
    }
    // An entry's left side: `M[a, b]` in text, `M_{a b}` in LaTeX.
    let entry = |symbol: &str, indices: &[String]| -> String {
        if latex {
            let symbol = match symbol {
                "φ" => "\\varphi",
                "γ" => "\\gamma",
                "v_t" => "v_{t}",
                "v_t2" => "v_{t2}",
                "∂f/∂u" => "\\frac{\\partial f}{\\partial u}",
                "∂u/∂φ" => "\\frac{\\partial u}{\\partial \\phi}",
                "parent" => "\\mathrm{parent}",
                other => other,
            };
            let indices: Vec<String> = indices.iter().map(|i| latex_name(i)).collect();
            format!("{symbol}_{{{}}}", indices.join(" \\, "))
        } else {
            format!("{symbol}[{}]", indices.join(", "))
        }
    };
    let c: Vec<String> = model.coordinates.iter().map(|c| c.to_string()).collect();
    if let Some(a) = parts_only(model, eq) {
        // The tree: each joint's angle, and the joint it hangs from.
        let joint = |j: usize| c[a.coordinate[j]].clone();
        let coordinate = |j: usize| {
            let name = if latex {
                latex_name(&joint(j))
            } else {
                joint(j)
            };
            match a.scale[j] {
                1.0 => name,
                k if latex => format!("{k} \\, {name}"),
                k => format!("{k}*{name}"),
            }
        };
        for j in 0..n {
            let angle = match a.base[j] {
                Some(b) => format!("{} + {}", entry("φ", &[joint(b)]), coordinate(j)),
                None => coordinate(j),
            };
            line(&mut out, entry("φ", &[joint(j)]), angle);
            let parent = match a.parent[j] {
                Some(p) if latex => latex_name(&joint(p)),
                Some(p) => joint(p),
                None if latex => "\\varnothing".to_string(),
                None => "none".to_string(),
            };
            line(&mut out, entry("parent", &[joint(j)]), parent);
        }
        for (part, id) in part_roots(model, a) {
            let lhs = match part {
                Part::Axis(j, k) => entry("u", &[joint(j), k.to_string()]),
                Part::Bend(j, k) => entry("∂u/∂φ", &[joint(j), k.to_string()]),
                Part::Mass(j, k) => entry("m", &[joint(j), k.to_string()]),
                Part::Inertia(j) => entry("J", &[joint(j)]),
                Part::Force(i) => entry("Q", std::slice::from_ref(&c[i])),
            };
            line(&mut out, lhs, r.text(id, 0));
        }
        if latex {
            out.push_str("\\end{aligned}\n");
        }
        return out;
    }
    for i in 0..n {
        for (j, cj) in c.iter().enumerate().skip(i) {
            let lhs = entry("M", &[c[i].clone(), cj.clone()]);
            line(&mut out, lhs, r.text(eq.mass[i][j], 0));
        }
    }
    for (ci, &fi) in c.iter().zip(&eq.forcing) {
        line(
            &mut out,
            entry("f", std::slice::from_ref(ci)),
            r.text(fi, 0),
        );
    }
    if let Some(ce) = &eq.constraints {
        let labels: Vec<String> = model.constraints.iter().map(|k| k.label.clone()).collect();
        for (name, &phi) in labels.iter().zip(&ce.values) {
            line(
                &mut out,
                entry("φ", std::slice::from_ref(name)),
                r.text(phi, 0),
            );
        }
        for (name, row) in labels.iter().zip(&ce.jacobian) {
            for (cj, &g) in c.iter().zip(row) {
                let lhs = entry("G", &[name.clone(), cj.clone()]);
                line(&mut out, lhs, r.text(g, 0));
            }
        }
        for (name, &gamma) in labels.iter().zip(&ce.bias) {
            line(
                &mut out,
                entry("γ", std::slice::from_ref(name)),
                r.text(gamma, 0),
            );
        }
    }
    if let Some(ce) = &eq.contacts {
        for (i, contact) in model.contacts.iter().enumerate() {
            let name = std::slice::from_ref(&contact.label);
            match contact.normal {
                Some(normal) => line(&mut out, entry("N", name), r.text(normal, 0)),
                None => line(&mut out, entry("g", name), r.text(ce.gaps.values[i], 0)),
            }
            if contact.slip.is_some() {
                let lhs = entry("v_t", name);
                line(&mut out, lhs, r.text(ce.slips.velocities[i], 0));
            }
            if let (Some(_), Some(second)) = (contact.second_slip, &ce.second_slips) {
                let lhs = entry("v_t2", name);
                line(&mut out, lhs, r.text(second.velocities[i], 0));
            }
        }
    }
    if let Some(rows) = &eq.input_jacobian {
        for (ci, row) in c.iter().zip(rows) {
            for (u, &d) in model.inputs.iter().zip(row) {
                let lhs = entry("∂f/∂u", &[ci.clone(), u.to_string()]);
                line(&mut out, lhs, r.text(d, 0));
            }
        }
    }
    if latex {
        out.push_str("\\end{aligned}\n");
    }
    out
}
