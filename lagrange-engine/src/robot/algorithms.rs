//! Featherstone's recursions run on traced scalars, so that each writes
//! the robot's own unrolled code: RNEA (inverse dynamics), CRBA (the mass
//! matrix), ABA (forward dynamics), and the energies. Every body's
//! quantities are in its own frame (the child link's joint frame);
//! spatial vectors are (angular; linear), gravity is the base's
//! acceleration upwards.

use super::trace::{ONE, Trace, Val, ZERO};
use super::tree::Body;
use super::urdf::JointKind;

type V3 = [Val; 3];
type M3 = [[Val; 3]; 3];

/// Gravity's magnitude along −z, Pinocchio's default.
pub const GRAVITY: f64 = 9.81;

fn k3(x: [f64; 3]) -> V3 {
    x.map(Val::K)
}

fn km3(x: [[f64; 3]; 3]) -> M3 {
    x.map(k3)
}

/// A motion or force vector: angular (or moment) part, linear part.
#[derive(Clone, Copy)]
struct Sv {
    w: V3,
    v: V3,
}

const SV0: Sv = Sv {
    w: [ZERO; 3],
    v: [ZERO; 3],
};

/// A symmetric spatial inertia `[[A, B], [Bᵀ, C]]`: `n = A ω + B v`,
/// `f = Bᵀ ω + C v` (a rigid body's: `A = Ī`, `B = [h]×`, `C = m 1`).
#[derive(Clone, Copy)]
struct Si {
    a: M3,
    b: M3,
    c: M3,
}

/// The transform from a parent body's frame to a body's, at `q`: the
/// constant joint placement then the joint's motion.
struct Xf {
    /// The joint frame's axes in the parent's coordinates (constant).
    ro: [[f64; 3]; 3],
    /// The body's origin in the parent's coordinates.
    r: V3,
    /// The joint's rotation (child axes in the joint frame), if it turns.
    rj: Option<M3>,
}

struct Cx<'a> {
    t: &'a mut Trace,
}

