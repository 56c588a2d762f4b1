//! The cart-pole's linearization against its hand-derived closed form at the
//! upright and hanging equilibria, and against differences of the runtime's
//! own right-hand side anywhere.

use crate::support::closed_form::{rng, uniform};
use lagrange::analysis::{Derivatives, linearize_with_inputs};
use lagrange::dynamics::acceleration;
use lagrange::models::CartPole;
use lagrange::nalgebra::{Vector1, Vector2};

fn model() -> CartPole {
    CartPole::new(1.3, 0.4, 0.7, 9.81)
}

/// At rest with no force, θ = 0 (upright, `cos θ = 1`) or π (hanging,
/// `cos θ = −1`): with `s = cos θ`, `M = [[mc + mp, mp l s], [mp l s,
/// mp l²]]`, `det M = mc mp l²`, and `∂f/∂θ = (0, mp g l s)`,
/// `∂f/∂u = (1, 0)`, so
///
/// ```text
/// ∂ẍ/∂θ = −mp g / mc,   ∂θ̈/∂θ = s (mc + mp) g / (mc l),
/// ∂ẍ/∂u = 1 / mc,       ∂θ̈/∂u = −s / (mc l),
/// ```
///
/// every other entry of the lower blocks zero. Both sides are a few flops
/// from the same parameters, so they agree to rounding: 1e-12 relative to
/// the largest entry leaves three orders of margin over ~1e-15.
#[test]
fn cart_pole_linearization_matches_the_closed_form_upright_and_hanging() {
    let p = model();
    for (theta, s) in [(0.0, 1.0), (std::f64::consts::PI, -1.0)] {
        let q = Vector2::new(0.3, theta);
        let lin =
            linearize_with_inputs(&p, 0.0, &q, &Vector2::zeros(), &Vector1::new(0.0)).unwrap();
        assert_eq!(lin.state.derivatives, Derivatives::Exact);
        let (a, b) = (lin.state.state_matrix(), lin.input_matrix());
        let mut want_a = lagrange::nalgebra::DMatrix::<f64>::zeros(4, 4);
        want_a[(0, 2)] = 1.0;
        want_a[(1, 3)] = 1.0;
        want_a[(2, 1)] = -p.mp * p.g / p.mc;
        want_a[(3, 1)] = s * (p.mc + p.mp) * p.g / (p.mc * p.l);
        let want_b = lagrange::nalgebra::DMatrix::from_column_slice(
            4,
            1,
            &[0.0, 0.0, 1.0 / p.mc, -s / (p.mc * p.l)],
        );
        let scale = want_a.amax().max(want_b.amax());
        let (ea, eb) = ((&a - &want_a).amax(), (&b - &want_b).amax());
        println!("θ = {theta:.3}: |A − A_closed| {ea:.1e}, |B − B_closed| {eb:.1e}");
        assert!(ea <= 1e-12 * scale && eb <= 1e-12 * scale, "A {a} B {b}");
    }
}

