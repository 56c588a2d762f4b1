//! Every compile error of `lagrange-ui/tests/ui/`, checked without
//! rustc: the engine expands the case's `lagrangian!` invocation, and the
//! expansion must hold exactly one `compile_error!`, with the message and
//! the span (line and column, start and end on one line) that the case's
//! `.stderr` records from rustc.
//!
//! This checks every case in a second, without building the runtime;
//! `lagrange-ui/tests/ui.rs` runs them through rustc itself
//! (trybuild), where what matters is rustc's own view: one error and no
//! other, the stub standing in for the model so that code using it still
//! compiles.

use std::path::Path;

use proc_macro2::{Delimiter, Span, TokenStream, TokenTree};

/// The tokens inside the first `lagrangian! { .. }` of `source`, with
/// their spans in the file.
fn invocation(source: &str) -> Option<TokenStream> {
    let tokens: TokenStream = source.parse().ok()?;
    find(tokens)
}

fn find(tokens: TokenStream) -> Option<TokenStream> {
    let trees: Vec<TokenTree> = tokens.into_iter().collect();
    for (i, tree) in trees.iter().enumerate() {
        if let TokenTree::Ident(ident) = tree {
            if ident == "lagrangian" {
                if let (Some(TokenTree::Punct(bang)), Some(TokenTree::Group(body))) =
                    (trees.get(i + 1), trees.get(i + 2))
                {
                    if bang.as_char() == '!' && body.delimiter() == Delimiter::Brace {
                        return Some(body.stream());
                    }
                }
            }
        }
        if let TokenTree::Group(group) = tree {
            if let Some(found) = find(group.stream()) {
                return Some(found);
            }
        }
    }
    None
}

/// Every `compile_error! { "message" }` of an expansion: its message and
/// the spans syn gives it (the start on the path, the end on the group).
fn compile_errors(tokens: TokenStream) -> Vec<(String, Span, Span)> {
    let trees: Vec<TokenTree> = tokens.into_iter().collect();
    let mut out = Vec::new();
    for (i, tree) in trees.iter().enumerate() {
        match tree {
            TokenTree::Ident(ident) if ident == "compile_error" => {
                if let Some(TokenTree::Group(group)) = trees.get(i + 2) {
                    let message = group.stream().to_string();
                    let literal: syn::LitStr = syn::parse_str(&message).expect("a string literal");
                    out.push((literal.value(), ident.span(), group.span()));
                }
            }
            TokenTree::Group(group) => out.extend(compile_errors(group.stream())),
            _ => {}
        }
    }
    out
}

/// What a `.stderr` records: the message, and the line, column and caret
/// width of its span.
struct Recorded {
    message: String,
    line: usize,
    column: usize,
    carets: Option<usize>,
}

fn recorded(stderr: &str) -> Recorded {
    let mut lines = stderr.lines();
    let message = lines
        .next()
        .and_then(|l| l.strip_prefix("error: "))
        .expect("an error line")
        .to_string();
    let location = lines
        .next()
        .and_then(|l| l.trim().strip_prefix("--> "))
        .expect("a location line");
    let mut parts = location.rsplitn(3, ':');
    let column: usize = parts.next().unwrap().parse().unwrap();
    let line: usize = parts.next().unwrap().parse().unwrap();
    // The caret line follows the source line: `  |      ^^^^`.
    let carets = stderr
        .lines()
        .skip(3)
        .find_map(|l| l.split_once('|').map(|(_, rest)| rest))
        .and_then(|rest| {
            let rest = rest.trim_start();
            (rest.starts_with('^')).then(|| rest.chars().take_while(|&c| c == '^').count())
        });
    Recorded {
        message,
        line,
        column,
        carets,
    }
}

#[test]
fn every_ui_case_expands_to_its_one_recorded_error() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../lagrange-ui/tests/ui");
    let mut cases: Vec<_> = std::fs::read_dir(&dir)
        .expect("tests/ui")
        .map(|e| e.expect("an entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "rs"))
        .collect();
    cases.sort();
    assert!(cases.len() > 50, "{} cases", cases.len());
    let (mut wrong, mut lexer) = (Vec::new(), Vec::new());
    for case in &cases {
        let name = case.file_name().unwrap().to_string_lossy().to_string();
        let source = std::fs::read_to_string(case).unwrap();
        let stderr = std::fs::read_to_string(case.with_extension("stderr")).unwrap();
        let expected = recorded(&stderr);
        let Some(input) = invocation(&source) else {
            if source.parse::<TokenStream>().is_err() {
                // Delimiters that do not balance never reach the macro:
                // rustc's lexer reports them (trybuild checks that case).
                lexer.push(name);
            } else {
                wrong.push(format!("{name}: no `lagrangian! {{ .. }}`"));
            }
            continue;
        };
        let errors = compile_errors(lagrange_engine::expand(input));
        let [(message, start, end)] = errors.as_slice() else {
            wrong.push(format!("{name}: {} compile errors", errors.len()));
            continue;
        };
        if *message != expected.message {
            wrong.push(format!(
                "{name}: message\n  {message}\n  recorded\n  {}",
                expected.message
            ));
        }
        let (start, end) = (start.start(), end.end());
        // rustc counts columns from 1, proc_macro2 from 0.
        if (start.line, start.column + 1) != (expected.line, expected.column) {
            wrong.push(format!(
                "{name}: at {}:{}, recorded {}:{}",
                start.line,
                start.column + 1,
                expected.line,
                expected.column
            ));
        }
        if let Some(carets) = expected.carets {
            if end.line == start.line && end.column - start.column != carets {
                wrong.push(format!(
                    "{name}: {} columns wide, recorded {carets}",
                    end.column - start.column
                ));
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    assert_eq!(
        lexer,
        ["unbalanced_parens.rs"],
        "cases only rustc's lexer sees"
    );
    println!(
        "{} cases, each one error with its recorded message and span ({} left to rustc's lexer)",
        cases.len() - lexer.len(),
        lexer.len()
    );
}
