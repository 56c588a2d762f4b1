//! The masses of `T` on a tree of increments (`derive/articulated.rs`):
//! found in a chain in absolute angles and in a branched tree in relative
//! ones, with the joints, angles and axes the runtime's recursion reads;
//! refused, so that the dense solve stays, wherever the form does not hold.
//! That the recursion then solves `M q̈ = f` is the runtime's test
//! (`tests/trajectories/articulated.rs`).

use crate::problems::{binary_tree_64, comb, comb_of, derive, error, indexed_chain};
use lagrange_engine::derive::articulated::{Articulated, FORMED_FROM, FROM_COORDINATES};

fn found(src: &str) -> Option<Articulated> {
    derive(src).equations.articulated
}

/// Two branches of `b` links of length `l` in relative angles, the second
/// hanging from the end of the first's first link (`l` pulled out of each
/// velocity's sum: its terms are distributed again to find the joints).
fn tree(b: usize) -> String {
    format!(
        "pub struct Tree {{
            const B = {b};
            coordinates: phi[B], psi[B];
            parameters: l;
            constants: g = 9.81;
            let ta[i in 0..B] = sum(j in 0..=i, phi[j]);
            let tb[i in 0..B] = ta[0] + sum(j in 0..=i, psi[j]);
            let xa[i in 0..B] = l*sum(j in 0..=i, sin(ta[j]));
            let ya[i in 0..B] = -l*sum(j in 0..=i, cos(ta[j]));
            let xb[i in 0..B] = xa[0] + l*sum(j in 0..=i, sin(tb[j]));
            let yb[i in 0..B] = ya[0] - l*sum(j in 0..=i, cos(tb[j]));
            kinetic: sum(i in 0..B, (dot(xa[i])^2 + dot(ya[i])^2 + dot(xb[i])^2 + dot(yb[i])^2)/2);
            potential: sum(i in 0..B, g*(ya[i] + yb[i]));
        }}"
    )
}

#[test]
fn a_chain_in_absolute_angles_is_a_path_of_hinges() {
    let n = FROM_COORDINATES;
    let a = found(&indexed_chain(n)).expect("the chain's form");
    assert_eq!(a.axes, 2);
    // Each link's increment at the end of the one before; each angle a
    // coordinate of its own.
    let parents: Vec<Option<usize>> = (0..n).map(|j| j.checked_sub(1)).collect();
    assert_eq!(a.parent, parents);
    assert_eq!(a.base, vec![None; n]);
    assert_eq!(a.coordinate, (0..n).collect::<Vec<_>>());
    assert_eq!(a.scale, vec![1.0; n]);
    // Axes, bends and masses for N joints in 2 axes, N inertias, N forces.
    assert_eq!(a.roots.len(), n * (3 * 2 + 2));
}

#[test]
fn a_branched_tree_in_relative_angles_is_a_tree_of_sums() {
    let b = FROM_COORDINATES.div_ceil(2);
    let a = found(&tree(b)).expect("the tree's form");
    assert_eq!(a.axes, 2);
    let n = 2 * b;
    // Every angle but the first is another joint's plus one coordinate,
    // every coordinate once; each joint's parent is its angle's base (a
    // hinge turns with the link it hangs from).
    assert_eq!(a.base.iter().filter(|b| b.is_none()).count(), 1);
    assert_eq!(a.parent, a.base);
    let mut coordinates = a.coordinate.clone();
    coordinates.sort_unstable();
    assert_eq!(coordinates, (0..n).collect::<Vec<_>>());
    // Two joints hang from the first link's end: the second of branch a and
    // the first of branch b.
    let children_of_first = a.parent.iter().filter(|p| **p == Some(0)).count();
    assert_eq!(children_of_first, 2);
    for (j, p) in a.parent.iter().enumerate() {
        assert!(p.is_none_or(|p| p < j), "a parent after its child");
    }
}

