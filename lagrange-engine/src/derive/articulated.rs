//! The masses of `T` hanging on a tree of increments, found where they do:
//! what lets the runtime solve `M q̈ = f` in `O(N)` without forming `M`
//! (`lagrange_runtime::linalg::articulated`, the articulated-body
//! recursion), instead of factoring the dense `M` in `O(N³)`.
//!
//! The form (each step proved on the expressions, else the model keeps the
//! dense solve alone):
//!
//! 1. `T = Σ_k c_k L_k²`, each `c_k` free of `t`, `q` and `q̇` (a mass), each
//!    `L_k` linear in `q̇` (a velocity component of a position: `dot(x)`);
//! 2. each `L_k = Σ_j g_kj(q) φ̇_j`, `φ_j = w_j · q` with constant `w_j`
//!    (a joint's angle: an absolute angle, or a sum of relative ones), and
//!    `g_kj` a function of `φ_j` alone (`∂g/∂q_i = w_i ∂g/∂φ`);
//! 3. `N` joints, each angle another joint's plus one coordinate times a
//!    number, every coordinate once (so `φ = A q` with `A⁻¹` and `A⁻ᵀ`
//!    applied in `O(N)`);
//! 4. a component with one joint and a constant `g` is that joint's own
//!    inertia (`½ J φ̇²`: a rigid link's rotation in the plane); the others
//!    fall into axes (components that share a joint with the same `g`:
//!    `x`, `y`, at most three), each joint one `g` per axis, its axis `u`;
//! 5. the joints a tree: the components grouped into points (two
//!    components one point where each holds the other's joints that move
//!    along its axis: `ẋ_i` and `ẏ_i` of one link's end), each point's
//!    joints exactly the path from the root to its deepest one, where its
//!    components' masses `2 c_k` sit on their axes; a joint that does not
//!    move along an axis (a cart along `x` under a chain) is in none of
//!    that axis's components, its axis there zero.
//!
//! Then `T = ½ Σ_n Σ_a m_na (Σ_{j on n's path} u_ja φ̇_j)² + ½ Σ_j J_j φ̇_j²`
//! exactly, which is the form the recursion solves. The generalized forces
//! other than `T`'s, `−∂V/∂q + Q − ∂R/∂q̇`, go to the runtime as they are.
//!
//! Looked for from [`FROM_COORDINATES`] coordinates on (at any size under
//! `#[lagrange(articulated)]`, never under `articulated = false`), after
//! every other stage and the emission's charge: the nodes it makes come
//! after all the others, so a model's other functions are written as
//! before, and a model it is not looked for in expands exactly as before.
//! Unasked, a search (with its function's emission) that does not fit in
//! what is left of the budget is forgotten (`Pool::rewind`): a model that
//! expanded before still does, with the dense solve.
//!
//! Except first ([`first`]), where the model, found to have the form,
//! would have its `M` and `f` [`formed`] from the parts at run time (from
//! [`FORMED_FROM`] coordinates, or asked for) and nothing asked is derived
//! from them (the residual's Jacobians, the parameter derivatives, the
//! regressor: [`looks_first`]): then the search runs on `T`, `V` and the
//! other forces before `M` and `f` would be derived, and where the form
//! holds they never are, which is what lets a 30-link comb expand within
//! the default budget (4.7 million steps, where deriving `M` and `f` took
//! 60 million). The parts are the same functions as found last (the
//! search reads `T`, `V` and the forces only), and compute the same bits
//! (the 2 × 5 tree's runs by every method are among the fingerprints,
//! `tests/trajectories/fingerprints.rs`). The mass matrix's checks are
//! then the form's: each coordinate is a joint with terms in `T`,
//! quadratic in the velocities by the form; a joint whose articulated
//! inertia is not positive at run time (a massless tip) is declined by the
//! recursion, and the dense solve of the formed `M` reports it as before. Where the form does not hold, unasked, the
//! model is lowered again from its definition and derived as before the
//! search came first, to the same bytes.

