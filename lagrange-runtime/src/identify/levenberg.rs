//! Levenberg–Marquardt over a residual whose Jacobian comes with it (one
//! sensitivity run gives both), and the least-squares statistics at the
//! solution: the singular values of the column-scaled Jacobian, which say
//! whether the directions are identifiable, and the covariance.
//!
//! Written here rather than taken from a crate: `levenberg-marquardt`
//! (the MINPACK port) is built on an older nalgebra than the runtime's, so
//! a user's build would carry two nalgebras and convert between them, and
//! its problem trait evaluates the residual and the Jacobian separately,
//! where a sensitivity run computes both at once. `argmin` is a framework
//! of its own (executors, observers, its own math backends) for what is
//! here a hundred lines.

use nalgebra::{DMatrix, DVector};

use crate::model::parameters::Domain;

/// A residual `r` and its Jacobian `J = ∂r/∂x` at one point.
pub(crate) struct Evaluation {
    pub(crate) residual: DVector<f64>,
    pub(crate) jacobian: DMatrix<f64>,
}

impl Evaluation {
    fn cost(&self) -> f64 {
        0.5 * self.residual.norm_squared()
    }
}

/// When to stop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Stop {
    pub(crate) max_iterations: usize,
    /// Relative step: stop when every `|δ_k| ≤ x_tol (|x_k| + x_tol)`.
    pub(crate) x_tol: f64,
    /// Relative decrease of the cost.
    pub(crate) f_tol: f64,
}

/// Where the iteration ended.
pub(crate) struct Solution {
    pub(crate) x: DVector<f64>,
    pub(crate) iterations: usize,
    pub(crate) evaluations: usize,
    pub(crate) converged: bool,
}

/// Minimizes `½|r(x)|²` from `x0` by Levenberg–Marquardt with Marquardt's
/// diagonal scaling and Nielsen's update of the damping. `evaluate`
/// returns `None` where `r` cannot be computed (a run that failed): the
/// step is rejected as if it raised the cost. The first evaluation's
/// failure is the caller's `Err`.
///
/// Each value is kept inside its domain (`x0` inside them all) by a
/// projected step ([`keep_inside`]); a step that stays inside is taken as
/// it is, bit for bit.
pub(crate) fn minimize<E>(
    x0: DVector<f64>,
    stop: Stop,
    domains: &[Domain],
    mut evaluate: impl FnMut(&DVector<f64>) -> Result<Evaluation, E>,
) -> Result<Solution, E> {
    let mut x = x0;
    let mut at = evaluate(&x)?;
    let mut evaluations = 1;
    let mut lambda = 1e-3;
    let mut nu = 2.0;
    for iteration in 1..=stop.max_iterations {
        let a = at.jacobian.transpose() * &at.jacobian;
        let g = at.jacobian.transpose() * &at.residual;
        let mut damped = a.clone();
        for k in 0..x.len() {
            // Marquardt's scaling, floored so that a column of zeros
            // (a direction the data do not see) still gets a damped step.
            damped[(k, k)] += lambda * a[(k, k)].max(1e-12 * a.diagonal().amax());
        }
        let Some(step) = damped.cholesky().map(|c| -c.solve(&g)) else {
            lambda *= nu;
            nu *= 2.0;
            continue;
        };
        let trial = &x + &step;
        let (trial, step) = match keep_inside(&x, &trial, domains) {
            Some(inside) => {
                let step = &inside - &x;
                (inside, step)
            }
            None => (trial, step),
        };
        let small = step
            .iter()
            .zip(x.iter())
            .all(|(d, x)| d.abs() <= stop.x_tol * (x.abs() + stop.x_tol));
        evaluations += 1;
        let next = evaluate(&trial).ok().filter(|e| e.cost().is_finite());
        let predicted = -(g.dot(&step) + 0.5 * step.dot(&(&a * &step)));
        match next {
            Some(next) if next.cost() < at.cost() => {
                let decrease = at.cost() - next.cost();
                let rho = decrease / predicted.max(f64::MIN_POSITIVE);
                lambda *= (1.0 - (2.0 * rho - 1.0).powi(3)).max(1.0 / 3.0);
                nu = 2.0;
                let done = small || decrease <= stop.f_tol * at.cost();
                x = trial;
                at = next;
                if done {
                    return Ok(Solution {
                        x,
                        iterations: iteration,
                        evaluations,
                        converged: true,
                    });
                }
            }
            _ => {
                if small {
                    // No smaller step can lower the cost: a minimum to
                    // the precision the runs give.
                    return Ok(Solution {
                        x,
                        iterations: iteration,
                        evaluations,
                        converged: true,
                    });
                }
                lambda *= nu;
                nu *= 2.0;
            }
        }
    }
    Ok(Solution {
        x,
        iterations: stop.max_iterations,
        evaluations,
        converged: false,
    })
}

