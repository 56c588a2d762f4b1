//! Control inputs in the engine: what `inputs:` derives (`∂f/∂u`) against
//! closed forms, the items it adds, the errors it gives, and that it
//! changes nothing for a model without it.

use crate::problems::{derive, error};

const CART_POLE: &str = "
    pub struct CartPole {
        coordinates: x, theta;
        parameters: mc, mp, l, g;
        inputs: force;
        let xb = x + l*sin(theta);
        let yb = l*cos(theta);
        kinetic: mc/2*dot(x)^2 + mp/2*(dot(xb)^2 + dot(yb)^2);
        potential: mp*g*yb;
        forces: x = force;
    }";

/// A few states `(t, q, q̇)`: the formulas hold everywhere.
const STATES: [(f64, [f64; 2], [f64; 2]); 3] = [
    (0.0, [0.3, -0.9], [1.1, 0.2]),
    (1.5, [-0.7, 0.4], [-0.3, 2.0]),
    (-2.0, [1.2, 3.0], [0.0, -0.8]),
];

// Tolerances: each entry is a handful of floating-point operations on
// values of order 10, so agreement to 1e-12 leaves a factor of ~100 over
// rounding and still catches any wrong term.

#[test]
fn cart_pole_motor_force_enters_the_cart_equation_only() {
    let d = derive(CART_POLE);
    let (mc, mp, l, g) = (1.0, 0.3, 0.7, 9.81);
    for (t, [x, th], [vx, vth]) in STATES {
        for u in [0.0, 2.5, -7.0] {
            let p = [mc, mp, l, g, u];
            let du = d.eval_input_jacobian(t, &[x, th], &[vx, vth], &p);
            assert_eq!(du, vec![vec![1.0], vec![0.0]], "∂f/∂u = (1, 0)");
            let f = d.eval_forcing(t, &[x, th], &[vx, vth], &p);
            let f0 = u + mp * l * th.sin() * vth * vth;
            let f1 = mp * g * l * th.sin();
            assert!((f[0] - f0).abs() < 1e-12, "{} vs {f0}", f[0]);
            assert!((f[1] - f1).abs() < 1e-12, "{} vs {f1}", f[1]);
        }
    }
}

#[test]
fn an_input_in_the_potential_and_a_let_is_differentiated_through_them() {
    // A torque motor on a pendulum written as a potential −τ θ and as a
    // force along a `let`: ∂f/∂τ = (1 + k·l) for the force `k*tau` at the bob.
    let d = derive(
        "pub struct Driven {
            coordinates: theta;
            parameters: m, l;
            inputs: tau[2];
            let s = l*theta;
            kinetic: m/2*l^2*dot(theta)^2;
            potential: -tau[0]*theta;
            forces: s = 3*tau[1];
        }",
    );
    let du = d.eval_input_jacobian(0.0, &[0.4], &[0.1], &[1.0, 0.5, 2.0, 3.0]);
    assert_eq!(du.len(), 1);
    assert!((du[0][0] - 1.0).abs() < 1e-15 && (du[0][1] - 1.5).abs() < 1e-15);
    assert_eq!(d.model.inputs.len(), 2);
}