use super::Equations;
use crate::expr::{ExprId, Node, Pool};
use crate::model::Model;
use std::collections::BTreeMap;

/// The fewest coordinates from which the engine looks for the form: below,
/// the dense `M` factored is as fast (measured by `benches/articulated.rs`
/// in `lagrange-studies`), and a small model's code stays as it was.
pub const FROM_COORDINATES: usize = 10;

/// The fewest coordinates from which a model with the form has its `M` and
/// `f` formed at run time from its parts (`lagrange::linalg::articulated`)
/// rather than generated entry by entry, unless `#[lagrange(articulated)]`
/// asks for the form, which forms them at any size. Below, the generated
/// ones are faster and build as fast: on the chain, `M + f` took 190 ns
/// generated against 299 ns formed at 10 links, 663 against 783 at 16,
/// 961 against 926 at 18 and 1,329 against 1,198 at 20, and from 18 links
/// the crate with the formed ones builds faster (`cargo run --release -p
/// lagrange-studies --example scaling -- --only 10,12,14,16,18,20 --no-ad
/// --no-write`, then with `--articulated`).
pub const FORMED_FROM: usize = 18;

/// Whether `model`, which has the form, has its `M` and `f` formed from its
/// parts ([`FORMED_FROM`]).
pub fn formed(model: &Model) -> bool {
    model.options.articulated == Some(true) || model.dof() >= FORMED_FROM
}

/// The most axes a tree of increments has here (a position in space).
const MAX_AXES: usize = 3;

/// What the runtime's recursion needs: the tree, and the roots of the
/// generated `articulated_parts`.
#[derive(Debug)]
pub struct Articulated {
    /// Each joint's parent (its increment starts at the parent's end), in
    /// the joints' order; `None` for a root.
    pub parent: Vec<Option<usize>>,
    /// The joint whose angle each joint's adds to; `None` for an angle
    /// that is a coordinate times a number.
    pub base: Vec<Option<usize>>,
    /// The coordinate each joint's angle adds.
    pub coordinate: Vec<usize>,
    /// Its factor.
    pub scale: Vec<f64>,
    /// The number of axes, `D`.
    pub axes: usize,
    /// Joint by joint: the `N·D` axes `u`, the `N·D` bends `∂u/∂φ`, the
    /// `N·D` masses, the `N` inertias `J`; then the `N` generalized forces
    /// other than `T`'s.
    pub roots: Vec<ExprId>,
}

/// A velocity component: `c L²` with `L = Σ g φ̇`, by joint.
struct Component {
    mass: ExprId,
    /// `(joint, g)`, one per joint, by joint.
    terms: Vec<(usize, ExprId)>,
}

/// A joint's angle `w · q`: `(coordinate, factor bits)`, by coordinate.
type Angle = Vec<(usize, u64)>;

/// Sets `eq.articulated` where the model has the form: looked for from
/// [`FROM_COORDINATES`] coordinates on, at any size under
/// `#[lagrange(articulated)]` (an error, on `kinetic:`, where the form does
/// not hold), never under `#[lagrange(articulated = false)]`.
pub fn articulated(model: &mut Model, eq: &mut Equations) -> syn::Result<()> {
    let wanted = model.options.articulated;
    let own_path = own_path(model);
    let looked = match wanted {
        Some(false) => false,
        Some(true) => own_path.is_none(),
        None => own_path.is_none() && model.dof() >= FROM_COORDINATES,
    };
    if looked && eq.forcing.len() == model.dof() {
        let mark = model.pool.mark();
        eq.articulated = find(model, eq);
        if let Some(found) = &eq.articulated {
            // The emission of `articulated_parts`, charged here: the other
            // functions' was charged before the search.
            let cost = crate::emit::emission_cost(model, &found.roots);
            model.pool.charge(cost);
        }
        // Unasked, a search that does not fit in what is left of the budget
        // is forgotten: a model that expanded before the search existed
        // still expands, with the dense solve.
        if wanted.is_none() && model.pool.exhausted() {
            model.pool.rewind(mark);
            eq.articulated = None;
        }
    }
    if wanted != Some(true) || eq.articulated.is_some() || model.pool.exhausted() {
        return Ok(());
    }
    Err(refusal(model, own_path))
}

