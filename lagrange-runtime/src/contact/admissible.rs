//! Forces that are not determined, chosen inside every friction cone
//! where a choice inside them exists: the least relative use of the cones
//! over the forces that give the same accelerations.
//!
//! Touching contacts whose rows are dependent leave their forces `λ`
//! undetermined along the null space `Z` of their responses (`M⁻¹ Dᵀ Z =
//! 0`: every `λ₀ + Z z` gives the same accelerations). Of those, a stuck
//! contact's friction is admissible where `|Fᵢ| ≤ μ_s Nᵢ` and every
//! normal force `Nᵢ ≥ 0`. The use of the cones is `ρ(z) = maxᵢ |Fᵢ| /
//! (μ_s Nᵢ)` over the stuck contacts, and `ρ* = inf_z ρ(z)` is the least
//! of it: an admissible distribution exists exactly where `ρ* ≤ 1`. For a
//! given `ρ`, the set `S(ρ) = {z : |Fᵢ| ≤ ρ μ_s Nᵢ, Nᵢ ≥ 0}` is a polyhedron
//! (planar friction: two half-spaces per cone, one per normal force),
//! empty below `ρ*`; so `ρ*` is found by bisection on the feasibility of
//! `S(ρ)`, to rounding.
//!
//! The forces taken are the given share `λ₀` (friction in proportion to
//! the cones, see `phase::share_friction`) where its own use `ρ₀` is at
//! most the target `ρ_t = (1 + ρ*)/2` (`ρ*` itself beyond 1), and
//! otherwise its projection onto `S(ρ_t)`: the nearest forces (in their
//! Euclidean norm) that use no cone more than halfway between the least
//! possible use and the limit. Then
//!
//! - every stuck contact keeps a margin `μ_s N − |F| ≥ (1 − ρ*) μ_s N / 2`,
//!   positive exactly while an admissible distribution exists, and
//!   reaching zero, at the contacts that limit it, exactly where none
//!   remains (the stick limit's event is located there, and only there);
//! - the choice is unique (a projection onto a convex set) and continuous in the state wherever `S(ρ_t)` has an
//!   interior (it moves with `ρ*` and the forces, and at the switch from
//!   `λ₀` to its projection `λ₀` lies on `S(ρ_t)`'s boundary); the forces
//!   stay bounded where the cones could squeeze the body without limit
//!   (a ladder wedged, `μ_w μ_f ≥ 1`), being the nearest to `λ₀`;
//! - where `λ₀` already qualifies (a crate on two corners, whose shares are
//!   one fraction of their cones, the least use), nothing is solved
//!   beyond one feasibility test, and the forces are `λ₀` bit for bit.
//!
//! A one-dimensional null space (two contacts of one planar body: a
//! ladder, a crate) is solved exactly, each half-space bounding an
//! interval; a larger one by Lemke's method on the projection's dual, `w
//! = d + C Cᵀ y` (`C z ≤ d` the polyhedron in orthonormal coordinates `z`
//! of the null space), whose matrix is positive semidefinite, so the
//! method finds the projection or proves the polyhedron empty.
//!
//! A contact whose friction acts in a plane bounds `S(ρ)` by a disc,
//! `|Fᵢ| ≤ ρ μ_s Nᵢ` with `Fᵢ` two components (a second-order cone), not
//! two half-spaces: the set is convex still. On a null space of one
//! dimension (a rod on two supports) each disc cuts an interval from the
//! line, found from the roots of a quadratic, and the test and the
//! projection are exact ([`Cones::on_a_line`]); on a larger one, each test
//! of it, and the projection, is a barrier method's (see
//! [`Cones::feasible`]).

use nalgebra::{DMatrix, DVector, RealField};

use super::ContactLaw;
use super::lcp::lemke;
use super::phase::Unknown;

/// One linear bound `c·z ≤ d₀ + ρ d₁` on the null-space coordinates, with
/// `c = c₀ + ρ c₁`: a side of a cone scaled by `ρ`, or a normal force's
/// sign (`c₁ = d₁ = 0`).
struct Bound<S: RealField + Copy> {
    c0: DVector<S>,
    c1: DVector<S>,
    d0: S,
    d1: S,
}

/// The cone of a stuck contact whose friction acts in a plane, in the
/// null-space coordinates: friction `F(z) = f₀ + A z` (two components)
/// and normal force `N(z) = n₀ + n·z`, held to `|F(z)| ≤ ρ μ_s N(z)`.
struct Disc<S: RealField + Copy> {
    f0: (S, S),
    rows: (DVector<S>, DVector<S>),
    n0: S,
    n: DVector<S>,
    mu: S,
}

