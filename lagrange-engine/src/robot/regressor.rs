//! The inertial-parameter regressor: `τ = Y(q, q̇, q̈) π`, with `π` ten
//! parameters per body, Pinocchio's order: `m`, the first moment `m c`
//! (3), the inertia about the body's joint frame `Ixx, Ixy, Iyy, Ixz, Iyz,
//! Izz`, in the body's axes. RNEA is linear in each body's spatial inertia:
//! body `k`'s force `f = I a + v ×* I v` is a 6 × 10 matrix times its `π`,
//! each column carried to the root through the joints as RNEA carries a
//! force, and read by each joint it passes (`Sᵀ f`). On a floating base
//! the base's body has its ten first, and the base's six rows read every
//! force that reaches it (its wrench, force then moment, in its frame).

use super::{
    Cx, Floating, SV0, Si, Sv, base_acceleration, gravity_in_base, split, subspace, transforms,
};
use crate::robot::trace::{ONE, Trace, Val, ZERO};
use crate::robot::tree::{Body, Mass};

/// Parameters per body.
pub const PER_BODY: usize = 10;

/// The index pairs of the inertia's six parameters, in `π`'s order.
const INERTIA: [(usize, usize); 6] = [(0, 0), (0, 1), (1, 1), (0, 2), (1, 2), (2, 2)];

/// A body's ten parameters, in `π`'s order.
pub fn parameters(b: &Body) -> [f64; PER_BODY] {
    mass_parameters(&b.mass, &b.h, &b.inertia)
}

/// A floating base's body's ten parameters, in `π`'s order.
pub fn base_parameters(m: &Mass) -> [f64; PER_BODY] {
    mass_parameters(&m.mass, &m.h, &m.inertia)
}

fn mass_parameters(mass: &f64, h: &[f64; 3], inertia: &[[f64; 3]; 3]) -> [f64; PER_BODY] {
    let mut p = [0.0; PER_BODY];
    p[0] = *mass;
    p[1..4].copy_from_slice(h);
    for (k, &(i, j)) in INERTIA.iter().enumerate() {
        p[4 + k] = inertia[i][j];
    }
    p
}

/// The spatial inertia of parameter `p` at one, the others zero.
fn unit(p: usize) -> Si {
    let mut si = Si {
        a: [[ZERO; 3]; 3],
        b: [[ZERO; 3]; 3],
        c: [[ZERO; 3]; 3],
    };
    match p {
        0 => {
            for i in 0..3 {
                si.c[i][i] = ONE;
            }
        }
        1..=3 => {
            let mut h = [ZERO; 3];
            h[p - 1] = ONE;
            si.b = Cx::skew(h);
        }
        _ => {
            let (i, j) = INERTIA[p - 4];
            si.a[i][j] = ONE;
            si.a[j][i] = ONE;
        }
    }
    si
}

/// `Y`, row-major: `N` rows of `10 N`; `τ = Y π` with gravity when
/// `gravity`. On a floating base (`fb`), `q̇` and `q̈` start with the
/// base's six (Pinocchio's order) and `Y` has `6 + N` rows of
/// `10 (1 + N)`, the base's body first.
pub fn regressor(
    t: &mut Trace,
    bodies: &[Body],
    fb: Option<&Floating>,
    q: &[Val],
    qd: &[Val],
    qdd: &[Val],
    gravity: bool,
) -> Vec<Vec<Val>> {
    let xs = transforms(t, bodies, q);
    let mut cx = Cx { t };
    let n = bodies.len();
    let (vb, qd) = split(fb.is_some(), qd);
    let (ab, qdd) = split(fb.is_some(), qdd);
    let mut v = vec![SV0; n];
    let mut a = vec![SV0; n];
    let a0 = if gravity { base_acceleration() } else { SV0 };
    // Rows and columns before the joints' (the base's), and the base's
    // velocity and acceleration (gravity's included).
    let (ro, co) = if fb.is_some() { (6, PER_BODY) } else { (0, 0) };
    let mut y = vec![vec![ZERO; co + PER_BODY * n]; ro + n];
    let (v_root, a_root) = match fb {
        Some(fb) => {
            let ab = if gravity {
                let g = gravity_in_base(&mut cx, fb);
                cx.sv_add(ab, g)
            } else {
                ab
            };
            (vb, ab)
        }
        None => (SV0, a0),
    };
    let base_rows = |y: &mut Vec<Vec<Val>>, col: usize, f: Sv| {
        for (r, x) in f.v.into_iter().chain(f.w).enumerate() {
            y[r][col] = x;
        }
    };
    if fb.is_some() {
        // The base's own body: `f = I a + v ×* I v`, read by its rows.
        for p in 0..PER_BODY {
            let inertia = unit(p);
            let ia = cx.inertia_times(&inertia, a_root);
            let iv = cx.inertia_times(&inertia, v_root);
            let vf = cx.cross_force(v_root, iv);
            let f = cx.sv_add(ia, vf);
            base_rows(&mut y, p, f);
        }
    }
    for k in 0..n {
        // RNEA's forward pass: the body's velocity and acceleration.
        let s = subspace(&bodies[k]);
        let (vp, ap) = match bodies[k].parent {
            Some(p) => (v[p], a[p]),
            None => (v_root, a_root),
        };
        let vj = Sv {
            w: cx.scale3(qd[k], s.w),
            v: cx.scale3(qd[k], s.v),
        };
        let vx = cx.motion(&xs[k], vp);
        v[k] = cx.sv_add(vx, vj);
        let ax = cx.motion(&xs[k], ap);
        let aj = Sv {
            w: cx.scale3(qdd[k], s.w),
            v: cx.scale3(qdd[k], s.v),
        };
        let c = cx.cross_motion(v[k], vj);
        let ak = cx.sv_add(ax, aj);
        a[k] = cx.sv_add(ak, c);
        for p in 0..PER_BODY {
            let inertia = unit(p);
            let ia = cx.inertia_times(&inertia, a[k]);
            let iv = cx.inertia_times(&inertia, v[k]);
            let vf = cx.cross_force(v[k], iv);
            let mut f = cx.sv_add(ia, vf);
            let col = co + PER_BODY * k + p;
            let mut j = k;
            loop {
                y[ro + j][col] = cx.sv_dot(subspace(&bodies[j]), f);
                match bodies[j].parent {
                    Some(parent) => {
                        f = cx.force(&xs[j], f);
                        j = parent;
                    }
                    None => break,
                }
            }
            if fb.is_some() {
                let f = cx.force(&xs[j], f);
                base_rows(&mut y, col, f);
            }
        }
    }
    y
}