/// The trial point `trial` from `x` (inside every domain) moved back inside
/// them, `None` where it is inside already. A closed end stops a value on
/// it (the projection onto the box of the domains, so a minimum on a bound,
/// a damping of zero, is reached exactly); an open end is approached by at
/// most 99 % of the distance left (the fraction-to-the-boundary rule of
/// interior-point methods), so a value never reaches it, and a minimum
/// outside the domain leaves the value converging towards the end
/// geometrically, each step a shorter one, until the steps are below
/// `x_tol`. Projection rather than a reparametrization (`l = exp(u)`):
/// a fit whose steps stay inside is unchanged, and a closed end is
/// reachable, where a reparametrization reaches neither and changes every
/// step of every bounded fit.
pub(crate) fn keep_inside(
    x: &DVector<f64>,
    trial: &DVector<f64>,
    domains: &[Domain],
) -> Option<DVector<f64>> {
    if domains
        .iter()
        .zip(trial.iter())
        .all(|(d, v)| d.contains(*v))
    {
        return None;
    }
    let mut inside = trial.clone();
    for (k, d) in domains.iter().enumerate() {
        let v = inside[k];
        if d.contains(v) {
            continue;
        }
        let (end, closed) = if v < d.lower || (v == d.lower && !d.lower_closed) {
            (d.lower, d.lower_closed)
        } else {
            (d.upper, d.upper_closed)
        };
        inside[k] = if closed {
            end
        } else {
            end + 0.01 * (x[k] - end)
        };
    }
    Some(inside)
}

/// The least-squares statistics of a Jacobian `J` (`m × D`) whose columns
/// are scaled by `scale` (the response to a relative change of each
/// direction): its singular values, largest first, and the right singular
/// vector of the smallest (the combination of relative changes the data
/// see least), and `(JᵀJ)⁻¹` of the unscaled `J`, from the same SVD.
pub(crate) struct Spectrum {
    pub(crate) singular_values: DVector<f64>,
    pub(crate) weakest: DVector<f64>,
    pub(crate) inverse_normal: DMatrix<f64>,
}

pub(crate) fn spectrum(jacobian: &DMatrix<f64>, scale: &DVector<f64>) -> Spectrum {
    let mut scaled = jacobian.clone();
    for (k, s) in scale.iter().enumerate() {
        scaled.column_mut(k).scale_mut(*s);
    }
    let svd = scaled.svd(false, true);
    let v_t = svd.v_t.expect("asked for V");
    let sigma = svd.singular_values;
    let d = sigma.len();
    // nalgebra orders the singular values decreasingly.
    let mut order: Vec<usize> = (0..d).collect();
    order.sort_by(|&i, &j| sigma[j].total_cmp(&sigma[i]));
    let weakest_index = order[d - 1];
    let weakest = v_t.row(weakest_index).transpose();
    // (JᵀJ)⁻¹ = S V Σ⁻² Vᵀ S with J = Js S⁻¹.
    let mut inverse = DMatrix::<f64>::zeros(d, d);
    for i in 0..d {
        let v = v_t.row(i).transpose();
        inverse += (&v * v.transpose()) / (sigma[i] * sigma[i]);
    }
    let s = DMatrix::from_diagonal(scale);
    Spectrum {
        singular_values: DVector::from_iterator(d, order.iter().map(|&i| sigma[i])),
        weakest,
        inverse_normal: &s * inverse * &s,
    }
}
