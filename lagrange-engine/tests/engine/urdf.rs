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
    let text = expand_with("urdf = \"x.urdf\", regressor = true", "");
    assert!(
        error_of(&text).contains("a robot's `regressor` takes no value"),
        "{text}"
    );
    let text = expand_with("urdf = \"x.urdf\", regressor, regressor", "");
    assert!(
        error_of(&text).contains("`regressor` is given twice"),
        "{text}"
    );
    let text = expand_with("urdf = \"x.urdf\", fixed", "");
    assert!(
        error_of(&text).contains("with `floating` for a floating base, `regressor` for the"),
        "{text}"
    );
}

/// `parameters(field = "link")`: each mistake one error on its tokens.
#[test]
fn urdf_parameters_misuse_is_one_error_on_its_tokens() {
    let tree = "urdf = \"../tests/data/robots/tree.urdf\"";
    let panda = "urdf = \"../tests/data/robots/panda.urdf\"";
    let locked = "locked: panda_finger_joint1 = 0.0, panda_finger_joint2 = 0.0;";
    for (attribute, body, message) in [
        ("parameters", "", "`parameters` lists fields and links"),
        ("parameters()", "", "`parameters()` names no field"),
        (
            "parameters(arm)",
            "",
            "`arm` names the link (or body) whose parameters it holds",
        ),
        (
            "parameters(a = \"arm\", a = \"hub\")",
            "",
            "field `a` is given twice",
        ),
        (
            "parameters(a = \"arm\", b = \"arm\")",
            "",
            "`arm` is given twice (its field is `a`)",
        ),
        (
            "parameters(a = \"arm\"), parameters(b = \"hub\")",
            "",
            "`parameters` is given twice",
        ),
        ("parameters(a = \"elbow\")", "", "has no link `elbow`"),
        (
            "parameters(a = \"base\")",
            "",
            "link `base` is the fixed base",
        ),
        (
            "parameters(a = \"weight\")",
            "",
            "link `weight` is welded to `wrist` (joint `weight_mount` is fixed): its mass is part of that body's",
        ),
    ] {
        let text = expand_with(&format!("{tree}, {attribute}"), body);
        let e = error_of(&text);
        assert!(e.contains(message), "{attribute}: {e}");
        assert_eq!(
            text.matches("compile_error").count(),
            1,
            "{attribute}: {text:.600}"
        );
    }
    // A link fixed to a fixed base moves with nothing.
    let ur5 = "urdf = \"../tests/data/robots/ur5.urdf\"";
    let text = expand_with(&format!("{ur5}, parameters(b = \"base_link\")"), "");
    assert!(
        error_of(&text)
            .contains("link `base_link` is fixed to the fixed base (through joint `world_joint`)"),
        "{text:.600}"
    );
    // A finger locked is welded to the hand, which is fixed to link 7.
    let text = expand_with(
        &format!("{panda}, parameters(f = \"panda_leftfinger\")"),
        locked,
    );
    assert!(
        error_of(&text).contains(
            "link `panda_leftfinger` is welded to `panda_link7` (joint `panda_finger_joint1` is locked)"
        ),
        "{text:.600}"
    );
    // Named, a link's parameters are fields the code reads.
    let text = expand_with(&format!("{tree}, parameters(wrist = \"wrist\")"), "");
    assert!(!text.contains("compile_error"), "{text:.600}");
    assert!(
        text.contains("pub wrist : [S ; 10]") && text.contains("self . wrist [9usize]"),
        "{text:.600}"
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
        for (function, [mul, add, recip, bytes]) in operation_counts(&text) {
            println!("  {function}: {mul} ×, {add} ±, {recip} 1/x, {bytes} bytes");
        }
    }
}

/// The arithmetic of each traced function of an expansion: every
/// statement `let vN: S = ..;` is one operation (a product, a product by a
/// constant, a sum or difference, a reciprocal), read from the text; and
/// the function's size in bytes.
fn operation_counts(text: &str) -> Vec<(String, [usize; 4])> {
    let mut out = Vec::new();
    for chunk in text.split(" fn ").skip(1) {
        let name = chunk
            .split(['(', '<', ' '])
            .next()
            .unwrap_or("")
            .to_string();
        let mut counts = [0, 0, 0, chunk.len()];
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
        if counts[..3].iter().sum::<usize>() > 0 {
            out.push((name, counts));
        }
    }
    out
}

