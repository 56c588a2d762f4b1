//! Robots from URDF: every refusal a compile error on the attribute's
//! string that names the element and its line, never a panic; the
//! expansion the same bytes every time.

use proc_macro2::TokenStream;

/// A URDF written to a scratch file, and the model's expansion of it.
fn expand_urdf(name: &str, urdf: &str, body: &str) -> String {
    let dir = std::env::temp_dir().join(format!("lagrange-urdf-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("{name}.urdf"));
    std::fs::write(&path, urdf).unwrap();
    expand_path(&path.display().to_string(), body)
}

fn expand_path(path: &str, body: &str) -> String {
    expand_with(&format!("urdf = {path:?}"), body)
}

/// The expansion with the attribute's inside given.
fn expand_with(attribute: &str, body: &str) -> String {
    let src = format!("#[lagrange({attribute})] pub struct Robot {{ {body} }}");
    let tokens: TokenStream = src.parse().unwrap();
    lagrange_engine::expand(tokens).to_string()
}

/// A URDF written to a scratch file, expanded on a floating base (with
/// `extra` after `floating` in the attribute).
fn expand_floating(name: &str, urdf: &str, extra: &str) -> String {
    let dir = std::env::temp_dir().join(format!("lagrange-urdf-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("{name}.urdf"));
    std::fs::write(&path, urdf).unwrap();
    expand_with(
        &format!("urdf = {:?}, floating{extra}", path.display().to_string()),
        "",
    )
}

const LINK: &str = r#"<inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>"#;

/// Two links and one joint between them, the joint's inside given.
fn one_joint(kind: &str, inside: &str) -> String {
    format!(
        "<robot name=\"r\">\n<link name=\"base\"/>\n<link name=\"arm\">{LINK}</link>\n\
         <joint name=\"j\" type=\"{kind}\">\n<parent link=\"base\"/><child link=\"arm\"/>\n{inside}\n</joint>\n</robot>\n"
    )
}

fn error_of(expansion: &str) -> &str {
    let start = expansion
        .find("compile_error")
        .unwrap_or_else(|| panic!("expected an error, got {expansion:.300}"));
    &expansion[start..]
}

#[test]
fn urdf_pendulum_expands_to_the_recursions() {
    let text = expand_urdf(
        "pendulum",
        &one_joint("revolute", "<origin xyz=\"0 0 1\"/><axis xyz=\"0 1 0\"/>"),
        "",
    );
    assert!(!text.contains("compile_error"), "{text:.400}");
    for f in [
        "inverse_dynamics",
        "forward_dynamics",
        "mass_matrix",
        "nonlinear_effects",
        "gravity_torques",
        "SOLVES_ACCELERATIONS",
    ] {
        assert!(text.contains(f), "{f} generated");
    }
}

#[test]
fn urdf_expansion_is_deterministic() {
    let urdf = one_joint("continuous", "<axis xyz=\"0.3 0.4 0.5\"/>");
    assert_eq!(
        expand_urdf("same_a", &urdf, ""),
        expand_urdf("same_a", &urdf, "")
    );
}

#[test]
fn urdf_missing_file_is_an_error() {
    let text = expand_path("no/such/robot.urdf", "");
    assert!(
        error_of(&text).contains("cannot read `no/such/robot.urdf`"),
        "{text}"
    );
}

#[test]
fn urdf_malformed_xml_names_its_line() {
    let text = expand_urdf(
        "malformed",
        "<robot name=\"r\">\n<link name=\"a\">\n</robot>\n",
        "",
    );
    let e = error_of(&text);
    assert!(
        e.contains("line 3") && e.contains("not well-formed XML"),
        "{e}"
    );
}

#[test]
fn urdf_unsupported_joints_are_errors_on_their_line() {
    for kind in ["planar", "floating"] {
        let text = expand_urdf(kind, &one_joint(kind, ""), "");
        let e = error_of(&text);
        assert!(
            e.contains("line 4") && e.contains(&format!("`{kind}`")),
            "{e}"
        );
    }
    let text = expand_urdf("mimic", &one_joint("revolute", "<mimic joint=\"k\"/>"), "");
    let e = error_of(&text);
    assert!(e.contains("line 6") && e.contains("mimic"), "{e}");
    // Locked, a mimic joint is no longer a coordinate, and not refused
    // (the Panda's second finger); with nothing left to move, the robot is.
    let text = expand_urdf(
        "mimic_locked",
        &one_joint("revolute", "<mimic joint=\"k\"/>"),
        "locked: j = 0.1;",
    );
    assert!(error_of(&text).contains("no moving joint"), "{text}");
}

#[test]
fn urdf_link_without_inertial_is_an_error_where_a_joint_moves_it() {
    let urdf = "<robot name=\"r\">\n<link name=\"base\"/>\n<link name=\"arm\"/>\n<joint name=\"j\" type=\"revolute\">\
                <parent link=\"base\"/><child link=\"arm\"/></joint>\n</robot>";
    let e = expand_urdf("no_inertial", urdf, "");
    let e = error_of(&e);
    assert!(
        e.contains("line 3") && e.contains("link `arm` has no `<inertial>`"),
        "{e}"
    );
}

#[test]
fn urdf_zero_axis_is_an_error() {
    let text = expand_urdf(
        "zero_axis",
        &one_joint("prismatic", "<axis xyz=\"0 0 0\"/>"),
        "",
    );
    let e = error_of(&text);
    assert!(e.contains("line 6") && e.contains("axis is zero"), "{e}");
}

#[test]
fn urdf_inertia_not_positive_definite_is_an_error() {
    let urdf = one_joint("revolute", "").replace("iyy=\"0.1\"", "iyy=\"-0.1\"");
    let text = expand_urdf("indefinite", &urdf, "");
    let e = error_of(&text);
    assert!(
        e.contains("line 3") && e.contains("not positive definite"),
        "{e}"
    );
}

#[test]
fn urdf_joint_moving_no_mass_is_an_error() {
    let urdf = one_joint("revolute", "").replace(LINK, r#"<inertial><mass value="0"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>"#);
    let text = expand_urdf("massless", &urdf, "");
    assert!(
        error_of(&text).contains("joint `j` moves no mass"),
        "{text}"
    );
}

#[test]
fn urdf_floating_base_expands_to_both_coordinates_and_its_constraint() {
    let urdf = one_joint("revolute", "<axis xyz=\"0 1 0\"/>").replace(
        "<link name=\"base\"/>",
        &format!("<link name=\"base\">{LINK}</link>"),
    );
    let text = expand_floating("floating", &urdf, "");
    assert!(!text.contains("compile_error"), "{text:.400}");
    for f in [
        "velocity_mass_matrix",
        "forward_dynamics",
        "rates",
        "Holonomic < 8usize , 1 >",
        "mass_regular_on_constraints_only",
        "\"base_qw\"",
    ] {
        assert!(text.contains(f), "{f} generated");
    }
    assert_eq!(
        text,
        expand_floating("floating", &urdf, ""),
        "deterministic"
    );
    // A free body alone: the base's 7 coordinates, no joint.
    let body = format!("<robot name=\"b\">\n<link name=\"base\">{LINK}</link>\n</robot>\n");
    let text = expand_floating("free_body", &body, "");
    assert!(!text.contains("compile_error"), "{text:.400}");
    assert!(text.contains("Holonomic < 7usize , 1 >"), "{text:.400}");
}

#[test]
fn urdf_floating_misuse_is_an_error() {
    let urdf = one_joint("revolute", "");
    let text = expand_floating("floating_value", &urdf, " = true");
    assert!(
        error_of(&text).contains("`floating` takes no value"),
        "{text}"
    );
    let text = expand_floating("floating_twice", &urdf, ", floating");
    assert!(
        error_of(&text).contains("`floating` is given twice"),
        "{text}"
    );
    let text = expand_floating(
        "floating_name",
        &urdf.replace("name=\"j\"", "name=\"base_x\""),
        "",
    );
    assert!(
        error_of(&text)
            .contains("joint `base_x` is named as one of the floating base's coordinates"),
        "{text}"
    );
    let massless = "<robot name=\"b\">\n<link name=\"base\"/>\n</robot>\n";
    let text = expand_floating("floating_massless", massless, "");
    assert!(
        error_of(&text).contains("the floating base carries no mass"),
        "{text}"
    );
    let text = expand_with("urdf = \"x.urdf\", fixed", "");
    assert!(
        error_of(&text).contains("floating)]` for a floating base"),
        "{text}"
    );
}

#[test]
fn urdf_lock_of_an_unknown_joint_is_an_error_on_its_name() {
    let text = expand_urdf("lock", &one_joint("revolute", ""), "locked: k = 0.5;");
    assert!(
        error_of(&text).contains("the robot has no joint `k`"),
        "{text}"
    );
}

#[test]
fn urdf_any_truncation_of_a_robot_expands_or_errs_without_panic() {
    let urdf = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/data/robots/tree.urdf"
    ))
    .unwrap();
    let mut cut = 0;
    while cut < urdf.len() {
        if urdf.is_char_boundary(cut) {
            let _ = expand_urdf("truncated", &urdf[..cut], "");
        }
        cut += 61;
    }
}

/// The vendored robots expand (printing the generated code's size and the
/// expansion's time, the figures of the language guide; nothing timed is
/// asserted).
#[test]
fn urdf_arms_expand_and_print_their_code_size_and_operations() {
    for (file, floating, body) in [
        ("ur5.urdf", "", ""),
        (
            "panda.urdf",
            "",
            "locked: panda_finger_joint1 = 0.0, panda_finger_joint2 = 0.0;",
        ),
        ("tree.urdf", "", ""),
        ("xarm7.urdf", "", ""),
        ("go2.urdf", ", floating", ""),
        ("romeo_small.urdf", ", floating", ""),
    ] {
        let path = format!("../tests/data/robots/{file}");
        let start = std::time::Instant::now();
        let text = expand_with(&format!("urdf = {path:?}{floating}"), body);
        let elapsed = start.elapsed();
        assert!(!text.contains("compile_error"), "{file}: {text:.300}");
        println!(
            "{file}: {} bytes of items in {:.1} ms",
            text.len(),
            elapsed.as_secs_f64() * 1e3
        );
        for (function, [mul, add, recip]) in operation_counts(&text) {
            println!("  {function}: {mul} ×, {add} ±, {recip} 1/x");
        }
    }
}

/// The arithmetic of each traced function of an expansion: every
/// statement `let vN: S = ..;` is one operation (a product, a product by a
/// constant, a sum or difference, a reciprocal), read from the text.
fn operation_counts(text: &str) -> Vec<(String, [usize; 3])> {
    let mut out = Vec::new();
    for chunk in text.split(" fn ").skip(1) {
        let name = chunk
            .split(['(', '<', ' '])
            .next()
            .unwrap_or("")
            .to_string();
        let mut counts = [0usize; 3];
        for statement in chunk.split("let v").skip(1) {
            let Some((_, rhs)) = statement.split_once(": S =") else {
                continue;
            };
            let rhs = rhs.split(';').next().unwrap_or("");
            if rhs.contains('*') {
                counts[0] += 1;
            } else if rhs.contains("simd_recip") {
                counts[2] += 1;
            } else if rhs.contains(" + ") || rhs.contains(" - ") {
                counts[1] += 1;
            }
        }
        if counts.iter().sum::<usize>() > 0 {
            out.push((name, counts));
        }
    }
    out
}
