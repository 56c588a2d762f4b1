//! Every mistake `lagrangian!` catches at compile time gives exactly one
//! error, on the user's tokens, saying the problem in physics terms.

#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*.rs");
}
