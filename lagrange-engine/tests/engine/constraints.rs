//! Holonomic constraints in the engine: what `constraints:` derives (`φ`,
//! `G = ∂φ/∂q`, `φ̇`, `γ`) against closed forms, the items it adds, the
//! errors it gives, and that it changes nothing for a model without it.

use crate::problems::{derive, error};
use lagrange_engine::Derived;
use lagrange_engine::derive::ConstraintEquations;

fn constraints(d: &Derived) -> &ConstraintEquations {
    d.equations
        .constraints
        .as_ref()
        .expect("a constrained model")
}

const CARTESIAN_PENDULUM: &str = "
    pub struct CartesianPendulum {
        coordinates: x, y;
        parameters: m, l, g;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*y;
        constraints: rod: x^2 + y^2 = l^2;
    }";

/// A few states `(t, q, q̇)`, off the manifold too: the formulas hold
/// everywhere.
const STATES: [(f64, [f64; 2], [f64; 2]); 3] = [
    (0.0, [0.3, -0.9], [1.1, 0.2]),
    (1.5, [-0.7, 0.4], [-0.3, 2.0]),
    (-2.0, [1.2, 0.05], [0.0, -0.8]),
];

#[test]
fn cartesian_pendulum_has_the_rod_jacobian_and_bias() {
    let d = derive(CARTESIAN_PENDULUM);
    let c = constraints(&d);
    let (m, l, g) = (1.3, 0.8, 9.81);
    for (t, [x, y], [vx, vy]) in STATES {
        let at = |ids: &[_]| d.eval(ids, t, &[x, y], &[vx, vy], &[m, l, g]);
        let phi = at(&c.values);
        assert!((phi[0] - (x * x + y * y - l * l)).abs() < 1e-12);
        let gj = at(&c.jacobian[0]);
        assert!((gj[0] - 2.0 * x).abs() < 1e-12 && (gj[1] - 2.0 * y).abs() < 1e-12);
        let gamma = at(&c.bias);
        assert!((gamma[0] - 2.0 * (vx * vx + vy * vy)).abs() < 1e-12);
        let phidot = at(&c.velocities);
        assert!((phidot[0] - 2.0 * (x * vx + y * vy)).abs() < 1e-12);
        assert_eq!(at(&c.time), vec![0.0]);
    }
}

#[test]
fn a_rheonomic_constraint_carries_its_time_terms() {
    let d = derive(
        "pub struct Driven {
            coordinates: x, y;
            parameters: m, a, w;
            kinetic: m/2*(dot(x)^2 + dot(y)^2);
            potential: 0;
            constraints: drive: x = a*sin(w*t);
        }",
    );
    let c = constraints(&d);
    let (m, a, w) = (2.0, 0.4, 3.0);
    for (t, q, [vx, vy]) in STATES {
        let at = |ids: &[_]| d.eval(ids, t, &q, &[vx, vy], &[m, a, w]);
        assert_eq!(at(&c.jacobian[0]), vec![1.0, 0.0]);
        let phi_t = at(&c.time)[0];
        assert!((phi_t + a * w * (w * t).cos()).abs() < 1e-12);
        let phidot = at(&c.velocities)[0];
        assert!((phidot - (vx - a * w * (w * t).cos())).abs() < 1e-12);
        // φ̈ = ẍ + a w² sin(w t): γ = a w² sin(w t).
        let gamma = at(&c.bias)[0];
        assert!((gamma - a * w * w * (w * t).sin()).abs() < 1e-12);
    }
}

#[test]
fn indexed_constraints_are_one_per_index() {
    let d = derive(
        "pub struct Beads {
            const N = 3;
            coordinates: x[N], y[N];
            parameters: m, l;
            kinetic: sum(i in 0..N, m/2*(dot(x[i])^2 + dot(y[i])^2));
            potential: 0;
            constraints: ring[i in 0..N]: x[i]^2 + y[i]^2 = l^2, rail: y[0] = 0;
        }",
    );
    let labels: Vec<&str> = d
        .model
        .constraints
        .iter()
        .map(|c| c.label.as_str())
        .collect();
    assert_eq!(labels, ["ring[0]", "ring[1]", "ring[2]", "rail"]);
    let tokens = d.tokens().to_string();
    assert!(
        tokens.contains(r#"[& 'static str ; 4] = ["ring[0]" , "ring[1]" , "ring[2]" , "rail"]"#)
    );
    assert!(tokens.contains(":: lagrange :: Holonomic < 6 , 4 >"));
}

