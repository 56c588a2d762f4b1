//! The workspace's README shows a model and the code `lagrangian!`
//! generates for it; this keeps the two true, from the engine alone.
//! `UPDATE_README=1 cargo test -p lagrange-engine --test engine -- readme::`
//! rewrites the generated block after an intended change to the emitted
//! code.

use std::path::Path;

const MODEL_START: &str = "<!-- readme-model:start -->\n```rust\n";
const GENERATED_START: &str = "<!-- readme-generated:start -->\n```rust\n";
const END: &str = "```\n";

fn block<'a>(text: &'a str, start: &str) -> (usize, &'a str) {
    let from = text.find(start).expect("README marker") + start.len();
    let len = text[from..].find(END).expect("end of README code block");
    (from, &text[from..from + len])
}

/// `mass_matrix_and_forcing` from the expansion, pretty-printed in its impl.
fn generated_hot_path(model_source: &str) -> String {
    let open = model_source
        .find("lagrangian! {")
        .expect("lagrangian! in the README model")
        + 13;
    let close = model_source.rfind('}').unwrap();
    let tokens: proc_macro2::TokenStream = model_source[open..close].parse().unwrap();
    let file: syn::File = syn::parse2(lagrange_engine::expand(tokens)).unwrap();
    let mut items = Vec::new();
    for item in file.items {
        if let syn::Item::Impl(mut imp) = item {
            if imp.trait_.is_some() {
                continue;
            }
            imp.attrs.clear();
            imp.items.retain(
                |i| matches!(i, syn::ImplItem::Fn(f) if f.sig.ident == "mass_matrix_and_forcing"),
            );
            items.push(syn::Item::Impl(imp));
        }
    }
    prettyplease::unparse(&syn::File {
        shebang: None,
        attrs: Vec::new(),
        items,
    })
}

#[test]
fn readme_shows_the_code_generated_for_its_model() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../README.md");
    let readme = std::fs::read_to_string(&path).unwrap();
    let (_, model) = block(&readme, MODEL_START);
    let expected = generated_hot_path(model);
    let (at, shown) = block(&readme, GENERATED_START);
    if std::env::var_os("UPDATE_README").is_some() {
        let updated = format!(
            "{}{}{}",
            &readme[..at],
            expected,
            &readme[at + shown.len()..]
        );
        std::fs::write(&path, updated).unwrap();
        return;
    }
    assert_eq!(
        shown, expected,
        "README's generated code is stale: run `UPDATE_README=1 cargo test -p lagrange-engine --test engine -- readme::`"
    );
}
