//! Properties of the emitted code itself: every `let` it writes is read,
//! fused multiply-add appears only under `cfg(target_feature = "fma")`, and
//! sines and cosines are lanes of the runtime's kernel, called once for all
//! the angles known at that point.

use crate::problems::indexed_chain;
use quote::ToTokens;

/// Every method of the model's inherent impl.
fn methods(source: &str) -> Vec<syn::ImplItemFn> {
    let file: syn::File = syn::parse2(lagrange_engine::expand(source.parse().unwrap())).unwrap();
    let mut out = Vec::new();
    for item in file.items {
        if let syn::Item::Impl(imp) = item {
            if imp.trait_.is_none() {
                for i in imp.items {
                    if let syn::ImplItem::Fn(f) = i {
                        out.push(f);
                    }
                }
            }
        }
    }
    out
}

/// The whole-word occurrences of `name` in `text` (tokens separated by spaces).
fn mentions(text: &str, name: &str) -> usize {
    text.split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .filter(|w| *w == name)
        .count()
}

#[test]
fn every_let_the_chain_binds_is_read() {
    for n in [2, 5, 10] {
        for f in methods(&indexed_chain(n)) {
            let body = f.block.to_token_stream().to_string();
            for stmt in &f.block.stmts {
                let syn::Stmt::Local(local) = stmt else {
                    continue;
                };
                let syn::Pat::Ident(p) = &local.pat else {
                    continue;
                };
                let name = p.ident.to_string();
                assert!(
                    mentions(&body, &name) > 1,
                    "N = {n}, {}: `{name}` is bound and never read",
                    f.sig.ident
                );
            }
        }
    }
}

#[test]
fn fused_multiply_add_only_where_the_target_has_it() {
    let mf = methods(&indexed_chain(5))
        .into_iter()
        .find(|f| f.sig.ident == "mass_matrix_and_forcing")
        .unwrap();
    let body = mf.block.to_token_stream().to_string();
    assert!(mentions(&body, "fma") > 10, "{body}");
    // One `simd_mul_add` (a scalar's own `mul_add`, lane by lane for SIMD
    // lanes), in the helper, under the cfg; the other branch plain.
    assert_eq!(mentions(&body, "simd_mul_add"), 1, "{body}");
    let cfg = body
        .find("# [cfg (target_feature = \"fma\")]")
        .expect("the cfg");
    let not_cfg = body
        .find("# [cfg (not (target_feature = \"fma\"))] { a * b + c }")
        .expect("the plain branch");
    let call = body.find("simd_mul_add").unwrap();
    assert!(cfg < call && call < not_cfg);
}

#[test]
fn every_angle_of_the_chain_is_one_lane_of_one_kernel_call() {
    // Three angles, each with its sine and cosine: one call of the runtime's
    // kernel on three lanes, and no other trigonometry.
    let mf = methods(&indexed_chain(3))
        .into_iter()
        .find(|f| f.sig.ident == "mass_matrix_and_forcing")
        .unwrap();
    let body = mf.block.to_token_stream().to_string();
    assert_eq!(mentions(&body, "sin_cos_array"), 1, "{body}");
    assert!(
        body.contains("sin_cos_array ([theta_0 , theta_1 , theta_2])"),
        "{body}"
    );
    for other in ["sin_cos", "sin", "cos"] {
        assert_eq!(mentions(&body, other), 0, "{other}: {body}");
    }
}

#[test]
fn an_angle_computed_from_a_sine_waits_for_it() {
    // `cos(sin θ)`: its lane reads `sin θ`, so it is a second call after the
    // first; its sine is not written (`_`).
    let source = "pub struct Nested {
        coordinates: theta;
        kinetic: dot(theta)^2 / 2;
        potential: cos(theta) + cos(sin(theta));
    }";
    let v = methods(source)
        .into_iter()
        .find(|f| f.sig.ident == "potential_energy")
        .unwrap();
    let body = v.block.to_token_stream().to_string();
    let trig = ":: lagrange :: trig :: sin_cos";
    let first = format!("let (e0 , e1) = {trig} (theta) ;");
    let second = format!("let (_ , e2) = {trig} (e0) ;");
    assert_eq!(mentions(&body, "sin_cos"), 2, "{body}");
    let (a, b) = (body.find(&first), body.find(&second));
    assert!(a.is_some() && b.is_some() && a < b, "{body}");
}
