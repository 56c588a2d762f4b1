//! The engine outside rustc: canonical forms, derivatives, determinism.

use crate::problems::{DOUBLE_PENDULUM, indexed_chain};
use lagrange_engine::expr::{ExprId, Func, Pool, SymId};

fn syms(pool: &mut Pool, n: u32) -> Vec<ExprId> {
    (0..n).map(|k| pool.sym(SymId(k))).collect()
}

#[test]
fn like_terms_and_powers_collect_to_one_node() {
    let mut p = Pool::default();
    let v = syms(&mut p, 3);
    let (x, y) = (v[0], v[1]);
    assert_eq!(p.sub(x, x), Pool::ZERO);
    let inv = p.div(Pool::ONE, x);
    assert_eq!(p.mul2(x, inv), Pool::ONE);
    let two = p.num(2.0);
    let three = p.num(3.0);
    let five = p.num(5.0);
    let a = p.mul2(two, x);
    let b = p.mul2(three, x);
    let expected = p.mul2(five, x);
    assert_eq!(p.add2(a, b), expected);
    // (x y)^2 = x^2 y^2
    let xy = p.mul2(x, y);
    let lhs = p.pow(xy, two);
    let x2 = p.pow(x, two);
    let y2 = p.pow(y, two);
    assert_eq!(lhs, p.mul2(x2, y2));
    // x·x = x²
    assert_eq!(p.mul2(x, x), x2);
    // 1/2 folds to 0.5
    let half = p.div(Pool::ONE, two);
    assert_eq!(p.as_num(half), Some(0.5));
}

#[test]
fn odd_and_even_functions_share_nodes_across_signs() {
    let mut p = Pool::default();
    let v = syms(&mut p, 2);
    let (a, b) = (v[0], v[1]);
    let amb = p.sub(a, b);
    let bma = p.sub(b, a);
    let c1 = p.func(Func::Cos, amb);
    assert_eq!(c1, p.func(Func::Cos, bma));
    let s1 = p.func(Func::Sin, amb);
    let s2 = p.func(Func::Sin, bma);
    assert_eq!(p.neg(s1), s2);
}

#[test]
fn pythagoras_folds_a_rotating_point_to_its_radius() {
    let mut p = Pool::default();
    let v = syms(&mut p, 3);
    let (theta, l, w) = (v[0], v[1], v[2]);
    let two = p.num(2.0);
    let s = p.func(Func::Sin, theta);
    let c = p.func(Func::Cos, theta);
    // (l cos θ w)^2 + (l sin θ w)^2 = l² w²
    let xs = p.mul(&[l, c, w]);
    let ys = p.mul(&[l, s, w]);
    let x2 = p.pow(xs, two);
    let y2 = p.pow(ys, two);
    let sum = p.add2(x2, y2);
    let l2 = p.pow(l, two);
    let w2 = p.pow(w, two);
    assert_eq!(sum, p.mul2(l2, w2));
    // sin² + cos² alone folds to 1
    let s2 = p.pow(s, two);
    let c2 = p.pow(c, two);
    assert_eq!(p.add2(s2, c2), Pool::ONE);
}

/// Central differences have error O(h²·f''') + O(eps/h); with h = 1e-5 on
/// these smooth functions of O(1) values that is ~1e-9, so 1e-6 relative
/// separates a wrong rule (O(1) error) from round-off with a wide margin.
#[test]
fn every_derivative_rule_matches_central_differences() {
    let mut p = Pool::default();
    let v = syms(&mut p, 2);
    let (x, y) = (v[0], v[1]);
    let two = p.num(2.0);
    let half = p.num(0.5);
    let x2 = p.pow(x, two);
    let xy = p.mul2(x, y);
    let mut cases: Vec<(&str, ExprId)> = Vec::new();
    for f in [
        Func::Sin,
        Func::Cos,
        Func::Tan,
        Func::Asin,
        Func::Acos,
        Func::Atan,
        Func::Sinh,
        Func::Cosh,
        Func::Tanh,
        Func::Exp,
        Func::Ln,
    ] {
        let arg = p.mul2(half, xy);
        cases.push((f.name(), p.func(f, arg)));
    }
    cases.push(("atan2", p.atan2(y, x2)));
    cases.push(("sqrt", p.sqrt(xy)));
    cases.push(("x^y", p.pow(x, y)));
    let inv = p.div(y, x2);
    cases.push(("quotient", inv));
    let poly = p.add(&[x2, xy, Pool::ONE]);
    let m3 = p.num(-3.0);
    cases.push(("negative power of a sum", p.pow(poly, m3)));
    let h = 1e-5;
    for (name, e) in cases {
        for (k, s) in [(0usize, SymId(0)), (1, SymId(1))] {
            let d = p.diff(e, s);
            let at = [0.7, 0.4];
            let mut plus = at;
            plus[k] += h;
            let mut minus = at;
            minus[k] -= h;
            let fd = (p.eval(e, &plus) - p.eval(e, &minus)) / (2.0 * h);
            let exact = p.eval(d, &at);
            assert!(
                (fd - exact).abs() <= 1e-6 * (1.0 + exact.abs()),
                "d{name}/d{k}: symbolic {exact}, central difference {fd}"
            );
        }
    }
}

