//! The named `let`s a model exposes (`LETS`, `lets`, `let_value`): the
//! positions a user wrote, at any state, for drawing a trajectory without
//! writing the kinematics again.

use lagrange::models::{Chain, DoublePendulum, FourBar};
use lagrange::nalgebra::{SVector, Vector2};

#[test]
fn the_double_pendulums_positions_by_name() {
    let p = DoublePendulum::new(1.0, 0.7, 1.2, 0.8, 9.81);
    assert_eq!(DoublePendulum::<f64>::LETS, ["x1", "y1", "x2", "y2"]);
    let (q, v) = (Vector2::new(0.4f64, -1.1), Vector2::new(0.3, 2.0));
    let [x1, y1, x2, y2] = p.lets(0.0, &q, &v);
    // The same formulas as the model's `let`s, written again here: the
    // generated code computes them with shared subexpressions and the
    // same operations, so they agree to a rounding or two.
    let (ex1, ey1) = (p.l1 * q[0].sin(), -p.l1 * q[0].cos());
    let (ex2, ey2) = (ex1 + p.l2 * q[1].sin(), ey1 - p.l2 * q[1].cos());
    for (got, want) in [(x1, ex1), (y1, ey1), (x2, ex2), (y2, ey2)] {
        assert!((got - want).abs() <= 4.0 * f64::EPSILON, "{got} vs {want}");
    }
    assert_eq!(p.let_value("x2", 0.0, &q, &v), Some(x2));
    assert_eq!(p.let_value("z", 0.0, &q, &v), None);
}

#[test]
fn an_indexed_let_is_named_element_by_element() {
    const N: usize = Chain::<f64>::DOF;
    let names = Chain::<f64>::LETS;
    assert_eq!(names.len(), 2 * N);
    assert_eq!((names[0], names[N - 1], names[N]), ("x[0]", "x[4]", "y[0]"));
    let chain = Chain::new([0.2; N], [0.3; N]);
    let q = SVector::<f64, N>::from_fn(|i, _| 0.1 * i as f64);
    let v = SVector::<f64, N>::zeros();
    // The tip: the sum of the links, as the model's `let x[i]` says.
    let tip_x: f64 = (0..N).map(|i| 0.3 * q[i].sin()).sum();
    let got = chain.let_value("x[4]", 0.0, &q, &v).unwrap();
    assert!(
        (got - tip_x).abs() <= 8.0 * f64::EPSILON,
        "{got} vs {tip_x}"
    );
}

#[test]
fn a_constrained_models_coupler_midpoint_comes_from_its_lets() {
    // The coupler's midpoint `(x2, y2)` from the crank side (the model's
    // `let`s) is, on the constraint manifold, also the midpoint of the
    // crank pin and the rocker pin `(d + c cos θ3, c sin θ3)`.
    assert_eq!(FourBar::<f64>::LETS, ["xa", "ya", "x2", "y2"]);
    let four_bar = FourBar::crank_rocker();
    let (q, v) = four_bar
        .state(0.9, 2.0)
        .expect("a crank angle the loop closes at");
    let [xa, ya, x2, y2] = four_bar.lets(0.0, &q, &v);
    let (xc, yc) = (
        four_bar.d + four_bar.c * q[2].cos(),
        four_bar.c * q[2].sin(),
    );
    // `state` closes the loop to rounding (1e-15 m); the two midpoints
    // then agree to a few roundings of the 0.6 m lengths.
    let err = ((xa + xc) / 2.0 - x2)
        .abs()
        .max(((ya + yc) / 2.0 - y2).abs());
    assert!(err < 1e-14, "{err}");
}