#[test]
fn a_constrained_model_gets_the_holonomic_items() {
    let d = derive(CARTESIAN_PENDULUM);
    let tokens = d.tokens().to_string();
    for item in [
        "pub const CONSTRAINTS : [& 'static str ; 1] = [\"rod\"]",
        "pub fn constraints (& self , t : S , q : & :: lagrange :: nalgebra :: SVector < S , 2 >) -> :: lagrange :: nalgebra :: SVector < S , 1 >",
        "pub fn constraint_jacobian (& self , t : S , q : & :: lagrange :: nalgebra :: SVector < S , 2 >) -> :: lagrange :: nalgebra :: SMatrix < S , 1 , 2 >",
        "pub fn constraint_velocities (",
        "pub fn constraint_bias (",
        "pub fn constrained_system (",
        "impl < S : :: lagrange :: nalgebra :: RealField + :: core :: marker :: Copy > :: lagrange :: Holonomic < 2 , 1 > for CartesianPendulum < S >",
        "fn visit_constraints < V : :: lagrange :: constraints :: Visitor < S , 2 >> (& self , visitor : V) -> :: core :: option :: Option < V :: Output > { :: core :: option :: Option :: Some (visitor . visit :: < Self , 1 > (self , :: core :: default :: Default :: default ())) }",
    ] {
        assert!(tokens.contains(item), "missing `{item}` in\n{tokens}");
    }
    let text = d.equations_text();
    for line in [
        "φ[rod] = ",
        "G[rod, x] = 2*x",
        "G[rod, y] = 2*y",
        "γ[rod] = ",
    ] {
        assert!(text.contains(line), "missing `{line}` in\n{text}");
    }
    // Valid Rust, whatever the runtime makes of it.
    syn::parse_file(&tokens).expect("the expansion parses as Rust");
}

#[test]
fn a_model_without_constraints_gets_no_constraint_items() {
    let d = derive(&CARTESIAN_PENDULUM.replace("constraints: rod: x^2 + y^2 = l^2;", ""));
    assert!(d.equations.constraints.is_none());
    let tokens = d.tokens().to_string();
    for absent in [
        "CONSTRAINTS",
        "Holonomic",
        "visit_constraints",
        "constraint_",
    ] {
        assert!(!tokens.contains(absent), "`{absent}` in {tokens}");
    }
}

#[test]
fn the_same_constrained_model_expands_to_the_same_tokens() {
    let once = || derive(CARTESIAN_PENDULUM).tokens().to_string();
    assert_eq!(once(), once());
    let expand = || lagrange_engine::expand(CARTESIAN_PENDULUM.parse().unwrap()).to_string();
    assert_eq!(expand(), expand());
}

#[test]
fn constraint_operation_counts_are_reported() {
    let d = derive(CARTESIAN_PENDULUM);
    let (shared, tree) = d.constraint_op_counts().unwrap();
    println!(
        "Cartesian pendulum, G and γ: {} operations emitted ({} as a tree)",
        shared.total(),
        tree.total()
    );
    assert!(shared.total() <= tree.total());
    assert!(shared.total() > 0 && shared.total() < 20);
}

