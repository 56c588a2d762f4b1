//! Properties of the emitted code itself: every `let` it writes is read,
//! and fused multiply-add appears only under `cfg(target_feature = "fma")`.

use quote::ToTokens;

fn indexed_chain(n: usize) -> String {
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
        }}"
    )
}

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
    // One `mul_add`, in the helper, under the cfg; the other branch plain.
    assert_eq!(mentions(&body, "mul_add"), 1, "{body}");
    let cfg = body
        .find("# [cfg (target_feature = \"fma\")]")
        .expect("the cfg");
    let not_cfg = body
        .find("# [cfg (not (target_feature = \"fma\"))] { a * b + c }")
        .expect("the plain branch");
    assert!(cfg < body.find("mul_add").unwrap() && body.find("mul_add").unwrap() < not_cfg);
}

#[test]
fn a_sine_and_a_cosine_of_one_angle_are_one_sin_cos() {
    let mf = methods(&indexed_chain(3))
        .into_iter()
        .find(|f| f.sig.ident == "mass_matrix_and_forcing")
        .unwrap();
    let body = mf.block.to_token_stream().to_string();
    assert_eq!(mentions(&body, "sin_cos"), 3, "{body}");
    assert_eq!(mentions(&body, "sin") + mentions(&body, "cos"), 0, "{body}");
}