/// What solves a model with `constraints:`, `contacts:` or `inputs:`
/// instead of the recursion, named; `None` for a model in minimal
/// coordinates without contacts or inputs.
fn own_path(model: &Model) -> Option<&'static str> {
    if !model.constraints.is_empty() {
        Some("constraints")
    } else if !model.contacts.is_empty() {
        Some("contacts")
    } else if !model.inputs.is_empty() {
        Some("control inputs")
    } else {
        None
    }
}

/// Whether the options let a model be solved by the recursion without
/// its `M` and `f` derived ([`first`]): not refused (`articulated =
/// false`), and nothing asked that is derived from `M` and `f` (the
/// residual's Jacobians, the parameter derivatives, the regressor).
/// Read before lowering, to keep the definition for a second lowering.
pub fn may_look_first(options: &crate::ast::Options) -> bool {
    options.articulated != Some(false)
        && !options.jacobians
        && !options.parameter_derivatives
        && options.regressor.is_none()
}

/// Whether the tree is looked for before `M` and `f` are derived: where
/// the options allow it ([`may_look_first`]) and the model, found to have
/// the form, would have its `M` and `f` [`formed`] from the parts (asked
/// for, or from [`FORMED_FROM`] coordinates), in minimal coordinates
/// without contacts or inputs.
pub fn looks_first(model: &Model) -> bool {
    may_look_first(&model.options) && own_path(model).is_none() && formed(model)
}

/// The tree looked for first, in a model that [`looks_first`], on the
/// equations of [`without_mass_matrix`](super::without_mass_matrix): `Ok(true)`
/// with `eq.articulated` set where `T` has the form, so that `M` and `f`
/// need never be derived; `Ok(false)` where it has not, unasked (the
/// caller then derives the model as before, from a fresh lowering);
/// under `#[lagrange(articulated)]`, the error that says what the form is.
pub fn first(model: &mut Model, eq: &mut Equations) -> syn::Result<bool> {
    eq.articulated = find(model, eq);
    if eq.articulated.is_some() || model.pool.exhausted() {
        return Ok(eq.articulated.is_some());
    }
    if model.options.articulated == Some(true) {
        return Err(refusal(model, None));
    }
    Ok(false)
}

/// The error of `#[lagrange(articulated)]` on a model the recursion does
/// not solve, on `kinetic:`.
fn refusal(model: &Model, own_path: Option<&str>) -> syn::Error {
    let range = model.kinetic.keyword_and_value();
    range.error(match own_path {
        Some(what) => format!(
            "`#[lagrange(articulated)]`: a model with {what} is solved by its own path (the saddle-point system, \
             the contact phases, the controller's forcing), not by the recursion over a tree of links: \
             remove the attribute"
        ),
        None => "`#[lagrange(articulated)]`: this kinetic energy is not masses hanging on a tree of links, \
                 so `M q̈ = f` cannot be solved by the recursion: it needs `T` as a sum of masses (free of `t`, \
                 `q` and `q̇`) times squared velocity components, each position a sum of increments along \
                 links, each link's increment a function of one angle (a coordinate, or a coordinate plus \
                 another link's angle), one link per coordinate, and the links nested as a tree; remove the \
                 attribute for the dense solve"
            .to_string(),
    })
}