// Robots written as bodies and joints in the macro's input: read into the
// URDF route's links and joints, so that everything after reading is the
// same code; each refusal one error on the tokens it is about.

/// `tests/data/robots/tree.urdf` written in the language, its numbers
/// copied: the inertias' `rpy` as `axes`, each `<origin>` as
/// `translate(xyz) * rotate_rpy(rpy)`.
const TREE: &str = "
    bodies:
        hub: mass 2.5, com [0.02, -0.01, 0.11], axes rotate_rpy(0.1, -0.2, 0.3),
             inertia [[0.031, 0.002, -0.001], [0.002, 0.027, 0.003], [-0.001, 0.003, 0.019]];
        slider: mass 1.2, com [0.1, 0.02, 0.0], inertia [[0.004, 0, 0.0005], [0, 0.011, 0], [0.0005, 0, 0.012]];
        wrist: mass 0.6, com [0, 0, 0.07], inertia [[0.002, 0.0001, 0], [0.0001, 0.0021, 0], [0, 0, 0.0009]];
        weight: mass 0.3, inertia diag(0.0003, 0.0003, 0.0003);
        tool;
        arm: mass 0.9, com [0, 0.12, 0], axes rotate_rpy(0, 0.3, 0), inertia diag(0.006, 0.001, 0.0055);
    joints:
        a_yaw: revolute base -> hub, at translate(0.05, 0, 0.2) * rotate_rpy(0, 0, 0.4), axis [0.1, 0.2, 0.97];
        b_slide: prismatic hub -> slider, at translate(0, 0.03, 0.25) * rotate_rpy(0.3, 0.5, -0.2), axis [0.8, 0, 0.6];
        c_wrist: revolute slider -> wrist, at translate(0.2, 0, 0) * rotate_x(PI / 2), axis [0, 1, 0];
        weight_mount: fixed wrist -> weight, at translate(0.03, -0.02, 0.12) * rotate_rpy(0.2, 0, 0);
        tool_frame: fixed weight -> tool, at translate(0, 0, 0.05);
        d_arm: revolute hub -> arm, at translate(0.04, 0, 0.15) * rotate_rpy(-0.4, 0.1, 1.1), axis [0.6, -0.48, 0.64];
";

/// The expansion of `pub struct Robot { body }`.
fn expand_inline(body: &str) -> String {
    let tokens: TokenStream = format!("pub struct Robot {{ {body} }}").parse().unwrap();
    lagrange_engine::expand(tokens).to_string()
}

/// The one `compile_error!` of a robot written in the language: its
/// message and the source text its span covers (start to end, on one line).
fn inline_error(body: &str) -> (String, String) {
    inline_error_with("", body)
}

/// [`inline_error`] with attributes before the struct.
fn inline_error_with(attributes: &str, body: &str) -> (String, String) {
    let src = format!("{attributes} pub struct Robot {{ {body} }}");
    let tokens: TokenStream = src.parse().unwrap();
    let out = lagrange_engine::expand(tokens);
    let mut found = Vec::new();
    let mut stack = vec![out];
    while let Some(ts) = stack.pop() {
        let trees: Vec<proc_macro2::TokenTree> = ts.into_iter().collect();
        for (i, t) in trees.iter().enumerate() {
            match t {
                proc_macro2::TokenTree::Ident(id) if id == "compile_error" => {
                    if let Some(proc_macro2::TokenTree::Group(g)) = trees.get(i + 2) {
                        let lit: syn::LitStr = syn::parse_str(&g.stream().to_string()).unwrap();
                        found.push((lit.value(), id.span().start(), g.span().end()));
                    }
                }
                proc_macro2::TokenTree::Group(g) => stack.push(g.stream()),
                _ => {}
            }
        }
    }
    assert_eq!(found.len(), 1, "one error: {found:?}");
    let (message, start, end) = found.remove(0);
    assert_eq!(start.line, end.line, "{message}");
    let line = src.lines().nth(start.line - 1).unwrap();
    let chars: Vec<char> = line.chars().collect();
    (message, chars[start.column..end.column].iter().collect())
}