impl Cx<'_> {
    fn add3(&mut self, a: V3, b: V3) -> V3 {
        [0, 1, 2].map(|i| self.t.add(a[i], b[i]))
    }
    fn sub3(&mut self, a: V3, b: V3) -> V3 {
        [0, 1, 2].map(|i| self.t.sub(a[i], b[i]))
    }
    fn scale3(&mut self, k: Val, a: V3) -> V3 {
        a.map(|x| self.t.mul(k, x))
    }
    fn dot3(&mut self, a: V3, b: V3) -> Val {
        self.t.dot(&a, &b)
    }
    fn cross(&mut self, a: V3, b: V3) -> V3 {
        let t = &mut *self.t;
        let mut c = |i: usize, j: usize| {
            let p = t.mul(a[i], b[j]);
            let q = t.mul(a[j], b[i]);
            t.sub(p, q)
        };
        [c(1, 2), c(2, 0), c(0, 1)]
    }
    /// `m x`.
    fn mv(&mut self, m: &M3, x: V3) -> V3 {
        [0, 1, 2].map(|i| self.t.dot(&m[i], &x))
    }
    /// `mᵀ x`.
    fn mtv(&mut self, m: &M3, x: V3) -> V3 {
        [0, 1, 2].map(|i| {
            let col = [m[0][i], m[1][i], m[2][i]];
            self.t.dot(&col, &x)
        })
    }
    /// Parent coordinates → child: `Eᵀ` of the placement's rotation.
    fn down(&mut self, x: &Xf, v: V3) -> V3 {
        let ro = km3(x.ro);
        let y = self.mtv(&ro, v);
        match &x.rj {
            Some(rj) => self.mtv(rj, y),
            None => y,
        }
    }
    /// Child coordinates → parent.
    fn up(&mut self, x: &Xf, v: V3) -> V3 {
        let y = match &x.rj {
            Some(rj) => self.mv(rj, v),
            None => v,
        };
        let ro = km3(x.ro);
        self.mv(&ro, y)
    }
    /// A motion vector from the parent's frame to the child's.
    fn motion(&mut self, x: &Xf, m: Sv) -> Sv {
        let rw = self.cross(x.r, m.w);
        let v = self.sub3(m.v, rw);
        Sv {
            w: self.down(x, m.w),
            v: self.down(x, v),
        }
    }
    /// A force vector from the child's frame to the parent's.
    fn force(&mut self, x: &Xf, f: Sv) -> Sv {
        let v = self.up(x, f.v);
        let w = self.up(x, f.w);
        let rf = self.cross(x.r, v);
        Sv {
            w: self.add3(w, rf),
            v,
        }
    }
    fn sv_add(&mut self, a: Sv, b: Sv) -> Sv {
        Sv {
            w: self.add3(a.w, b.w),
            v: self.add3(a.v, b.v),
        }
    }
    /// `a ×m b`.
    fn cross_motion(&mut self, a: Sv, b: Sv) -> Sv {
        let w = self.cross(a.w, b.w);
        let p = self.cross(a.w, b.v);
        let q = self.cross(a.v, b.w);
        Sv {
            w,
            v: self.add3(p, q),
        }
    }
    /// `a ×f b`.
    fn cross_force(&mut self, a: Sv, b: Sv) -> Sv {
        let p = self.cross(a.w, b.w);
        let q = self.cross(a.v, b.v);
        Sv {
            w: self.add3(p, q),
            v: self.cross(a.w, b.v),
        }
    }
    fn inertia_times(&mut self, i: &Si, m: Sv) -> Sv {
        let aw = self.mv(&i.a, m.w);
        let bv = self.mv(&i.b, m.v);
        let btw = self.mtv(&i.b, m.w);
        let cv = self.mv(&i.c, m.v);
        Sv {
            w: self.add3(aw, bv),
            v: self.add3(btw, cv),
        }
    }
    fn sv_dot(&mut self, a: Sv, b: Sv) -> Val {
        let x = self.dot3(a.w, b.w);
        let y = self.dot3(a.v, b.v);
        self.t.add(x, y)
    }
    fn matmul(&mut self, a: &M3, b: &M3) -> M3 {
        [0, 1, 2].map(|i| {
            [0, 1, 2].map(|j| {
                let col = [b[0][j], b[1][j], b[2][j]];
                self.t.dot(&a[i], &col)
            })
        })
    }
    fn transpose(m: &M3) -> M3 {
        [0, 1, 2].map(|i| [0, 1, 2].map(|j| m[j][i]))
    }
    /// `Eᵀ X E`: a child-frame matrix in the parent's coordinates.
    fn congruence_up(&mut self, x: &Xf, m: &M3, symmetric: bool) -> M3 {
        // Columns of Eᵀ m, then Eᵀ applied to the rows of the result.
        let cols = [0, 1, 2].map(|j| self.up(x, [m[0][j], m[1][j], m[2][j]]));
        let w = Self::transpose(&cols); // w = Eᵀ m
        let mut out = [[ZERO; 3]; 3];
        for (i, row) in w.iter().enumerate() {
            let r = self.up(x, *row); // (Eᵀ (Eᵀ m)ᵀ) column i = row i of (Eᵀ m) E
            for j in 0..3 {
                if !symmetric || j >= i {
                    out[i][j] = r[j];
                }
            }
        }
        if symmetric {
            for i in 0..3 {
                for j in 0..i {
                    out[i][j] = out[j][i];
                }
            }
        }
        out
    }
    fn skew(r: V3) -> M3 {
        [
            [ZERO, r[2].negated(), r[1]],
            [r[2], ZERO, r[0].negated()],
            [r[1].negated(), r[0], ZERO],
        ]
    }
    /// `Xᵀ I X`: a child's inertia in its parent's frame.
    fn inertia_up(&mut self, x: &Xf, i: &Si) -> Si {
        let a1 = self.congruence_up(x, &i.a, true);
        let b1 = self.congruence_up(x, &i.b, false);
        let c1 = self.congruence_up(x, &i.c, true);
        let rx = Self::skew(x.r);
        // B₂ = B₁ + [r]× C₁; A₂ = A₁ − Q − Qᵀ − [r]× C₁ [r]×, Q = B₁ [r]×.
        let p = self.matmul(&rx, &c1);
        let mut b2 = [[ZERO; 3]; 3];
        for k in 0..3 {
            for l in 0..3 {
                b2[k][l] = self.t.add(b1[k][l], p[k][l]);
            }
        }
        let q = self.matmul(&b1, &rx);
        let prx = self.matmul(&p, &rx);
        let mut a2 = [[ZERO; 3]; 3];
        for k in 0..3 {
            for l in k..3 {
                let s = self.t.add(q[k][l], q[l][k]);
                let s = self.t.add(s, prx[k][l]);
                a2[k][l] = self.t.sub(a1[k][l], s);
                a2[l][k] = a2[k][l];
            }
        }
        Si {
            a: a2,
            b: b2,
            c: c1,
        }
    }
    fn si_add(&mut self, x: &Si, y: &Si) -> Si {
        let mut out = *x;
        for k in 0..3 {
            for l in 0..3 {
                out.a[k][l] = self.t.add(x.a[k][l], y.a[k][l]);
                out.b[k][l] = self.t.add(x.b[k][l], y.b[k][l]);
                out.c[k][l] = self.t.add(x.c[k][l], y.c[k][l]);
            }
        }
        out
    }
}

