//! Local names in generated code.

use crate::expr::SymId;
use crate::model::{Model, Scalar, SymKind};
use proc_macro2::{Ident, Span};
use quote::format_ident;
use std::collections::HashSet;

/// Local names: the user's names for coordinates and parameters, `<q>_dot`
/// for velocities, fresh `e<k>`/`k<k>` for intermediates and constants, none
/// of which can collide with a user name or the function's arguments.
#[derive(Clone)]
pub(super) struct Namer {
    taken: HashSet<String>,
    pub(super) symbol: Vec<Ident>,
}

impl Namer {
    pub(super) fn new(model: &Model) -> Self {
        let mut taken: HashSet<String> = ["t", "q", "qdot", "qddot", "S", "self", "Self"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        // The user's scalar names are kept as they are; elements of indexed
        // names become `theta_0`, `theta_1`, ... (renamed if that is taken).
        for n in model.coordinates.iter().chain(&model.parameters) {
            taken.insert(n.name.to_string());
        }
        let mut namer = Namer {
            taken,
            symbol: Vec::new(),
        };
        let s = &model.symbols;
        let mut symbol = Vec::with_capacity(s.count());
        let local = |namer: &mut Namer, x: &Scalar| match x.index {
            None => x.name.clone(),
            Some(k) => namer.fresh(&format!("{}_{k}", x.name), false),
        };
        let coordinates: Vec<Ident> = model
            .coordinates
            .iter()
            .map(|c| local(&mut namer, c))
            .collect();
        let parameters: Vec<Ident> = model
            .parameters
            .iter()
            .map(|p| local(&mut namer, p))
            .collect();
        for k in 0..s.count() {
            symbol.push(match s.kind(SymId(k as u32)) {
                SymKind::Time => format_ident!("t"),
                SymKind::Coordinate(i) => coordinates[i].clone(),
                SymKind::Parameter(p) => parameters[p].clone(),
                SymKind::Acceleration(i) => namer.fresh(&format!("{}_ddot", coordinates[i]), false),
                SymKind::Velocity(i) => namer.fresh(&format!("{}_dot", coordinates[i]), false),
            });
        }
        namer.symbol = symbol;
        namer
    }

    /// `base` if free (and `numbered` is false), else `base<k>` or `base_`.
    pub(super) fn fresh(&mut self, base: &str, numbered: bool) -> Ident {
        let mut k = 0usize;
        let mut name = if numbered {
            format!("{base}{k}")
        } else {
            base.to_string()
        };
        while self.taken.contains(&name) {
            k += 1;
            name = if numbered {
                format!("{base}{k}")
            } else {
                format!("{base}{}", "_".repeat(k))
            };
        }
        self.taken.insert(name.clone());
        Ident::new(&name, Span::call_site())
    }
}
