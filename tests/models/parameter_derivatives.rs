//! `#[lagrange(parameter_derivatives)]`: `∂M/∂p`, `∂f/∂p` and the
//! residual's `∂r/∂p`, derived at compile time, against forward-mode dual
//! numbers (num-dual's `Dual64`) carried through the generated `M` and `f`
//! themselves, one parameter scalar at a time: the same derivatives by
//! another road, on the damped double pendulum (`lagrange::models`) and the
//! 5-link chain (an indexed model, its parameters `m[N]` and `l[N]`); and
//! both models' regressors against `M q̈ − f`.

pub(crate) use lagrange::models::DampedDoublePendulum;
use lagrange::nalgebra::{SMatrix, SVector};
use lagrange::prelude::*;
use num_dual::Dual64;
use rand::{Rng, SeedableRng, rngs::StdRng};

lagrangian! {
    /// The 5-link chain of point masses in absolute angles, its regressor in
    /// every mass and length.
    #[lagrange(jacobians, parameter_derivatives, regressor(m, l))]
    pub struct ChainOfFive {
        const N = 5;
        coordinates: theta[N];
        parameters: m[N], l[N];
        constants: g = 9.81;
        let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));
        let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));
        kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2));
        potential: sum(i in 0..N, m[i]*g*y[i]);
    }
}

/// A model built from its parameter scalars in the order of
/// `PARAMETER_SCALARS`, in `f64` or in dual numbers.
pub(crate) trait FromScalars<S>: Sized {
    fn from_scalars(p: &[S]) -> Self;
}

impl<S: lagrange::nalgebra::RealField + Copy> FromScalars<S> for DampedDoublePendulum<S> {
    fn from_scalars(p: &[S]) -> Self {
        Self::new(p[0], p[1], p[2], p[3], p[4], p[5], p[6])
    }
}

impl<S: lagrange::nalgebra::RealField + Copy> FromScalars<S> for ChainOfFive<S> {
    fn from_scalars(p: &[S]) -> Self {
        Self::new(
            std::array::from_fn(|i| p[i]),
            std::array::from_fn(|i| p[5 + i]),
        )
    }
}

/// The generated parameter derivatives of one model at one state.
struct Generated<const N: usize, const P: usize> {
    mass: [SMatrix<f64, N, N>; P],
    forcing: SMatrix<f64, N, P>,
    residual: SMatrix<f64, N, P>,
}

/// Every generated parameter derivative against the dual numbers' at
/// random parameters and states. Both are exact derivatives evaluated in
/// f64 along different sequences of some hundred operations on values of
/// O(1) to O(100) (a chain's `M` sums five masses times lengths squared):
/// each carries rounding of a few hundred ulps of the largest entry at
/// most, so 1e-13 relative to the largest entry of each derivative bounds
/// their difference, and a wrong term (an O(1) error) fails.
fn check<D, const N: usize, const P: usize>(
    generated: impl Fn(
        &[f64],
        f64,
        &SVector<f64, N>,
        &SVector<f64, N>,
        &SVector<f64, N>,
    ) -> Generated<N, P>,
    ranges: [(f64, f64); P],
    seed: u64,
) where
    D: Lagrangian<N, Scalar = Dual64> + FromScalars<Dual64>,
{
    let mut rng = StdRng::seed_from_u64(seed);
    for _ in 0..20 {
        let p: [f64; P] = std::array::from_fn(|k| rng.gen_range(ranges[k].0..ranges[k].1));
        let t: f64 = rng.gen_range(0.0..10.0);
        let q = SVector::<f64, N>::from_fn(|_, _| rng.gen_range(-3.0..3.0));
        let v = SVector::<f64, N>::from_fn(|_, _| rng.gen_range(-3.0..3.0));
        let a = SVector::<f64, N>::from_fn(|_, _| rng.gen_range(-3.0..3.0));
        let g = generated(&p, t, &q, &v, &a);
        let dual = |x: f64| Dual64::new(x, 0.0);
        let (td, qd, vd, ad) = (dual(t), q.map(dual), v.map(dual), a.map(dual));
        for k in 0..P {
            let seeded: Vec<Dual64> = (0..P)
                .map(|j| Dual64::new(p[j], if j == k { 1.0 } else { 0.0 }))
                .collect();
            let model = D::from_scalars(&seeded);
            let mass = model.mass_matrix(td, &qd);
            let forcing = model.forcing(td, &qd, &vd);
            let residual = mass * ad - forcing;
            let dm = mass.map(|x| x.eps);
            let df = forcing.map(|x| x.eps);
            let dr = residual.map(|x| x.eps);
            let close = |what: &str, exact: f64, by_duals: f64, scale: f64| {
                assert!(
                    (exact - by_duals).abs() <= 1e-13 * (1.0 + scale),
                    "{what} by parameter {k}: generated {exact:e}, dual numbers {by_duals:e}"
                );
            };
            let scale = g.mass[k].amax();
            for (exact, by_duals) in g.mass[k].iter().zip(dm.iter()) {
                close("∂M/∂p", *exact, *by_duals, scale);
            }
            let scale = g.forcing.column(k).amax();
            for (exact, by_duals) in g.forcing.column(k).iter().zip(df.iter()) {
                close("∂f/∂p", *exact, *by_duals, scale);
            }
            let scale = g.residual.column(k).amax();
            for (exact, by_duals) in g.residual.column(k).iter().zip(dr.iter()) {
                close("∂r/∂p", *exact, *by_duals, scale);
            }
        }
    }
}