/// The form, if `T` has it (garbage, quickly, once the pool is exhausted).
fn find(model: &mut Model, eq: &Equations) -> Option<Articulated> {
    let n = model.dof();
    let s = model.symbols.clone();
    let pool = &mut model.pool;
    let velocities = Pool::symbol_set(&s.velocities);
    let mut moving: Vec<_> = s.coordinates.clone();
    moving.extend(&s.velocities);
    moving.push(s.time);
    let moving = Pool::symbol_set(&moving);
    let mut positional: Vec<_> = s.velocities.clone();
    positional.push(s.time);
    let positional = Pool::symbol_set(&positional);
    let kinds = Kinds {
        velocities: &velocities,
        moving: &moving,
        positional: &positional,
        velocity_of: |id| s.velocities.iter().position(|v| *v == id),
    };

    // 1. and 2.: T as squares of velocity components, each by joint.
    let mut squares = Vec::new();
    kinds.squares(pool, model.kinetic.value, Vec::new(), &mut squares)?;
    let mut angles: BTreeMap<Angle, usize> = BTreeMap::new();
    let mut joint_angles: Vec<Angle> = Vec::new();
    let mut components = Vec::with_capacity(squares.len());
    for (factors, bases) in squares {
        let velocity = pool.mul(&bases);
        let mut linear = Vec::new();
        kinds.linear(pool, velocity, Vec::new(), &mut linear)?;
        // Regrouped by the terms of the coefficients: `Σ_m g_m q̇_m`, each
        // `g_m` a sum over the joints before (relative angles), becomes
        // `Σ_j g_j φ̇_j`.
        let mut rates: BTreeMap<ExprId, Vec<f64>> = BTreeMap::new();
        for (factors, rate) in linear {
            let g = pool.mul(&factors);
            let mut atoms = Vec::new();
            terms_of(pool, g, ATOM_DEPTH, &mut atoms);
            for atom in atoms {
                let (c, atom) = pool.split_coeff(atom);
                let w = rates.entry(atom).or_insert_with(|| vec![0.0; n]);
                for &(i, wi) in &rate {
                    w[i] += c * f64::from_bits(wi);
                }
            }
        }
        let mut by_joint: BTreeMap<usize, Vec<ExprId>> = BTreeMap::new();
        for (atom, w) in rates {
            // The angle's first factor made 1: `g φ̇` the same however the
            // sign of a component was written.
            let Some(first) = w.iter().copied().find(|&x| x != 0.0) else {
                continue;
            };
            let angle: Angle = (0..n)
                .filter(|&i| w[i] != 0.0)
                .map(|i| (i, (w[i] / first).to_bits()))
                .collect();
            let next = joint_angles.len();
            let joint = *angles.entry(angle.clone()).or_insert(next);
            if joint == next {
                joint_angles.push(angle);
            }
            let c = pool.num(first);
            let g = pool.mul2(c, atom);
            by_joint.entry(joint).or_default().push(g);
        }
        let terms = by_joint
            .into_iter()
            .map(|(joint, gs)| (joint, pool.add(&gs)))
            .collect();
        let mass = pool.mul(&factors);
        components.push(Component { mass, terms });
        if pool.exhausted() {
            return None;
        }
    }
    if joint_angles.len() != n {
        return None;
    }

    // Each g a function of its joint's angle alone, and its derivative by
    // that angle (the bend).
    let mut bend_of: BTreeMap<ExprId, ExprId> = BTreeMap::new();
    for c in &components {
        for &(joint, g) in &c.terms {
            if bend_of.contains_key(&g) {
                continue;
            }
            let bend = along_angle(pool, &s.coordinates, g, &joint_angles[joint])?;
            bend_of.insert(g, bend);
        }
    }

    // 4.: the joints' own inertias, and the axes.
    let two = pool.num(2.0);
    let mut inertia: Vec<Vec<ExprId>> = vec![Vec::new(); n];
    let mut spread = Vec::new();
    for (k, c) in components.iter().enumerate() {
        match c.terms[..] {
            [(joint, g)] if !pool.depends_on_any(g, &moving) => {
                let j = pool.mul(&[two, c.mass, g, g]);
                inertia[joint].push(j);
            }
            [] => return None,
            _ => spread.push(k),
        }
    }
    let mut axis_root: Vec<usize> = (0..components.len()).collect();
    let mut first_with: BTreeMap<(usize, ExprId), usize> = BTreeMap::new();
    for &k in &spread {
        for &term in &components[k].terms {
            let other = *first_with.entry(term).or_insert(k);
            let (a, b) = (root(&mut axis_root, k), root(&mut axis_root, other));
            axis_root[a.max(b)] = a.min(b);
        }
    }
    let mut axis_ids: BTreeMap<usize, usize> = BTreeMap::new();
    let mut axis_of = vec![0; components.len()];
    for &k in &spread {
        let r = root(&mut axis_root, k);
        let next = axis_ids.len();
        axis_of[k] = *axis_ids.entry(r).or_insert(next);
    }
    let axes = axis_ids.len().max(1);
    if axes > MAX_AXES {
        return None;
    }
    let mut axis = vec![vec![Pool::ZERO; axes]; n];
    for &k in &spread {
        for &(joint, g) in &components[k].terms {
            let slot = &mut axis[joint][axis_of[k]];
            if *slot != Pool::ZERO && *slot != g {
                return None;
            }
            *slot = g;
        }
    }

    // 5.: the tree. A joint that does not move along an axis (a cart along
    // `x` under a chain) is in none of that axis's components: the
    // components are first grouped into points, two components one point
    // where each holds the other's joints that move along its axis
    // (`x_i` and `y_i` of the same link's end); the joints' sets of points
    // then nest, and each point's joints are the path to its deepest one.
    let moves = |j: usize, a: usize| axis[j][a] != Pool::ZERO;
    // Each component's joints that move along each axis, listed once.
    let moving_along: BTreeMap<usize, Vec<Vec<usize>>> = spread
        .iter()
        .map(|&k| {
            let along = |a| {
                let joints = components[k].terms.iter().map(|&(j, _)| j);
                joints.filter(|&j| moves(j, a)).collect()
            };
            (k, (0..axes).map(along).collect())
        })
        .collect();
    pool.charge((spread.len() * spread.len() * n) as u64 / 8 + 1);
    if pool.exhausted() {
        return None;
    }
    let mut point_root: Vec<usize> = (0..components.len()).collect();
    for (i, &k) in spread.iter().enumerate() {
        for &l in &spread[..i] {
            let (a, b) = (axis_of[k], axis_of[l]);
            if moving_along[&k][b] == moving_along[&l][a] {
                let (r, s) = (root(&mut point_root, k), root(&mut point_root, l));
                point_root[r.max(s)] = r.min(s);
            }
        }
    }
    let point_of: Vec<usize> = (0..components.len())
        .map(|k| root(&mut point_root, k))
        .collect();
    // Each joint's points, and the joints of each point.
    let mut points_held: Vec<Vec<usize>> = vec![Vec::new(); n];
    let mut joints_of: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for &k in &spread {
        for &(j, _) in &components[k].terms {
            points_held[j].push(point_of[k]);
            joints_of.entry(point_of[k]).or_default().push(j);
        }
    }
    for list in points_held.iter_mut().chain(joints_of.values_mut()) {
        list.sort_unstable();
        list.dedup();
    }
    // Joints by how many points they hold, most first (of two that hold
    // the same, the one moving along fewer axes first: the cart above its
    // chain); each one's parent the last before it holding all its points.
    let axes_moved = |j: usize| (0..axes).filter(|&a| moves(j, a)).count();
    let mut by_size: Vec<usize> = (0..n).collect();
    by_size.sort_by_key(|&j| (std::cmp::Reverse(points_held[j].len()), axes_moved(j), j));
    pool.charge((n * n) as u64 * components.len() as u64 / 8 + 1);
    if pool.exhausted() {
        return None;
    }
    let mut parent = vec![None; n];
    for (place, &j) in by_size.iter().enumerate() {
        if points_held[j].is_empty() {
            continue;
        }
        parent[j] = by_size[..place].iter().rev().copied().find(|&k| {
            points_held[j]
                .iter()
                .all(|p| points_held[k].binary_search(p).is_ok())
        });
    }
    let rank: Vec<usize> = {
        let mut rank = vec![0; n];
        for (place, &j) in by_size.iter().enumerate() {
            rank[j] = place;
        }
        rank
    };
    // Each point's joints the path to its deepest; each of its components
    // holds the path's joints that move along its axis, and its mass sits
    // on the deepest joint.
    let mut masses = vec![vec![Vec::new(); axes]; n];
    let mut deepest_of: BTreeMap<usize, usize> = BTreeMap::new();
    for (&point, joints) in &joints_of {
        let deepest = joints.iter().copied().max_by_key(|&j| rank[j])?;
        let mut path = Vec::new();
        let mut at = Some(deepest);
        while let Some(j) = at {
            path.push(j);
            at = parent[j];
            if path.len() > n {
                return None;
            }
        }
        path.sort_unstable();
        if &path != joints {
            return None;
        }
        deepest_of.insert(point, deepest);
    }
    for &k in &spread {
        let c = &components[k];
        let a = axis_of[k];
        let point = point_of[k];
        let along: Vec<usize> = joints_of[&point]
            .iter()
            .copied()
            .filter(|&j| moves(j, a))
            .collect();
        if along.len() != c.terms.len() || along.iter().zip(&c.terms).any(|(x, (y, _))| x != y) {
            return None;
        }
        let m = pool.mul2(two, c.mass);
        masses[deepest_of[&point]][a].push(m);
    }

    // 3.: the angles as joints' angles plus one coordinate.
    let mut base = vec![None; n];
    let mut coordinate = vec![0; n];
    let mut scale = vec![0.0; n];
    let mut used = vec![false; n];
    for j in 0..n {
        let angle = &joint_angles[j];
        let (extra, with_base) = if let [(i, w)] = angle[..] {
            ((i, w), None)
        } else {
            let found = (0..n).find_map(|k| {
                let other = &joint_angles[k];
                if other.len() + 1 != angle.len() {
                    return None;
                }
                let mut rest = angle.iter().filter(|a| !other.contains(a));
                match (rest.next(), rest.next()) {
                    (Some(&extra), None) if other.iter().all(|o| angle.contains(o)) => {
                        Some((extra, k))
                    }
                    _ => None,
                }
            })?;
            (found.0, Some(found.1))
        };
        if used[extra.0] {
            return None;
        }
        used[extra.0] = true;
        coordinate[j] = extra.0;
        scale[j] = f64::from_bits(extra.1);
        base[j] = with_base;
    }

    // The joints in an order where parents and bases come first (Kahn's,
    // the smallest ready joint next).
    let mut waiting: Vec<usize> = (0..n)
        .map(|j| usize::from(parent[j].is_some()) + usize::from(base[j].is_some()))
        .collect();
    let mut ready: std::collections::BTreeSet<usize> =
        (0..n).filter(|&j| waiting[j] == 0).collect();
    let mut order = Vec::with_capacity(n);
    while let Some(j) = ready.pop_first() {
        order.push(j);
        for k in 0..n {
            for edge in [parent[k], base[k]] {
                if edge == Some(j) {
                    waiting[k] -= 1;
                    if waiting[k] == 0 {
                        ready.insert(k);
                    }
                }
            }
        }
    }
    if order.len() != n {
        return None;
    }
    let mut place = vec![0; n];
    for (p, &j) in order.iter().enumerate() {
        place[j] = p;
    }

    // The roots, in the joints' order.
    let mut roots = Vec::with_capacity(n * (3 * axes + 2));
    for &j in &order {
        roots.extend(&axis[j]);
    }
    for &j in &order {
        for &g in &axis[j] {
            roots.push(if g == Pool::ZERO { g } else { bend_of[&g] });
        }
    }
    for &j in &order {
        for m in &masses[j] {
            roots.push(pool.add(m));
        }
    }
    for &j in &order {
        roots.push(pool.add(&inertia[j]));
    }
    for (i, &q) in s.coordinates.iter().enumerate() {
        let dv = pool.diff(model.potential.value, q);
        let f = pool.sub(eq.nonconservative[i], dv);
        roots.push(f);
    }
    if pool.exhausted() {
        return None;
    }
    Some(Articulated {
        parent: order.iter().map(|&j| parent[j].map(|p| place[p])).collect(),
        base: order.iter().map(|&j| base[j].map(|b| place[b])).collect(),
        coordinate: order.iter().map(|&j| coordinate[j]).collect(),
        scale: order.iter().map(|&j| scale[j]).collect(),
        axes,
        roots,
    })
}

