//! `#[lagrange(parameter_derivatives)]` in the engine: the items it adds,
//! sized by the parameter scalars, their absence without it, and the stub
//! of a model with an error keeping them, so that code calling them gets
//! no second error. (Their values against dual numbers are the facade's
//! `tests/models/parameter_derivatives.rs`.)

const PENDULUM: &str = "
    #[lagrange(parameter_derivatives)]
    pub struct Pendulum {
        const N = 2;
        coordinates: theta;
        parameters: m, l[N], g;
        kinetic: m/2*(l[0] + l[1])^2*dot(theta)^2;
        potential: -m*g*(l[0] + l[1])*cos(theta);
    }";

fn expand(src: &str) -> String {
    lagrange_engine::expand(src.parse().unwrap()).to_string()
}

#[test]
fn the_option_adds_the_derivatives_sized_by_the_parameter_scalars() {
    let tokens = expand(PENDULUM);
    assert!(!tokens.contains("compile_error"), "{tokens}");
    // m, l[0], l[1], g: four columns.
    assert!(tokens.contains(
        "pub const PARAMETER_SCALARS : [& 'static str ; 4] = [\"m\" , \"l[0]\" , \"l[1]\" , \"g\"]"
    ));
    assert!(tokens.contains("pub fn mass_matrix_parameter_derivatives"));
    assert!(tokens.contains("[:: lagrange :: nalgebra :: SMatrix < S , 1 , 1 > ; 4]"));
    assert!(tokens.contains("pub fn forcing_parameter_jacobian"));
    assert!(tokens.contains("pub fn residual_parameter_jacobian"));
    assert!(tokens.contains(":: lagrange :: nalgebra :: SMatrix < S , 1 , 4 >"));
    // No constraints, no constraint derivatives.
    assert!(!tokens.contains("constraint_parameter_jacobian"));
    syn::parse_file(&tokens).expect("the items parse as Rust");

    let without = expand(&PENDULUM.replace("#[lagrange(parameter_derivatives)]", ""));
    for item in [
        "PARAMETER_SCALARS",
        "parameter_derivatives",
        "parameter_jacobian",
    ] {
        assert!(!without.contains(item), "{item} without the option");
    }
}

#[test]
fn a_model_with_an_error_keeps_its_parameter_derivatives_in_the_stub() {
    let tokens = expand(&PENDULUM.replace("cos(theta)", "cos(dot(theta))"));
    assert_eq!(tokens.matches("compile_error").count(), 1, "{tokens}");
    assert!(tokens.contains("pub const PARAMETER_SCALARS : [& 'static str ; 4]"));
    assert!(tokens.contains("pub fn residual_parameter_jacobian"));
    assert!(!tokens.contains("constraint_parameter_jacobian"));
    syn::parse_file(&tokens).expect("the stub parses as Rust");

    // A constrained model's stub has its constraints' derivatives, `C × P`.
    let constrained = PENDULUM
        .replace("coordinates: theta;", "coordinates: theta, r;")
        .replace(
            "potential:",
            "constraints: rod: r = l[0] + l[1]; potential:",
        );
    let tokens = expand(&constrained.replace("cos(theta)", "cos(dot(theta))"));
    assert_eq!(tokens.matches("compile_error").count(), 1, "{tokens}");
    assert!(tokens.contains("pub fn constraint_acceleration_parameter_jacobian"));
    assert!(tokens.contains(":: lagrange :: nalgebra :: SMatrix < S , 1 , 4 >"));
    syn::parse_file(&tokens).expect("the stub parses as Rust");
}