#[test]
fn the_double_pendulums_parameter_derivatives_match_dual_numbers() {
    assert_eq!(
        DampedDoublePendulum::<f64>::PARAMETER_SCALARS,
        ["m1", "m2", "l1", "l2", "g", "c1", "c2"]
    );
    check::<DampedDoublePendulum<Dual64>, 2, 7>(
        |p, t, q, v, a| {
            let m = DampedDoublePendulum::from_scalars(p);
            Generated {
                mass: m.mass_matrix_parameter_derivatives(t, q),
                forcing: m.forcing_parameter_jacobian(t, q, v),
                residual: m.residual_parameter_jacobian(t, q, v, a),
            }
        },
        [
            (0.5, 2.0),
            (0.5, 2.0),
            (0.5, 2.0),
            (0.5, 2.0),
            (5.0, 15.0),
            (0.0, 1.0),
            (0.0, 1.0),
        ],
        1,
    );
}

#[test]
fn the_chains_parameter_derivatives_match_dual_numbers() {
    assert_eq!(
        ChainOfFive::<f64>::PARAMETER_SCALARS,
        [
            "m[0]", "m[1]", "m[2]", "m[3]", "m[4]", "l[0]", "l[1]", "l[2]", "l[3]", "l[4]"
        ]
    );
    check::<ChainOfFive<Dual64>, 5, 10>(
        |p, t, q, v, a| {
            let m = ChainOfFive::from_scalars(p);
            Generated {
                mass: m.mass_matrix_parameter_derivatives(t, q),
                forcing: m.forcing_parameter_jacobian(t, q, v),
                residual: m.residual_parameter_jacobian(t, q, v, a),
            }
        },
        [(0.5, 2.0); 10],
        2,
    );
}

/// The derivatives are of the equations the model integrates: with the
/// masses scaled by one factor and no damping, `M` and `f` scale by it, so
/// `∂M/∂m · m` summed over the masses is `M` itself, and likewise for `f`
/// (Euler's theorem for functions homogeneous of degree one).
#[test]
fn mass_derivatives_sum_to_the_homogeneous_whole() {
    let model = ChainOfFive::new([1.0, 1.2, 0.8, 1.5, 0.9], [1.0, 0.7, 1.3, 0.6, 1.1]);
    let q = SVector::<f64, 5>::from([0.3, -0.5, 1.1, 0.2, -0.9]);
    let v = SVector::<f64, 5>::from([0.4, 1.0, -0.6, 0.8, -1.2]);
    let dm = model.mass_matrix_parameter_derivatives(0.0, &q);
    let df = model.forcing_parameter_jacobian(0.0, &q, &v);
    let (mut m, mut f) = (SMatrix::<f64, 5, 5>::zeros(), SVector::<f64, 5>::zeros());
    for (k, (dm_k, mass)) in dm.iter().zip(model.m).enumerate() {
        m += dm_k * mass;
        f += df.column(k) * mass;
    }
    // Sums of five products of O(10) values: rounding of a few ulps.
    assert!((m - model.mass_matrix(0.0, &q)).amax() <= 1e-13 * m.amax());
    assert!((f - model.forcing(0.0, &q, &v)).amax() <= 1e-13 * (1.0 + f.amax()));
}

lagrangian! {
    /// A bob on a rod from a pivot driven along x: a rheonomic constraint
    /// whose every level (`φ`, `φ̇`, `G q̈ + γ`) depends on the parameters.
    #[lagrange(parameter_derivatives)]
    pub struct DrivenRodPendulum {
        coordinates: x, y;
        parameters: m, l, g, a, w;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*y;
        constraints: rod: (x - a*sin(w*t))^2 + y^2 = l^2;
    }
}