#[test]
fn a_component_written_with_the_other_sign_has_the_same_joints() {
    // `y` written upward: its velocity's terms carry the opposite sign,
    // the same joints.
    let src = indexed_chain(FROM_COORDINATES).replace(
        "let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));",
        "let y[i in 0..N] = sum(j in 0..=i, l[j]*cos(theta[j]));",
    );
    let a = found(&src).expect("the form, whatever the sign");
    assert_eq!(a.scale, vec![1.0; FROM_COORDINATES]);
}

#[test]
fn models_without_the_form_keep_the_dense_solve() {
    let n = FROM_COORDINATES;
    // Below the size where the recursion pays.
    assert!(found(&indexed_chain(n - 1)).is_none());
    // Links that stretch: a length is a coordinate, and the direction it
    // moves along depends on another (`g` is not a function of its own
    // joint's angle).
    let elastic = format!(
        "pub struct Elastic {{
            const N = {n};
            coordinates: theta[N], r[N];
            constants: g = 9.81, k = 50.0;
            let x[i in 0..N] = sum(j in 0..=i, r[j]*sin(theta[j]));
            let y[i in 0..N] = -sum(j in 0..=i, r[j]*cos(theta[j]));
            kinetic: sum(i in 0..N, (dot(x[i])^2 + dot(y[i])^2)/2);
            potential: sum(i in 0..N, g*y[i] + k/2*(r[i] - 1)^2);
        }}"
    );
    assert!(found(&elastic).is_none());
    // A support driven in time: `T` holds `t` outside the squares' masses.
    let driven = indexed_chain(n).replace(
        "let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));",
        "let x[i in 0..N] = 0.1*sin(3*t) + sum(j in 0..=i, l[j]*sin(theta[j]));",
    );
    assert!(found(&driven).is_none());
    // Masses that depend on the configuration.
    let varying = indexed_chain(n).replace("m[i]/2*", "(1 + cos(theta[0])^2)*m[i]/2*");
    assert!(found(&varying).is_none());
    // A spring between two masses couples nothing in `T`: the form holds,
    // and `V`'s forces go to the runtime as they are.
    let sprung = indexed_chain(n).replace(
        "potential: sum(i in 0..N, m[i]*g*y[i]);",
        "potential: sum(i in 0..N, m[i]*g*y[i]) + 3*(x[N-1] - x[0])^2;",
    );
    assert!(found(&sprung).is_some());
}

#[test]
fn rigid_links_bring_their_inertias_to_their_joints() {
    // Rigid links in relative angles, each with a moment of inertia about
    // its end (`½ I φ̇²`, the link's absolute rate): the inertias are the
    // joints' own, not one more axis.
    let n = FROM_COORDINATES;
    let src = format!(
        "pub struct RigidChain {{
            const N = {n};
            coordinates: theta[N];
            constants: g = 9.81, inertia = 0.2;
            let phi[i in 0..N] = sum(j in 0..=i, theta[j]);
            let x[i in 0..N] = sum(j in 0..=i, sin(phi[j]));
            let y[i in 0..N] = -sum(j in 0..=i, cos(phi[j]));
            kinetic: sum(i in 0..N, (dot(x[i])^2 + dot(y[i])^2)/2 + inertia/2*dot(phi[i])^2);
            potential: sum(i in 0..N, g*y[i]);
        }}"
    );
    let a = found(&src).expect("the rigid chain's form");
    assert_eq!(a.axes, 2);
    assert_eq!(a.base.iter().filter(|b| b.is_none()).count(), 1);
}