fn rigid(b: &Body) -> Si {
    let h = k3(b.h);
    let m = Val::K(b.mass);
    Si {
        a: km3(b.inertia),
        b: Cx::skew(h),
        c: [[m, ZERO, ZERO], [ZERO, m, ZERO], [ZERO, ZERO, m]],
    }
}

/// The joint's motion subspace `S` (a unit twist in the body's frame).
fn subspace(b: &Body) -> Sv {
    let a = k3(b.axis);
    match b.kind {
        JointKind::Prismatic => Sv { w: [ZERO; 3], v: a },
        _ => Sv { w: a, v: [ZERO; 3] },
    }
}

/// The transforms of every body at `q` (sines and cosines traced).
fn transforms(t: &mut Trace, bodies: &[Body], q: &[Val]) -> Vec<Xf> {
    bodies
        .iter()
        .zip(q)
        .map(|(b, &qi)| {
            let p = k3(b.placement.pos);
            match b.kind {
                JointKind::Prismatic => {
                    // r = p + R_o a q
                    let mut cx = Cx { t };
                    let ra = cx.mv(&km3(b.placement.rot), k3(b.axis));
                    let d = cx.scale3(qi, ra);
                    Xf {
                        ro: b.placement.rot,
                        r: cx.add3(p, d),
                        rj: None,
                    }
                }
                _ => {
                    let (s, c) = t.sin_cos(qi);
                    // R = c 1 + (1 − c) a aᵀ + s [a]×
                    let a = b.axis;
                    let skew = [[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]];
                    let rj = [0, 1, 2].map(|i| {
                        [0, 1, 2].map(|j| {
                            let aa = a[i] * a[j];
                            let delta = if i == j { 1.0 } else { 0.0 };
                            let x = t.mul(Val::K(delta - aa), c);
                            let x = t.add(x, Val::K(aa));
                            let y = t.mul(Val::K(skew[i][j]), s);
                            t.add(x, y)
                        })
                    });
                    Xf {
                        ro: b.placement.rot,
                        r: p,
                        rj: Some(rj),
                    }
                }
            }
        })
        .collect()
}

fn base_acceleration() -> Sv {
    Sv {
        w: [ZERO; 3],
        v: [ZERO, ZERO, Val::K(GRAVITY)],
    }
}

/// RNEA: the joint forces `τ(q, q̇, q̈)` (gravity included when `gravity`).
pub fn rnea(
    t: &mut Trace,
    bodies: &[Body],
    q: &[Val],
    qd: &[Val],
    qdd: &[Val],
    gravity: bool,
) -> Vec<Val> {
    let xs = transforms(t, bodies, q);
    let mut cx = Cx { t };
    let n = bodies.len();
    let mut v = vec![SV0; n];
    let mut a = vec![SV0; n];
    let mut f = vec![SV0; n];
    let a0 = if gravity { base_acceleration() } else { SV0 };
    for i in 0..n {
        let s = subspace(&bodies[i]);
        let (vp, ap) = match bodies[i].parent {
            Some(p) => (v[p], a[p]),
            None => (SV0, a0),
        };
        let vj = Sv {
            w: cx.scale3(qd[i], s.w),
            v: cx.scale3(qd[i], s.v),
        };
        let vx = cx.motion(&xs[i], vp);
        v[i] = cx.sv_add(vx, vj);
        let ax = cx.motion(&xs[i], ap);
        let aj = Sv {
            w: cx.scale3(qdd[i], s.w),
            v: cx.scale3(qdd[i], s.v),
        };
        let c = cx.cross_motion(v[i], vj);
        let ai = cx.sv_add(ax, aj);
        a[i] = cx.sv_add(ai, c);
        let inertia = rigid(&bodies[i]);
        let ia = cx.inertia_times(&inertia, a[i]);
        let iv = cx.inertia_times(&inertia, v[i]);
        let vf = cx.cross_force(v[i], iv);
        f[i] = cx.sv_add(ia, vf);
    }
    let mut tau = vec![ZERO; n];
    for i in (0..n).rev() {
        let s = subspace(&bodies[i]);
        tau[i] = cx.sv_dot(s, f[i]);
        if let Some(p) = bodies[i].parent {
            let fp = cx.force(&xs[i], f[i]);
            f[p] = cx.sv_add(f[p], fp);
        }
    }
    tau
}

