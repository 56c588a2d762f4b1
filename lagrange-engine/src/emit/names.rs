//! Local names in generated code.

use crate::expr::SymId;
use crate::model::{Model, Scalar, SymKind};
use proc_macro2::{Ident, Span};
use quote::format_ident;
use std::collections::{HashMap, HashSet};
use std::rc::Rc;

/// Local names: the user's names for coordinates, parameters and inputs, `<q>_dot`
/// for velocities, fresh `e<k>`/`k<k>` for intermediates and constants, none
/// of which can collide with a user name or the function's arguments.
///
/// Each function's emitter clones the namer; the model's names are shared
/// between the clones, not copied, since a model may have many.
#[derive(Clone)]
pub(super) struct Namer {
    /// The names of the model (its symbols, `t`, `q`...), fixed once built.
    model_names: Rc<HashSet<String>>,
    /// The names given since (one function's `e<k>` and `k<k>`).
    taken: HashSet<String>,
    /// For each numbered base, the number every smaller one is taken below,
    /// so that a function with many `let`s names each in constant time.
    next: HashMap<String, usize>,
    pub(super) symbol: Rc<Vec<Ident>>,
}

impl Namer {
    pub(super) fn new(model: &Model) -> Self {
        let mut taken: HashSet<String> = ["t", "q", "qdot", "qddot", "S", "self", "Self"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        // The user's scalar names are kept as they are; elements of indexed
        // names become `theta_0`, `theta_1`, ... (renamed if that is taken).
        for n in model
            .coordinates
            .iter()
            .chain(&model.parameters)
            .chain(&model.inputs)
        {
            taken.insert(n.name.to_string());
        }
        let mut namer = Namer {
            model_names: Rc::default(),
            taken,
            next: HashMap::new(),
            symbol: Rc::default(),
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
        let inputs: Vec<Ident> = model.inputs.iter().map(|u| local(&mut namer, u)).collect();
        for k in 0..s.count() {
            symbol.push(match s.kind(SymId(k as u32)) {
                SymKind::Time => format_ident!("t"),
                SymKind::Coordinate(i) => coordinates[i].clone(),
                SymKind::Parameter(p) => parameters[p].clone(),
                SymKind::Acceleration(i) => namer.fresh(&format!("{}_ddot", coordinates[i]), false),
                SymKind::Velocity(i) => namer.fresh(&format!("{}_dot", coordinates[i]), false),
                SymKind::Input(k) => inputs[k].clone(),
            });
        }
        namer.symbol = Rc::new(symbol);
        namer.model_names = Rc::new(std::mem::take(&mut namer.taken));
        namer
    }

    fn is_taken(&self, name: &str) -> bool {
        self.model_names.contains(name) || self.taken.contains(name)
    }

    /// `base` if free (and `numbered` is false), else `base<k>` or `base_`.
    pub(super) fn fresh(&mut self, base: &str, numbered: bool) -> Ident {
        // Names are only ever added, so the first free number is at or
        // after the last one given.
        let mut k = if numbered {
            self.next.get(base).copied().unwrap_or(0)
        } else {
            0
        };
        let mut name = if numbered {
            format!("{base}{k}")
        } else {
            base.to_string()
        };
        while self.is_taken(&name) {
            k += 1;
            name = if numbered {
                format!("{base}{k}")
            } else {
                format!("{base}{}", "_".repeat(k))
            };
        }
        if numbered {
            self.next.insert(base.to_string(), k + 1);
        }
        self.taken.insert(name.clone());
        Ident::new(&name, Span::call_site())
    }
}