/// The set `S(ρ)` where some cones are discs: the linear bounds (the
/// planar cones' sides, the normal forces' signs) and the discs, tested
/// and projected onto by a barrier method (see [`Self::feasible`]).
struct Cones<S: RealField + Copy> {
    k: usize,
    bounds: Vec<Bound<S>>,
    discs: Vec<Disc<S>>,
    /// The problem's force scale (its largest force), for the stopping
    /// tolerances.
    scale: S,
}

/// One term of the barrier at a point: its value, gradient and Hessian
/// in the variables `(z, s)` (`s` the phase-one slack, absent in a
/// projection).
struct Barrier<S: RealField + Copy> {
    value: S,
    gradient: DVector<S>,
    hessian: DMatrix<S>,
}

impl<S: RealField + Copy> Cones<S> {
    /// `−Σ log` of every bound's slack at `y = (z, s)` (the slack `s`
    /// added to each where `phase_one`): `d − c·z (+ s)` for a linear
    /// bound, `τ² − |F|²` with `τ = ρ μ_s N (+ s)` for a disc (the
    /// second-order cone's barrier). `None` outside the set's interior.
    fn barrier(&self, y: &DVector<S>, rho: S, phase_one: bool) -> Option<Barrier<S>> {
        let n = y.len();
        let z = y.rows(0, self.k);
        let s = if phase_one { y[self.k] } else { S::zero() };
        let two = S::one() + S::one();
        let mut value = S::zero();
        let mut gradient = DVector::zeros(n);
        let mut hessian = DMatrix::zeros(n, n);
        // A row of the variables: `c` on z, `1` on s in phase one.
        let row = |c: &DVector<S>, on_s: S| {
            let mut r = DVector::zeros(n);
            r.rows_mut(0, self.k).copy_from(c);
            if phase_one {
                r[self.k] = on_s;
            }
            r
        };
        for b in &self.bounds {
            let c = &b.c0 + &b.c1 * rho;
            let slack = b.d0 + b.d1 * rho - c.dot(&z) + s;
            if slack <= S::zero() {
                return None;
            }
            let r = row(&c, -S::one());
            // −log(slack), slack = d − r·y.
            value -= slack.ln();
            gradient += &r / slack;
            hessian += &r * r.transpose() / (slack * slack);
        }
        for d in &self.discs {
            let f = (d.f0.0 + d.rows.0.dot(&z), d.f0.1 + d.rows.1.dot(&z));
            let tau = rho * d.mu * (d.n0 + d.n.dot(&z)) + s;
            let q = tau * tau - f.0 * f.0 - f.1 * f.1;
            if tau <= S::zero() || q <= S::zero() {
                return None;
            }
            let rt = row(&(&d.n * (rho * d.mu)), S::one());
            let r0 = row(&d.rows.0, S::zero());
            let r1 = row(&d.rows.1, S::zero());
            // −log(τ² − F₀² − F₁²): gradient −(2τ ∇τ − 2F₀ ∇F₀ − 2F₁ ∇F₁)/q,
            // Hessian −(2 ∇τ∇τᵀ − 2 ∇F₀∇F₀ᵀ − 2 ∇F₁∇F₁ᵀ)/q + g gᵀ.
            let g = (&rt * tau - &r0 * f.0 - &r1 * f.1) * (-two / q);
            value -= q.ln();
            hessian += (&r0 * r0.transpose() + &r1 * r1.transpose() - &rt * rt.transpose())
                * (two / q)
                + &g * g.transpose();
            gradient += g;
        }
        Some(Barrier {
            value,
            gradient,
            hessian,
        })
    }