/// CRBA: the mass matrix, row-major, symmetric.
pub fn crba(t: &mut Trace, bodies: &[Body], q: &[Val]) -> Vec<Vec<Val>> {
    let xs = transforms(t, bodies, q);
    let mut cx = Cx { t };
    let n = bodies.len();
    let mut ic: Vec<Si> = bodies.iter().map(rigid).collect();
    for i in (0..n).rev() {
        if let Some(p) = bodies[i].parent {
            let up = cx.inertia_up(&xs[i], &ic[i]);
            ic[p] = cx.si_add(&ic[p], &up);
        }
    }
    let mut m = vec![vec![ZERO; n]; n];
    for i in 0..n {
        let mut f = cx.inertia_times(&ic[i], subspace(&bodies[i]));
        m[i][i] = cx.sv_dot(subspace(&bodies[i]), f);
        let mut j = i;
        while let Some(p) = bodies[j].parent {
            f = cx.force(&xs[j], f);
            j = p;
            let mij = cx.sv_dot(subspace(&bodies[j]), f);
            m[i][j] = mij;
            m[j][i] = mij;
        }
    }
    m
}

/// ABA: the accelerations `q̈(q, q̇, τ)`, gravity included.
pub fn aba(t: &mut Trace, bodies: &[Body], q: &[Val], qd: &[Val], tau: &[Val]) -> Vec<Val> {
    let xs = transforms(t, bodies, q);
    let mut cx = Cx { t };
    let n = bodies.len();
    let mut v = vec![SV0; n];
    let mut c = vec![SV0; n];
    let mut ia: Vec<Si> = bodies.iter().map(rigid).collect();
    let mut pa = vec![SV0; n];
    for i in 0..n {
        let s = subspace(&bodies[i]);
        let vj = Sv {
            w: cx.scale3(qd[i], s.w),
            v: cx.scale3(qd[i], s.v),
        };
        let vp = bodies[i].parent.map_or(SV0, |p| v[p]);
        let vx = cx.motion(&xs[i], vp);
        v[i] = cx.sv_add(vx, vj);
        c[i] = cx.cross_motion(v[i], vj);
        let iv = cx.inertia_times(&ia[i], v[i]);
        pa[i] = cx.cross_force(v[i], iv);
    }
    let mut u_vec = vec![SV0; n];
    let mut d_inv = vec![ONE; n];
    let mut u = vec![ZERO; n];
    for i in (0..n).rev() {
        let s = subspace(&bodies[i]);
        let ui = cx.inertia_times(&ia[i], s);
        let d = cx.sv_dot(s, ui);
        let di = cx.t.recip(d);
        let sp = cx.sv_dot(s, pa[i]);
        u[i] = cx.t.sub(tau[i], sp);
        u_vec[i] = ui;
        d_inv[i] = di;
        if let Some(p) = bodies[i].parent {
            // Iᵃ = Iᴬ − U Uᵀ / D, pᵃ = pᴬ + Iᵃ c + U u / D.
            let ud = Sv {
                w: cx.scale3(di, ui.w),
                v: cx.scale3(di, ui.v),
            };
            let mut a_art = ia[i];
            for k in 0..3 {
                for l in 0..3 {
                    if l >= k {
                        let x = cx.t.mul(ud.w[k], ui.w[l]);
                        a_art.a[k][l] = cx.t.sub(a_art.a[k][l], x);
                        a_art.a[l][k] = a_art.a[k][l];
                        let y = cx.t.mul(ud.v[k], ui.v[l]);
                        a_art.c[k][l] = cx.t.sub(a_art.c[k][l], y);
                        a_art.c[l][k] = a_art.c[k][l];
                    }
                    let z = cx.t.mul(ud.w[k], ui.v[l]);
                    a_art.b[k][l] = cx.t.sub(a_art.b[k][l], z);
                }
            }
            let ic = cx.inertia_times(&a_art, c[i]);
            let uu = Sv {
                w: cx.scale3(u[i], ud.w),
                v: cx.scale3(u[i], ud.v),
            };
            let p_art = cx.sv_add(pa[i], ic);
            let p_art = cx.sv_add(p_art, uu);
            let i_up = cx.inertia_up(&xs[i], &a_art);
            ia[p] = cx.si_add(&ia[p], &i_up);
            let p_up = cx.force(&xs[i], p_art);
            pa[p] = cx.sv_add(pa[p], p_up);
        }
    }
    let mut a = vec![SV0; n];
    let mut qdd = vec![ZERO; n];
    for i in 0..n {
        let ap = bodies[i].parent.map_or(base_acceleration(), |p| a[p]);
        let ax = cx.motion(&xs[i], ap);
        let ai = cx.sv_add(ax, c[i]);
        let ua = cx.sv_dot(u_vec[i], ai);
        let r = cx.t.sub(u[i], ua);
        qdd[i] = cx.t.mul(d_inv[i], r);
        let s = subspace(&bodies[i]);
        let aj = Sv {
            w: cx.scale3(qdd[i], s.w),
            v: cx.scale3(qdd[i], s.v),
        };
        a[i] = cx.sv_add(ai, aj);
    }
    qdd
}

