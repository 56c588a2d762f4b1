//! A readable rendering of the derived equations, for docs and debugging:
//! the shared subexpressions first (`e0 = ...`), then each entry of `M` and
//! `f`, for a constrained model of `φ`, `G` and `γ`, and for a model with
//! inputs of `∂f/∂u`. Velocities read `dot(x)`, as in the model.

use crate::derive::Equations;
use crate::expr::cse::dag_uses;
use crate::expr::{ExprId, Node, Pool};
use crate::model::{Model, SymKind};
use std::collections::HashMap;
use std::fmt::Write;

struct Renderer<'a> {
    model: &'a Model,
    names: HashMap<ExprId, String>,
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
        if p < prec {
            format!("({s})")
        } else {
            s
        }
    }

    fn inline(&self, id: ExprId) -> (String, u8) {
        let pool = self.pool();
        match pool.node(id) {
            Node::Num(bits) => {
                let v = f64::from_bits(*bits);
                (format!("{v}"), if v < 0.0 { 0 } else { 2 })
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

/// The entries of `∂f/∂u` row by row (none for a model without inputs).
pub fn input_roots(eq: &Equations) -> Vec<ExprId> {
    eq.input_jacobian
        .iter()
        .flatten()
        .flatten()
        .copied()
        .collect()
}

pub fn render(model: &Model, eq: &Equations) -> String {
    let n = model.dof();
    let mut roots = Vec::new();
    for i in 0..n {
        for j in i..n {
            roots.push(eq.mass[i][j]);
        }
    }
    roots.extend(&eq.forcing);
    roots.extend(constraint_roots(eq));
    roots.extend(input_roots(eq));
    let (order, uses) = dag_uses(&model.pool, &roots);
    let mut r = Renderer {
        model,
        names: HashMap::new(),
    };
    let mut out = String::new();
    let mut k = 0;
    for &id in &order {
        // Name only what is shared by more than one user; powers expanded
        // into products in code need no name in text.
        if uses[id.index()] > 1 && !matches!(model.pool.node(id), Node::Num(_) | Node::Sym(_)) {
            let (s, _) = r.inline(id);
            let name = format!("e{k}");
            k += 1;
            writeln!(out, "{name} = {s}").unwrap();
            r.names.insert(id, name);
        }
    }
    let c = &model.coordinates;
    for i in 0..n {
        for (j, cj) in c.iter().enumerate().skip(i) {
            writeln!(out, "M[{}, {cj}] = {}", c[i], r.text(eq.mass[i][j], 0)).unwrap();
        }
    }
    for (ci, &fi) in c.iter().zip(&eq.forcing) {
        writeln!(out, "f[{ci}] = {}", r.text(fi, 0)).unwrap();
    }
    if let Some(ce) = &eq.constraints {
        let labels: Vec<&str> = model.constraints.iter().map(|k| k.label.as_str()).collect();
        for (name, &phi) in labels.iter().zip(&ce.values) {
            writeln!(out, "φ[{name}] = {}", r.text(phi, 0)).unwrap();
        }
        for (name, row) in labels.iter().zip(&ce.jacobian) {
            for (cj, &g) in c.iter().zip(row) {
                writeln!(out, "G[{name}, {cj}] = {}", r.text(g, 0)).unwrap();
            }
        }
        for (name, &gamma) in labels.iter().zip(&ce.bias) {
            writeln!(out, "γ[{name}] = {}", r.text(gamma, 0)).unwrap();
        }
    }
    if let Some(rows) = &eq.input_jacobian {
        for (ci, row) in c.iter().zip(rows) {
            for (u, &d) in model.inputs.iter().zip(row) {
                writeln!(out, "∂f/∂u[{ci}, {u}] = {}", r.text(d, 0)).unwrap();
            }
        }
    }
    out
}