#[test]
fn a_cart_under_a_chain_is_a_joint_along_one_axis() {
    // The cart moves along `x` alone: it is in no `y` component, and its
    // joint's axis along `y` is zero. Grouped into points (each link's
    // end, `x_i` with `y_i`), the joints' sets still nest, the cart's
    // holding every point: the root, with the links hanging from it.
    let n = FROM_COORDINATES;
    let src = format!(
        "pub struct CartChain {{
            const N = {n};
            coordinates: s, theta[N];
            constants: g = 9.81, inertia = 0.2;
            let phi[i in 0..N] = sum(j in 0..=i, theta[j]);
            let x[i in 0..N] = s + sum(j in 0..=i, sin(phi[j]));
            let y[i in 0..N] = -sum(j in 0..=i, cos(phi[j]));
            kinetic: 3*dot(s)^2/2 + sum(i in 0..N, (dot(x[i])^2 + dot(y[i])^2)/2 + inertia/2*dot(phi[i])^2);
            potential: sum(i in 0..N, g*y[i]);
        }}"
    );
    let derived = derive(&src);
    let a = derived
        .equations
        .articulated
        .as_ref()
        .expect("the cart and chain's form");
    assert_eq!(a.axes, 2);
    // The cart first, its coordinate `s` (0); each link below the one
    // before, the first below the cart.
    assert_eq!(a.coordinate[0], 0);
    let parents: Vec<Option<usize>> = (0..=n).map(|j| j.checked_sub(1)).collect();
    assert_eq!(a.parent, parents);
    // Axes: the cart's `(1, 0)` (constants), its bends zero.
    let joints = n + 1;
    let number = |id| derived.model.pool.as_num(id);
    let (axes, bends) = (&a.roots[..2 * joints], &a.roots[2 * joints..4 * joints]);
    assert_eq!((number(axes[0]), number(axes[1])), (Some(1.0), Some(0.0)));
    assert_eq!((number(bends[0]), number(bends[1])), (Some(0.0), Some(0.0)));
}

#[test]
fn the_attribute_asks_for_the_recursion_or_refuses_it_at_any_size() {
    let asked = format!("#[lagrange(articulated)] {}", indexed_chain(2));
    assert_eq!(
        found(&asked).expect("asked for").parent,
        vec![None, Some(0)]
    );
    let refused = format!(
        "#[lagrange(articulated = false)] {}",
        indexed_chain(FROM_COORDINATES)
    );
    assert!(found(&refused).is_none());
    // Asked of a model without the form: an error that says what the form
    // is, on `kinetic:`; asked of a constrained one: its own path.
    let spring = "#[lagrange(articulated)] pub struct SpringPendulum {
        coordinates: r, theta;
        parameters: m, k, l, g;
        kinetic: m/2*(dot(r)^2 + r^2*dot(theta)^2);
        potential: k/2*(r - l)^2 - m*g*r*cos(theta);
    }";
    assert!(error(spring).contains("not masses hanging on a tree of links"));
    let constrained = "#[lagrange(articulated)] pub struct Bead {
        coordinates: x, y;
        parameters: m, g, l;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*y;
        constraints: rod: x^2 + y^2 = l^2;
    }";
    assert!(error(constrained).contains("a model with constraints is solved by its own path"));
}

#[test]
fn a_model_that_expanded_within_its_budget_still_does() {
    // The chain's expansion with the dense solve alone takes `spent` steps;
    // with exactly that budget, the search for the tree (and its
    // function's emission) does not fit, is forgotten, and the model
    // expands to the same code as with `articulated = false`.
    let chain = indexed_chain(FROM_COORDINATES);
    let dense = format!("#[lagrange(articulated = false)] {chain}");
    let spent = lagrange_engine::derive_with_budget(dense.parse().unwrap(), 1 << 40)
        .unwrap()
        .model
        .pool
        .spent();
    let tight = lagrange_engine::derive_with_budget(chain.parse().unwrap(), spent).unwrap();
    assert!(tight.equations.articulated.is_none());
    let expand = |options: &str| {
        let source = format!("#[lagrange({options}budget = {spent})] {chain}");
        lagrange_engine::expand(source.parse().unwrap()).to_string()
    };
    assert_eq!(expand(""), expand("articulated = false, "));
    // With room, the form is found.
    assert!(found(&chain).is_some());
}