/// The kinetic energy `½ Σ vᵢᵀ Iᵢ vᵢ`.
pub fn kinetic(t: &mut Trace, bodies: &[Body], q: &[Val], qd: &[Val]) -> Val {
    let xs = transforms(t, bodies, q);
    let mut cx = Cx { t };
    let mut v = vec![SV0; bodies.len()];
    let mut twice = ZERO;
    for (i, b) in bodies.iter().enumerate() {
        let s = subspace(b);
        let vj = Sv {
            w: cx.scale3(qd[i], s.w),
            v: cx.scale3(qd[i], s.v),
        };
        let vp = b.parent.map_or(SV0, |p| v[p]);
        let vx = cx.motion(&xs[i], vp);
        v[i] = cx.sv_add(vx, vj);
        let iv = cx.inertia_times(&rigid(b), v[i]);
        let e = cx.sv_dot(v[i], iv);
        twice = cx.t.add(twice, e);
    }
    cx.t.mul(Val::K(0.5), twice)
}

/// The potential energy `g Σ (mᵢ zᵢ + ẑ · hᵢ)`, with `ẑ` the world's up
/// in each body's axes and `zᵢ` its origin's height.
pub fn potential(t: &mut Trace, bodies: &[Body], q: &[Val]) -> Val {
    let xs = transforms(t, bodies, q);
    let mut cx = Cx { t };
    let n = bodies.len();
    let mut up = vec![[ZERO; 3]; n];
    let mut height = vec![ZERO; n];
    let mut sum = ZERO;
    for (i, b) in bodies.iter().enumerate() {
        let (zp, hp) = b
            .parent
            .map_or(([ZERO, ZERO, ONE], ZERO), |p| (up[p], height[p]));
        let dz = cx.dot3(zp, xs[i].r);
        height[i] = cx.t.add(hp, dz);
        up[i] = cx.down(&xs[i], zp);
        let mz = cx.t.mul(Val::K(b.mass), height[i]);
        let zh = cx.dot3(up[i], k3(b.h));
        let e = cx.t.add(mz, zh);
        sum = cx.t.add(sum, e);
    }
    cx.t.mul(Val::K(GRAVITY), sum)
}

// Beside the recursions, on the same spatial arithmetic: the frames'
// kinematics and the inertial-parameter regressor.
#[path = "frames.rs"]
pub mod frames;
#[path = "regressor.rs"]
pub mod regressor;