/// How deep [`terms_of`] distributes products over sums.
const ATOM_DEPTH: u32 = 4;

/// The terms of `g` with its products distributed over its sums (`l (cos a
/// \+ cos b)` is `l cos a + l cos b`), `depth` levels deep: what a joint's
/// coefficient is a sum of, one term per joint.
fn terms_of(pool: &mut Pool, g: ExprId, depth: u32, out: &mut Vec<ExprId>) {
    pool.charge(1);
    if pool.exhausted() {
        return;
    }
    match pool.node(g).clone() {
        Node::Add(terms) if depth > 0 => {
            for t in terms.iter() {
                terms_of(pool, *t, depth - 1, out);
            }
        }
        Node::Mul(xs) if depth > 0 => {
            let mut sums = xs
                .iter()
                .enumerate()
                .filter_map(|(k, &x)| match pool.node(x) {
                    Node::Add(terms) => Some((k, terms.clone())),
                    _ => None,
                });
            let (Some((k, terms)), None) = (sums.next(), sums.next()) else {
                out.push(g);
                return;
            };
            for t in terms.iter() {
                let mut factors = xs.to_vec();
                factors[k] = *t;
                let product = pool.mul(&factors);
                terms_of(pool, product, depth - 1, out);
            }
        }
        _ => out.push(g),
    }
}

