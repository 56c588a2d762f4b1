//! The decisions at a switch: the impact of the touching contacts, which
//! of them push, stick or slide afterwards (one complementarity problem
//! each), and the state projected back onto them.

use nalgebra::{DMatrix, DVector, RealField, SMatrix, SVector};

use super::erased::Erased;
use super::held::Held;
use super::lcp::lemke;
use super::phase::{Slips, Terms, least_squares, normal_direction};
use crate::model::Lagrangian;
use crate::trajectory::State;

use super::{Cause, ContactError, ContactLaw, ContactSettings, Contacts, Mode, Switch};

/// One touching contact's unknowns in a complementarity problem: a normal
/// force along a known direction (frictionless, or sliding with known
/// friction), or a normal force with the planar friction cone of
/// coefficient `mu` (four unknowns: `N`, `β⁺`, `β⁻`, `σ`), or a contact
/// with a given normal force `normal` sticking or not (the cone with `N`
/// known: three unknowns, `β⁺`, `β⁻`, `σ`), or a normal force with the
/// friction cone of a slip vector, a disc (`N`, one `β` per side of the
/// polygon of [`FACETS`] sides that stands for it, `σ`).
#[derive(Clone, Copy)]
enum Entry<S> {
    Normal { contact: usize, mode: Mode },
    Cone { contact: usize, mu: S },
    Given { contact: usize, mu: S, normal: S },
    Disc { contact: usize, mu: S },
}

/// The directions of the polygon that stands for a disc of friction in
/// the complementarity problems (the regular polygon of 32 sides
/// inscribed in the circle): the decisions at switches and the impulses
/// of impacts. A force inside it is inside the disc, so every decided
/// force is admissible; along a side's middle it reaches `cos(π/32)`
/// (99.5 %) of the disc's radius. Between switches friction is the
/// disc's own (`|F| ≤ μ_s N` watched exactly, slip friction `μ_k N`
/// against the slip's direction), so only a decision within 0.5 % of the
/// limit, or an impact's friction impulse, sees the polygon.
pub(crate) const FACETS: usize = 32;

/// The solution of a contact complementarity problem: per contact, its
/// normal force (or impulse), its friction force, and for a cone whether
/// it slips and which way; and `M⁻¹ Dᵀ z`, the change it makes.
struct Solution<S: RealField + Copy, const N: usize, const K: usize> {
    normal: SVector<S, K>,
    friction: SVector<S, K>,
    second_friction: SVector<S, K>,
    /// For a cone entry: `Some(forward)` where it slips, `None` where it
    /// sticks.
    slips: [Option<bool>; K],
    change: SVector<S, N>,
}