/// Anywhere (random angle, rates and force, not an equilibrium) the exact
/// `A` and `B` agree with central differences of the runtime's own
/// `q̈ = acceleration(..)`: steps `h = 1e-5` give a truncation error
/// `h² |q̈'''| / 6 ≈ 1e-10 · |q̈'''|` and a rounding error
/// `ε |q̈| / h ≈ 2e-11 · |q̈|`; with `|q̈| ≲ 1e2` and its third
/// derivatives of the same order here, 1e-6 absolute bounds both with two
/// orders to spare, while a missing term (the `∂(M q̈)/∂q` of a moving
/// state, `mp l θ̇²`, …) is of order one.
#[test]
fn cart_pole_linearization_matches_differences_of_the_right_hand_side_anywhere() {
    let p = model();
    let mut rng = rng(12);
    let h = 1e-5;
    let mut worst = 0.0f64;
    for _ in 0..20 {
        let q = Vector2::new(uniform(&mut rng, -1.0, 1.0), uniform(&mut rng, -3.0, 3.0));
        let v = Vector2::new(uniform(&mut rng, -2.0, 2.0), uniform(&mut rng, -4.0, 4.0));
        let u = Vector1::new(uniform(&mut rng, -5.0, 5.0));
        let lin = linearize_with_inputs(&p, 0.0, &q, &v, &u).unwrap();
        let (a, b) = (lin.state.state_matrix(), lin.input_matrix());
        let qdd = |q: &Vector2<f64>, v: &Vector2<f64>, u: f64| {
            acceleration(&p.with_inputs(&Vector1::new(u)), 0.0, q, v).unwrap()
        };
        for k in 0..5 {
            let (mut qp, mut qm, mut vp, mut vm, mut up, mut um) = (q, q, v, v, u[0], u[0]);
            match k {
                0 | 1 => {
                    qp[k] += h;
                    qm[k] -= h;
                }
                2 | 3 => {
                    vp[k - 2] += h;
                    vm[k - 2] -= h;
                }
                _ => {
                    up += h;
                    um -= h;
                }
            }
            let column = (qdd(&qp, &vp, up) - qdd(&qm, &vm, um)) / (2.0 * h);
            for i in 0..2 {
                let exact = if k < 4 { a[(2 + i, k)] } else { b[(2 + i, 0)] };
                worst = worst.max((exact - column[i]).abs());
            }
        }
    }
    println!("largest gap between exact A, B and differences at 20 states: {worst:.1e}");
    assert!(worst < 1e-6, "{worst:.2e}");
}

lagrange::lagrangian! {
    /// A bob on a rod in x, y, driven by forces `fx`, `fy` along the axes.
    struct PushedPendulum {
        coordinates: x, y;
        parameters: m, l, g;
        inputs: fx, fy;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*y;
        forces: x = fx, y = fy;
        constraints: rod: x^2 + y^2 = l^2;
    }
}

/// On the constraint manifold, `B` keeps only the inputs' tangential part:
/// at angle θ from the downward vertical the bob moves along the circle,
/// unit tangent `(cos θ, sin θ)`, so in the arc coordinate `z` (the
/// orthonormal basis, up to its sign) `z̈ = (fx cos θ + fy sin θ) / m`, as
/// the θ pendulum's `l θ̈` says. The multiplier solve is exact, so the
/// entries agree to rounding (1e-12 of `1/m`).
#[test]
fn pushed_pendulum_input_matrix_on_its_manifold_is_the_tangential_force() {
    use lagrange::analysis::linearize_on_manifold_with_inputs;
    let (m, l) = (1.7, 0.9);
    let model: PushedPendulum = PushedPendulum::new(m, l, 9.81);
    for theta in [0.0f64, 0.4, -1.1, 2.5] {
        let (s, c) = theta.sin_cos();
        let q = Vector2::new(l * s, -l * c);
        let lin = linearize_on_manifold_with_inputs(
            &model,
            0.0,
            &q,
            &Vector2::zeros(),
            &Vector2::zeros(),
        )
        .unwrap();
        let b = &lin.input_matrix;
        assert_eq!((b.nrows(), b.ncols()), (2, 2));
        assert!(b[(0, 0)] == 0.0 && b[(0, 1)] == 0.0);
        let err_x = (b[(1, 0)].abs() - c.abs() / m).abs();
        let err_y = (b[(1, 1)].abs() - s.abs() / m).abs();
        // The two entries share the sign of the basis direction.
        let same = (b[(1, 0)] * c + b[(1, 1)] * s).abs() - 1.0 / m;
        println!("θ = {theta}: |B_x| err {err_x:.1e}, |B_y| err {err_y:.1e}, tangent {same:.1e}");
        assert!(err_x < 1e-12 / m && err_y < 1e-12 / m && same.abs() < 1e-12 / m);
    }
}