    /// The barrier method (Boyd and Vandenberghe, *Convex Optimization*,
    /// §11.3): `t · objective(y) + barrier(y)` minimized by Newton's method
    /// with a backtracking line search that stays inside, for `t` rising
    /// twentyfold until the duality gap, the bounds' count over `t`, is
    /// below `1e-13` of the force scale. The objective is `s` in phase one
    /// (where `stop` ends it as soon as `s < 0`: a point inside `S(ρ)`
    /// found), `|z|²/2` in a projection. `None` where Newton's system is
    /// not solvable.
    fn minimize(&self, mut y: DVector<S>, rho: S, phase_one: bool) -> Option<DVector<S>> {
        let c = nalgebra::convert::<f64, S>;
        let n = y.len();
        let count = c((self.bounds.len() + 2 * self.discs.len()) as f64);
        let objective = |y: &DVector<S>| {
            if phase_one {
                (y[self.k], {
                    let mut g = DVector::zeros(n);
                    g[self.k] = S::one();
                    g
                })
            } else {
                let z = y.rows(0, self.k).into_owned();
                (z.norm_squared() / c(2.0), y.clone())
            }
        };
        let tolerance = c(1e-13) * self.scale;
        let mut t = S::one() / self.scale;
        for _ in 0..40 {
            for _ in 0..100 {
                if phase_one && y[self.k] < S::zero() {
                    return Some(y);
                }
                let b = self.barrier(&y, rho, phase_one)?;
                let (f, g) = objective(&y);
                let mut hessian = b.hessian;
                // A direction no bound sees (none in these problems, whose
                // null spaces the bounds close) kept solvable.
                let ridge = c(1e-14) * hessian.diagonal().amax();
                for i in 0..n {
                    hessian[(i, i)] += ridge;
                }
                if !phase_one {
                    for i in 0..self.k {
                        hessian[(i, i)] += t;
                    }
                }
                let gradient = g * t + b.gradient;
                let step = hessian.cholesky()?.solve(&(-&gradient));
                let decrement = -gradient.dot(&step);
                // Centred enough: the gap, not this, sets the accuracy.
                if decrement <= c(1e-12) {
                    break;
                }
                let value = t * f + b.value;
                let mut alpha = S::one();
                let mut moved = false;
                for _ in 0..60 {
                    let next = &y + &step * alpha;
                    if let Some(nb) = self.barrier(&next, rho, phase_one) {
                        let next_value = t * objective(&next).0 + nb.value;
                        if next_value <= value - c(0.25) * alpha * decrement {
                            // Progress below the value's rounding: as
                            // centred as it can be.
                            moved =
                                value - next_value > c(64.0) * S::default_epsilon() * value.abs();
                            y = next;
                            break;
                        }
                    }
                    alpha /= c(2.0);
                }
                if !moved {
                    break;
                }
            }
            // Centred: the least slack is at least `s` less the gap, so a
            // positive one proves `S(ρ)` empty.
            if count / t <= tolerance || (phase_one && y[self.k] - count / t > tolerance) {
                break;
            }
            t *= c(20.0);
        }
        Some(y)
    }

    /// A point inside `S(ρ)` (every bound and disc held strictly), or
    /// `None` where the least slack that holds them all is positive to the
    /// duality gap (`S(ρ)` empty, or too thin to be told from empty at the
    /// forces' rounding): phase one of the barrier method from the origin,
    /// with the slack that makes it inside.
    fn feasible(&self, rho: S) -> Option<DVector<S>> {
        let zero = S::zero();
        let mut start = zero;
        for b in &self.bounds {
            start = start.max(-(b.d0 + b.d1 * rho));
        }
        for d in &self.discs {
            start = start.max(d.f0.0.hypot(d.f0.1) - rho * d.mu * d.n0);
        }
        let mut y = DVector::zeros(self.k + 1);
        y[self.k] = start + self.scale;
        let y = self.minimize(y, rho, true)?;
        (y[self.k] < zero).then(|| y.rows(0, self.k).into_owned())
    }

    /// The point of `S(ρ)` nearest the origin, to the duality gap, inside
    /// it: the barrier method's projection from a point inside.
    fn project(&self, rho: S) -> Option<DVector<S>> {
        let inside = self.feasible(rho)?;
        self.minimize(inside, rho, false)
    }