/// `parameters(..)` on a robot written as bodies and joints: each mistake
/// one error, on the tokens it is about.
#[test]
fn inline_parameters_mistakes_land_on_their_tokens() {
    for (attributes, message, tokens) in [
        (
            "#[lagrange(parameters(w = \"weight\"))]",
            "body `weight` is welded to `wrist` (joint `weight_mount` is fixed)",
            "\"weight\"",
        ),
        (
            "#[lagrange(parameters(w = \"elbow\"))]",
            "robot `Robot` has no body `elbow`",
            "\"elbow\"",
        ),
        (
            "#[lagrange(parameters(w = \"base\"))]",
            "body `base` is the fixed base",
            "\"base\"",
        ),
        (
            "#[lagrange(parameters(w = \"hub\", w = \"arm\"))]",
            "field `w` is given twice",
            "w",
        ),
        (
            "#[lagrange(parameters(w = \"hub\", v = \"hub\"))]",
            "`hub` is given twice (its field is `w`)",
            "\"hub\"",
        ),
        (
            "#[lagrange(parameters(w))]",
            "`w` names the link (or body) whose parameters it holds",
            "w",
        ),
        (
            "#[lagrange(parameters())]",
            "`parameters()` names no field",
            "()",
        ),
    ] {
        let (got, span) = inline_error_with(attributes, TREE);
        assert!(got.contains(message), "{attributes}: {got}");
        assert_eq!(span, tokens, "{attributes}: {got}");
    }
}

/// A one-body robot whose body and joint are given.
fn one_body(body: &str, joint: &str) -> String {
    format!("bodies: arm: {body}; joints: j: {joint};")
}

const ARM: &str = "mass 1, com [0, 0, 0.5], inertia diag(0.1, 0.1, 0.02)";

#[test]
fn inline_tree_expands_to_the_same_items_as_its_urdf() {
    let inline = expand_inline(TREE);
    assert!(!inline.contains("compile_error"), "{inline:.600}");
    // The file's own tokens: the include that rebuilds on a change, and
    // the path in a doc string.
    let file = expand_with("urdf = \"../tests/data/robots/tree.urdf\"", "")
        .replace(
            "const _ : & [u8] = include_bytes ! (concat ! (env ! (\"CARGO_MANIFEST_DIR\") , \"/\" , \"../tests/data/robots/tree.urdf\")) ; ",
            "",
        )
        .replace("`../tests/data/robots/tree.urdf`", "`Robot`");
    // `rotate_x(PI / 2)` is the file's `rpy="1.5707963267948966 0 0"`
    // after snapping: every item, recursion, frame and regressor the same
    // tokens, so the same bits.
    if let Some(at) = inline.bytes().zip(file.bytes()).position(|(a, b)| a != b) {
        let from = at.saturating_sub(300);
        panic!(
            "the expansions differ at byte {at}:\n{}\n{}",
            &inline[from..(at + 200).min(inline.len())],
            &file[from..(at + 200).min(file.len())]
        );
    }
    assert_eq!(inline.len(), file.len());
}

#[test]
fn inline_expansion_is_deterministic_and_a_floating_base_expands() {
    assert_eq!(expand_inline(TREE), expand_inline(TREE));
    let text = expand_inline(&format!(
        "bodies: trunk: {ARM}; leg: {ARM}; joints: free: floating base -> trunk; \
         hip: revolute trunk -> leg, at translate(0, 0.1, 0), axis [0, 1, 0];"
    ));
    assert!(!text.contains("compile_error"), "{text:.600}");
    for item in ["velocity_mass_matrix", "base_qw", "VELOCITIES", "Holonomic"] {
        assert!(text.contains(item), "{item}");
    }
}

