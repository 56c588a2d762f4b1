//! The engine never panics, overflows its stack or runs away, whatever the
//! input: each model here once did one of these (found by fuzzing, issue
//! 10), and now expands or stops with a clear error.
//!
//! Every input runs on a thread of 2 MiB. rustc runs a proc macro on a
//! thread of 8 MiB; the engine's limits on nesting (`MAX_NESTING` levels of
//! syntax, checked on the brackets before syn reads them, and `MAX_DEPTH`
//! nodes of expression) keep it far below even 2 MiB, and its work budget
//! (`DEFAULT_BUDGET` steps) bounds its time and memory. (Built here with
//! syn at opt-level 1; rustc's proc-macro builds compile syn at opt-level
//! 0 by default, where the deep cases below still pass on 2 MiB: checked
//! by building the tests so, once.)

use crate::problems::indexed_chain;
use lagrange_engine::expr::{DEFAULT_BUDGET, MAX_DEPTH};
use lagrange_engine::parse::expression::MAX_NESTING;

/// The stack the engine is tested on: a quarter of rustc's.
const STACK: usize = 2 << 20;

/// What the engine makes of `source` with `budget`: the derived equations
/// as text, or the error's message. On a thread of [`STACK`] bytes; a
/// panic fails the test, a stack overflow aborts it.
fn derive(source: String, budget: u64) -> Result<String, String> {
    std::thread::Builder::new()
        .stack_size(STACK)
        .spawn(move || {
            let tokens: proc_macro2::TokenStream = source.parse().expect("the model lexes");
            match lagrange_engine::derive_with_budget(tokens, budget) {
                Ok(derived) => {
                    // The items are written too, on the same small stack.
                    assert!(!derived.tokens().is_empty());
                    Ok(derived.equations_text())
                }
                Err(e) => Err(e.to_string()),
            }
        })
        .expect("a thread")
        .join()
        .expect("the engine does not panic")
}

/// The forcing `f(q)` of a one-coordinate model at rest, derived with the
/// default budget on a thread of [`STACK`] bytes.
fn forcing_at(source: String, q: f64) -> f64 {
    std::thread::Builder::new()
        .stack_size(STACK)
        .spawn(move || {
            let derived = lagrange_engine::derive(source.parse().expect("the model lexes"))
                .expect("the model derives");
            derived.eval_forcing(0.0, &[q], &[0.0], &[])[0]
        })
        .expect("a thread")
        .join()
        .expect("the engine does not panic")
}

/// The error of a model that must not derive.
fn error(source: String, budget: u64) -> String {
    match derive(source, budget) {
        Ok(text) => panic!("derived, but should not have:\n{text}"),
        Err(e) => e,
    }
}

/// A one-coordinate model with potential energy `v`.
fn with_potential(v: &str) -> String {
    format!("struct M {{ coordinates: x; kinetic: dot(x)^2; potential: {v}; }}")
}

const TOO_DEEP: &str = "levels deep (parentheses, calls, unary minuses, exponents or method calls)";
const OVER_BUDGET: &str = "exceeds the engine's work budget";

// Integer arithmetic on the user's numbers: checked, never wrapped.

#[test]
fn a_const_that_overflows_is_an_error_naming_the_operation() {
    let e = error(
        "struct M { const N = -2097152*2097152*2097152/-1; }".into(),
        DEFAULT_BUDGET,
    );
    assert!(
        e.contains("index arithmetic overflows: -9223372036854775808 / -1 is not a 64-bit integer"),
        "{e}"
    );
}

/// `-2097152*2097152*2097152` is the least 64-bit integer: a range from it
/// to itself is empty, and its last element does not exist.
const LEAST: &str = "-2097152*2097152*2097152";

#[test]
fn an_element_of_an_empty_indexed_let_is_out_of_range_not_a_wrapped_one() {
    let e = error(
        format!(
            "struct M {{ coordinates: x; let y[i in {LEAST}..{LEAST}] = 0; potential: y[0]; }}"
        ),
        DEFAULT_BUDGET,
    );
    assert!(
        e.contains("index 0 is out of range: `y` has no elements (its range `-9223372036854775808..-9223372036854775808` is empty)"),
        "{e}"
    );
}