/// Solves `w = A z + b ≥ 0, z ≥ 0, zᵀ w = 0` for `entries`, where the
/// normal rows' base values are `base_n` (gap rates or accelerations with
/// no contact force) and the tangential ones' `base_t`.
fn complementarity<S: RealField + Copy, const N: usize, const K: usize>(
    terms: &Terms<S, N, K>,
    (laws, slips): (&[ContactLaw<S>; K], &Slips<S, K>),
    entries: &[Entry<S>],
    base_n: &SVector<S, K>,
    (base_t, base_t2): (&SVector<S, K>, &SVector<S, K>),
) -> Result<Option<Solution<S, N, K>>, ()> {
    // Columns: (force direction, row vector whose product with the
    // change is this column's row's own term, sign of that product).
    struct Column<S: RealField + Copy, const N: usize> {
        direction: Option<SVector<S, N>>,
        row: Option<(SVector<S, N>, S)>,
        base: S,
    }
    let mut columns: Vec<Column<S, N>> = Vec::new();
    // For a cone at column c: its σ couples c+1, c+2 (β±) and c+3 (σ);
    // for a given normal force's at c, c and c+1 (β±) and c+2 (σ).
    let mut cones = Vec::new();
    let mut given = Vec::new();
    let mut discs = Vec::new();
    let facet = |j: usize| {
        let angle = nalgebra::convert::<f64, S>(core::f64::consts::TAU * j as f64 / FACETS as f64);
        (angle.cos(), angle.sin())
    };
    // A friction force as β⁺ and β⁻ along the slip row, and the slip rate
    // σ, whose row's known part is `sigma` (μ N where N is given).
    let friction = |columns: &mut Vec<Column<S, N>>, contact: usize, sigma: S| {
        let t = terms.t.row(contact).transpose();
        columns.push(Column {
            direction: Some(t),
            row: Some((t, S::one())),
            base: base_t[contact],
        });
        columns.push(Column {
            direction: Some(-t),
            row: Some((t, -S::one())),
            base: -base_t[contact],
        });
        columns.push(Column {
            direction: None,
            row: None,
            base: sigma,
        });
    };
    for entry in entries {
        match *entry {
            Entry::Normal { contact, mode } => columns.push(Column {
                direction: Some(normal_direction(
                    terms,
                    contact,
                    mode,
                    laws[contact].kinetic_friction,
                    slips,
                )),
                row: Some((terms.g.row(contact).transpose(), S::one())),
                base: base_n[contact],
            }),
            Entry::Cone { contact, mu } => {
                let g = terms.g.row(contact).transpose();
                cones.push((columns.len(), mu));
                columns.push(Column {
                    direction: Some(g),
                    row: Some((g, S::one())),
                    base: base_n[contact],
                });
                friction(&mut columns, contact, S::zero());
            }
            Entry::Given {
                contact,
                mu,
                normal,
            } => {
                given.push(columns.len());
                // σ row: μ N − β⁺ − β⁻, with μ N known.
                friction(&mut columns, contact, mu * normal);
            }
            Entry::Disc { contact, mu } => {
                let g = terms.g.row(contact).transpose();
                discs.push((columns.len(), mu));
                columns.push(Column {
                    direction: Some(g),
                    row: Some((g, S::one())),
                    base: base_n[contact],
                });
                let (t1, t2) = (
                    terms.t.row(contact).transpose(),
                    terms.t2.row(contact).transpose(),
                );
                for j in 0..FACETS {
                    let (c, s) = facet(j);
                    let d = t1 * c + t2 * s;
                    columns.push(Column {
                        direction: Some(d),
                        row: Some((d, S::one())),
                        base: base_t[contact] * c + base_t2[contact] * s,
                    });
                }
                columns.push(Column {
                    direction: None,
                    row: None,
                    base: S::zero(),
                });
            }
        }
    }
    let m = columns.len();
    if m == 0 {
        return Ok(None);
    }
    let mut responses = Vec::with_capacity(m);
    for c in &columns {
        responses.push(match &c.direction {
            Some(d) => Some(terms.solve(d).ok_or(())?),
            None => None,
        });
    }
    let mut a = DMatrix::zeros(m, m);
    let mut b = DVector::zeros(m);
    for (r, col) in columns.iter().enumerate() {
        b[r] = col.base;
        if let Some((w, sign)) = &col.row {
            for (c, response) in responses.iter().enumerate() {
                if let Some(response) = response {
                    a[(r, c)] = w.dot(response) * *sign;
                }
            }
        }
    }
    for &(c, mu) in &cones {
        // β± rows: σ ± a_t; σ row: μ N − β⁺ − β⁻.
        a[(c + 1, c + 3)] = S::one();
        a[(c + 2, c + 3)] = S::one();
        a[(c + 3, c)] = mu;
        a[(c + 3, c + 1)] = -S::one();
        a[(c + 3, c + 2)] = -S::one();
    }
    for &(c, mu) in &discs {
        // β_j rows: σ + d_j · a_t; σ row: μ N − Σ β_j.
        let sigma = c + FACETS + 1;
        for j in 1..=FACETS {
            a[(c + j, sigma)] = S::one();
            a[(sigma, c + j)] = -S::one();
        }
        a[(sigma, c)] = mu;
    }
    for &c in &given {
        a[(c, c + 2)] = S::one();
        a[(c + 1, c + 2)] = S::one();
        a[(c + 2, c)] = -S::one();
        a[(c + 2, c + 1)] = -S::one();
    }
    let z = lemke(&a, &b).map_err(|_| ())?;
    let mut solution = Solution {
        normal: SVector::zeros(),
        friction: SVector::zeros(),
        second_friction: SVector::zeros(),
        slips: [None; K],
        change: SVector::zeros(),
    };
    for (c, response) in responses.iter().enumerate() {
        if let Some(response) = response {
            solution.change += response * z[c];
        }
    }
    // A slip rate this small is nil, as a normal acceleration is (see
    // `rest` in `modes`): where the forces are not determined (a
    // ladder stuck at both ends), the pivoting may leave a contact at its
    // cone's edge with a slip rate of rounding, which is no slip.
    let rest = nalgebra::convert::<f64, S>(1e-9) * b.amax();
    let mut c = 0;
    for entry in entries {
        match *entry {
            Entry::Normal { contact, mode } => {
                solution.normal[contact] = z[c];
                if let Mode::Sliding { forward } = mode {
                    let f = laws[contact].kinetic_friction * z[c];
                    solution.friction[contact] = if forward { -f } else { f };
                }
                c += 1;
            }
            Entry::Cone { contact, .. } => {
                solution.normal[contact] = z[c];
                solution.friction[contact] = z[c + 1] - z[c + 2];
                if z[c + 3] > rest {
                    // Slipping: friction at the cone's edge against it.
                    solution.slips[contact] = Some(z[c + 2] > z[c + 1]);
                }
                c += 4;
            }
            Entry::Given {
                contact, normal, ..
            } => {
                solution.normal[contact] = normal;
                solution.friction[contact] = z[c] - z[c + 1];
                if z[c + 2] > rest {
                    solution.slips[contact] = Some(z[c + 1] > z[c]);
                }
                c += 3;
            }
            Entry::Disc { contact, .. } => {
                solution.normal[contact] = z[c];
                for j in 0..FACETS {
                    let (cos, sin) = facet(j);
                    solution.friction[contact] += z[c + 1 + j] * cos;
                    solution.second_friction[contact] += z[c + 1 + j] * sin;
                }
                if z[c + FACETS + 1] > rest {
                    // Slipping, against its friction (which way is the
                    // friction's own, not this flag).
                    solution.slips[contact] = Some(true);
                }
                c += FACETS + 2;
            }
        }
    }
    Ok(Some(solution))
}