#[test]
fn constraint_mistakes_are_errors_in_physics_terms() {
    let model = |constraints: &str| {
        format!(
            "pub struct P {{
                coordinates: x, y, z;
                parameters: m, l;
                constants: c0 = 0;
                let r = x^2 + y^2;
                kinetic: m/2*(dot(x)^2 + dot(y)^2 + dot(z)^2);
                potential: 0;
                constraints: {constraints};
            }}"
        )
    };
    for (constraints, expected) in [
        (
            "a: dot(x)*dot(y) - y",
            "constraint `a` is not linear in the velocities: ∂φ/∂dot(x) depends on `dot(y)`",
        ),
        ("a: l - 1", "names no coordinate: it constrains nothing"),
        (
            "a: x, b: y, c: z",
            "3 constraints on 3 coordinates leave no motion (`c` removes",
        ),
        ("a: x - y, b: 2*x = 2*y", "constraint `b` is redundant"),
        ("a: x, a: y", "`a` is declared twice as a constraint"),
        (
            "x: y",
            "`x` is declared twice, as a coordinate and as a constraint",
        ),
        ("l: y", "as a parameter and as a constraint"),
        ("r: y", "as a `let` and as a constraint"),
        ("c0: y", "as a constant and as a constraint"),
        ("a: x/c0", "infinite or undefined constant"),
        ("a: r = ", "expected"),
        (
            "x^2 + y^2 = l^2",
            "expected `:` after the constraint's name",
        ),
        ("a[i in 0..4]: x - i", "4 constraints on 3 coordinates"),
        (
            "a: x - y, b: y - x + l",
            "at every state its gradient ∂φ/∂q is a combination of the gradients of the constraints before it (`a`)",
        ),
        ("t: x", "`t` is time and is reserved"),
    ] {
        let e = error(&model(constraints));
        assert!(e.contains(expected), "`{constraints}`: {e}");
    }
    // Under an index, the error still names the element.
    let e = error(&model("a[i in 1..2]: x + i*dot(y)^2"));
    assert!(
        e.contains(
            "constraint `a[1]` is not linear in the velocities: ∂φ/∂dot(y) depends on `dot(y)`"
        ),
        "{e}"
    );
}

#[test]
fn a_model_with_a_constraint_error_stubs_the_constraint_items() {
    let src = CARTESIAN_PENDULUM.replace("x^2 + y^2 = l^2", "dot(x)^2");
    let tokens = lagrange_engine::expand(src.parse().unwrap()).to_string();
    assert_eq!(tokens.matches("compile_error").count(), 1, "{tokens}");
    assert!(tokens.contains(":: lagrange :: Holonomic < 2 , 1 >"));
    assert!(tokens.contains("pub fn constraint_jacobian"));
    syn::parse_file(&tokens).expect("the stub parses as Rust");
}

/// A velocity constraint `A(t, q) q̇ + b(t, q) = 0`: its row of G is
/// `A = ∂φ/∂q̇`, its velocity residual φ itself, its bias
/// `γ = ∂φ/∂q q̇ + ∂φ/∂t`, and it has no position level (zero). The knife
/// edge `cos θ ẏ − sin θ ẋ − a θ̇ = 0`: `A = (−sin θ, cos θ, −a)`,
/// `γ = −(cos θ ẋ + sin θ ẏ) θ̇`.
#[test]
fn a_velocity_constraint_has_g_a_and_the_bias_of_its_rate() {
    let d = derive(
        "pub struct Sleigh {
            coordinates: x, y, theta;
            parameters: m, i, a;
            kinetic: m/2*(dot(x)^2 + dot(y)^2) + i/2*dot(theta)^2;
            potential: 0;
            constraints: edge: cos(theta)*dot(y) - sin(theta)*dot(x) = a*dot(theta);
        }",
    );
    let c = constraints(&d);
    assert_eq!(c.velocity_rows, [true]);
    let (m, i, a) = (2.0, 0.3, 0.4);
    for (t, q, v) in [
        (0.0, [0.1, -0.2, 0.7], [0.5, 0.3, 1.5]),
        (2.0, [1.0, 0.4, -2.1], [-0.2, 1.1, 0.3]),
    ] {
        let at = |ids: &[_]| d.eval(ids, t, &q, &v, &[m, i, a]);
        let (s, co) = q[2].sin_cos();
        assert_eq!(at(&c.values)[0], 0.0);
        let g = at(&c.jacobian[0]);
        for (got, want) in g.iter().zip([-s, co, -a]) {
            assert!((got - want).abs() < 1e-15, "G: {g:?}");
        }
        let residual = co * v[1] - s * v[0] - a * v[2];
        assert!((at(&c.velocities)[0] - residual).abs() < 1e-15);
        let gamma = -(co * v[0] + s * v[1]) * v[2];
        assert!((at(&c.bias)[0] - gamma).abs() < 1e-15);
    }
    let tokens = d.tokens().to_string();
    assert!(
        tokens.contains("fn velocity_constraint_rows"),
        "the impl says so"
    );
}