#[test]
fn the_same_model_always_expands_to_the_same_tokens() {
    let a = lagrange_engine::expand(DOUBLE_PENDULUM.parse().unwrap()).to_string();
    for _ in 0..3 {
        let b = lagrange_engine::expand(DOUBLE_PENDULUM.parse().unwrap()).to_string();
        assert_eq!(a, b);
    }
}

#[test]
fn sharing_keeps_the_double_pendulum_small() {
    let d = lagrange_engine::derive(DOUBLE_PENDULUM.parse().unwrap()).unwrap();
    let (shared, tree) = d.op_counts();
    // Sine and cosine of each angle, one `sin_cos` call per angle, are all
    // the model needs.
    assert_eq!(shared.calls, 2, "{}", d.equations_text());
    assert!(shared.total() < tree.total(), "{shared:?} vs {tree:?}");
}

#[test]
fn derived_double_pendulum_matches_its_closed_form_numerically() {
    let d = lagrange_engine::derive(DOUBLE_PENDULUM.parse().unwrap()).unwrap();
    let (m1, m2, l1, l2, g) = (1.3, 0.7, 0.9, 1.1, 9.81);
    let params = [m1, m2, l1, l2, g];
    let (q, qd) = ([0.3, -1.2], [0.8, 2.1]);
    let m = d.eval_mass_matrix(0.0, &q, &params);
    let f = d.eval_forcing(0.0, &q, &qd, &params);
    let delta: f64 = q[0] - q[1];
    let m_ref = [
        [(m1 + m2) * l1 * l1, m2 * l1 * l2 * delta.cos()],
        [m2 * l1 * l2 * delta.cos(), m2 * l2 * l2],
    ];
    let f_ref = [
        -m2 * l1 * l2 * qd[1] * qd[1] * delta.sin() - (m1 + m2) * g * l1 * q[0].sin(),
        m2 * l1 * l2 * qd[0] * qd[0] * delta.sin() - m2 * g * l2 * q[1].sin(),
    ];
    // A few dozen flops on O(10) values: round-off ~1e-14; 1e-12 is margin.
    for i in 0..2 {
        assert!(
            (f[i] - f_ref[i]).abs() < 1e-12,
            "f[{i}]: {} vs {}",
            f[i],
            f_ref[i]
        );
        for j in 0..2 {
            assert!((m[i][j] - m_ref[i][j]).abs() < 1e-12);
        }
    }
}

#[test]
fn a_derivation_past_the_budget_is_an_error_naming_the_budget() {
    let err = lagrange_engine::derive_with_budget(DOUBLE_PENDULUM.parse().unwrap(), 600)
        .err()
        .expect("the double pendulum needs more than 600 steps");
    let msg = err.to_string();
    assert!(msg.contains("work budget of 600 steps"), "{msg}");
    // The default budget is ample for it.
    assert!(lagrange_engine::derive(DOUBLE_PENDULUM.parse().unwrap()).is_ok());
}

const WITH_EVERY_SECTION: &str = r#"
    pub struct Everything {
        coordinates: x, theta;
        parameters: m, l, k, c, g, w;
        let px = x + l*sin(theta);
        let py = -l*theta.cos();
        kinetic: m/2*dot(x)^2 + m/2*(dot(px)^2 + dot(py)^2);
        potential: k/2*x^2 + m*g*py + atan2(x, l)^-1*0;
        dissipation: c/2*dot(x)^2;
        forces: x = w*sin(t), theta = -c*dot(theta);
    }
"#;