/// Union–find's root, halving the path.
fn root(parents: &mut [usize], mut k: usize) -> usize {
    while parents[k] != k {
        parents[k] = parents[parents[k]];
        k = parents[k];
    }
    k
}

/// `∂g/∂φ` where `g` depends on `q` only through `φ = w · q`: `None`
/// where it does not (some `∂g/∂q_i ≠ w_i ∂g/∂q_p / w_p`).
fn along_angle(
    pool: &mut Pool,
    coordinates: &[crate::expr::SymId],
    g: ExprId,
    angle: &Angle,
) -> Option<ExprId> {
    let &(pivot, w) = angle.first()?;
    let w = f64::from_bits(w);
    for (i, &q) in coordinates.iter().enumerate() {
        if pool.depends_on(g, q) && !angle.iter().any(|&(a, _)| a == i) {
            return None;
        }
    }
    let dp = pool.diff(g, coordinates[pivot]);
    for &(i, wi) in &angle[1..] {
        let di = pool.diff(g, coordinates[i]);
        let ratio = pool.num(f64::from_bits(wi) / w);
        if pool.mul2(ratio, dp) != di {
            return None;
        }
    }
    let inverse = pool.num(1.0 / w);
    Some(pool.mul2(inverse, dp))
}

/// Which symbols are which, as dependency sets.
struct Kinds<'a, F> {
    /// `q̇`.
    velocities: &'a [u64],
    /// `t`, `q`, `q̇`: what a mass does not depend on.
    moving: &'a [u64],
    /// `t`, `q̇`: what a joint's `g` does not depend on.
    positional: &'a [u64],
    velocity_of: F,
}