    /// On a null space of one dimension (`k = 1`), exactly: `S(ρ)` is an
    /// interval, the intersection of each linear bound's half-line and
    /// each disc's interval, and the point nearest the origin is the
    /// origin clamped into it; `None` where it is empty. A disc on the
    /// line `z` is `|f₀ + r z| ≤ τ₀ + τ₁ z` (`τ = ρ μ_s N`): the second-order
    /// cone cut by a line, an interval, bounded by the roots of `q(z) = A
    /// z² + 2 B z + C` (`A = |r|² − τ₁²`, `B = f₀·r − τ₀ τ₁`, `C = |f₀|² −
    /// τ₀²`) on the side where `τ ≥ 0`: between them where `A > 0`, beyond
    /// the one on the rising side of `τ` where `A < 0`. Microseconds,
    /// where the barrier method takes milliseconds.
    fn on_a_line(&self, rho: S) -> Option<DVector<S>> {
        debug_assert_eq!(self.k, 1);
        let zero = S::zero();
        let tiny = nalgebra::convert::<f64, S>(1e-13) * self.scale;
        let (mut lo, mut hi) = on_line(
            self.bounds
                .iter()
                .map(|b| (b.c0[0] + b.c1[0] * rho, b.d0 + b.d1 * rho)),
            tiny,
        )?;
        for d in &self.discs {
            let (r0, r1) = (d.rows.0[0], d.rows.1[0]);
            let (t0, t1) = (rho * d.mu * d.n0, rho * d.mu * d.n[0]);
            let a = r0 * r0 + r1 * r1 - t1 * t1;
            let b = d.f0.0 * r0 + d.f0.1 * r1 - t0 * t1;
            let c = d.f0.0 * d.f0.0 + d.f0.1 * d.f0.1 - t0 * t0;
            // τ ≥ 0.
            if t1.abs() <= tiny {
                if t0 < zero {
                    return None;
                }
            } else if t1 > zero {
                lo = lo.max(-t0 / t1);
            } else {
                hi = hi.min(-t0 / t1);
            }
            let discriminant = b * b - a * c;
            if a == zero {
                // q linear: 2 B z + C ≤ 0.
                if b > zero {
                    hi = hi.min(-c / (b + b));
                } else if b < zero {
                    lo = lo.max(-c / (b + b));
                } else if c > zero {
                    return None;
                }
                continue;
            }
            if discriminant < zero {
                // q of one sign: ≤ 0 nowhere where A > 0 (empty), and
                // everywhere where A < 0 (τ ≥ 0 is then the bound).
                if a > zero {
                    return None;
                }
                continue;
            }
            // The roots without cancellation: q = −(B + sign(B) √D), z =
            // q / A and C / q.
            let root = discriminant.sqrt();
            let q = -(b + if b < zero { -root } else { root });
            let (z1, z2) = if q == zero {
                (zero, zero)
            } else {
                let (u, v) = (q / a, c / q);
                (u.min(v), u.max(v))
            };
            if a > zero {
                lo = lo.max(z1);
                hi = hi.min(z2);
            } else if t1 > zero {
                lo = lo.max(z2);
            } else {
                hi = hi.min(z1);
            }
        }
        (lo <= hi).then(|| DVector::from_element(1, zero.max(lo).min(hi)))
    }
}