/// Every one-character deletion and every one-token swap of a model that
/// uses every section: the engine must answer with items or a
/// `compile_error!`, never a panic (a panic in a proc macro is an ICE-like
/// message on the whole invocation, with no span on the mistake).
#[test]
fn no_edit_of_a_model_makes_the_engine_panic() {
    let mut variants: Vec<String> = Vec::new();
    for (i, _) in WITH_EVERY_SECTION.char_indices() {
        let mut s = WITH_EVERY_SECTION.to_string();
        s.remove(i);
        variants.push(s);
    }
    let words = [
        "dot(",
        "^",
        "-",
        "*",
        "/",
        ";",
        ",",
        "t",
        "theta",
        "x",
        "(",
        ")",
        "0",
        "1e400",
        "sqrt(-1)",
        "ln(0)",
        "dot(dot(x))",
        "forces",
        "kinetic",
        "let",
        "r#type",
        "x.y",
        ".sin()",
        "^-",
    ];
    let tokens: Vec<&str> = WITH_EVERY_SECTION.split(' ').collect();
    for k in 0..tokens.len() {
        for w in words {
            let mut t = tokens.clone();
            t[k] = w;
            variants.push(t.join(" "));
        }
    }
    let (mut errors, mut items) = (0, 0);
    for v in &variants {
        let Ok(input) = v.parse::<proc_macro2::TokenStream>() else {
            continue; // rustc's lexer rejects it before any macro runs
        };
        let out = std::panic::catch_unwind(|| lagrange_engine::expand(input).to_string());
        let out = out.unwrap_or_else(|_| panic!("engine panicked on:\n{v}"));
        assert!(
            out.contains("compile_error") || out.contains("fn mass_matrix_and_forcing"),
            "neither items nor an error for:\n{v}"
        );
        if out.contains("compile_error") {
            errors += 1;
        } else {
            items += 1;
        }
    }
    // Most edits break the model, some leave it valid (a deleted space): both
    // paths must have been exercised for the test to mean anything.
    assert!(
        errors > 500 && items > 50,
        "{errors} errors, {items} valid models"
    );
}