#[test]
fn inline_values_are_constant_expressions_of_constants() {
    // `0.3 / 2`, `PI / 2`, a vector and a matrix constant, composed
    // transforms, a rotation times a vector.
    let text = expand_inline(
        "constants: l = 0.3, z = [0, 0, 1], I = diag(0.01, 0.01, 0.002), tilt = rotate_x(PI / 2);
         bodies: upper: mass 1.2, com l / 2 * z, inertia I; fore: mass 0.8, com [0, 0, 0.12], inertia 0.5 * I;
         joints: shoulder: revolute base -> upper, at translate(0, 0, 0.1) * rotate_z(-PI / 4), axis z;
                 elbow: revolute upper -> fore, at translate(l * z) * tilt, axis tilt * [0, 1, 0];
         locked: elbow = PI / 6;",
    );
    assert!(!text.contains("compile_error"), "{text:.600}");
    assert!(text.contains("\"shoulder\""));
}

/// Each mistake: one error, its words, and the tokens it lands on.
#[test]
fn inline_mistakes_are_one_error_on_their_tokens() {
    let indefinite = "mass 1, inertia [[0.1, 0, 0], [0, -0.1, 0], [0, 0, 0.1]]";
    let triangle = "mass 1, inertia diag(0.1, 0.1, 0.3)";
    let revolute = "revolute base -> arm, axis [0, 0, 1]";
    let cases: &[(String, &str, &str)] = &[
        (
            one_body(indefinite, revolute),
            "body `arm`'s inertia is not positive definite",
            "[[0.1, 0, 0], [0, -0.1, 0], [0, 0, 0.1]]",
        ),
        (
            one_body(triangle, revolute),
            "break the triangle inequality",
            "diag(0.1, 0.1, 0.3)",
        ),
        (
            one_body(ARM, "revolute base -> arm, axis [0, 0.0, 0]"),
            "joint `j`'s axis is zero",
            "[0, 0.0, 0]",
        ),
        (
            one_body("mass -2, inertia diag(1, 1, 1)", revolute),
            "body `arm` has a negative mass, -2",
            "-2",
        ),
        (
            one_body(ARM, "revolute base -> hand, axis [0, 0, 1]"),
            "joint `j`'s child `hand` is no body of the robot",
            "hand",
        ),
        (
            one_body(ARM, "revolute base -> arm"),
            "joint `j` is revolute and needs an `axis`",
            "j",
        ),
        (
            one_body(ARM, "hinge base -> arm"),
            "a joint is `revolute`, `continuous`, `prismatic`, `fixed` or `floating`",
            "hinge",
        ),
        (
            one_body(ARM, "revolute base -> arm, axis [0, 0, 1], pitch 2"),
            "a revolute joint takes `at` (its frame in the parent's) and `axis`, not `pitch`",
            "pitch",
        ),
        (
            one_body(
                "mass 1, inertia [[0.1, 0.01, 0], [0, 0.1, 0], [0, 0, 0.1]]",
                revolute,
            ),
            "inertia is not symmetric",
            "[[0.1, 0.01, 0], [0, 0.1, 0], [0, 0, 0.1]]",
        ),
        (
            one_body("mass 0, inertia diag(0.1, 0.1, 0.1)", revolute),
            "no mass but an inertia",
            "diag(0.1, 0.1, 0.1)",
        ),
        (
            one_body("mass 1", revolute),
            "body `arm` has a mass but no `inertia`",
            "arm",
        ),
        (
            one_body("mass 1, inertia [0.1, 0.1, 0.1]", revolute),
            "an inertia is a matrix",
            "[0.1, 0.1, 0.1]",
        ),
        (
            one_body(
                ARM,
                "revolute base -> arm, at translate(0, 0, 1) + rotate_x(1), axis [0, 0, 1]",
            ),
            "a transform plus a transform",
            "+",
        ),
        (
            one_body(ARM, "revolute base -> arm, axis [0, 0, 1] / 0"),
            "division by zero",
            "/",
        ),
        (
            one_body(ARM, "revolute base -> arm, axis [0, 0, l]"),
            "`l` is no constant",
            "l",
        ),
        (
            one_body(ARM, "revolute base -> arm, at turn(1), axis [0, 0, 1]"),
            "`turn` is no function",
            "turn",
        ),
        (
            one_body(ARM, "revolute base -> arm, axis [0, 0, 1]; locked: k = 0.1"),
            "the robot has no joint `k`",
            "k",
        ),
        (
            one_body("", revolute).replace("arm: ;", "arm: mass 1, mass 2;"),
            "`mass` is given twice",
            "mass",
        ),
        (
            one_body(ARM, "fixed base -> arm"),
            "the robot has no moving joint",
            "Robot",
        ),
        (
            one_body(ARM, "revolute base -> arm, axis [0, 0, 1]").replace("arm:", "base:"),
            "`base` is the world",
            "base",
        ),
        (
            format!("bodies: arm: {ARM}; arm: {ARM}; joints: j: {revolute};"),
            "body `arm` is defined twice",
            "arm",
        ),
        (
            format!(
                "bodies: arm: {ARM}; hand: {ARM}; joints: j: {revolute}; j: revolute arm -> hand, axis [1, 0, 0];"
            ),
            "joint `j` is defined twice",
            "j",
        ),
        (
            format!(
                "bodies: arm: {ARM}; hand: {ARM}; joints: j: {revolute}; k: revolute base -> hand, axis [1, 0, 0]; l: fixed hand -> arm;"
            ),
            "body `arm` is attached twice: by joint `j` and by joint `l`",
            "arm",
        ),
        (
            format!("bodies: arm: {ARM}; hand: {ARM}; joints: j: {revolute};"),
            "body `hand` is attached to nothing",
            "hand",
        ),
        (
            format!(
                "bodies: arm: {ARM}; hand: {ARM}; foot: {ARM}; joints: j: {revolute}; k: revolute hand -> foot, axis [1, 0, 0]; l: revolute foot -> hand, axis [1, 0, 0];"
            ),
            "body `hand` lies on a loop of joints",
            "hand",
        ),
        (
            format!(
                "bodies: arm: {ARM}; hand: mass 0; joints: j: {revolute}; k: revolute arm -> hand, axis [1, 0, 0];"
            ),
            "robot `Robot`: the mass matrix is singular: joint `k` moves no mass",
            "k",
        ),
        (
            format!(
                "bodies: trunk: {ARM}; leg: {ARM}; joints: f: floating base -> trunk; g: floating base -> leg;"
            ),
            "a second floating joint",
            "g",
        ),
        (
            format!(
                "bodies: trunk: {ARM}; leg: {ARM}; joints: f: floating base -> trunk; g: revolute base -> leg, axis [1, 0, 0];"
            ),
            "every other joint hangs from the floating body `trunk`",
            "base",
        ),
        (
            format!(
                "bodies: trunk: {ARM}; leg: {ARM}; joints: f: floating trunk -> leg; g: {revolute};"
            )
            .replace("-> arm", "-> trunk"),
            "a floating base hangs from `base`",
            "trunk",
        ),
        (
            "masses: 1; joints: j: revolute base -> arm, axis [0, 0, 1];".to_string(),
            "takes the sections",
            "masses: 1",
        ),
        (
            one_body(ARM, "revolute base -> arm, axis [0, 0, 1]; masses: 1"),
            "a joint reads `masses: revolute parent -> child",
            "1",
        ),
    ];
    for (body, message, at) in cases {
        let (got, span) = inline_error(body);
        assert!(
            got.contains(message),
            "{body}\n  gave: {got}\n  expected: {message}"
        );
        assert_eq!(span, *at, "{body}: {got}");
    }
}