/// Which contacts touch: a gap within the tolerance, or a contact that
/// was touching until now (its gap drifted by the integration's error, at
/// most, which the projection after the decision takes back), or one with
/// a given normal force (always).
pub(crate) fn touching<S: RealField + Copy, const N: usize, const K: usize>(
    model: &Erased<'_, S, N, K>,
    settings: &ContactSettings<S>,
    (t, q): (S, &SVector<S, N>),
    current: &[Mode; K],
) -> [bool; K] {
    let gaps = model.gaps(t, q);
    let laws = model.contact_laws();
    core::array::from_fn(|i| {
        laws[i].normal.is_some() || current[i].touching() || gaps[i] <= settings.gap_tolerance
    })
}

/// The modes after a decision at `(t, q, q̇)`: every touching contact at
/// rest along its normal decided together, the `forced` ones (each its
/// mode, from an event) taken as given; `slips` says where the friction of
/// a contact forced to slip in a plane points. With them, for each contact
/// decided to slip in a plane from rest, the direction its friction
/// takes (against the slip it sets off in), zero for the others.
#[allow(clippy::type_complexity)]
pub(crate) fn modes<S: RealField + Copy, const N: usize, const K: usize>(
    model: &Erased<'_, S, N, K>,
    settings: &ContactSettings<S>,
    (t, q, qdot): (S, &SVector<S, N>, &SVector<S, N>),
    (current, forced, slips): (&[Mode; K], &[Option<Mode>; K], &Slips<S, K>),
) -> Result<([Mode; K], [(S, S); K]), ContactError<S, N>> {
    let laws = model.contact_laws();
    let touch = touching(model, settings, (t, q), current);
    let rate = model.gap_velocities(t, q, qdot);
    let slip = model.slip_velocities(t, q, qdot);
    let slip2 = model.second_slip_velocities(t, q, qdot);
    // A slip's size: its one component, or a slip vector's length.
    let speed = |i: usize| {
        if laws[i].in_plane {
            (slip[i] * slip[i] + slip2[i] * slip2[i]).sqrt()
        } else {
            slip[i].abs()
        }
    };
    let terms = Terms::new(model, t, q, qdot).ok_or(ContactError::DependentContacts {
        t,
        q: *q,
        qdot: *qdot,
    })?;
    // The contacts with a given normal force first: each slides on (a
    // known force), or is a candidate to stick, decided with the others.
    let mut given = [Mode::Open; K];
    for i in 0..K {
        if laws[i].normal.is_none() {
            continue;
        }
        given[i] = match forced[i] {
            Some(mode) if mode.touching() => mode,
            _ if !laws[i].has_friction() => Mode::Closed,
            _ if current[i] == Mode::Stuck || slip[i].abs() <= settings.velocity_tolerance => {
                Mode::Stuck
            }
            _ => Mode::Sliding {
                forward: slip[i] > nalgebra::zero::<S>(),
            },
        };
    }
    let (_, known) = super::phase::given_friction(&terms, &laws, &given);
    let free = terms
        .free(&(terms.forcing + known))
        .ok_or(ContactError::DependentContacts {
            t,
            q: *q,
            qdot: *qdot,
        })?;
    let base_n = terms.g * free + terms.gamma;
    let base_t = terms.t * free + terms.gamma_t;
    let base_t2 = terms.t2 * free + terms.gamma_t2;
    let mut entries = Vec::new();
    for i in 0..K {
        if let Some(normal) = laws[i].normal {
            if given[i] == Mode::Stuck {
                entries.push(Entry::Given {
                    contact: i,
                    mu: laws[i].static_friction,
                    normal,
                });
            }
            continue;
        }
        match forced[i] {
            Some(Mode::Open) => continue,
            Some(mode) => {
                entries.push(Entry::Normal { contact: i, mode });
                continue;
            }
            None => {}
        }
        // A contact held until now (not struck by an impact in this
        // switch) is at rest along its normal, and a stuck one along its
        // surface, whatever drift the integration left in its rates: the
        // projection after the decision takes it back.
        let held = current[i].touching();
        if !touch[i] || (!held && rate[i].abs() > settings.velocity_tolerance) {
            continue;
        }
        let at_rest = current[i] == Mode::Stuck || speed(i) <= settings.velocity_tolerance;
        let entry = if !laws[i].has_friction() {
            Entry::Normal {
                contact: i,
                mode: Mode::Closed,
            }
        } else if at_rest && laws[i].in_plane {
            Entry::Disc {
                contact: i,
                mu: laws[i].static_friction,
            }
        } else if at_rest {
            Entry::Cone {
                contact: i,
                mu: laws[i].static_friction,
            }
        } else if laws[i].in_plane {
            Entry::Normal {
                contact: i,
                mode: Mode::Slipping,
            }
        } else {
            Entry::Normal {
                contact: i,
                mode: Mode::Sliding {
                    forward: slip[i] > nalgebra::zero::<S>(),
                },
            }
        };
        entries.push(entry);
    }
    let no_mode = ContactError::NoConsistentMode {
        t,
        q: *q,
        qdot: *qdot,
        at_impact: false,
    };
    let solution = complementarity(
        &terms,
        (&laws, slips),
        &entries,
        &base_n,
        (&base_t, &base_t2),
    )
    .map_err(|()| no_mode)?;
    // The contacts with a given normal force touch whatever the solution.
    let mut modes = given;
    // A normal acceleration this small is nil: the solve's rounding of
    // the largest one.
    let rest = nalgebra::convert::<f64, S>(1e-9) * base_n.amax();
    let mut directions = [(S::zero(), S::zero()); K];
    if let Some(solution) = solution {
        for entry in &entries {
            let (i, mode) = match *entry {
                Entry::Normal { contact, mode } => (contact, mode),
                Entry::Given { contact, .. } => {
                    modes[contact] = match solution.slips[contact] {
                        Some(forward) => Mode::Sliding { forward },
                        None => Mode::Stuck,
                    };
                    continue;
                }
                Entry::Cone { contact, .. } => (
                    contact,
                    match solution.slips[contact] {
                        Some(forward) => Mode::Sliding { forward },
                        None => Mode::Stuck,
                    },
                ),
                Entry::Disc { contact, .. } => {
                    if solution.slips[contact].is_some() {
                        // It sets off against its friction.
                        let f = (
                            solution.friction[contact],
                            solution.second_friction[contact],
                        );
                        let length = (f.0 * f.0 + f.1 * f.1).sqrt();
                        if length > S::zero() {
                            directions[contact] = (-f.0 / length, -f.1 / length);
                        }
                        (contact, Mode::Slipping)
                    } else {
                        (contact, Mode::Stuck)
                    }
                }
            };
            // A contact the solution leaves without force but on the
            // surface (its normal acceleration nil: four corners of a face,
            // whose loads are not determined, of which the pivoting loads
            // two) touches still: left open, it would sit at a zero gap
            // unwatched (its arrival cannot arm), and the body could turn
            // through it about the loaded ones.
            let acceleration = (terms.g.row(i) * (free + solution.change))[0] + terms.gamma[i];
            if solution.normal[i] > nalgebra::zero::<S>() || acceleration <= rest {
                modes[i] = mode;
            }
        }
    }
    Ok((modes, directions))
}