/// The constraints' parameter derivatives against dual numbers through the
/// generated `φ`, `φ̇`, `G` and `γ`, at random parameters and states (on
/// the constraint or off it: the derivatives hold everywhere). The same
/// bound as above: exact derivatives in f64 along different roads, a few
/// ulps of values of O(10) to O(100).
#[test]
fn the_constraints_parameter_derivatives_match_dual_numbers() {
    let mut rng = StdRng::seed_from_u64(3);
    for _ in 0..20 {
        let p: [f64; 5] = std::array::from_fn(|_| rng.gen_range(0.5..2.0));
        let t: f64 = rng.gen_range(0.0..10.0);
        let q = SVector::<f64, 2>::from_fn(|_, _| rng.gen_range(-2.0..2.0));
        let v = SVector::<f64, 2>::from_fn(|_, _| rng.gen_range(-2.0..2.0));
        let a = SVector::<f64, 2>::from_fn(|_, _| rng.gen_range(-2.0..2.0));
        let model = DrivenRodPendulum::new(p[0], p[1], p[2], p[3], p[4]);
        let by = [
            model.constraint_parameter_jacobian(t, &q),
            model.constraint_velocity_parameter_jacobian(t, &q, &v),
            model.constraint_acceleration_parameter_jacobian(t, &q, &v, &a),
        ];
        let dual = |x: f64| Dual64::new(x, 0.0);
        let (td, qd, vd, ad) = (dual(t), q.map(dual), v.map(dual), a.map(dual));
        for k in 0..5 {
            let s: [Dual64; 5] =
                std::array::from_fn(|j| Dual64::new(p[j], if j == k { 1.0 } else { 0.0 }));
            let d = DrivenRodPendulum::new(s[0], s[1], s[2], s[3], s[4]);
            let levels = [
                d.constraints(td, &qd)[0],
                d.constraint_velocities(td, &qd, &vd)[0],
                (d.constraint_jacobian(td, &qd) * ad + d.constraint_bias(td, &qd, &vd))[0],
            ];
            for (level, (exact, by_duals)) in by.iter().zip(levels).enumerate() {
                let (exact, by_duals) = (exact[(0, k)], by_duals.eps);
                assert!(
                    (exact - by_duals).abs() <= 1e-13 * (1.0 + exact.abs().max(by_duals.abs())),
                    "level {level}, parameter {k}: generated {exact:e}, dual numbers {by_duals:e}"
                );
            }
        }
    }
}

/// `Y π + r₀ = M q̈ − f` at random states and parameters. Both sides are
/// sums of a few dozen products of O(1) to O(100) values evaluated along
/// different orders: they agree to a few hundred ulps of the largest
/// term, 1e-13 relative to `1 + |M q̈| + |f|`; a wrong or missing column
/// is an O(1) error.
fn regressor_reproduces_the_residual<L, const N: usize, const K: usize>(
    make: impl Fn(&mut StdRng) -> L,
    regressor: impl Fn(
        &L,
        &SVector<f64, N>,
        &SVector<f64, N>,
        &SVector<f64, N>,
    ) -> (SMatrix<f64, N, K>, SVector<f64, N>),
    parameters: impl Fn(&L) -> SVector<f64, K>,
    seed: u64,
) where
    L: Lagrangian<N, Scalar = f64>,
{
    let mut rng = StdRng::seed_from_u64(seed);
    for _ in 0..20 {
        let model = make(&mut rng);
        let q = SVector::<f64, N>::from_fn(|_, _| rng.gen_range(-3.0..3.0));
        let v = SVector::<f64, N>::from_fn(|_, _| rng.gen_range(-3.0..3.0));
        let a = SVector::<f64, N>::from_fn(|_, _| rng.gen_range(-3.0..3.0));
        let (m, f) = model.mass_matrix_and_forcing(0.0, &q, &v);
        let residual = m * a - f;
        let (y, offset) = regressor(&model, &q, &v, &a);
        let linear = y * parameters(&model) + offset;
        let scale = 1.0 + (m * a).amax() + f.amax();
        assert!(
            (linear - residual).amax() <= 1e-13 * scale,
            "Y π + r₀ = {linear}, M q̈ − f = {residual}"
        );
    }
}

#[test]
fn the_double_pendulums_regressor_is_linear_in_its_masses_and_dampers() {
    assert_eq!(
        DampedDoublePendulum::<f64>::REGRESSOR_PARAMETERS,
        ["m1", "m2", "c1", "c2"]
    );
    regressor_reproduces_the_residual(
        |rng| {
            let p: Vec<f64> = (0..7).map(|_| rng.gen_range(0.5..2.0)).collect();
            DampedDoublePendulum::from_scalars(&p)
        },
        |m, q, v, a| (m.regressor(0.0, q, v, a), m.regressor_offset(0.0, q, v, a)),
        |m| m.regressor_parameters(),
        3,
    );
}

/// Every mass and length unknown: the chain's base parameters, `l_i l_j`
/// times the mass beyond `max(i, j)` (15) and `l_i` times the mass beyond
/// `i` for gravity (5), each the sum of the products whose columns
/// coincide.
#[test]
fn the_chains_regressor_is_in_its_base_parameters() {
    let names = ChainOfFive::<f64>::REGRESSOR_PARAMETERS;
    assert_eq!(names.len(), 20);
    assert!(
        names.contains(&"m[3]*l[0]*l[3] + m[4]*l[0]*l[3]"),
        "{names:?}"
    );
    regressor_reproduces_the_residual(
        |rng| {
            let p: Vec<f64> = (0..10).map(|_| rng.gen_range(0.5..2.0)).collect();
            ChainOfFive::from_scalars(&p)
        },
        |m, q, v, a| (m.regressor(0.0, q, v, a), m.regressor_offset(0.0, q, v, a)),
        |m| m.regressor_parameters(),
        4,
    );
}