#[test]
fn an_empty_indexed_let_used_whole_says_it_has_no_elements() {
    let e = error(
        format!("struct M {{ coordinates: x; let y[i in {LEAST}..{LEAST}] = 0; potential: y; }}"),
        DEFAULT_BUDGET,
    );
    assert!(
        e.contains("`y` is an indexed `let` with no elements"),
        "{e}"
    );
}

#[test]
fn a_range_across_all_integers_counts_its_elements_exactly() {
    let greatest = format!("-({LEAST} + 1)");
    let e = error(
        with_potential(&format!("sum(i in {LEAST}..{greatest}, x)")),
        DEFAULT_BUDGET,
    );
    assert!(
        e.contains("this range has 18446744073709551615 elements, more than the limit of 10000"),
        "{e}"
    );
    let e = error(
        with_potential(&format!("sum(i in 0..={greatest}, x)")),
        DEFAULT_BUDGET,
    );
    assert!(
        e.contains("index arithmetic overflows: 9223372036854775807 + 1 (the end of `..=`)"),
        "{e}"
    );
}

// Nesting: sums and products are flat, nesting is limited far below the
// stack's reach.

#[test]
fn a_sum_of_twenty_thousand_terms_is_flat_and_expands() {
    let v = vec!["x"; 19_400].join(" + ");
    let text = derive(with_potential(&v), DEFAULT_BUDGET).unwrap();
    assert!(text.contains("f[x] = -19400"), "{text}");
}

#[test]
fn a_product_of_twenty_thousand_factors_is_flat_and_expands() {
    let v = vec!["x"; 20_000].join(" * ");
    let text = derive(with_potential(&v), DEFAULT_BUDGET).unwrap();
    assert!(text.contains("f[x] = -20000*x^19999"), "{text}");
}

#[test]
fn every_kind_of_nesting_past_the_limit_is_an_error() {
    let deep = [
        (
            "7000 parentheses",
            format!("{}x{}", "(".repeat(7000), ")".repeat(7000)),
        ),
        ("50000 unary minuses", format!("{}x", "-".repeat(50_000))),
        (
            "5000 nested sin",
            format!("{}x{}", "sin(".repeat(5000), ")".repeat(5000)),
        ),
        ("x^x^... 10000 deep", vec!["x"; 10_000].join("^")),
        (
            "30000 chained .sin()",
            format!("x{}", ".sin()".repeat(30_000)),
        ),
        ("4000 chained .cos()", format!("x{}", ".cos()".repeat(4000))),
        (
            "3000 nested sin",
            format!("{}x{}", "sin(".repeat(3000), ")".repeat(3000)),
        ),
        (
            "3000 nested exp(ln(..))",
            format!("{}x{}", "exp(ln(".repeat(3000), "))".repeat(3000)),
        ),
    ];
    for (what, v) in deep {
        let e = error(with_potential(&v), DEFAULT_BUDGET);
        assert!(
            e.contains(&format!("nests more than {MAX_NESTING} {TOO_DEEP}")),
            "{what}: {e}"
        );
    }
}

#[test]
fn the_deepest_nesting_allowed_expands_on_a_small_stack() {
    let n = MAX_NESTING;
    let at_limit = [
        format!("{}x{}", "(".repeat(n), ")".repeat(n)),
        format!("{}x{}", "sum(i in 0..1, ".repeat(n), ")".repeat(n)),
        format!("{}x{}", "sin(".repeat(n), ")".repeat(n)),
        format!("{}x", "-".repeat(n)),
        format!("x{}", ".cos()".repeat(n)),
    ];
    for v in at_limit {
        assert!(derive(with_potential(&v), DEFAULT_BUDGET).is_ok(), "{v}");
        let one_more = format!("({v})");
        assert!(error(with_potential(&one_more), DEFAULT_BUDGET).contains(TOO_DEEP));
    }
}