/// A singular `M` is accepted where the constraints make up for it, and
/// refused where they do not, with the count of what is missing: a
/// coordinate without kinetic energy whose velocity a constraint fixes
/// (`y = x²`) is fine; one that no constraint fixes is not.
#[test]
fn a_singular_mass_matrix_is_accepted_only_where_the_constraints_fix_what_it_misses() {
    let model = |coordinates: &str, constraints: &str| {
        format!(
            "pub struct P {{
                coordinates: {coordinates};
                parameters: m;
                kinetic: m/2*dot(x)^2;
                potential: 0;
                constraints: {constraints};
            }}"
        )
    };
    let d = derive(&model("x, y", "curve: y = x^2"));
    assert!(constraints(&d).mass_regular_on_constraints_only);
    let e = error(&model("x, y, z", "curve: y = x^2"));
    assert!(
        e.contains("of the 2 velocity combinations they allow, the kinetic energy sees only 1"),
        "{e}"
    );
    // A regular M is not marked.
    let d = derive(CARTESIAN_PENDULUM);
    assert!(!constraints(&d).mass_regular_on_constraints_only);
}

#[test]
fn contact_mistakes_are_errors_in_physics_terms() {
    // Contacts derive as constraints do (`check/contacts.rs`); their own
    // mistakes, one error each, in the words of the contact.
    let model = |contacts: &str| {
        format!(
            "pub struct B {{
                coordinates: x, y;
                parameters: m, g, mu, e, f;
                kinetic: m/2*(dot(x)^2 + dot(y)^2);
                potential: m*g*y;
                contacts: {contacts};
            }}"
        )
    };
    for (contacts, expected) in [
        (
            "floor: y + dot(y) >= 0",
            "contact `floor`'s gap depends on a velocity",
        ),
        ("floor: m >= 0", "contact `floor`'s gap names no coordinate"),
        (
            "floor: y >= 0 { friction: mu }",
            "has friction but no slip velocity",
        ),
        (
            "floor: y >= 0 { slip: dot(x) }",
            "has a slip velocity but no friction",
        ),
        (
            "floor: y >= 0 { friction: mu, slip: dot(x)^2 }",
            "must be linear in the velocities",
        ),
        (
            "floor: y >= 0 { restitution: y }",
            "`restitution` depends on the state",
        ),
        ("floor: y >= 0 { bounce: e }", "unknown entry `bounce`"),
        (
            "floor: y >= 0 { friction: mu, kinetic_friction: mu }",
            "gives `kinetic_friction` twice",
        ),
        (
            "floor: y >= 0 { static_friction: mu, slip: dot(x) }",
            "gives one friction coefficient",
        ),
        ("floor: y = 0", "expected `>=` or `<=`"),
        (
            "floor: y >= 0 { normal: f, friction: mu, slip: dot(x) }",
            "has a gap, so its normal force is the reaction",
        ),
        (
            "brake: { friction: mu, slip: dot(x) }",
            "contact `brake` has no gap: write its gap",
        ),
        (
            "brake: { normal: f, restitution: e, friction: mu, slip: dot(x) }",
            "has no gap, so it has no impacts",
        ),
        (
            "brake: { normal: f }",
            "has a given normal force but no friction",
        ),
        (
            "brake: { normal: m*g*y, friction: mu, slip: dot(x) }",
            "`normal` depends on the state",
        ),
    ] {
        let e = error(&model(contacts));
        assert!(e.contains(expected), "`{contacts}`: {e}");
    }
    // Without a gap, with a given normal force: it derives, its gap rows
    // zero, its slip velocity as written.
    let d = derive(&model("brake: { normal: f, friction: mu, slip: dot(x) }"));
    assert!(
        d.equations_text().contains("N[brake] = f"),
        "{}",
        d.equations_text()
    );
    assert!(
        d.equations_text().contains("v_t[brake] = "),
        "{}",
        d.equations_text()
    );
}