/// Every prefix of the tree's tokens (a model cut anywhere) expands or
/// errs, never panics.
#[test]
fn inline_any_truncation_expands_or_errs_without_panic() {
    let tokens: Vec<proc_macro2::TokenTree> =
        TREE.parse::<TokenStream>().unwrap().into_iter().collect();
    for n in 0..=tokens.len() {
        let body: TokenStream = tokens[..n].iter().cloned().collect();
        let src: TokenStream = format!("pub struct Robot {{ {body} }}").parse().unwrap();
        let _ = lagrange_engine::expand(src);
    }
}

/// A chain of `n` links written in the language, its axes turning from
/// joint to joint (no two neighbours parallel, so that little folds).
fn inline_chain(n: usize) -> String {
    let mut body = String::from("bodies: ");
    let mut joints = String::from("joints: ");
    let axes = ["[0, 1, 0]", "[1, 0, 0]", "[0.6, 0, 0.8]"];
    for k in 0..n {
        body += &format!("b{k}: mass 1, com [0, 0, 0.2], inertia diag(0.02, 0.02, 0.004); ");
        let parent = if k == 0 {
            "base".to_string()
        } else {
            format!("b{}", k - 1)
        };
        joints += &format!(
            "j{k}: revolute {parent} -> b{k}, at translate(0, 0, 0.3) * rotate_x(0.3), axis {}; ",
            axes[k % 3]
        );
    }
    body + &joints
}

