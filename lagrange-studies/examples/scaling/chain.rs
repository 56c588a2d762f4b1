//! The N-link pendulum chain as `lagrangian!` source: N point masses on
//! massless rods, angles from the downward vertical, in one of two spellings
//! of the same physics.

use std::fmt::Write;

/// How the model is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Form {
    /// The indexed DSL: `theta[N]`, `m[N]`, `let x[i in 0..N] = sum(..)`,
    /// `g` a compile-time constant. Source of the same size for every N.
    Indexed,
    /// Every coordinate, parameter and position written out (`theta0`,
    /// `x1 = x0 + l1*sin(theta1)`, ...), `g` a runtime parameter. Source
    /// grows linearly with N.
    Scalar,
}

impl Form {
    pub fn name(self) -> &'static str {
        match self {
            Form::Indexed => "the indexed DSL (`theta[N]`, `sum(..)`, `g` a constant)",
            Form::Scalar => "the written-out form (`theta0, theta1, ...`, `g` a parameter)",
        }
    }
}

/// The tokens inside `lagrangian! { ... }` for the `n`-link chain. With
/// `#[lagrange(articulated = false)]` unless `articulated`: this study
/// measures the generated `M` and `f`, which from 18 coordinates a chain
/// would otherwise not have (`--articulated`: `#[lagrange(articulated)]`,
/// so that they are formed at run time from the links' parts at every
/// size, the model's code those parts; the recursion over them is
/// `benches/articulated.rs`'s).
pub fn model_body(n: usize, form: Form, articulated: bool) -> String {
    let body = match form {
        Form::Indexed => indexed(n),
        Form::Scalar => scalar(n),
    };
    let attribute = if articulated {
        "articulated"
    } else {
        "articulated = false"
    };
    format!("#[lagrange({attribute})]\n{body}")
}

/// A Rust expression for `Chain::<f64>::new(..)` from arrays `m`, `l`
/// (`[f64; N]`) and the constant `G` in scope.
pub fn constructor(n: usize, form: Form) -> String {
    match form {
        Form::Indexed => "Chain::new(m, l)".to_string(),
        Form::Scalar => {
            let m = (0..n).map(|i| format!("m[{i}]"));
            let l = (0..n).map(|i| format!("l[{i}]"));
            let args: Vec<String> = m.chain(l).chain(["G".to_string()]).collect();
            format!("Chain::new({})", args.join(", "))
        }
    }
}

fn indexed(n: usize) -> String {
    format!(
        "pub struct Chain {{
    const N = {n};
    coordinates: theta[N];
    parameters: m[N], l[N];
    constants: g = 9.81;
    let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));
    let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));
    kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2));
    potential: sum(i in 0..N, m[i]*g*y[i]);
}}
"
    )
}

fn scalar(n: usize) -> String {
    let names = |p: &str| (0..n).map(|i| format!("{p}{i}")).collect::<Vec<_>>();
    let mut s = String::from("pub struct Chain {\n");
    writeln!(s, "    coordinates: {};", names("theta").join(", ")).unwrap();
    writeln!(
        s,
        "    parameters: {}, {}, g;",
        names("m").join(", "),
        names("l").join(", ")
    )
    .unwrap();
    for i in 0..n {
        if i == 0 {
            writeln!(s, "    let x0 = l0*sin(theta0);").unwrap();
            writeln!(s, "    let y0 = -l0*cos(theta0);").unwrap();
        } else {
            let p = i - 1;
            writeln!(s, "    let x{i} = x{p} + l{i}*sin(theta{i});").unwrap();
            writeln!(s, "    let y{i} = y{p} - l{i}*cos(theta{i});").unwrap();
        }
    }
    let kinetic: Vec<String> = (0..n)
        .map(|i| format!("m{i}/2*(dot(x{i})^2 + dot(y{i})^2)"))
        .collect();
    let potential: Vec<String> = (0..n).map(|i| format!("m{i}*g*y{i}")).collect();
    writeln!(s, "    kinetic: {};", kinetic.join(" + ")).unwrap();
    writeln!(s, "    potential: {};", potential.join(" + ")).unwrap();
    s.push_str("}\n");
    s
}
