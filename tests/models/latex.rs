//! `LATEX`, the derived equations typeset, shown in `docs/equations.md`
//! for the two textbook models; this keeps the page true.
//! `UPDATE_DOCS=1 cargo test --test suite -- models::latex::` rewrites it.

use lagrange::models::{DoublePendulum, TwoMassChain};

/// The page as it must read.
fn page() -> String {
    format!(
        "# The derived equations, typeset\n\n\
         Every model has `LATEX` beside `EQUATIONS`: the same entries (shared \
         subexpressions `e_k` first, then `M`, `f`, and where the model has \
         them `φ`, `G`, `γ` or `∂f/∂u`; for a model solved by the recursion \
         over a tree of links without `M` and `f`, its tree and parts) as one \
         LaTeX `aligned` block. Below, \
         the two textbook models of `lagrange::models`, written by \
         `tests/models/latex.rs` from the constants themselves.\n\n\
         ## `DoublePendulum` (`src/models/double_pendulum.rs`)\n\n$$\n{}$$\n\n\
         ## `TwoMassChain` (`src/models/two_mass_chain.rs`)\n\n$$\n{}$$\n",
        DoublePendulum::<f64>::LATEX,
        TwoMassChain::<f64>::LATEX
    )
}

#[test]
fn the_typeset_equations_page_is_current() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/equations.md");
    let want = page();
    if std::env::var_os("UPDATE_DOCS").is_some() {
        std::fs::write(path, &want).unwrap();
    }
    let have = std::fs::read_to_string(path).unwrap_or_default();
    assert!(
        have == want,
        "docs/equations.md is stale: run UPDATE_DOCS=1 cargo test --test suite -- models::latex::"
    );
    // The blocks are LaTeX, not the text form.
    assert!(want.contains("\\begin{aligned}") && want.contains("\\dot{"));
}
