//! The checks of `contacts:`: each gap a function of `t` and `q` that
//! names some coordinate; each slip velocity linear in the velocities and
//! naming one; each coefficient (and a given normal force) a constant of
//! the parameters; friction only along a slip velocity, and a slip
//! velocity only with friction; friction for a given normal force.
//! `constraints:` may stand beside them: a contact run holds the model's
//! own constraints with the touching contacts.

use crate::ast::{Expr, SpanRange};
use crate::expr::{ExprId, Pool};
use crate::model::Model;

/// The tokens of contact `k`'s inequality where `bad` holds, narrowed to
/// the smallest piece at fault; the whole inequality if neither side
/// alone is.
fn locate_gap(model: &mut Model, k: usize, bad: &dyn Fn(&mut Pool, ExprId) -> bool) -> SpanRange {
    let c = &model.contacts[k];
    let def = &model.contact_defs[c.entry];
    let sides = [(def.lhs.clone(), c.sides.0), (def.rhs.clone(), c.sides.1)];
    let whole = def.range();
    for (side, id) in sides {
        if bad(&mut model.pool, id) {
            return model.locate(&side, bad);
        }
    }
    whole
}

/// The key's span, the expression written and its lowered value for `key`
/// in contact `k`'s law, if written.
fn law_entry(model: &Model, k: usize, key: &str) -> Option<(proc_macro2::Span, Expr, ExprId)> {
    let c = &model.contacts[k];
    let def = &model.contact_defs[c.entry];
    def.fields
        .iter()
        .zip(&c.fields)
        .find(|((name, _), _)| name == key)
        .map(|((name, e), &id)| (name.span(), e.clone(), id))
}

