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

/// The user's crate (`user-crate/`, built and run by CI) holds the
/// README's model and its use as the README shows them: the model's block
/// verbatim, the use's lines in order inside `main`.
#[test]
fn the_user_crate_holds_the_readme_model_and_its_use() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let main = std::fs::read_to_string(root.join("user-crate/src/main.rs")).unwrap();
    let (_, model) = block(&readme, MODEL_START);
    assert!(
        main.contains(model),
        "user-crate/src/main.rs lacks the README's model"
    );
    let (_, usage) = block(&readme, "<!-- readme-use:start -->\n```rust\n");
    let body = &main[main.find("fn main()").expect("a main function")..];
    let mut rest = body;
    for line in usage.lines().filter(|l| !l.trim().is_empty()) {
        let at = rest.find(line).unwrap_or_else(|| {
            panic!("user-crate/src/main.rs lacks, or has out of order, the README's line {line:?}")
        });
        rest = &rest[at + line.len()..];
    }
}