#[test]
fn a_model_with_the_form_forms_m_and_f_from_its_parts() {
    // From `FORMED_FROM` coordinates, or asked for by
    // `#[lagrange(articulated)]` at any size, its `mass_matrix`, `forcing`
    // and `mass_matrix_and_forcing` call the runtime on the parts instead
    // of writing `M`'s entries out; found unasked below `FORMED_FROM`, they
    // are generated as without the form (faster at that size). That the
    // formed ones are the derived `M` and `f` is the runtime's test
    // (`tests/trajectories/articulated.rs`).
    let code = |source: &str| lagrange_engine::expand(source.parse().unwrap()).to_string();
    let calls = |code: &str| {
        ["mass_matrix", "forcing", "mass_matrix_and_forcing"]
            .iter()
            .filter(|function| {
                code.contains(&format!(
                    "articulated :: {function} (& Self :: ARTICULATED_TREE"
                ))
            })
            .count()
    };
    let large = indexed_chain(FORMED_FROM);
    let formed = code(&large);
    let generated = code(&format!("#[lagrange(articulated = false)] {large}"));
    assert_eq!(
        calls(&formed),
        3,
        "M and f are not formed at {FORMED_FROM} links"
    );
    assert_eq!(calls(&generated), 0, "M and f are formed without the form");
    // The entries gone: at 18 links the expansion is under 0.8 of the one
    // with `M` and `f` written out (their three functions); less at more
    // links.
    assert!(
        formed.len() * 10 < generated.len() * 8,
        "{} against {} bytes",
        formed.len(),
        generated.len()
    );
    let small = indexed_chain(FROM_COORDINATES);
    let found = code(&small);
    assert!(found.contains("ARTICULATED_TREE"), "the form is not found");
    assert_eq!(
        calls(&found),
        0,
        "M and f are formed below {FORMED_FROM} links unasked"
    );
    let asked = code(&format!("#[lagrange(articulated)] {small}"));
    assert_eq!(
        calls(&asked),
        3,
        "M and f are not formed where the form is asked for"
    );
}

#[test]
fn large_trees_expand_at_the_default_budget_without_m_and_f() {
    // The comb (30 coordinates) and the binary tree of 64 links, unasked,
    // and the 100-link chain: the tree is found before `M` and `f` would be
    // derived, and they never are (their dense derivation: 60 million
    // steps for the comb, beyond the default budget). The text is the
    // parts': O(N) entries, where `M` alone has N(N+1)/2 (the comb's dense
    // EQUATIONS and LATEX: 12.8 MB; these: 81 KB, 56 KB and 169 KB,
    // `cargo run --release -p lagrange-studies --example large_trees`).
    for (source, joints) in [
        (comb(""), 30),
        (binary_tree_64(""), 64),
        (indexed_chain(100), 100),
    ] {
        let d = derive(&source);
        let a = d.equations.articulated.as_ref().expect("the tree");
        assert_eq!(a.parent.len(), joints);
        assert!(d.equations.mass.is_empty() && d.equations.forcing.is_empty());
        let text = d.equations_text();
        assert!(text.contains("parent[") && !text.contains("M["), "{text}");
        // Each entry at most a sum along one path: measured 0.9 (the
        // binary tree) to 2.7 KB (the comb, whose angles are long sums)
        // per joint, both texts together.
        let size = text.len() + d.equations_latex().len();
        assert!(size < 4_000 * joints, "{size} bytes of text");
        let code = d.tokens().to_string();
        assert!(code.contains("ARTICULATED_TREE"));
        assert!(!code.contains("compile_error"));
    }
    // The comb's branches hang from the ends of the chain's 4th, 8th, ...
    // links: the joints whose parents hold two children.
    let a = found(&comb("")).expect("the comb's tree");
    let mut forks: Vec<usize> = (0..30)
        .filter(|&j| a.parent.iter().filter(|p| **p == Some(j)).count() == 2)
        .map(|j| a.coordinate[j])
        .collect();
    forks.sort_unstable();
    assert_eq!(forks, [3, 7, 11, 15]);
    // (The 20th link's branch is its only child.)
    assert_eq!(a.parent.iter().filter(|p| p.is_none()).count(), 1);
}

