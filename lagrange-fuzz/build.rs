//! The seed corpus: every `lagrangian! { .. }` written in the repository (the
//! examples and benchmarks, the integration and UI tests, the engine's tests), extracted at
//! build time so that the mutator starts from real models and follows them as
//! they change.

use proc_macro2::{Delimiter, TokenStream, TokenTree};
use std::fmt::Write;
use std::path::{Path, PathBuf};

const DIRS: [&str; 6] = [
    "lagrange-studies",
    "tests",
    "lagrange-ui/tests",
    "src",
    "lagrange-engine/src",
    "lagrange-engine/tests",
];

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the fuzz crate sits in the workspace root")
        .to_path_buf();
    let mut files = Vec::new();
    for dir in DIRS {
        println!("cargo:rerun-if-changed=../{dir}");
        rust_files(&root.join(dir), &mut files);
    }
    let mut models: Vec<String> = Vec::new();
    for file in &files {
        let Ok(text) = std::fs::read_to_string(file) else {
            continue;
        };
        // Templates and files that are not Rust tokens are skipped.
        let Ok(tokens) = text.parse::<TokenStream>() else {
            continue;
        };
        let mut found = Vec::new();
        invocations(tokens, &mut found);
        models.extend(found.into_iter().map(|t| t.to_string()));
    }
    models.sort();
    models.dedup();
    let mut out =
        String::from("/// Bodies of the repository's `lagrangian!` invocations, sorted.\n");
    out.push_str("pub const CORPUS: &[&str] = &[\n");
    for m in &models {
        writeln!(out, "    {m:?},").unwrap();
    }
    out.push_str("];\n");
    let dest = PathBuf::from(std::env::var("OUT_DIR").unwrap()).join("corpus.rs");
    std::fs::write(dest, out).unwrap();
}

/// All `.rs` files under `dir`, sorted.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = entries.filter_map(|e| e.ok()).map(|e| e.path()).collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The bodies of `lagrangian! { .. }` at any depth of `stream`.
fn invocations(stream: TokenStream, found: &mut Vec<TokenStream>) {
    let tokens: Vec<TokenTree> = stream.into_iter().collect();
    for (i, tt) in tokens.iter().enumerate() {
        if let TokenTree::Group(g) = tt {
            let after_bang = i >= 2
                && matches!(&tokens[i - 1], TokenTree::Punct(p) if p.as_char() == '!')
                && matches!(&tokens[i - 2], TokenTree::Ident(id) if id == "lagrangian");
            if after_bang && g.delimiter() == Delimiter::Brace {
                found.push(g.stream());
            } else {
                invocations(g.stream(), found);
            }
        }
    }
}