/// Every contact admissible (see the module's docs).
pub fn contacts_are_admissible(model: &mut Model) -> syn::Result<()> {
    if model.contacts.is_empty() {
        return Ok(());
    }
    let velocities = model.symbols.velocities.clone();
    let coordinates = model.symbols.coordinates.clone();
    let time = model.symbols.time;
    for k in 0..model.contacts.len() {
        let (label, gap, slip, second_slip) = {
            let c = &model.contacts[k];
            (c.label.clone(), c.gap, c.slip, c.second_slip)
        };
        // Finite constants, as in every section.
        if model.pool.has_non_finite(gap) {
            let range = locate_gap(model, k, &|pool: &mut Pool, id| pool.has_non_finite(id));
            return Err(range.error(
                "this evaluates to an infinite or undefined constant (a division by zero, or a function outside its domain)",
            ));
        }
        let fields = model.contacts[k].fields.clone();
        if let Some(i) = fields.iter().position(|&id| model.pool.has_non_finite(id)) {
            let e = model.contact_defs[model.contacts[k].entry].fields[i]
                .1
                .clone();
            let range = model.locate(&e, &|pool: &mut Pool, id| pool.has_non_finite(id));
            return Err(range.error(
                "this evaluates to an infinite or undefined constant (a division by zero, or a function outside its domain)",
            ));
        }
        // The gap: positions only.
        if velocities.iter().any(|&v| model.pool.depends_on(gap, v)) {
            let range = locate_gap(model, k, &|pool: &mut Pool, id| {
                velocities.iter().any(|&v| pool.depends_on(id, v))
            });
            return Err(range.error(format!(
                "contact `{label}`'s gap depends on a velocity: a gap is a function of the positions (and \
                 time) that stays non-negative; the velocity friction acts against goes in its law, \
                 `{{ slip: dot(x) }}`"
            )));
        }
        let has_gap = model.contact_defs[model.contacts[k].entry].has_gap;
        if has_gap && !coordinates.iter().any(|&q| model.pool.depends_on(gap, q)) {
            let def = &model.contact_defs[model.contacts[k].entry];
            return Err(def.range().error(format!(
                "contact `{label}`'s gap names no coordinate: it can never open or close (a gap is a \
                 function of the positions, as in `floor: y >= 0`)"
            )));
        }
        // The law's coefficients: constants of the parameters.
        for key in [
            "restitution",
            "friction",
            "static_friction",
            "kinetic_friction",
            "normal",
        ] {
            let Some((_, e, id)) = law_entry(model, k, key) else {
                continue;
            };
            let varies = |pool: &mut Pool, id: ExprId| {
                coordinates
                    .iter()
                    .chain(&velocities)
                    .chain(std::iter::once(&time))
                    .any(|&s| pool.depends_on(id, s))
            };
            if varies(&mut model.pool, id) {
                let range = model.locate(&e, &varies);
                return Err(range.error(format!(
                    "contact `{label}`'s `{key}` depends on the state: it is a constant of the contact, \
                     written with parameters and numbers{}",
                    if key == "normal" {
                        " (a normal force that varies with the state is a contact's reaction: write \
                         the gap it keeps instead)"
                    } else {
                        ""
                    }
                )));
            }
        }
        let friction = ["friction", "static_friction", "kinetic_friction"]
            .iter()
            .find_map(|key| law_entry(model, k, key));
        match (slip, friction) {
            (None, Some((span, _, _))) => {
                return Err(syn::Error::new(
                    span,
                    format!(
                        "contact `{label}` has friction but no slip velocity to act against: add \
                         `slip: ...`, the velocity of the contact point along the surface (as in \
                         `{{ friction: mu, slip: dot(x) }}`)"
                    ),
                ));
            }
            (None, None) if !has_gap => {
                let def = &model.contact_defs[model.contacts[k].entry];
                return Err(def.range().error(format!(
                    "contact `{label}` has a given normal force but no friction: it would do nothing; \
                     add `friction: mu` and the `slip:` velocity it acts against"
                )));
            }
            (Some(_), None) => {
                let (span, _, _) = law_entry(model, k, "slip").expect("written");
                return Err(syn::Error::new(
                    span,
                    format!(
                        "contact `{label}` has a slip velocity but no friction: add `friction: mu` (or \
                         leave the slip velocity out of a frictionless contact)"
                    ),
                ));
            }
            _ => {}
        }
        // Friction against a given load along one direction only: a brake
        // or a bearing slips along its joint.
        if second_slip.is_some() && !has_gap {
            let (_, e, _) = law_entry(model, k, "slip").expect("written");
            return Err(e.range().error(format!(
                "contact `{label}` has a given normal force and a slip vector: friction against a \
                 given load acts along one slip velocity (a joint's), write `slip:` as a number"
            )));
        }
        // A slip vector's second component: finite constants.
        if let Some(second) = second_slip {
            if model.pool.has_non_finite(second) {
                let (_, e, _) = law_entry(model, k, "slip").expect("written");
                let range = model.locate(&e, &|pool: &mut Pool, id| pool.has_non_finite(id));
                return Err(range.error(
                    "this evaluates to an infinite or undefined constant (a division by zero, or a function outside its domain)",
                ));
            }
        }
        // The slip velocity (each component of a slip vector): linear in
        // the velocities, and naming one.
        for slip in [slip, second_slip].into_iter().flatten() {
            let (_, e, _) = law_entry(model, k, "slip").expect("written");
            let names_velocity = velocities.iter().any(|&v| model.pool.depends_on(slip, v));
            let linear = velocities.iter().all(|&v| {
                let d = model.pool.diff(slip, v);
                !velocities.iter().any(|&w| model.pool.depends_on(d, w))
            });
            if !names_velocity || !linear {
                let range = if names_velocity {
                    let vs = velocities.clone();
                    model.locate(&e, &move |pool: &mut Pool, id| {
                        vs.iter().any(|&v| {
                            let d = pool.diff(id, v);
                            vs.iter().any(|&w| pool.depends_on(d, w))
                        })
                    })
                } else {
                    e.range()
                };
                return Err(range.error(format!(
                    "contact `{label}`'s slip velocity must be linear in the velocities and name one, \
                     `T(t, q) q̇ + b(t, q)`, as in `slip: dot(x) + r*dot(phi)`"
                )));
            }
        }
    }
    Ok(())
}