/// One contact's impulse at an impact: normal, tangential along the
/// slip's first row, along a slip vector's second.
pub(crate) type Impulse<S> = (S, S, S);

/// A contact whose rebound was too short to resolve, flying it out
/// unwatched by its gap: it settles where the rebounds cut off would have
/// accumulated, `2 ġ⁺ / (|g̈| (1 − e))` after the impact (their flights
/// `2 ġ⁺ eᵏ / |g̈|` summed at a constant acceleration), a time that the
/// coordinates' origin and scale do not move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Accumulation<S> {
    /// Where its rebounds accumulate: it settles there.
    pub(crate) at: S,
    /// How deep its flight takes it by then, past its landing.
    depth: S,
}

impl<S: RealField + Copy> Accumulation<S> {
    /// Rebounding at `rate` (`ġ⁺`) from an impact at `t` of restitution
    /// `e`, falling back at `fall` (`|g̈|`).
    fn new(t: S, rate: S, fall: S, e: S) -> Self {
        let one = S::one();
        let two = one + one;
        let flight = two * rate / (fall * (one - e));
        Self {
            at: t + flight,
            depth: (fall * flight * flight / two - rate * flight).max(S::zero()),
        }
    }

    /// The contact's arrival watched while it flies out: its gap and rate
    /// (`g + max(ġ, 0)`, as an open contact's) plus the depth its flight
    /// reaches and `tolerance`, so that it passes zero only where the
    /// contact goes in deeper than that (a method's error on the flight,
    /// or a force that drives it in), and no penetration goes unseen.
    pub(crate) fn ahead(&self, gap: S, rate: S, tolerance: S) -> S {
        gap + rate.max(S::zero()) + self.depth + tolerance
    }
}

