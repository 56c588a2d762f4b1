//! What the Gauss collocation methods share: the stage system, its
//! simplified Newton iteration and its starting guess. [`ImplicitMidpoint`]
//! and [`GaussLegendre`] only choose a tableau.
//!
//! For `y = (q, v)`, `F(t, y) = (v, a(t, q, v))`, a step of an `s`-stage
//! implicit Runge–Kutta method solves for the stage increments
//! `Z_i = Y_i − y_n` (dimension `2 N s`):
//!
//! ```text
//! Z_i = h Σ_j a_ij F(t_n + c_j h, y_n + Z_j),      i = 1..s
//! y_{n+1} = y_n + Σ_j d_j Z_j,                      dᵀ = bᵀ A⁻¹
//! ```
//!
//! The last line is `y_n + h Σ b_j F(Y_j)` without evaluating `F` again.
//! The Hamiltonian of a model with `M(q)` is not separable, so no
//! partitioned shortcut applies: this is the general form. What the
//! methods conserve, and how the Newton iteration below stops and what it
//! costs, is told to users in the
//! [crate documentation](crate#implicit-methods-symmetric-and-when-symplectic).
//!
//! [`ImplicitMidpoint`]: super::ImplicitMidpoint
//! [`GaussLegendre`]: super::GaussLegendre

use nalgebra::{DMatrix, DVector, RealField, SMatrix, SVector};

use crate::driver::fixed::{FixedStep, FixedWalk};
use crate::driver::{Recorder, check_step_size, newton_noise_floor};
use crate::dynamics::acceleration_jacobians;
use crate::error::{IntegrationError, InvalidInput};
use crate::linalg::lu::Lu;
use crate::model::Lagrangian;
use crate::trajectory::State;

/// Butcher tableau of an implicit method, with `dᵀ = bᵀ A⁻¹` precomputed.
#[derive(Debug, Clone)]
pub struct Tableau<S> {
    pub(crate) a: DMatrix<S>,
    /// The weights: the step uses `d` instead, and the tests check `d`
    /// against them.
    #[cfg_attr(not(test), allow(dead_code))]
    pub(crate) b: DVector<S>,
    pub(crate) c: DVector<S>,
    pub(crate) d: DVector<S>,
}

impl<S: RealField + Copy> Tableau<S> {
    pub(crate) fn stages(&self) -> usize {
        self.c.len()
    }
}

/// The settings every fixed-step implicit method has.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings<S> {
    pub(crate) h: S,
    pub(crate) max_steps: usize,
    pub(crate) max_iterations: usize,
}

impl<S: RealField + Copy> Settings<S> {
    pub(crate) fn new(h: S) -> Self {
        Self {
            h,
            max_steps: 10_000_000,
            max_iterations: 20,
        }
    }
}

/// The walker of an implicit method of `tableau`, named `method` in
/// errors: the fixed-step loop around its stage solver, whose workspace is
/// allocated here, once per run (or per [`Stepper`](crate::stepper::Stepper)).
pub(crate) fn walker<S: RealField + Copy, const N: usize>(
    method: &'static str,
    tableau: Tableau<S>,
    settings: Settings<S>,
) -> Result<FixedWalk<S, StageSolver<S, N>>, InvalidInput<S>> {
    if settings.max_iterations == 0 {
        return Err(InvalidInput::NoNewtonIterations { method });
    }
    check_step_size(settings.h)?;
    let stages = StageSolver::new(tableau, settings.max_iterations);
    Ok(FixedWalk::new(stages, settings.h, settings.max_steps))
}

impl<S: RealField + Copy, const N: usize> FixedStep<S, N> for StageSolver<S, N> {
    fn step<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        t: S,
        (q, qdot): (&SVector<S, N>, &SVector<S, N>),
        h: S,
    ) -> Result<State<S, N>, IntegrationError<S, N>> {
        StageSolver::step(self, rec, model, t, q, qdot, h)
    }

    fn restart(&mut self) {
        StageSolver::restart(self);
    }
}

/// The Newton iteration stops once the scaled correction is below
/// `TOLERANCE · ε`: the stages then solve their equations to about the
/// rounding of `y` itself, so symmetry and quadratic invariants hold to
/// round-off rather than to a solver tolerance.
const TOLERANCE: f64 = 10.0;

/// A contraction rate above this means the Jacobian from the step start no
/// longer describes the stages well: evaluate it again, once per step.
const SLOW: f64 = 0.5;