impl<F: Fn(crate::expr::SymId) -> Option<usize>> Kinds<'_, F> {
    /// `id · Π factors` as a sum of `c L²`, pushed as `(c's factors, L's
    /// factors)`.
    fn squares(
        &self,
        pool: &Pool,
        id: ExprId,
        factors: Vec<ExprId>,
        out: &mut Vec<(Vec<ExprId>, Vec<ExprId>)>,
    ) -> Option<()> {
        pool.charge(1);
        // Each visit paid for: a shared node reached along many paths
        // ends the search at the budget, not after it.
        if pool.exhausted() {
            return None;
        }
        match pool.node(id) {
            Node::Add(terms) => {
                for &t in terms.iter() {
                    self.squares(pool, t, factors.clone(), out)?;
                }
                Some(())
            }
            Node::Mul(xs) => {
                if let Some((inner, rest)) =
                    self.one_with_velocities(pool, xs, factors.clone(), self.moving)
                {
                    return self.squares(pool, inner, rest, out);
                }
                // A square of a product, its power distributed by the pool:
                // `(l sin θ θ̇)²` is `l² sin²θ θ̇²`, one square of
                // `l sin θ θ̇` (as the same link's term is in the other
                // squares: its `g`, `l sin θ`, compared across them).
                let mut factors = factors;
                let mut bases = Vec::new();
                for &x in xs.iter() {
                    match pool.node(x) {
                        Node::Pow(base, exponent) if pool.as_num(*exponent) == Some(2.0) => {
                            bases.push(*base)
                        }
                        _ if pool.depends_on_any(x, self.moving) => return None,
                        _ => factors.push(x),
                    }
                }
                out.push((factors, bases));
                Some(())
            }
            Node::Pow(base, exponent) if pool.as_num(*exponent) == Some(2.0) => {
                out.push((factors, vec![*base]));
                Some(())
            }
            _ => None,
        }
    }

    /// `id · Π factors`, linear in `q̇`, as a sum of `g φ̇`, pushed as
    /// `(g's factors, φ)`.
    fn linear(
        &self,
        pool: &Pool,
        id: ExprId,
        factors: Vec<ExprId>,
        out: &mut Vec<(Vec<ExprId>, Angle)>,
    ) -> Option<()> {
        pool.charge(1);
        // Each visit paid for: a shared node reached along many paths
        // ends the search at the budget, not after it.
        if pool.exhausted() {
            return None;
        }
        if let Some(angle) = self.rate(pool, id) {
            out.push((factors, angle));
            return Some(());
        }
        match pool.node(id) {
            Node::Add(terms) => {
                for &t in terms.iter() {
                    self.linear(pool, t, factors.clone(), out)?;
                }
                Some(())
            }
            Node::Mul(xs) => {
                let (inner, rest) = self.one_with_velocities(pool, xs, factors, self.positional)?;
                self.linear(pool, inner, rest, out)
            }
            _ => None,
        }
    }

    /// The one factor of `xs` with velocities, and the others appended to
    /// `factors`, each free of `excluded`.
    fn one_with_velocities(
        &self,
        pool: &Pool,
        xs: &[ExprId],
        mut factors: Vec<ExprId>,
        excluded: &[u64],
    ) -> Option<(ExprId, Vec<ExprId>)> {
        let mut inner = None;
        for &x in xs {
            if pool.depends_on_any(x, self.velocities) {
                if inner.replace(x).is_some() {
                    return None;
                }
            } else if pool.depends_on_any(x, excluded) {
                return None;
            } else {
                factors.push(x);
            }
        }
        Some((inner?, factors))
    }

    /// `id` as `w · q̇` with numbers `w`: a velocity, a number times one,
    /// or a sum of those.
    fn rate(&self, pool: &Pool, id: ExprId) -> Option<Angle> {
        let one = |id: ExprId| -> Option<(usize, f64)> {
            match pool.node(id) {
                Node::Sym(s) => Some(((self.velocity_of)(*s)?, 1.0)),
                Node::Mul(xs) => match xs[..] {
                    [c, v] => {
                        let c = pool.as_num(c)?;
                        match pool.node(v) {
                            Node::Sym(s) => Some(((self.velocity_of)(*s)?, c)),
                            _ => None,
                        }
                    }
                    _ => None,
                },
                _ => None,
            }
        };
        let mut angle: Vec<(usize, f64)> = match pool.node(id) {
            Node::Add(terms) => terms.iter().map(|&t| one(t)).collect::<Option<_>>()?,
            _ => vec![one(id)?],
        };
        angle.sort_by_key(|a| a.0);
        if angle.windows(2).any(|w| w[0].0 == w[1].0) || angle.iter().any(|a| a.1 == 0.0) {
            return None;
        }
        Some(angle.into_iter().map(|(i, w)| (i, w.to_bits())).collect())
    }
}