/// `let a0 = sin(x); let a1 = sin(a0); ...`: each line is shallow, the
/// expression `a{n-1}` is `n` nodes deep.
fn nested_lets(n: usize) -> String {
    let lets: String = (1..n)
        .map(|k| format!("let a{k} = sin(a{});", k - 1))
        .collect();
    format!(
        "struct M {{ coordinates: x; let a0 = sin(x); {lets} kinetic: dot(x)^2; potential: a{}; }}",
        n - 1
    )
}

#[test]
fn an_expression_as_deep_as_allowed_through_lets_derives_on_a_small_stack() {
    // 2 nodes of depth are left to the derivative's product and sign.
    let text = derive(nested_lets(MAX_DEPTH as usize - 2), DEFAULT_BUDGET).unwrap();
    // f = −V' = −cos(x)·cos(a0)·cos(a1)⋯
    assert!(text.contains("f[x] = -cos(x)*cos(e0)*cos(e1)*"), "{text}");
}

#[test]
fn five_thousand_nested_lets_stop_at_the_one_too_deep() {
    let e = error(nested_lets(5000), DEFAULT_BUDGET);
    assert!(
        e.contains(&format!(
            "this expression nests more than {MAX_DEPTH} levels deep, counting the `let`s it uses"
        )),
        "{e}"
    );
}

// The work budget sees every kind of work, so that any model expands or
// stops within seconds.

#[test]
fn nested_sums_that_build_nothing_run_out_of_budget() {
    // A tenth of the default budget, to stop in a tenth of the time: the
    // terms cost steps though they build no node.
    let budget = DEFAULT_BUDGET / 10;
    for v in [
        "sum(i in 0..1000, sum(j in 0..1000, sum(k in 0..1000, x)))",
        "sum(i in 0..10000, sum(j in 0..10000, x))",
    ] {
        let e = error(with_potential(v), budget);
        assert!(
            e.contains(&format!("{OVER_BUDGET} of {budget} steps")),
            "{v}: {e}"
        );
    }
}

#[test]
fn three_thousand_coordinates_run_out_of_budget() {
    let e = error(
        "struct M { const N = 3000; coordinates: q[N]; kinetic: sum(i in 0..N, dot(q[i])^2); potential: 0; }".into(),
        DEFAULT_BUDGET,
    );
    assert!(e.contains(OVER_BUDGET), "{e}");
}

#[test]
fn wide_sums_and_long_polynomials_expand_within_the_budget() {
    // A thousand `let`s, each a sum of 1001 terms: within the budget, but
    // `lets` alone would be 8.3 MB of code, over the default limit on the
    // generated code; within a limit raised for it, the model expands.
    let wide = "struct M { const N = 1000; coordinates: x; parameters: a[N], b[N]; \
                let y[i in 0..N] = sum(j in 0..N, a[j]) + b[i]; kinetic: dot(x)^2; potential: x*y[N-1]; }";
    let e = error(wide.into(), DEFAULT_BUDGET);
    assert!(
        e.contains("raise the limit with `#[lagrange(max_code = "),
        "{e}"
    );
    let raised = format!("#[lagrange(max_code = 20000000)] {wide}");
    assert!(derive(raised, DEFAULT_BUDGET).is_ok());
    // V = Σ x^k, k = 1..3000: f(1/2) = −Σ k/2^(k−1) = −4 (the tail past
    // k = 3000 is 2^-2990); 1e-12 is some hundred roundings of sums of 4.
    let terms: Vec<String> = (1..=3000).map(|k| format!("x^{k}")).collect();
    let f = forcing_at(with_potential(&terms.join(" + ")), 0.5);
    assert!((f + 4.0).abs() < 1e-12, "{f}");
}