/// What an impact leaves: the velocities after it, per contact the
/// impulses `(normal, tangential, second tangential)`, whether it was made
/// plastic as a rebound too short to resolve (settled), and the contacts
/// whose short rebounds fly out to their accumulation instead.
pub(crate) type Impact<S, const N: usize, const K: usize> = (
    SVector<S, N>,
    [Impulse<S>; K],
    bool,
    [Option<Accumulation<S>>; K],
);

/// An impact of the touching contacts at `(t, q, q̇⁻)` (see [`Impact`]);
/// made plastic where `settle` (its contact's rebounds accumulated).
/// `None` where nothing approaches.
pub(crate) fn impact<S: RealField + Copy, const N: usize, const K: usize>(
    model: &Erased<'_, S, N, K>,
    settings: &ContactSettings<S>,
    (t, q, qdot): (S, &SVector<S, N>, &SVector<S, N>),
    current: &[Mode; K],
    settle: bool,
) -> Result<Option<Impact<S, N, K>>, ContactError<S, N>> {
    let laws = model.contact_laws();
    let touch = touching(model, settings, (t, q), current);
    let rate = model.gap_velocities(t, q, qdot);
    // An impact needs an arriving contact: one held until now approaches
    // only by the integration's drift, which the projection takes back.
    let arriving = |i: usize| {
        laws[i].normal.is_none() && !current[i].touching() && rate[i] < -settings.velocity_tolerance
    };
    if !(0..K).any(|i| touch[i] && arriving(i)) {
        return Ok(None);
    }
    let dependent = ContactError::DependentContacts {
        t,
        q: *q,
        qdot: *qdot,
    };
    let terms = Terms::new(model, t, q, qdot).ok_or(dependent.clone())?;
    let slip = model.slip_velocities(t, q, qdot);
    let slip2 = model.second_slip_velocities(t, q, qdot);
    // A given normal force is finite: no impulse, no part in an impact.
    let entries: Vec<Entry<S>> = (0..K)
        .filter(|&i| touch[i] && laws[i].normal.is_none())
        .map(|i| {
            if laws[i].has_friction() && laws[i].in_plane {
                Entry::Disc {
                    contact: i,
                    mu: laws[i].kinetic_friction,
                }
            } else if laws[i].has_friction() {
                Entry::Cone {
                    contact: i,
                    mu: laws[i].kinetic_friction,
                }
            } else {
                Entry::Normal {
                    contact: i,
                    mode: Mode::Closed,
                }
            }
        })
        .collect();
    let no_mode = ContactError::NoConsistentMode {
        t,
        q: *q,
        qdot: *qdot,
        at_impact: true,
    };
    let none = Slips::none(nalgebra::zero());
    let plastic = complementarity(&terms, (&laws, &none), &entries, &rate, (&slip, &slip2))
        .map_err(|()| no_mode)?
        .ok_or(dependent.clone())?;
    let one = nalgebra::one::<S>();
    let e = (0..K)
        .filter(|&i| plastic.normal[i] > nalgebra::zero::<S>())
        .map(|i| laws[i].restitution)
        .fold(one, |a, b| a.min(b));
    let after = |e: S| qdot + plastic.change * (one + e);
    let mut e = if settle { nalgebra::zero() } else { e };
    let mut velocity = after(e);
    let mut settled = settle;
    let mut accumulating = [None; K];
    if e > nalgebra::zero::<S>() {
        // A rebound too short to resolve: its flight 2 ġ⁺ / |g̈|, with the
        // contacts open, below the shortest flight.
        let rebound = model.gap_velocities(t, q, &velocity);
        let (m, f) = model.mass_matrix_and_forcing(t, q, &velocity);
        let terms_after = Terms::with(model, (t, q, &velocity), &m, f).ok_or(dependent.clone())?;
        let free = terms_after.free(&terms_after.forcing).ok_or(dependent)?;
        let fall = terms_after.g * free + terms_after.gamma;
        let two = one + one;
        let zero = nalgebra::zero::<S>();
        let rounding = nalgebra::convert::<f64, S>(64.0 * f64::EPSILON);
        for i in 0..K {
            let (v, a) = (rebound[i], -fall[i]);
            // The rounding of the gap's value, from its terms' sizes.
            let resolution =
                rounding * (0..N).fold(zero, |sum, j| sum + (terms_after.g[(i, j)] * q[j]).abs());
            let short = plastic.normal[i] > zero
                && v > zero
                && a > zero
                && (two * v < settings.shortest_flight * a || v * v < two * a * resolution);
            if short {
                accumulating[i] = Some(Accumulation::new(t, v, a, e));
            }
        }
        // Elastic rebounds never accumulate: a short one is made plastic
        // where it stands.
        settled = e >= one && accumulating.iter().any(Option::is_some);
        if settled {
            accumulating = [None; K];
            e = nalgebra::zero::<S>();
            velocity = after(e);
        }
    }
    let impulses = core::array::from_fn(|i| {
        (
            plastic.normal[i] * (one + e),
            plastic.friction[i] * (one + e),
            plastic.second_friction[i] * (one + e),
        )
    });
    Ok(Some((velocity, impulses, settled, accumulating)))
}

