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

/// `#[lagrange(regressor(..))]`: the lumped parameters named and grouped
/// at compile time, the stub keeping the API, and each refusal on the
/// offending parameter.
mod regressor {
    use super::expand;
    use crate::problems::error;

    const CHAIN: &str = "
        #[lagrange(regressor(m, l))]
        pub struct Chain {
            const N = 3;
            coordinates: theta[N];
            parameters: m[N], l[N];
            constants: g = 9.81;
            let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));
            let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));
            kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2));
            potential: sum(i in 0..N, m[i]*g*y[i]);
        }";

    /// The chain's base parameters: `l_i l_j (m_j + … + m_{N−1})` for
    /// `i ≤ j` (N(N+1)/2 = 6 of them) and the gravity terms
    /// `l_i (m_i + … + m_{N−1})` (3): nine, each the sum of the products
    /// whose columns coincide.
    #[test]
    fn the_chains_lumped_parameters_are_its_base_parameters() {
        let tokens = expand(CHAIN);
        assert!(!tokens.contains("compile_error"), "{tokens}");
        let start = tokens.find("REGRESSOR_PARAMETERS").unwrap();
        let names = &tokens[start..start + tokens[start..].find("] ;").unwrap() + 1];
        assert!(names.contains("; 9]"), "{names}");
        for base in [
            "\"m[0]*l[0] + m[1]*l[0] + m[2]*l[0]\"",
            "\"m[2]*l[2]^2\"",
            "\"m[1]*l[0]*l[1] + m[2]*l[0]*l[1]\"",
        ] {
            assert!(tokens.contains(base), "{base} in {names}");
        }
        assert!(tokens.contains("pub fn regressor ("));
        assert!(tokens.contains("pub fn regressor_offset ("));
        assert!(tokens.contains("pub fn regressor_parameters (& self ,)"));
        syn::parse_file(&tokens).expect("the items parse as Rust");
    }

    #[test]
    fn a_model_with_an_error_keeps_its_regressor_in_the_stub() {
        let tokens = expand(&CHAIN.replace("sin(theta[j])", "sin(dot(theta[j]))"));
        assert_eq!(tokens.matches("compile_error").count(), 1, "{tokens}");
        assert!(tokens.contains("pub const REGRESSOR_PARAMETERS : [& 'static str ; 6]"));
        assert!(tokens.contains("pub fn regressor ("));
        syn::parse_file(&tokens).expect("the stub parses as Rust");
    }

    #[test]
    fn a_parameter_in_a_function_is_refused_on_its_token() {
        let message = error(
            "#[lagrange(regressor(m, alpha))]
            pub struct Incline {
                coordinates: x;
                parameters: m, alpha;
                constants: g = 9.81;
                kinetic: m/2*dot(x)^2;
                potential: -m*g*x*sin(alpha);
            }",
        );
        assert!(message.contains("not a polynomial in `alpha`"), "{message}");
    }

    /// `(I + m l²) θ̈` with `l` known: the columns of `I` and `m` are
    /// `θ̈` and `l² θ̈`, proportional by a factor that is not a constant.
    #[test]
    fn parameters_the_equations_cannot_tell_apart_are_refused() {
        let message = error(
            "#[lagrange(regressor(I, m))]
            pub struct Wheel {
                coordinates: theta;
                parameters: I, m, l;
                kinetic: (I + m*l^2)/2*dot(theta)^2;
                potential: 0;
            }",
        );
        assert!(
            message.contains("the equations see `m` only in combination"),
            "{message}"
        );
    }

    #[test]
    fn a_name_that_is_not_a_parameter_is_refused() {
        let message = error(
            "#[lagrange(regressor(m, k))]
            pub struct Spring {
                coordinates: x;
                parameters: m, c;
                kinetic: m/2*dot(x)^2;
                potential: x^2;
            }",
        );
        assert!(message.contains("`k` is not a parameter"), "{message}");
        assert!(message.contains("(here: m, c)"), "{message}");
    }
}

/// Domains after the parameters' names: each scalar's in `DOMAINS` (an
/// indexed parameter's for each element, `REAL` where none is declared),
/// the checked constructors beside `new`, and the sensitivities' sizes for
/// every number of directions, `1 ..= P + 2N`.
#[test]
fn domains_reach_the_parameter_scalars_and_the_checked_constructors() {
    let tokens = expand(&PENDULUM.replace(
        "parameters: m, l[N], g;",
        "parameters: m > 0, l[N] in [0.5, 2], g;",
    ));
    assert!(!tokens.contains("compile_error"), "{tokens}");
    let real = ":: lagrange :: Domain :: REAL";
    let positive =
        ":: lagrange :: Domain :: new (0.0 , false , :: core :: f64 :: INFINITY , false)";
    let closed = ":: lagrange :: Domain :: new (0.5 , true , 2.0 , true)";
    assert!(
        tokens.contains(&format!(
            "const DOMAINS : [:: lagrange :: Domain ; 4] = [{positive} , {closed} , {closed} , {real}]"
        )),
        "{tokens}"
    );
    assert!(tokens.contains(&format!("{closed} . check_all (\"l\" , & self . l) ?")));
    for item in [
        "pub struct PendulumParameters < S = f64 >",
        "pub fn try_new (m : S , l : [S ; 2] , g : S)",
        "pub fn from_parameters (parameters : PendulumParameters < S >)",
        "pub fn check_parameters (& self)",
    ] {
        assert!(tokens.contains(item), "{item}");
    }
    // P = 4 scalars and N = 1 coordinate: 1 to 6 directions, N (1 + D).
    assert!(tokens.contains("Augmented < 6 , 7 > for Pendulum < S >"));
    assert!(!tokens.contains("Augmented < 7 ,"));
    syn::parse_file(&tokens).expect("the items parse as Rust");
    // The same model expands to the same bytes.
    assert_eq!(
        tokens,
        expand(&PENDULUM.replace(
            "parameters: m, l[N], g;",
            "parameters: m > 0, l[N] in [0.5, 2], g;"
        ))
    );
}

/// Each malformed domain is one error, on its tokens, and the stub keeps
/// every parameter (its `new` takes them all).
#[test]
fn a_malformed_domain_is_one_error_and_the_stub_keeps_the_parameter() {
    for (domain, message) in [
        ("l[N] > ", "the bound after `>` is missing"),
        ("l[N] in [2, 1]", "the domain of `l` is empty"),
        ("l[N] in [1, 1]", "holds the one value 1"),
        ("l[N] >= g", "must be a number literal"),
        ("l[N] in 3", "expected an interval after `in`"),
        (
            "l[N] in [0 1]",
            "expected `,` between the interval's two ends",
        ),
    ] {
        let tokens = expand(&PENDULUM.replace("l[N]", domain));
        assert_eq!(
            tokens.matches("compile_error").count(),
            1,
            "{domain}: {tokens}"
        );
        assert!(tokens.contains(message), "{domain}: {tokens}");
        assert!(
            tokens.contains("fn new (m : S , l : [S ; 2] , g : S)"),
            "{domain}"
        );
    }
}