#[test]
fn the_hundred_link_chain_stops_with_the_budget_error() {
    // Derived whole (`articulated = false`): `M` and `f` are beyond the
    // budget. As written, the recursion solves it without them
    // (`articulated::large_trees_expand_at_the_default_budget_without_m_and_f`).
    let dense = format!("#[lagrange(articulated = false)] {}", indexed_chain(100));
    let e = error(dense, DEFAULT_BUDGET);
    assert!(
        e.contains(&format!("{OVER_BUDGET} of {DEFAULT_BUDGET} steps")),
        "{e}"
    );
    assert!(
        e.contains("raise the budget with `#[lagrange(budget = "),
        "{e}"
    );
}

#[test]
fn the_smallest_budget_is_an_error_not_a_panic() {
    let one = indexed_chain(2).replacen("pub struct", "#[lagrange(budget = 1)] pub struct", 1);
    assert!(error(one, DEFAULT_BUDGET).contains(&format!("{OVER_BUDGET} of 1 steps")));
}

#[test]
fn the_budget_attribute_raises_the_budget_of_one_model() {
    let small = 200_000;
    assert!(error(indexed_chain(8), small).contains(&format!("{OVER_BUDGET} of {small} steps")));
    let raised =
        indexed_chain(8).replacen("pub struct", "#[lagrange(budget = 5000000)] pub struct", 1);
    assert!(derive(raised, small).is_ok());
}

/// Found by the long fuzz run: roots nested 30–45 deep (`sqrt(sqrt(..))` in
/// a force, a length or an energy) once took 2^depth steps to write as
/// `EQUATIONS` text (each level wrote its base twice), over 10 s from depth
/// 27. Writing them is linear now; at depth 100 (within the nesting limit)
/// the 2^100 of before would never end.
#[test]
fn deeply_nested_roots_are_written_as_text_in_linear_time() {
    let depth = 100;
    let force = format!("{}atan(dot(y)){}", "sqrt(".repeat(depth), ")".repeat(depth));
    let model = format!(
        "struct M {{ coordinates: y; kinetic: dot(y)^2; potential: 0; forces: y = {force}; }}"
    );
    let text = derive(model, DEFAULT_BUDGET).expect("the model derives");
    assert_eq!(text.matches("sqrt(").count(), depth, "{text}");
}

/// A sum over the longest range allowed (10 000 terms, in a `let` that the
/// equations do not use, so that it stays within the budget) expands into
/// code of bounded nesting: written as one chain `a + b + …`, rustc parsed
/// it into a tree 10 000 deep and overflowed its stack (an internal
/// compiler error; found by the fuzzer on a mutation of
/// `tests/models/vectors.rs`), and so did syn on rustc's 8 MiB. The sum is
/// now written in pieces of 128 terms, each added to the partial sum of
/// the previous ones (the same additions in the same order). Checked by
/// parsing the expansion as Rust on a quarter of rustc's stack.
#[test]
fn a_sum_over_the_longest_range_expands_to_code_rustc_can_parse() {
    let source = "pub struct LongSum {
        coordinates: x;
        parameters: c;
        let s = sum(i in 0..10000, (i + 1)*sin(i*c + x));
        kinetic: dot(x)^2/2;
        potential: x^2/2;
    }";
    let text = std::thread::Builder::new()
        .stack_size(STACK)
        .spawn(move || {
            let tokens: proc_macro2::TokenStream = source.parse().expect("the model lexes");
            lagrange_engine::expand(tokens).to_string()
        })
        .expect("a thread")
        .join()
        .expect("no panic");
    assert!(!text.contains("compile_error"), "the model expands");
    // Read back as Rust items by syn, standing in for rustc (which parses
    // it with its own parser): syn's expression parser recurses along the
    // long sum (beyond 2 MiB with syn at opt-level 0), so on a thread of
    // rustc's size.
    let parsed = std::thread::Builder::new()
        .stack_size(8 << 20)
        .spawn(move || syn::parse_str::<syn::File>(&text).is_ok())
        .expect("a thread")
        .join()
        .expect("no panic");
    assert!(parsed, "the expansion is Rust items");
}