/// The workspace of the stage system, allocated once per integration (or
/// per [`Stepper`](crate::stepper::Stepper)) so that a step allocates nothing. Stage
/// `j` occupies rows `2 N j .. 2 N (j + 1)` of the stage vectors: its `q`
/// part, then its `v` part.
pub struct StageSolver<S: RealField + Copy, const N: usize> {
    tableau: Tableau<S>,
    max_iterations: usize,
    /// Stage increments `Z`.
    z: DVector<S>,
    /// The previous step's `Z`, for the starting guess.
    z_prev: DVector<S>,
    /// The previous step's size; `None` before the first step.
    h_prev: Option<S>,
    /// `F` at the stages.
    f: DVector<S>,
    /// The residual, then the Newton correction in its place.
    delta: DVector<S>,
    /// `I − h A ⊗ J`, then its LU factors.
    lu: Lu<S>,
}

impl<S: RealField + Copy, const N: usize> StageSolver<S, N> {
    pub(crate) fn new(tableau: Tableau<S>, max_iterations: usize) -> Self {
        let dim = 2 * N * tableau.stages();
        Self {
            tableau,
            max_iterations,
            z: DVector::zeros(dim),
            z_prev: DVector::zeros(dim),
            h_prev: None,
            f: DVector::zeros(dim),
            delta: DVector::zeros(dim),
            lu: Lu::new(dim),
        }
    }

    /// Forgets the previous step, whose stages are the starting guess of
    /// the next: after the state or the model changed under a stepper.
    pub(crate) fn restart(&mut self) {
        self.h_prev = None;
    }