/// The state projected onto the touching contacts of `modes` and the
/// model's own constraints: a few Newton steps on `g = 0` (and `φ = 0`)
/// and one on `ġ = 0` (and `v_t = 0` for stuck ones, `φ̇ = 0`), each the
/// least change in the metric of `M` (`M + k BᵀB` where `M` is regular
/// only on the constraints).
pub(crate) fn project<S: RealField + Copy, const N: usize, const K: usize>(
    model: &Erased<'_, S, N, K>,
    modes: &[Mode; K],
    t: S,
    (mut q, mut qdot): (SVector<S, N>, SVector<S, N>),
) -> Option<State<S, N>> {
    // The gaps of the touching contacts (a given normal force has none),
    // and the slip of every stuck one.
    let laws = model.contact_laws();
    let touching: Vec<usize> = (0..K)
        .filter(|&i| modes[i].touching() && laws[i].normal.is_none())
        .collect();
    let stuck: Vec<usize> = (0..K).filter(|&i| modes[i] == Mode::Stuck).collect();
    let constrained = model.constrained();
    if touching.is_empty() && stuck.is_empty() && !constrained {
        return Some((q, qdot));
    }
    let correct = |rows: &[SVector<S, N>],
                   residual: &DVector<S>,
                   m: &SMatrix<S, N, N>|
     -> Option<SVector<S, N>> {
        let factor = crate::linalg::mass::factor_mass_matrix(m).ok()?;
        let responses: Vec<SVector<S, N>> = rows
            .iter()
            .map(|r| factor.solve(r).ok())
            .collect::<Option<_>>()?;
        let k = rows.len();
        let a = DMatrix::from_fn(k, k, |i, j| rows[i].dot(&responses[j]));
        let y = least_squares(a, residual)?;
        let mut dx = SVector::zeros();
        for j in 0..k {
            dx -= responses[j] * y[j];
        }
        Some(dx)
    };
    // The metric at `q`: `M`, or `M + k BᵀB` with the model's constraints.
    let metric = |q: &SVector<S, N>, held: Option<&Held<S>>| {
        let m = model.mass_matrix(t, q);
        held.map_or(m, |held| held.metric(&m).0)
    };
    for _ in 0..3 {
        if touching.is_empty() && !constrained {
            break;
        }
        // The residuals first: the terms of a correction only where one
        // is needed.
        let held = model.held(t, &q, &qdot, true);
        let gaps = model.gaps(t, &q);
        let mut residual: Vec<S> = touching.iter().map(|&i| gaps[i]).collect();
        let positions: Vec<usize> = held.as_ref().map_or(Vec::new(), |held| {
            (0..held.values.len())
                .filter(|&i| !held.velocity_rows[i])
                .collect()
        });
        if let Some(held) = &held {
            residual.extend(positions.iter().map(|&i| held.values[i]));
        }
        if residual.iter().all(|g| *g == nalgebra::zero::<S>()) {
            break;
        }
        let g = model.gap_jacobian(t, &q);
        let mut rows: Vec<_> = touching.iter().map(|&i| g.row(i).transpose()).collect();
        if let Some(held) = &held {
            rows.extend(positions.iter().map(|&i| held.row(i)));
        }
        q += correct(
            &rows,
            &DVector::from_vec(residual),
            &metric(&q, held.as_ref()),
        )?;
    }
    let held = model.held(t, &q, &qdot, true);
    let m = metric(&q, held.as_ref());
    let g = model.gap_jacobian(t, &q);
    let tt = model.slip_jacobian(t, &q);
    let rate = model.gap_velocities(t, &q, &qdot);
    let slip = model.slip_velocities(t, &q, &qdot);
    // A slip vector's second rows, where some contact has one.
    let second = model.planes().then(|| {
        (
            model.second_slip_jacobian(t, &q),
            model.second_slip_velocities(t, &q, &qdot),
        )
    });
    let mut rows = Vec::new();
    let mut residual = Vec::new();
    for &i in &touching {
        rows.push(g.row(i).transpose());
        residual.push(rate[i]);
        if modes[i] == Mode::Stuck {
            rows.push(tt.row(i).transpose());
            residual.push(slip[i]);
            if let (true, Some((t2, slip2))) = (laws[i].in_plane, &second) {
                rows.push(t2.row(i).transpose());
                residual.push(slip2[i]);
            }
        }
    }
    for &i in &stuck {
        if laws[i].normal.is_some() {
            rows.push(tt.row(i).transpose());
            residual.push(slip[i]);
        }
    }
    if let Some(held) = &held {
        for i in 0..held.velocities.len() {
            rows.push(held.row(i));
            residual.push(held.velocities[i]);
        }
    }
    let residual = DVector::from_vec(residual);
    qdot += correct(&rows, &residual, &m)?;
    Some((q, qdot))
}