/// The forces of `first` moved along the null space of `responses` (the
/// `N × m` responses of the unknowns, column by column) to the choice
/// described in the module's docs, the nearest in the forces' Euclidean
/// norm; `first`
/// itself where it qualifies, or where nothing admissible can be solved.
pub(super) fn admissible<S: RealField + Copy>(
    responses: &DMatrix<S>,
    first: DVector<S>,
    unknowns: &[Unknown],
    laws: &[ContactLaw<S>],
) -> DVector<S> {
    let m = unknowns.len();
    let zero = S::zero();
    let normal_index = |contact: usize| {
        unknowns
            .iter()
            .position(|u| u.contact == contact && !u.tangential)
    };
    // A friction unknown's partner along the second row of a slip vector
    // (for the first row of a contact whose friction acts in a plane).
    let second_index = |contact: usize| {
        unknowns
            .iter()
            .position(|u| u.contact == contact && u.tangential && u.second)
    };
    // The share's own use of the cones (unbounded where a normal force
    // pulls, or friction acts without one).
    let infinite = S::one() / zero;
    let mut use0 = zero;
    for (c, u) in unknowns.iter().enumerate() {
        if !u.tangential {
            if first[c] < zero {
                use0 = infinite;
            }
            continue;
        }
        if u.second {
            continue;
        }
        let normal = laws[u.contact]
            .normal
            .or_else(|| normal_index(u.contact).map(|k| first[k]))
            .unwrap_or(zero);
        let capacity = laws[u.contact].static_friction * normal;
        let size = match second_index(u.contact) {
            Some(c2) => (first[c] * first[c] + first[c2] * first[c2]).sqrt(),
            None => first[c].abs(),
        };
        if size > zero {
            use0 = if capacity > zero {
                use0.max(size / capacity)
            } else {
                infinite
            };
        }
    }
    let one = S::one();
    let two = one + one;
    // Kept where `use0 ≤ ρ_t(ρ*)`, i.e. `ρ* ≥ ρ_t⁻¹(use0)`: where no
    // distribution uses the cones less than that.
    let threshold = if use0 <= one { two * use0 - one } else { use0 };
    let slack = nalgebra::convert::<f64, S>(1e-10);
    if threshold <= slack {
        return first;
    }
    let Some(basis) = null_space(responses, m) else {
        return first;
    };
    let k = basis.ncols();
    let mut bounds = Vec::new();
    let mut discs = Vec::new();
    for (c, u) in unknowns.iter().enumerate() {
        let row = basis.row(c).transpose();
        if !u.tangential {
            // −(λ₀ + Z z)ₙ ≤ 0.
            bounds.push(Bound {
                c0: -row,
                c1: DVector::zeros(k),
                d0: first[c],
                d1: zero,
            });
            continue;
        }
        if u.second {
            continue;
        }
        let mu = laws[u.contact].static_friction;
        let (n_row, n0) = match (laws[u.contact].normal, normal_index(u.contact)) {
            (Some(given), _) => (DVector::zeros(k), given),
            (None, Some(n)) => (basis.row(n).transpose(), first[n]),
            (None, None) => (DVector::zeros(k), zero),
        };
        if let Some(c2) = second_index(u.contact) {
            discs.push(Disc {
                f0: (first[c], first[c2]),
                rows: (row, basis.row(c2).transpose()),
                n0,
                n: n_row,
                mu,
            });
            continue;
        }
        // ±F − ρ μ N ≤ 0, each side.
        for sign in [one, -one] {
            bounds.push(Bound {
                c0: &row * sign,
                c1: &n_row * (-mu),
                d0: -sign * first[c],
                d1: mu * n0,
            });
        }
    }
    let scale = first.amax();
    let cones = Cones {
        k,
        bounds,
        discs,
        scale,
    };
    // Friction along one direction only: the polyhedron's projection, by
    // intervals or Lemke's method; with discs, the barrier method's (the
    // bisection only asks whether a point exists).
    let planar = cones.discs.is_empty();
    // Exact, by intervals or Lemke's method: without discs, or with them on
    // a line.
    let exact = planar || k == 1;
    let project = |rho: S| {
        if planar {
            project(&cones.bounds, k, rho)
        } else if k == 1 {
            cones.on_a_line(rho)
        } else {
            cones.feasible(rho)
        }
    };
    // ρ* by bisection between `lo` (S(lo) empty, or lo = 0) and `hi`
    // (S(hi) not): from below the threshold, or where the share itself
    // does not bound it, from the least power of two that is feasible.
    let mut hi = if threshold.is_finite() {
        threshold * (one - slack)
    } else {
        let mut hi = one;
        let most = nalgebra::convert::<f64, S>(1e12);
        while project(hi).is_none() {
            if hi > most {
                return first;
            }
            hi *= two;
        }
        hi
    };
    if project(hi).is_none() {
        return first;
    }
    let mut lo = zero;
    if project(zero).is_some() {
        hi = zero;
    }
    let eps = nalgebra::convert::<f64, S>(4.0) * S::default_epsilon();
    // With discs, each test is a barrier method's: `ρ*` only to `1e-6` of
    // its distance from the limit where that is larger than rounding (the
    // margin it leaves is then `(1 − ρ*)/2` of the cones to that share; it
    // is exact where it matters, as `ρ*` reaches 1).
    let coarse = if exact {
        zero
    } else {
        nalgebra::convert::<f64, S>(1e-6)
    };
    while hi - lo > (eps * hi.max(one)).max(coarse * (one - hi)) {
        let mid = (lo + hi) / two;
        if project(mid).is_some() {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let target = if hi <= one { (one + hi) / two } else { hi };
    let nearest = if exact {
        project(target)
    } else {
        cones.project(target)
    };
    match nearest {
        Some(z) => first + basis * z,
        None => first,
    }
}

/// An orthonormal basis of the null space of the `N × m` matrix
/// `responses` (as columns, `m × k`), from its singular values with the
/// tolerance of `least_solve`'s rank; `None` where it is trivial or a
/// value is not finite.
fn null_space<S: RealField + Copy>(responses: &DMatrix<S>, m: usize) -> Option<DMatrix<S>> {
    if !responses.iter().all(|x| x.is_finite()) {
        return None;
    }
    // Square, so that the decomposition gives every right singular vector.
    let rows = responses.nrows().max(m);
    let mut square = DMatrix::zeros(rows, m);
    square
        .view_mut((0, 0), (responses.nrows(), m))
        .copy_from(responses);
    let scale = square.iter().fold(S::zero(), |s, x| s.max(x.abs()));
    let eps = nalgebra::convert::<f64, S>(1e-12) * scale;
    let svd = square.svd(false, true);
    let v_t = svd.v_t?;
    let null: Vec<usize> = (0..m).filter(|&i| svd.singular_values[i] <= eps).collect();
    if null.is_empty() {
        return None;
    }
    Some(DMatrix::from_fn(m, null.len(), |r, c| v_t[(null[c], r)]))
}

/// The interval `[lo, hi]` (ends infinite where unbounded) of the line's
/// coordinate `z` that linear bounds `c z ≤ d` leave, or `None` where a
/// bound along no direction (`|c| ≤ tiny`) is violated (`d < −tiny`); it
/// may be empty, `lo > hi`.
fn on_line<S: RealField + Copy>(bounds: impl Iterator<Item = (S, S)>, tiny: S) -> Option<(S, S)> {
    let zero = S::zero();
    let (mut lo, mut hi) = (-S::one() / zero, S::one() / zero);
    for (c, d) in bounds {
        if c.abs() <= tiny {
            if d < -tiny {
                return None;
            }
        } else if c > zero {
            hi = hi.min(d / c);
        } else {
            lo = lo.max(d / c);
        }
    }
    Some((lo, hi))
}

/// The point of `S(ρ)` nearest the origin (in `k` orthonormal
/// coordinates of the null space), or `None` where `S(ρ)` is empty.
fn project<S: RealField + Copy>(bounds: &[Bound<S>], k: usize, rho: S) -> Option<DVector<S>> {
    let rows: Vec<(DVector<S>, S)> = bounds
        .iter()
        .map(|b| (&b.c0 + &b.c1 * rho, b.d0 + b.d1 * rho))
        .collect();
    let scale = rows
        .iter()
        .fold(S::zero(), |s, (c, d)| s.max(c.amax()).max(d.abs()));
    let tiny = nalgebra::convert::<f64, S>(1e-13) * scale;
    if k == 1 {
        // Each bound an end of an interval; the origin clamped into it.
        let (lo, hi) = on_line(rows.iter().map(|(c, d)| (c[0], *d)), tiny)?;
        return (lo <= hi).then(|| DVector::from_element(1, S::zero().max(lo).min(hi)));
    }
    // The projection's dual: w = d + C Cᵀ y ≥ 0, y ≥ 0, yᵀ w = 0, and
    // z = −Cᵀ y (the basis orthonormal: the metric of the forces is the
    // coordinates' own).
    let c = DMatrix::from_fn(rows.len(), k, |r, j| rows[r].0[j]);
    let d = DVector::from_iterator(rows.len(), rows.iter().map(|(_, d)| *d));
    let ct = c.transpose();
    let y = lemke(&(&c * &ct), &d).ok()?;
    let z = -(&ct * y);
    let violation = (&c * &z - &d).max();
    (violation <= tiny).then_some(z)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two stuck contacts of one body that push along one direction and
    /// rub along another (`N × m` responses `[e₀, e₁, e₀, e₁]`): only the
    /// sums `N₁ + N₂` and `F₁ + F₂` are determined, a null space of two
    /// dimensions (load and friction both move between them), solved by
    /// Lemke's method.
    fn two_contacts(mu: f64) -> (DMatrix<f64>, [Unknown; 4], [ContactLaw<f64>; 2]) {
        let responses = DMatrix::from_row_slice(2, 4, &[1.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0]);
        let unknown = |contact, tangential| Unknown {
            contact,
            tangential,
            second: false,
        };
        let unknowns = [
            unknown(0, false),
            unknown(0, true),
            unknown(1, false),
            unknown(1, true),
        ];
        let law = ContactLaw::frictionless(0.0).with_friction(mu);
        (responses, unknowns, [law, law])
    }

    #[test]
    fn a_share_outside_a_cone_moves_to_the_nearest_using_them_halfway_from_the_least_to_the_limit()
    {
        let mu = 0.6;
        let (responses, unknowns, laws) = two_contacts(mu);
        // N = (1.5, 0.5), F = (0, 1): the second contact at 3.33 times its
        // cone; the least use is the sums' `1 / (0.6 × 2)`, so the target
        // is halfway from it to 1.
        let first = DVector::from_vec(vec![1.5, 0.0, 0.5, 1.0]);
        let least = 1.0 / (mu * 2.0);
        let target = (1.0 + least) / 2.0;
        let x = admissible(&responses, first.clone(), &unknowns, &laws);
        // The same accelerations: the sums to rounding.
        assert!((x[0] + x[2] - 2.0).abs() < 1e-14, "{x}");
        assert!((x[1] + x[3] - 1.0).abs() < 1e-14, "{x}");
        let uses = [x[1].abs() / (mu * x[0]), x[3].abs() / (mu * x[2])];
        for u in uses {
            assert!(u <= target * (1.0 + 1e-12), "{uses:?} beyond {target}");
        }
        // Nearest to the share: the contact it overloaded at the target's
        // bound exactly (the projection moves no further than it must).
        assert!((uses[1] - target).abs() < 1e-9, "{uses:?}, target {target}");
    }

    #[test]
    fn a_share_within_its_bound_is_kept_bit_for_bit_and_none_admissible_is_the_least_use() {
        let mu = 0.6;
        let (responses, unknowns, laws) = two_contacts(mu);
        // Each at 0.5 of its cone, the least use of the sums: kept.
        let even = DVector::from_vec(vec![1.0, 0.3, 1.0, 0.3]);
        assert_eq!(admissible(&responses, even.clone(), &unknowns, &laws), even);
        // Friction of 1.5 against cones of 1.2 in all: none admissible;
        // the forces use the cones as little as can be, 1.25 each.
        let beyond = DVector::from_vec(vec![1.5, 0.0, 0.5, 1.5]);
        let x = admissible(&responses, beyond, &unknowns, &laws);
        let uses = [x[1].abs() / (mu * x[0]), x[3].abs() / (mu * x[2])];
        for u in uses {
            assert!((u - 1.25).abs() < 1e-9, "{uses:?}");
        }
    }

    /// Three contacts with friction in a plane against given loads (1, 2
    /// and 3), on one body whose friction is determined only by its sum
    /// (`2 × 6` responses): a null space of four dimensions, solved by
    /// the barrier method.
    fn three_discs(mu: f64) -> (DMatrix<f64>, [Unknown; 6], [ContactLaw<f64>; 3]) {
        let responses = DMatrix::from_row_slice(
            2,
            6,
            &[1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0],
        );
        let unknown = |contact, second| Unknown {
            contact,
            tangential: true,
            second,
        };
        let unknowns = [
            unknown(0, false),
            unknown(0, true),
            unknown(1, false),
            unknown(1, true),
            unknown(2, false),
            unknown(2, true),
        ];
        let law = |n| ContactLaw::given_normal(n, mu, mu).in_plane();
        (responses, unknowns, [law(1.0), law(2.0), law(3.0)])
    }

    fn disc_uses(x: &DVector<f64>, mu: f64) -> [f64; 3] {
        [0, 1, 2].map(|i| x[2 * i].hypot(x[2 * i + 1]) / (mu * (i + 1) as f64))
    }

    #[test]
    fn friction_in_discs_moves_to_the_nearest_using_them_halfway_from_the_least_to_the_limit() {
        let mu = 0.5;
        let (responses, unknowns, laws) = three_discs(mu);
        // The sum (1.2, 0.9), of size 1.5, all on the first contact: 3
        // times its disc. The least use is the sum's over the discs' 3, 0.5.
        let first = DVector::from_vec(vec![1.2, 0.9, 0.0, 0.0, 0.0, 0.0]);
        let target = (1.0 + 0.5) / 2.0;
        let x = admissible(&responses, first, &unknowns, &laws);
        // The same accelerations: the sums to rounding.
        assert!((x[0] + x[2] + x[4] - 1.2).abs() < 1e-13, "{x}");
        assert!((x[1] + x[3] + x[5] - 0.9).abs() < 1e-13, "{x}");
        let uses = disc_uses(&x, mu);
        // Within the target, which the bisection finds to `1e-6` of the
        // least use's distance from 1 (0.5 here): 2.5e-7.
        for u in uses {
            assert!(u <= target + 3e-7, "{uses:?} beyond {target}");
        }
        // Nearest to the share: the contact it overloaded at the target's
        // bound (the projection moves no further than it must), to the
        // barrier method's duality gap and the target's own error.
        assert!((uses[0] - target).abs() < 3e-7, "{uses:?}, target {target}");
    }

    #[test]
    fn friction_in_discs_beyond_every_distribution_uses_them_as_little_as_can_be() {
        let mu = 0.5;
        let (responses, unknowns, laws) = three_discs(mu);
        // A sum of size 3.6 against discs of 3 in all: none admissible;
        // the least use, 1.2, on every disc.
        let first = DVector::from_vec(vec![0.0, 0.0, 0.0, 0.0, 2.88, 2.16]);
        let x = admissible(&responses, first, &unknowns, &laws);
        assert!((x[0] + x[2] + x[4] - 2.88).abs() < 1e-13, "{x}");
        for u in disc_uses(&x, mu) {
            assert!((u - 1.2).abs() < 1e-9, "{x}");
        }
    }

    /// A rod on two supports (`models::PushedRod`: loads 0.4 and 0.6 of
    /// its weight 9.81, pushed by `p` at 30° from its axis, 0.3 ahead of
    /// its centre of mass) at rest: its six unknowns' responses, a null
    /// space of one dimension (friction along the rod moved from one
    /// support to the other), and the proportional share.
    fn rod(
        p: f64,
    ) -> (
        DMatrix<f64>,
        DVector<f64>,
        [Unknown; 6],
        [ContactLaw<f64>; 2],
    ) {
        let (a1, a2, c, j, a) = (0.6, 0.4, 0.3, 0.1, 30f64.to_radians());
        // Columns: back N, F, F₂, front N, F, F₂; rows x, y, z, yaw, pitch
        // (M = diag(1, 1, 1, j, j)).
        let d = DMatrix::from_column_slice(
            5,
            6,
            &[
                0.0, 0.0, 1.0, 0.0, a1, //
                1.0, 0.0, 0.0, 0.0, 0.0, //
                0.0, 1.0, 0.0, -a1, 0.0, //
                0.0, 0.0, 1.0, 0.0, -a2, //
                1.0, 0.0, 0.0, 0.0, 0.0, //
                0.0, 1.0, 0.0, a2, 0.0,
            ],
        );
        let responses =
            DMatrix::from_diagonal(&DVector::from_vec(vec![1.0, 1.0, 1.0, 1.0 / j, 1.0 / j])) * d;
        let span = a1 + a2;
        let (n0, n1) = (9.81 * a2 / span, 9.81 * a1 / span);
        let along = -p * a.cos() / 9.81;
        let across = -p * a.sin() / span;
        let first = DVector::from_vec(vec![
            n0,
            along * n0,
            across * (a2 - c),
            n1,
            along * n1,
            across * (a1 + c),
        ]);
        let unknown = |contact, tangential, second| Unknown {
            contact,
            tangential,
            second,
        };
        let unknowns = [
            unknown(0, false, false),
            unknown(0, true, false),
            unknown(0, true, true),
            unknown(1, false, false),
            unknown(1, true, false),
            unknown(1, true, true),
        ];
        let law = ContactLaw::frictionless(0.0).with_friction(0.5).in_plane();
        (responses, first, unknowns, [law, law])
    }

    #[test]
    fn the_rod_on_two_supports_keeps_both_discs_up_to_its_closed_form_push() {
        // Its closed-form breakaway push, 4.6429 (`PushedRod::breakaway_push`).
        for p in [3.0, 3.7, 3.72, 3.9, 4.2, 4.5, 4.6, 4.64] {
            let (responses, first, unknowns, laws) = rod(p);
            let x = admissible(&responses, first.clone(), &unknowns, &laws);
            let uses = [
                x[1].hypot(x[2]) / (0.5 * x[0]),
                x[4].hypot(x[5]) / (0.5 * x[3]),
            ];
            assert!((&responses * (&x - &first)).amax() < 1e-12, "{x}");
            for u in uses {
                assert!(u < 1.0, "p = {p}: {uses:?}");
            }
        }
        // On the line of its null space the discs are solved exactly: 1e-9
        // of the push on either side of the closed form (4.642930807794184,
        // `PushedRod::breakaway_push`, bisected to rounding) is told apart,
        // the least use there within 1e-8 of 1 (the use is linear in the
        // push near it, of slope about 1/P).
        let p_b = 4.642930807794184;
        for (p, holds) in [(p_b * (1.0 - 1e-9), true), (p_b * (1.0 + 1e-9), false)] {
            let (responses, first, unknowns, laws) = rod(p);
            let x = admissible(&responses, first, &unknowns, &laws);
            let uses = [
                x[1].hypot(x[2]) / (0.5 * x[0]),
                x[4].hypot(x[5]) / (0.5 * x[3]),
            ];
            let most = uses[0].max(uses[1]);
            assert_eq!(most <= 1.0, holds, "p = {p}: {uses:?}");
            assert!((most - 1.0).abs() < 1e-8, "p = {p}: {uses:?}");
        }
        // Beyond it, no distribution is admissible: the least use is above
        // 1 on some disc.
        for p in [4.65, 4.8] {
            let (responses, first, unknowns, laws) = rod(p);
            let x = admissible(&responses, first, &unknowns, &laws);
            let most = (x[1].hypot(x[2]) / (0.5 * x[0])).max(x[4].hypot(x[5]) / (0.5 * x[3]));
            assert!(most > 1.0, "p = {p}: {most}");
        }
    }
}