    /// One step of size `h` from `(t, q, v)`.
    pub(crate) fn step<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        t: S,
        q: &SVector<S, N>,
        v: &SVector<S, N>,
        h: S,
    ) -> Result<State<S, N>, IntegrationError<S, N>> {
        let diverged = |iterations| IntegrationError::NewtonDivergence {
            t,
            h,
            iterations,
            q: *q,
            qdot: *v,
        };
        // Simplified Newton: one Jacobian, at the step start, for all
        // iterations. Errors here are the model's, at a state on the
        // trajectory, and are reported as such.
        let a0 = rec.rhs(model, t, q, v)?;
        let (jq, jv) = acceleration_jacobians(model, t, q, v, &a0, &mut rec.stats)?;
        if !self.factor(h, &jq, &jv) {
            return Err(diverged(0));
        }
        self.starting_guess(h, v, &a0);

        let (tolerance, slow) = thresholds::<S>();
        let mut previous_norm: Option<S> = None;
        let mut refreshed = false;
        for iteration in 1..=self.max_iterations {
            // Past the starting guess, an iterate that breaks the model is
            // Newton's failure, not the model's.
            let evaluated = self.evaluate_stages(rec, model, t, q, v, h);
            if let Err(error) = evaluated {
                return Err(if iteration == 1 {
                    error
                } else {
                    diverged(iteration - 1)
                });
            }
            self.residual(h);
            self.lu.solve_in_place(&mut self.delta);
            rec.stats.linear_solves += 1;
            rec.stats.newton_iterations += 1;
            if !crate::linalg::all_finite(self.delta.as_slice()) {
                return Err(diverged(iteration));
            }
            self.z += &self.delta;
            let norm = self.scaled_norm(q, v);
            let Some(previous) = previous_norm.replace(norm) else {
                if norm <= tolerance {
                    return Ok(self.finish(q, v, h));
                }
                continue;
            };
            // At contraction rate θ the error left in Z after a correction
            // ‖ΔZ‖ is about θ / (1 − θ) ‖ΔZ‖ (Hairer & Wanner, Solving ODEs
            // II, §IV.8), which saves the iteration that would only confirm it.
            let rate = norm / previous;
            if rate < S::one() && norm * rate / (S::one() - rate) <= tolerance {
                return Ok(self.finish(q, v, h));
            }
            // A correction that no longer shrinks fast but is below the
            // noise of evaluating the residual: more iterations cannot make
            // the stages more accurate than the accelerations they are made
            // of, and would only stir the noise.
            if rate >= slow && norm <= newton_noise_floor(model, t, q) {
                return Ok(self.finish(q, v, h));
            }
            if rate >= slow && !refreshed {
                refreshed = true;
                if !self.refresh(rec, model, t, q, v, h) {
                    return Err(diverged(iteration));
                }
            } else if rate >= S::one() {
                // Growing corrections with the Jacobian already refreshed.
                return Err(diverged(iteration));
            }
        }
        Err(diverged(self.max_iterations))
    }

    /// Assembles and factors `I − h A ⊗ J` with `J = [[0, I], [∂a/∂q, ∂a/∂v]]`;
    /// `false` if it is singular.
    fn factor(&mut self, h: S, jq: &SMatrix<S, N, N>, jv: &SMatrix<S, N, N>) -> bool {
        let a = &self.tableau.a;
        let newton = self.lu.matrix_mut();
        newton.fill_with_identity();
        for i in 0..a.nrows() {
            for j in 0..a.ncols() {
                let ha = h * a[(i, j)];
                let (row, col) = (2 * N * i, 2 * N * j);
                for k in 0..N {
                    newton[(row + k, col + N + k)] -= ha;
                    for m in 0..N {
                        newton[(row + N + k, col + m)] -= ha * jq[(k, m)];
                        newton[(row + N + k, col + N + m)] -= ha * jv[(k, m)];
                    }
                }
            }
        }
        self.lu.factor().is_ok()
    }

    /// Evaluates the Jacobian again at the mean of the current stages, where
    /// the iteration actually is; `false` if the model fails there or the new
    /// Newton matrix is singular (Newton's failure, not the model's: the
    /// stages are not on the trajectory yet).
    fn refresh<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        t: S,
        q: &SVector<S, N>,
        v: &SVector<S, N>,
        h: S,
    ) -> bool {
        let s = self.tableau.stages();
        let weight = S::one() / nalgebra::convert::<f64, S>(s as f64);
        let (mut qm, mut vm) = (*q, *v);
        for j in 0..s {
            for k in 0..N {
                qm[k] += weight * self.z[2 * N * j + k];
                vm[k] += weight * self.z[2 * N * j + N + k];
            }
        }
        let tm = t + h * self.tableau.c.mean();
        let jacobians = rec
            .rhs(model, tm, &qm, &vm)
            .and_then(|am| acceleration_jacobians(model, tm, &qm, &vm, &am, &mut rec.stats));
        match jacobians {
            Ok((jq, jv)) => self.factor(h, &jq, &jv),
            Err(_) => false,
        }
    }

    /// The starting guess for `Z`: the previous step's collocation polynomial
    /// extrapolated over this step (error `O(h^{s+1})`, so Newton starts
    /// close), or Euler's `Z_i = c_i h F(y_n)` on the first step and after a
    /// step less than half as long (a sliver before a sample time), which a
    /// polynomial of degree `s` should not be stretched over.
    fn starting_guess(&mut self, h: S, v: &SVector<S, N>, a0: &SVector<S, N>) {
        let c = &self.tableau.c;
        let s = c.len();
        let two = S::one() + S::one();
        let Some(h_prev) = self.h_prev.filter(|&h_prev| h <= two * h_prev) else {
            for i in 0..s {
                let hc = h * c[i];
                for k in 0..N {
                    self.z[2 * N * i + k] = hc * v[k];
                    self.z[2 * N * i + N + k] = hc * a0[k];
                }
            }
            return;
        };
        // The previous step's collocation polynomial u, relative to that
        // step's start and in units of its length: u(0) = 0, u(c_j) = Z_j,
        // and u(1) = y_n − y_{n−1}. This step's stages sit at θ = 1 + r c_i,
        // so Z_i ≈ u(1 + r c_i) − u(1).
        let r = h / h_prev;
        let lagrange = |j: usize, theta: S| {
            let mut l = theta / c[j];
            for m in (0..s).filter(|&m| m != j) {
                l *= (theta - c[m]) / (c[j] - c[m]);
            }
            l
        };
        self.z.fill(S::zero());
        for j in 0..s {
            let at_end = lagrange(j, S::one());
            for i in 0..s {
                let weight = lagrange(j, S::one() + r * c[i]) - at_end;
                let (new, old) = (2 * N * i, 2 * N * j);
                for k in 0..2 * N {
                    self.z[new + k] += weight * self.z_prev[old + k];
                }
            }
        }
    }

    /// `F` at each stage `y_n + Z_j`, into `self.f`.
    fn evaluate_stages<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        t: S,
        q: &SVector<S, N>,
        v: &SVector<S, N>,
        h: S,
    ) -> Result<(), IntegrationError<S, N>> {
        for j in 0..self.tableau.stages() {
            let row = 2 * N * j;
            let qj = q + self.z.fixed_rows::<N>(row);
            let vj = v + self.z.fixed_rows::<N>(row + N);
            let aj = rec.rhs(model, t + self.tableau.c[j] * h, &qj, &vj)?;
            self.f.fixed_rows_mut::<N>(row).copy_from(&vj);
            self.f.fixed_rows_mut::<N>(row + N).copy_from(&aj);
        }
        Ok(())
    }

    /// `−Z + h (A ⊗ I) F`, into `self.delta`.
    fn residual(&mut self, h: S) {
        let a = &self.tableau.a;
        let dim = 2 * N;
        for i in 0..a.nrows() {
            for k in 0..dim {
                let mut sum = S::zero();
                for j in 0..a.ncols() {
                    sum += a[(i, j)] * self.f[dim * j + k];
                }
                self.delta[dim * i + k] = h * sum - self.z[dim * i + k];
            }
        }
    }

    /// The largest correction relative to the size of what it corrects, per
    /// block: `|ΔZ_q| / max(|q_n|, |q_n + Z_q|)` in the max norm over all
    /// stages, and likewise for `v`. One scale per block rather than per
    /// component, so that a coordinate passing through zero is not asked for
    /// more digits than the rounding of its neighbours allows; a block that
    /// is zero throughout has no scale and is measured absolutely.
    fn scaled_norm(&self, q: &SVector<S, N>, v: &SVector<S, N>) -> S {
        let dim = 2 * N;
        let mut norm = S::zero();
        for (offset, y) in [(0, q), (N, v)] {
            let (mut scale, mut correction) = (y.amax(), S::zero());
            for j in 0..self.tableau.stages() {
                for k in 0..N {
                    let row = dim * j + offset + k;
                    scale = scale.max((y[k] + self.z[row]).abs());
                    correction = correction.max(self.delta[row].abs());
                }
            }
            if scale == S::zero() {
                scale = S::one();
            }
            norm = norm.max(correction / scale);
        }
        norm
    }

    /// `y_{n+1} = y_n + Σ d_j Z_j`, and `Z` kept for the next starting guess.
    fn finish(&mut self, q: &SVector<S, N>, v: &SVector<S, N>, h: S) -> State<S, N> {
        let (mut q_next, mut v_next) = (*q, *v);
        for j in 0..self.tableau.stages() {
            let (row, d) = (2 * N * j, self.tableau.d[j]);
            q_next += self.z.fixed_rows::<N>(row) * d;
            v_next += self.z.fixed_rows::<N>(row + N) * d;
        }
        self.z_prev.copy_from(&self.z);
        self.h_prev = Some(h);
        (q_next, v_next)
    }
}

