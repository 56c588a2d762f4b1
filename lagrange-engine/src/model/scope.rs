//! Names: what each name of the model is bound to while lowering, and the
//! rule that every name is declared once.

use crate::expr::{ExprId, SymId};
use std::collections::HashMap;
use syn::Ident;

/// What a name stands for.
#[derive(Clone, Copy, Debug)]
pub(super) enum Binding {
    Symbol(SymId),
    Let(ExprId),
    /// A `const` (a compile-time integer).
    Const(i64),
    /// An indexed name; its elements are bound as `name[k]`, `k` in `lo..hi`.
    Array {
        lo: i64,
        hi: i64,
        role: Role,
    },
}

/// What an indexed name is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Role {
    Coordinate,
    Parameter,
    Input,
    Let,
    /// A `let` of a vector (`let r = vector(..)`): its elements are the
    /// components.
    Vector,
}

/// The names declared so far, each with what it was declared as.
#[derive(Default)]
pub(super) struct Declared(HashMap<String, &'static str>);

impl Declared {
    /// Declares `name` as a `what` (`"coordinate"`, ...): an error if it is
    /// `t` or was declared before.
    pub(super) fn declare(&mut self, name: &Ident, what: &'static str) -> syn::Result<()> {
        if name == "t" {
            return Err(syn::Error::new(
                name.span(),
                format!("`t` is time and is reserved: choose another name for this {what}"),
            ));
        }
        if let Some(first) = self.0.get(&name.to_string()) {
            let a = |role: &str| if role == "input" { "an" } else { "a" };
            let roles = if *first == what {
                format!(" as {} {what}", a(what))
            } else {
                format!(", as {} {first} and as {} {what}", a(first), a(what))
            };
            // A constraint's name is a label, not a quantity, but it is
            // still one of the model's names: in `EQUATIONS`, in
            // `CONSTRAINTS` and in the errors.
            let rule = if *first == "input" || what == "input" {
                "each input needs its own name, distinct from the coordinates, parameters, constants, constraints and `let`s"
            } else if *first == "constraint" || what == "constraint" {
                "each constraint needs its own name, distinct from the coordinates, parameters, constants and `let`s"
            } else {
                "each coordinate, parameter, constant and `let` needs its own name"
            };
            return Err(syn::Error::new(
                name.span(),
                format!("`{name}` is declared twice{roles}: {rule}"),
            ));
        }
        self.0.insert(name.to_string(), what);
        Ok(())
    }
}
