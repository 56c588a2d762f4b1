//! The generated code does not change by accident.
//!
//! Every `lagrangian! { .. }` written anywhere in the repository (the crate's
//! models, tests, examples and the UI tests' error cases), plus the indexed
//! chain at N = 20, is expanded here and its exact output fingerprinted
//! (length and FNV-1a 64 of the token string), keyed by the model's name and
//! a fingerprint of its input, so that a model may move between files.
//! `tests/data/golden.txt` holds the fingerprints of the last deliberate
//! change: every model found must expand exactly as recorded there. A change
//! meant to alter the generated code updates the file with
//! `LAGRANGE_BLESS=1 cargo test -p lagrange-engine --test engine -- golden::` and says why
//! in its commit. Recorded models no longer in the repository, and models new
//! since the last bless, are listed, not failed (tests move and merge), but
//! the double pendulum and the 20-link chain are always checked.
//!
//! The double pendulum's expansion is also kept whole
//! (`tests/data/double_pendulum.expanded.rs`), so that a change shows as a
//! readable diff.

use crate::problems::{DOUBLE_PENDULUM, indexed_chain};
use proc_macro2::{TokenStream, TokenTree};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the engine crate sits in the workspace root")
        .to_path_buf()
}

/// All `.rs` files under `dir`, sorted, skipping build output.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<_> = entries.filter_map(|e| e.ok()).map(|e| e.path()).collect();
    entries.sort();
    for path in entries {
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
        if path.is_dir() {
            if name != "target" && !name.starts_with('.') {
                rust_files(&path, out);
            }
        } else if name.ends_with(".rs") {
            out.push(path);
        }
    }
}

fn fnv1a(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h
}

/// The struct's name: the identifier after `struct`, or `?`.
fn struct_name(body: &TokenStream) -> String {
    let mut after_struct = false;
    for tt in body.clone() {
        if let TokenTree::Ident(id) = tt {
            if after_struct {
                return id.to_string();
            }
            after_struct = id == "struct";
        }
    }
    "?".into()
}

fn key(body: &TokenStream) -> String {
    format!(
        "{}:{:016x}",
        struct_name(body),
        fnv1a(body.to_string().as_bytes())
    )
}

/// Key of each model (name and input fingerprint) → its expansion; and
/// the models outside the UI tests' error cases that expanded to an error
/// here (each compiles where it is written, so an error here is the
/// test's own: a URDF path resolved against the wrong crate).
fn expansions() -> (BTreeMap<String, String>, Vec<String>) {
    let root = repo_root();
    let mut files = Vec::new();
    for dir in [
        "src",
        "tests",
        "lagrange-studies",
        "lagrange-ui/tests",
        "lagrange-runtime",
    ] {
        rust_files(&root.join(dir), &mut files);
    }
    let mut out = BTreeMap::new();
    let mut errors = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        if !text.contains("lagrangian!") {
            continue;
        }
        // Files that do not tokenize (none today) are skipped, not failed:
        // the test is about the engine's output, not the repo's syntax.
        let Ok(stream) = text.parse::<TokenStream>() else {
            continue;
        };
        // A robot's URDF path is relative to the manifest of the crate
        // the file belongs to (the nearest directory above it with a
        // `Cargo.toml`), as the macro resolves it there.
        let manifest_dir = file
            .ancestors()
            .skip(1)
            .find(|dir| dir.join("Cargo.toml").is_file())
            .unwrap_or(&root);
        let error_cases = file.starts_with(root.join("lagrange-ui"));
        for body in lagrange_engine::invocations(stream) {
            let k = key(&body);
            // A model written in a `macro_rules!` (its `$` metavariables
            // unbound here) or a template's placeholder is not one the
            // crate compiles as it stands.
            let text = body.to_string();
            let template = text.contains('$') || text.contains("__MODEL__");
            let expansion = lagrange_engine::expand_in(body, manifest_dir).to_string();
            if !error_cases && !template && expansion.contains("compile_error") {
                errors.push(format!("{k} in {}", file.display()));
            }
            out.insert(k, expansion);
        }
    }
    for text in [DOUBLE_PENDULUM.to_string(), indexed_chain(20)] {
        let body: TokenStream = text.parse().unwrap();
        let k = key(&body);
        out.insert(k, lagrange_engine::expand(body).to_string());
    }
    (out, errors)
}

fn manifest(expansions: &BTreeMap<String, String>) -> String {
    let mut s =
        String::from("# model  bytes  fnv1a64 of lagrange_engine::expand(..).to_string()\n");
    for (name, text) in expansions {
        s += &format!("{name}  {}  {:016x}\n", text.len(), fnv1a(text.as_bytes()));
    }
    s
}

fn parse_manifest(text: &str) -> BTreeMap<String, String> {
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .filter_map(|l| l.split_once("  "))
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect()
}

#[test]
fn every_model_in_the_repository_expands_to_the_recorded_code() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let (all, errors) = expansions();
    // The scan must have found the models it is meant to guard, and
    // expanded them as their crates do.
    assert!(all.len() > 50, "only {} models found", all.len());
    assert!(
        errors.is_empty(),
        "models that compile where they are written expanded to errors here:\n{}",
        errors.join("\n")
    );
    let dp_key = key(&DOUBLE_PENDULUM.parse().unwrap());
    let chain_key = key(&indexed_chain(20).parse().unwrap());
    let dp = syn::parse_file(&all[&dp_key]).expect("the expansion is Rust");
    let dp_pretty = prettyplease::unparse(&dp);
    let got = manifest(&all);
    if std::env::var_os("LAGRANGE_BLESS").is_some() {
        std::fs::create_dir_all(&data).unwrap();
        std::fs::write(data.join("golden.txt"), &got).unwrap();
        std::fs::write(data.join("double_pendulum.expanded.rs"), &dp_pretty).unwrap();
        return;
    }
    let want_dp = std::fs::read_to_string(data.join("double_pendulum.expanded.rs")).unwrap();
    assert_eq!(
        dp_pretty, want_dp,
        "the double pendulum's expansion changed (tests/data/double_pendulum.expanded.rs)"
    );
    let want = parse_manifest(&std::fs::read_to_string(data.join("golden.txt")).unwrap());
    let got = parse_manifest(&got);
    for must in [&dp_key, &chain_key] {
        assert_eq!(got.get(must), want.get(must), "{must} changed");
    }
    let changed: Vec<_> = got
        .iter()
        .filter_map(|(k, v)| match want.get(k) {
            Some(w) if w != v => Some(format!("{k}: now {v}, recorded {w}")),
            _ => None,
        })
        .collect();
    let new = got.keys().filter(|k| !want.contains_key(*k)).count();
    if new > 0 {
        eprintln!("{new} models are new since the last bless (not checked until blessed)");
    }
    let gone = want.keys().filter(|k| !got.contains_key(*k)).count();
    if gone > 0 {
        eprintln!("{gone} recorded models are no longer in the repository");
    }
    assert!(
        changed.is_empty(),
        "{} of {} expansions differ from tests/data/golden.txt; bless with LAGRANGE_BLESS=1 only if the change is meant:\n{}",
        changed.len(),
        got.len(),
        changed.join("\n")
    );
}
