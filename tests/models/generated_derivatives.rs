//! What the macro generates beyond M and f: the momenta, ∂L/∂q and the
//! non-conservative forces (for variational integrators), and on request the
//! exact Jacobians of the residual `r = M q̈ − f` (for implicit integrators).

use lagrange::Stats;
use lagrange::nalgebra::{SMatrix, Vector2};
use lagrange::prelude::*;
use rand::{Rng, SeedableRng, rngs::StdRng};

lagrangian! {
    /// A double pendulum hanging from a support driven along x (rheonomic),
    /// with a damper on the first joint and a torque on the second.
    #[lagrange(jacobians)]
    pub struct DrivenDoublePendulum {
        coordinates: theta1, theta2;
        parameters: m1, m2, l1, l2, g, a, w, c, tau;
        let xs = a*cos(w*t);
        let x1 = xs + l1*sin(theta1);
        let y1 = -l1*cos(theta1);
        let x2 = x1 + l2*sin(theta2);
        let y2 = y1 - l2*cos(theta2);
        kinetic: m1/2*(dot(x1)^2 + dot(y1)^2) + m2/2*(dot(x2)^2 + dot(y2)^2);
        potential: m1*g*y1 + m2*g*y2;
        dissipation: c/2*dot(theta1)^2;
        forces: theta2 = tau*sin(t)*dot(theta2)^2;
    }
}

fn model(rng: &mut StdRng) -> DrivenDoublePendulum {
    let mut p = || rng.gen_range(0.5..2.0);
    DrivenDoublePendulum::new(p(), p(), p(), p(), 9.81, p(), p(), p(), p())
}

fn state(rng: &mut StdRng) -> (f64, Vector2<f64>, Vector2<f64>, Vector2<f64>) {
    let mut x = || rng.gen_range(-2.0..2.0);
    (
        x(),
        Vector2::new(x(), x()),
        Vector2::new(x(), x()),
        Vector2::new(x(), x()),
    )
}

fn residual(
    m: &DrivenDoublePendulum,
    t: f64,
    q: &Vector2<f64>,
    v: &Vector2<f64>,
    a: &Vector2<f64>,
) -> Vector2<f64> {
    m.mass_matrix(t, q) * a - m.forcing(t, q, v)
}

/// Central differences with step h = 1e-6 on O(1)–O(10) values: truncation
/// ~h²·|r'''| ~ 1e-11, round-off ~eps·|r|/h ~ 1e-9; 1e-6 relative to the
/// Jacobian's scale separates any wrong entry (an O(1) error) from both.
#[test]
fn exact_residual_jacobians_match_central_differences() {
    let mut rng = StdRng::seed_from_u64(7);
    let h = 1e-6;
    for _ in 0..50 {
        let m = model(&mut rng);
        let (t, q, v, a) = state(&mut rng);
        let (jq, jv) = m.residual_jacobians(t, &q, &v, &a);
        let mut fd_q = SMatrix::<f64, 2, 2>::zeros();
        let mut fd_v = SMatrix::<f64, 2, 2>::zeros();
        for k in 0..2 {
            let e = Vector2::ith(k, h);
            fd_q.set_column(
                k,
                &((residual(&m, t, &(q + e), &v, &a) - residual(&m, t, &(q - e), &v, &a))
                    / (2.0 * h)),
            );
            fd_v.set_column(
                k,
                &((residual(&m, t, &q, &(v + e), &a) - residual(&m, t, &q, &(v - e), &a))
                    / (2.0 * h)),
            );
        }
        let scale = 1.0 + jq.amax().max(jv.amax());
        assert!(
            (jq - fd_q).amax() <= 1e-6 * scale,
            "∂r/∂q\n{jq}\nvs\n{fd_q}"
        );
        assert!(
            (jv - fd_v).amax() <= 1e-6 * scale,
            "∂r/∂q̇\n{jv}\nvs\n{fd_v}"
        );
    }
}

/// `f = ∂L/∂q − (∂p/∂q) q̇ − ∂p/∂t + Q_nc` must hold with the generated p,
/// ∂L/∂q and Q_nc; ∂p/∂q and ∂p/∂t by central differences (error ~1e-9, so
/// 1e-6 of the scale). Also `p = M q̇ + p(q̇ = 0)`: T is quadratic in q̇.
#[test]
fn momenta_gradient_and_nonconservative_forces_rebuild_the_forcing() {
    let mut rng = StdRng::seed_from_u64(11);
    let h = 1e-6;
    for _ in 0..50 {
        let m = model(&mut rng);
        let (t, q, v, _) = state(&mut rng);
        let p = m.momentum(t, &q, &v);
        let p0 = m.momentum(t, &q, &Vector2::zeros());
        // Linear in q̇ up to round-off of O(10) terms.
        assert!((p - (m.mass_matrix(t, &q) * v + p0)).amax() <= 1e-12 * (1.0 + p.amax()));
        let mut dp_dq_v = Vector2::zeros();
        for k in 0..2 {
            let e = Vector2::ith(k, h);
            let dp = (m.momentum(t, &(q + e), &v) - m.momentum(t, &(q - e), &v)) / (2.0 * h);
            dp_dq_v += dp * v[k];
        }
        let dp_dt = (m.momentum(t + h, &q, &v) - m.momentum(t - h, &q, &v)) / (2.0 * h);
        let rebuilt = m.lagrangian_gradient(t, &q, &v) - dp_dq_v - dp_dt
            + m.nonconservative_forces(t, &q, &v);
        let f = m.forcing(t, &q, &v);
        assert!(
            (rebuilt - f).amax() <= 1e-6 * (1.0 + f.amax()),
            "{rebuilt} vs {f}"
        );
    }
}

/// The runtime's acceleration Jacobians from the exact residual Jacobians
/// agree with its forward-difference fallback (error ~√eps ≈ 1e-8 of the
/// scale, so 1e-5), and the exact path costs no right-hand side.
#[test]
fn runtime_uses_exact_jacobians_when_the_model_has_them() {
    use lagrange::dynamics::acceleration;
    use lagrange::dynamics::acceleration_jacobians;

    let mut rng = StdRng::seed_from_u64(3);
    let m = model(&mut rng);
    let (t, q, v, _) = state(&mut rng);
    let a = acceleration(&m, t, &q, &v).unwrap();
    let mut exact_stats = Stats::default();
    let (eq, ev) = acceleration_jacobians(&m, t, &q, &v, &a, &mut exact_stats).unwrap();
    let mut fd_stats = Stats::default();
    let (fq, fv) =
        acceleration_jacobians(&m.without_jacobians(), t, &q, &v, &a, &mut fd_stats).unwrap();
    let scale = 1.0 + eq.amax().max(ev.amax());
    assert!((eq - fq).amax() <= 1e-5 * scale, "{eq} vs {fq}");
    assert!((ev - fv).amax() <= 1e-5 * scale, "{ev} vs {fv}");
    assert_eq!(exact_stats.rhs_evals, 0);
    assert_eq!(fd_stats.rhs_evals, 4);
    assert_eq!(
        (exact_stats.jacobian_evals, fd_stats.jacobian_evals),
        (1, 1)
    );
}