/// The same chain written out name by name, as before indices existed.
fn written_out_chain(n: usize) -> String {
    let list = |p: &str| {
        (0..n)
            .map(|k| format!("{p}{k}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut s = format!(
        "pub struct Chain {{ coordinates: {}; parameters: {}, {}; constants: g = 9.81;\n",
        list("theta"),
        list("m"),
        list("l")
    );
    for k in 0..n {
        let (px, py) = if k == 0 {
            (String::new(), String::new())
        } else {
            (format!("x{} + ", k - 1), format!("y{} ", k - 1))
        };
        s += &format!("let x{k} = {px}l{k}*sin(theta{k});\n");
        s += &format!("let y{k} = {py}- l{k}*cos(theta{k});\n");
    }
    let t: Vec<String> = (0..n)
        .map(|k| format!("m{k}/2*(dot(x{k})^2 + dot(y{k})^2)"))
        .collect();
    let v: Vec<String> = (0..n).map(|k| format!("m{k}*g*y{k}")).collect();
    s += &format!(
        "kinetic: {};\npotential: {};\n}}",
        t.join(" + "),
        v.join(" + ")
    );
    s
}

#[test]
fn indexed_and_written_out_chains_derive_the_same_equations() {
    let n = 4;
    let a = lagrange_engine::derive(indexed_chain(n).parse().unwrap()).unwrap();
    let b = lagrange_engine::derive(written_out_chain(n).parse().unwrap()).unwrap();
    let mut seed = 11u64;
    let mut next = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..50 {
        let q: Vec<f64> = (0..n).map(|_| 6.0 * next() - 3.0).collect();
        let v: Vec<f64> = (0..n).map(|_| 4.0 * next() - 2.0).collect();
        // Both order their parameters m[0..n], l[0..n].
        let p: Vec<f64> = (0..2 * n).map(|_| 0.5 + next()).collect();
        let (ma, mb) = (
            a.eval_mass_matrix(0.0, &q, &p),
            b.eval_mass_matrix(0.0, &q, &p),
        );
        let (fa, fb) = (
            a.eval_forcing(0.0, &q, &v, &p),
            b.eval_forcing(0.0, &q, &v, &p),
        );
        // Same smooth functions in a different order of operations: a few
        // ulps per operation on O(10²) operations of size O(10).
        for i in 0..n {
            assert!(
                (fa[i] - fb[i]).abs() < 1e-11,
                "f[{i}]: {} vs {}",
                fa[i],
                fb[i]
            );
            for j in 0..n {
                assert!((ma[i][j] - mb[i][j]).abs() < 1e-11);
            }
        }
    }
}

#[test]
fn the_indexed_chain_expands_to_the_same_code_every_time() {
    let a = lagrange_engine::expand(indexed_chain(8).parse().unwrap()).to_string();
    let b = lagrange_engine::expand(indexed_chain(8).parse().unwrap()).to_string();
    assert!(!a.contains("compile_error"), "{a}");
    assert_eq!(a, b);
}

#[test]
fn a_chain_past_the_budget_stops_with_the_budget_error() {
    // A 40-link chain needs some 16 million steps; with a budget of
    // 200 000 the derivation must stop and say so, not run on.
    let err = lagrange_engine::derive_with_budget(indexed_chain(40).parse().unwrap(), 200_000)
        .err()
        .expect("40 links need more than 200 000 steps");
    assert!(
        err.to_string().contains("work budget of 200000 steps"),
        "{err}"
    );
}

#[test]
fn the_chain_forcing_is_the_textbook_one_without_cancelling_terms() {
    // f_i = −l_i (g S_i sin θ_i + Σ_j S_max(i,j) l_j sin(θ_i − θ_j) θ̇_j²),
    // S_k the sum of the masses from k on: about 2,200 operations at N = 20
    // by hand count. Derived through L, f carried exactly cancelling terms
    // (5,171 operations). Derived without the tree (`articulated =
    // false`): from 18 links the recursion solves the chain unasked, and
    // `f` is then never derived.
    let n = 20;
    let source = format!("#[lagrange(articulated = false)] {}", indexed_chain(n));
    let d = lagrange_engine::derive(source.parse().unwrap()).unwrap();
    let ops = lagrange_engine::expr::cse::shared_ops(&d.model.pool, &d.equations.forcing);
    assert!(
        ops.total() <= 2_860,
        "{ops:?}: more than 1.3 × the hand count"
    );
    let q: Vec<f64> = (0..n).map(|i| 0.3 + 0.9 * (1.7 * i as f64).sin()).collect();
    let qd: Vec<f64> = (0..n).map(|i| 0.5 * (1.3 * i as f64).cos()).collect();
    let m: Vec<f64> = (0..n).map(|i| 1.0 + 0.1 * i as f64).collect();
    let l: Vec<f64> = (0..n).map(|i| 1.0 - 0.5 * i as f64 / n as f64).collect();
    let tail = |k: usize| m[k..].iter().sum::<f64>();
    let params: Vec<f64> = m.iter().chain(&l).copied().collect();
    let f = d.eval_forcing(0.0, &q, &qd, &params);
    for i in 0..n {
        let velocity: f64 = (0..n)
            .map(|j| tail(i.max(j)) * l[j] * (q[i] - q[j]).sin() * qd[j] * qd[j])
            .sum();
        let expected = -l[i] * (9.81 * tail(i) * q[i].sin() + velocity);
        assert!(
            (f[i] - expected).abs() < 1e-12 * (1.0 + expected.abs()),
            "f[{i}] = {} vs {expected}",
            f[i]
        );
    }
}

#[test]
fn a_kinetic_energy_with_linear_and_static_terms_keeps_its_forcing() {
    // T = ½ẋ² + a x ẋ + ½ x² (a term linear in ẋ and one without it):
    // p = ẋ + a x, f = ∂L/∂x − ṗ + ẍ = a ẋ + x − a ẋ − k x = (1 − k) x.
    let linear = "struct L { coordinates: x; parameters: a, k; \
                  kinetic: dot(x)^2/2 + a*x*dot(x) + x^2/2; potential: k*x^2/2; }";
    let d = lagrange_engine::derive(linear.parse().unwrap()).unwrap();
    let f = d.eval_forcing(0.0, &[0.7], &[1.3], &[0.4, 3.0]);
    assert!((f[0] - (1.0 - 3.0) * 0.7).abs() < 1e-15, "{f:?}");
}

/// The LaTeX rendering (`LATEX`): the same entries as the text, with
/// subscripts, dots, `\frac`, `\sin` and one `aligned` block.
#[test]
fn equations_as_latex() {
    let pendulum = r#"
        pub struct Pendulum {
            coordinates: theta;
            parameters: m, l, g;
            let y = -l*cos(theta);
            kinetic: m/2*l^2*dot(theta)^2;
            potential: m*g*y;
        }
    "#;
    let d = lagrange_engine::derive(pendulum.parse().unwrap()).unwrap();
    assert_eq!(
        d.equations_latex(),
        "\\begin{aligned}\n\
         M_{\\theta \\, \\theta} &= m \\, l^{2} \\\\\n\
         f_{\\theta} &= -l \\, m \\, g \\, \\sin\\left(\\theta\\right) \\\\\n\
         \\end{aligned}\n"
    );
    let d = lagrange_engine::derive(DOUBLE_PENDULUM.parse().unwrap()).unwrap();
    let latex = d.equations_latex();
    println!("{latex}");
    // Every line of the text has its row, and the velocities read as dots.
    assert_eq!(
        latex.lines().count(),
        d.equations_text().lines().count() + 2
    );
    assert!(latex.contains("\\dot{\\theta}_{1}"), "{latex}");
    // A division is a fraction.
    let kepler = "pub struct Radial { coordinates: r; parameters: k; \
                  kinetic: dot(r)^2/2; potential: -k/r; }";
    let d = lagrange_engine::derive(kepler.parse().unwrap()).unwrap();
    assert!(
        d.equations_latex().contains("f_{r} &= -\\frac{k}{r^{2}}"),
        "{}",
        d.equations_latex()
    );
}