/// `(TOLERANCE ε, SLOW)` in the model's scalar type.
fn thresholds<S: RealField + Copy>() -> (S, S) {
    let eps = S::default_epsilon();
    (eps * nalgebra::convert(TOLERANCE), nalgebra::convert(SLOW))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::Tableau;

    /// Checks a Gauss tableau against the conditions that define it and the
    /// properties the docs claim, each to a few ε (entries are O(1) sums of
    /// a handful of rounded terms).
    pub(crate) fn assert_collocation_conditions(tableau: &Tableau<f64>) {
        const TOL: f64 = 1e-15;
        let (a, b, c, d) = (&tableau.a, &tableau.b, &tableau.c, &tableau.d);
        let s = tableau.stages();
        let close = |x: f64, y: f64, what: &str| assert!((x - y).abs() < TOL, "{what}: {x} vs {y}");
        // B(2s): the quadrature is exact for polynomials of degree 2s − 1.
        for k in 1..=2 * s {
            let sum: f64 = (0..s).map(|i| b[i] * c[i].powi(k as i32 - 1)).sum();
            close(sum, 1.0 / k as f64, &format!("B({k})"));
        }
        // C(s): each stage is the collocation polynomial's integral.
        for i in 0..s {
            for k in 1..=s {
                let sum: f64 = (0..s).map(|j| a[(i, j)] * c[j].powi(k as i32 - 1)).sum();
                close(
                    sum,
                    c[i].powi(k as i32) / k as f64,
                    &format!("C({k}), stage {i}"),
                );
            }
        }
        for i in 0..s {
            // dᵀ A = bᵀ, so y_n + Σ d_j Z_j = y_n + h Σ b_j F(Y_j).
            let sum: f64 = (0..s).map(|j| d[j] * a[(j, i)]).sum();
            close(sum, b[i], &format!("dᵀA = bᵀ, column {i}"));
            for j in 0..s {
                // Conservation of quadratic invariants (Cooper 1987).
                let m = b[i] * a[(i, j)] + b[j] * a[(j, i)] - b[i] * b[j];
                close(
                    m,
                    0.0,
                    &format!("b_i a_ij + b_j a_ji = b_i b_j, ({i}, {j})"),
                );
                // Symmetry: the adjoint method has the same tableau.
                let adjoint = b[j] - a[(s - 1 - i, s - 1 - j)];
                close(a[(i, j)], adjoint, &format!("symmetry, ({i}, {j})"));
            }
        }
    }
}