/// The bytes of one generated method's tokens, from its name to the next
/// method's.
fn method_size(text: &str, name: &str) -> usize {
    let start = text
        .find(&format!("pub fn {name} "))
        .unwrap_or_else(|| panic!("{name} generated"));
    let rest = &text[start + 1..];
    rest.find("pub fn ").map_or(rest.len(), |end| end + 1)
}

/// How a robot's generated code grows with its joints: chains of 4 to 32
/// links written in the language (printed, the figures of the language
/// reference). Sizes are tokens, deterministic. Past the first links
/// (where the base's known axes fold more), each doubling of the chain at
/// most 2.5 times `q̈` by ABA and `τ` by RNEA (linear growth doubles them)
/// and more than 3 times `M` by CRBA (quadratic growth, an entry per pair
/// of joints, quadruples it).
#[test]
fn inline_chains_print_how_their_code_grows() {
    let mut sizes = Vec::new();
    println!(
        "links | items (bytes) | forward_dynamics | inverse_dynamics | mass_matrix | expanded in"
    );
    for n in [4, 8, 16, 32] {
        let start = std::time::Instant::now();
        let text = expand_inline(&inline_chain(n));
        let elapsed = start.elapsed();
        assert!(!text.contains("compile_error"), "{n}: {text:.300}");
        let s = [
            method_size(&text, "forward_dynamics"),
            method_size(&text, "inverse_dynamics"),
            method_size(&text, "mass_matrix"),
        ];
        println!(
            "{n} | {} | {} | {} | {} | {:.1} ms",
            text.len(),
            s[0],
            s[1],
            s[2],
            elapsed.as_secs_f64() * 1e3
        );
        sizes.push(s);
    }
    for w in sizes[2..].windows(2) {
        let (before, after) = (w[0], w[1]);
        assert!(
            after[0] * 2 < before[0] * 5,
            "ABA grows linearly: {before:?} to {after:?}"
        );
        assert!(
            after[1] * 2 < before[1] * 5,
            "RNEA grows linearly: {before:?} to {after:?}"
        );
        assert!(
            after[2] > before[2] * 3,
            "M grows quadratically: {before:?} to {after:?}"
        );
    }
}

/// The regressor is opt-in on both routes: written only where
/// `#[lagrange(regressor)]` asks for it, and any other option refused.
#[test]
fn the_regressor_is_written_only_where_asked_for() {
    let without = expand_inline(TREE);
    let tokens: TokenStream = format!("#[lagrange(regressor)] pub struct Robot {{ {TREE} }}")
        .parse()
        .unwrap();
    let with = lagrange_engine::expand(tokens).to_string();
    assert!(!with.contains("compile_error"), "{with:.300}");
    assert!(with.contains("pub fn regressor") && with.contains("PARAMETERS"));
    assert!(!without.contains("pub fn regressor") && !without.contains("PARAMETERS"));
    let tokens: TokenStream = format!("#[lagrange(jacobians)] pub struct Robot {{ {TREE} }}")
        .parse()
        .unwrap();
    let refused = lagrange_engine::expand(tokens).to_string();
    assert!(
        refused.contains("takes two `#[lagrange(..)]` options, `regressor`"),
        "{refused:.300}"
    );
}