#[test]
fn inputs_are_fields_not_constructor_arguments() {
    let code = derive(CART_POLE).tokens().to_string();
    assert!(code.contains("pub force : S"), "{code}");
    assert!(code.contains("pub fn new (mc : S , mp : S , l : S , g : S) -> Self"));
    assert!(
        code.contains(r#"pub const PARAMETERS : [& 'static str ; 4] = ["mc" , "mp" , "l" , "g"]"#),
        "{code}"
    );
    assert!(
        code.contains(r#"pub const INPUTS : [& 'static str ; 1] = ["force"]"#),
        "{code}"
    );
    for item in [
        "pub fn input_jacobian (& self , t : S , q :",
        "pub fn inputs (& self)",
        "pub fn set_inputs (& mut self , u :",
        "pub fn with_inputs (mut self , u :",
        ":: lagrange :: Actuated < 2 , 1 > for CartPole < S >",
        "fn visit_inputs < V : :: lagrange :: inputs :: Visitor < S , 2 >> (& self , visitor : V)",
    ] {
        assert!(code.contains(item), "{item} missing from {code}");
    }
    // Unset inputs are NaN fields, so the parameters' check must not read them.
    let finite = code.split("fn parameters_are_finite").nth(1).unwrap();
    let finite = &finite[..finite.find('}').unwrap()];
    assert!(!finite.contains("force"), "{finite}");
}

#[test]
fn indexed_inputs_are_flattened_in_their_names() {
    let code = derive(
        "pub struct Arm {
            coordinates: a, b;
            parameters: m;
            inputs: tau[2], push;
            kinetic: m/2*(dot(a)^2 + dot(b)^2);
            potential: 0;
            forces: a = tau[0] + push, b = tau[1];
        }",
    )
    .tokens()
    .to_string();
    assert!(code.contains(r#"["tau[0]" , "tau[1]" , "push"]"#), "{code}");
    assert!(code.contains("pub tau : [S ; 2]"), "{code}");
}

#[test]
fn equations_text_lists_the_input_jacobian() {
    let text = derive(CART_POLE).equations_text();
    assert!(text.contains("∂f/∂u[x, force] = 1\n"), "{text}");
    assert!(text.contains("∂f/∂u[theta, force] = 0\n"), "{text}");
}

#[test]
fn a_model_without_inputs_has_no_input_items() {
    let code = derive(
        "pub struct P { coordinates: x; parameters: m; kinetic: m/2*dot(x)^2; potential: 0; }",
    )
    .tokens()
    .to_string();
    for item in [
        "INPUTS",
        "input_jacobian",
        "Actuated",
        "visit_inputs",
        "set_inputs",
    ] {
        assert!(!code.contains(item), "{item} in {code}");
    }
    assert!(code.contains("pub const fn new"));
}

/// Each error the section can give, and a fragment of its message.
#[test]
fn input_mistakes_are_one_error_each() {
    let model = |extra: &str| {
        format!(
            "pub struct M {{ coordinates: x; parameters: m; {extra}
             kinetic: m/2*dot(x)^2; potential: 0; }}"
        )
    };
    for (extra, says) in [
        (
            "inputs: x;",
            "`x` is declared twice, as a coordinate and as an input",
        ),
        ("inputs: m;", "as a parameter and as an input"),
        ("inputs: u, u;", "`u` is declared twice as an input"),
        ("inputs: u; let u = 2*x;", "each input needs its own name"),
        (
            "inputs: g; constants: g = 9.81;",
            "each input needs its own name",
        ),
        ("inputs: t;", "`t` is time and is reserved"),
        (
            "inputs: u; let p = u*x; forces: x = dot(p);",
            "holds the input `u`",
        ),
        (
            "inputs: u; forces: u = 1;",
            "force on `u`, which is an input",
        ),
        ("inputs: u[2]; forces: x = u;", "`u` is an indexed input"),
        ("inputs: u[2]; forces: x = u[2];", "index 2 is out of range"),
    ] {
        let e = error(&model(extra));
        assert!(e.contains(says), "{extra}: {e}");
    }
}

#[test]
fn an_input_in_a_momentum_or_a_constraint_is_refused() {
    let e = error(
        "pub struct M { coordinates: x; parameters: m; inputs: u;
         kinetic: (m + u)/2*dot(x)^2; potential: 0; }",
    );
    assert!(
        e.contains("the momentum ∂T/∂dot(x) depends on the input `u`"),
        "{e}"
    );
    let e = error(
        "pub struct M { coordinates: x, y; parameters: m; inputs: u;
         kinetic: m/2*(dot(x)^2 + dot(y)^2); potential: 0;
         constraints: c: x - u*y; }",
    );
    assert!(e.contains("constraint `c` depends on the input `u`"), "{e}");
}