#[test]
fn the_parts_found_first_are_the_parts_found_last() {
    // `#[lagrange(articulated)]` alone finds the tree first, with `M` and
    // `f` never derived; with `jacobians`, which are derived from `M` and
    // `f`, the model is derived whole and the tree found last. The parts
    // are the same functions: equal at every state, to the last bit
    // (each evaluated by the same arithmetic on the same tree, the nodes
    // hash-consed alike).
    let tree = comb_of(8, "#[lagrange(articulated)]");
    let first = derive(&tree);
    let last = derive(&tree.replace("articulated)]", "articulated, jacobians)]"));
    assert!(first.equations.mass.is_empty());
    assert_eq!(last.equations.mass.len(), 12);
    let (a, b) = (
        first.equations.articulated.as_ref().expect("found first"),
        last.equations.articulated.as_ref().expect("found last"),
    );
    assert_eq!(
        (&a.parent, &a.base, &a.coordinate),
        (&b.parent, &b.base, &b.coordinate)
    );
    let params: Vec<f64> = (0..13).map(|k| 0.5 + 0.1 * k as f64).collect();
    for k in 0..20 {
        let q: Vec<f64> = (0..12)
            .map(|i| (0.37 * (7 * i + 13 * k) as f64).sin())
            .collect();
        let v: Vec<f64> = (0..12)
            .map(|i| (0.61 * (5 * i + 11 * k) as f64).cos())
            .collect();
        assert_eq!(
            first.eval(&a.roots, 0.0, &q, &v, &params),
            last.eval(&b.roots, 0.0, &q, &v, &params)
        );
    }
}

#[test]
fn a_large_model_without_the_form_expands_as_before() {
    // From 18 coordinates the tree is looked for first; where it is not
    // found, the model is lowered again and derived as before the search
    // came first: the same code as with the search refused.
    let elastic = "pub struct Elastic {
        const N = 9;
        coordinates: theta[N], r[N];
        constants: g = 9.81, k = 50.0;
        let x[i in 0..N] = sum(j in 0..=i, r[j]*sin(theta[j]));
        let y[i in 0..N] = -sum(j in 0..=i, r[j]*cos(theta[j]));
        kinetic: sum(i in 0..N, (dot(x[i])^2 + dot(y[i])^2)/2);
        potential: sum(i in 0..N, g*y[i] + k/2*(r[i] - 1)^2);
    }";
    let code = |source: &str| lagrange_engine::expand(source.parse().unwrap()).to_string();
    let unasked = code(elastic);
    assert!(!unasked.contains("compile_error") && !unasked.contains("ARTICULATED_TREE"));
    assert_eq!(
        unasked,
        code(&format!("#[lagrange(articulated = false)] {elastic}"))
    );
}

#[test]
fn the_dense_comb_is_refused_by_the_code_limit() {
    // Derived whole within a raised budget, the comb's `M` and `f` would be
    // 8.4 MB of code (rustc: 2 min 42 s and 17.9 GB of memory, issue 50):
    // the limit on the generated code stops it with an error that says
    // what to write instead, before any of it is written.
    let dense = comb("#[lagrange(articulated = false, budget = 100000000)]");
    let e = error(&dense);
    assert!(
        e.contains("the code generated for `Comb` would be about"),
        "{e}"
    );
    assert!(
        e.contains("write `#[lagrange(articulated)]` instead"),
        "{e}"
    );
    assert!(e.contains("`#[lagrange(max_code = "), "{e}");
}

#[test]
fn the_code_size_estimate_follows_the_code() {
    // The estimate the limit is checked against, against the functions
    // actually written (the expansion's text less `EQUATIONS` and
    // `LATEX`), on dense expansions from 0.3 to 1.4 MB: never under by
    // more than a tenth (a model under the limit by the estimate is under
    // it by the code, give or take), at most 1.6 times over (measured 1.14
    // to 1.42: `BYTES_PER_OPERAND` is the largest ratio measured).
    for source in [
        format!("#[lagrange(articulated = false)] {}", indexed_chain(20)),
        format!("#[lagrange(articulated = false)] {}", indexed_chain(30)),
        comb_of(12, "#[lagrange(articulated = false, budget = 100000000)]"),
    ] {
        let d = derive(&source);
        let text = d.equations_text().len() + d.equations_latex().len();
        let code = d.tokens().to_string().len() - text;
        let estimate = d.estimated_code_bytes() as usize;
        assert!(
            estimate * 10 >= code * 9 && estimate * 10 <= code * 16,
            "estimated {estimate} bytes for {code}"
        );
    }
}