/// Appends a switch for every contact whose mode changed, and for every
/// contact with an impulse.
#[allow(clippy::too_many_arguments)]
pub(crate) fn record<S: RealField + Copy, const N: usize, const K: usize>(
    switches: &mut Vec<Switch<S, N>>,
    names: &[&'static str; K],
    (t, q, qdot): (S, SVector<S, N>, SVector<S, N>),
    (from, to, directions): (&[Mode; K], &[Mode; K], &[(S, S); K]),
    causes: impl Fn(usize) -> Cause,
    impulses: Option<&[Impulse<S>; K]>,
    energy_lost: S,
) {
    for i in 0..K {
        let (normal, tangential, second) =
            impulses.map_or((S::zero(), S::zero(), S::zero()), |p| p[i]);
        let impulse = (normal, tangential);
        let struck = impulse.0 != S::zero();
        if from[i] != to[i] || struck {
            switches.push(Switch {
                t,
                contact: i,
                name: names[i],
                from: from[i],
                to: to[i],
                cause: causes(i),
                impulse,
                second_impulse: second,
                slip_direction: if to[i] == Mode::Slipping {
                    directions[i]
                } else {
                    (S::zero(), S::zero())
                },
                energy_lost: if struck { energy_lost } else { S::zero() },
                q,
                qdot,
            });
        }
    }
}
