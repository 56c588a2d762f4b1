//! The runtime's layers, checked: every module imports only from modules
//! below it, by the real path of what it imports (never through the
//! crate root's re-exports), so there is no import loop and no import
//! from a lower layer to a higher one. ARCHITECTURE.md draws the same
//! order.

use std::collections::BTreeSet;
use std::path::Path;

/// The top-level modules, lowest first. A module may import from the
/// ones before it. `constraints` and `inputs` are the user's doors (docs
/// and re-exports of the contract and the dynamics): nothing inside
/// imports through them.
const LAYERS: &[&str] = &[
    "names",       // serde of the names errors and events carry
    "trig",        // the sine and cosine of generated code
    "trajectory",  // samples, events, statistics: data
    "error",       // what went wrong, with the trajectory so far
    "linalg",      // matrices, no models
    "model",       // the contract: Lagrangian, its capabilities, layers
    "dynamics",    // q̈ and λ of a model at a state; blame
    "sensitivity", // a model with its forward sensitivities
    "events",      // functions of the state, located on an interpolant
    "driver",      // the run loops, recording, validation
    "integrators", // one method per file
    "stepper",     // frame by frame
    "ensemble",    // states in SIMD lanes, stepped together
    "contact",     // contacts and friction: modes switched at events
    "analysis",    // small motions
    "identify",    // parameters fitted to measurements
    "export",      // results out
    "interop",     // other crates' solvers
    "constraints", // the user's door to constraints
    "inputs",      // the user's door to inputs
];

/// Every `crate::<module>` a source file names in code (comments, doc
/// comments included, are skipped), with `use crate::{a, b}` groups split.
fn imported(source: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for line in source.lines() {
        let code = line.split("//").next().unwrap_or("");
        let mut rest = code;
        while let Some(at) = rest.find("crate::") {
            rest = &rest[at + "crate::".len()..];
            if let Some(group) = rest.strip_prefix('{') {
                let end = group.find('}').unwrap_or(group.len());
                for item in group[..end].split(',') {
                    let name = item.trim().split("::").next().unwrap_or("");
                    out.insert(name.trim().to_string());
                }
            } else {
                let name: String = rest
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                out.insert(name);
            }
        }
    }
    out.remove("");
    out
}

fn sources(dir: &Path, out: &mut Vec<(String, String)>) {
    for entry in std::fs::read_dir(dir).expect("reads the source tree") {
        let path = entry.expect("an entry").path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let text = std::fs::read_to_string(&path).expect("reads a source file");
            out.push((path.display().to_string(), text));
        }
    }
}

#[test]
fn every_module_imports_only_from_the_layers_below_it() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    sources(&src, &mut files);
    let mut wrong = Vec::new();
    for (path, text) in &files {
        let relative = path.trim_start_matches(&*src.display().to_string());
        let module = relative
            .trim_start_matches('/')
            .split('/')
            .next()
            .unwrap_or("")
            .trim_end_matches(".rs");
        if module == "lib" || module == "layers" {
            continue;
        }
        let Some(level) = LAYERS.iter().position(|m| *m == module) else {
            wrong.push(format!("{relative}: module `{module}` is in no layer"));
            continue;
        };
        for name in imported(text) {
            match LAYERS.iter().position(|m| *m == name) {
                Some(at) if at < level || name == module => {}
                Some(_) => wrong.push(format!("{relative}: `{module}` imports `{name}`, above it")),
                None => wrong.push(format!(
                    "{relative}: `crate::{name}` goes through the crate root, not the module that defines it"
                )),
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// The files of `model/`: the contract (what a model is and can do, and
/// the data it is read as), then the layers over it. A contract file names
/// no layer, so that the contract has no import circle through them and a
/// layer is added without touching it.
const MODEL_CONTRACT: &[&str] = &[
    "mod",
    "constraints",
    "inputs",
    "lets",
    "parameters",
    "settings",
    "reference",
];
const MODEL_LAYERS: &[&str] = &["layer", "controller", "handling", "passed_on", "with"];

/// The `model/` modules a file's code names, as `super::x` or
/// `crate::model::x` (comments skipped; the module root's `mod` and
/// `pub use` lines declare and re-export, they import nothing).
fn model_modules_named(source: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for line in source.lines() {
        let code = line.split("//").next().unwrap_or("");
        let declaration = code.trim_start();
        if declaration.starts_with("pub use ")
            || declaration.starts_with("mod ")
            || declaration.starts_with("pub mod ")
            || declaration.starts_with("pub(crate) mod ")
        {
            continue;
        }
        for prefix in ["super::", "crate::model::"] {
            let mut rest = code;
            while let Some(at) = rest.find(prefix) {
                rest = &rest[at + prefix.len()..];
                let names: Vec<&str> = match rest.strip_prefix('{') {
                    Some(group) => group[..group.find('}').unwrap_or(group.len())]
                        .split(',')
                        .map(|item| item.trim().split("::").next().unwrap_or(""))
                        .collect(),
                    None => vec![
                        rest.split(|c: char| !(c.is_alphanumeric() || c == '_'))
                            .next()
                            .unwrap_or(""),
                    ],
                };
                out.extend(names.into_iter().map(|n| n.trim().to_string()));
            }
        }
    }
    out
}

#[test]
fn the_model_contract_names_no_layer() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/model");
    let mut files = Vec::new();
    sources(&dir, &mut files);
    let mut wrong = Vec::new();
    for (path, text) in &files {
        let name = Path::new(path)
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("");
        let known = MODEL_CONTRACT.contains(&name) || MODEL_LAYERS.contains(&name);
        if !known {
            wrong.push(format!("model/{name}.rs is neither contract nor layer"));
        }
        if MODEL_CONTRACT.contains(&name) {
            for named in model_modules_named(text) {
                if MODEL_LAYERS.contains(&named.as_str()) {
                    wrong.push(format!(
                        "model/{name}.rs (contract) names the layer `{named}`"
                    ));
                }
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}
