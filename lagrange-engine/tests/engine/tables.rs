//! The tables the generated API is written from: every method and const
//! documented, every method named once.

use lagrange_engine::emit::api::{CONSTS, Doc, METHODS};

#[test]
fn every_doc_line_makes_a_doc_attribute() {
    for m in METHODS {
        assert!(!Doc::Lines(m.doc).attributes().is_empty(), "{}", m.name);
    }
    for c in CONSTS {
        assert!(!c.doc.attributes().is_empty(), "{}", c.name);
    }
    assert_eq!(
        Doc::Lines(&[r#"say "hi""#]).attributes().to_string(),
        r####"# [doc = r#" say "hi""#]"####
    );
}

#[test]
fn methods_are_named_once() {
    for (k, m) in METHODS.iter().enumerate() {
        assert!(METHODS[..k].iter().all(|o| o.name != m.name), "{}", m.name);
    }
}
