//! Featherstone's recursions run on traced scalars, so that each writes
//! the robot's own unrolled code: RNEA (inverse dynamics), CRBA (the mass
//! matrix), ABA (forward dynamics), and the energies. Every body's
//! quantities are in its own frame (the child link's joint frame);
//! spatial vectors are (angular; linear), gravity is the base's
//! acceleration upwards.
//!
//! A floating base is the standard treatment: a 6-DoF joint from the world
//! to the root link, its motion subspace the identity, its velocity the
//! base's spatial velocity in the base frame. Its vectors enter and leave
//! in Pinocchio's free-flyer order, (linear; angular) then the joints: the
//! velocity `(v, ω, q̇ⱼ)`, the forces `(f, n, τⱼ)`; ABA ends at the base by
//! solving its 6 × 6 articulated inertia (`LDLᵀ`, traced).

use super::trace::{ONE, Trace, Val, ZERO};
use super::tree::{Body, Mass};
use super::urdf::JointKind;

/// A traced 3-vector.
pub type V3 = [Val; 3];
/// A traced 3 × 3 matrix, row-major.
pub type M3 = [[Val; 3]; 3];

/// A floating base in the trace: its body, and where it is.
pub struct Floating<'a> {
    /// The root link's mass, and what is fixed to it.
    pub mass: &'a Mass,
    /// The base's axes in the world's coordinates (columns).
    pub rot: M3,
    /// The base's origin in the world.
    pub pos: V3,
}

/// The rotation (body to space) of the quaternion `(w, x, y, z)` in its
/// homogeneous form `q v q̄`: `|q|²` times a rotation, the rotation itself
/// on the unit sphere where the constraint holds the quaternion.
pub fn quaternion_rotation(t: &mut Trace, quat: [Val; 4]) -> M3 {
    let [w, x, y, z] = quat;
    let mut p = |a: Val, b: Val| t.mul(a, b);
    let (ww, xx, yy, zz) = (p(w, w), p(x, x), p(y, y), p(z, z));
    let (xy, xz, yz) = (p(x, y), p(x, z), p(y, z));
    let (wx, wy, wz) = (p(w, x), p(w, y), p(w, z));
    let two = Val::K(2.0);
    let mut d = |a: Val, b: Val, c: Val, e: Val| {
        let s = t.add(a, b);
        let s = t.sub(s, c);
        t.sub(s, e)
    };
    let r00 = d(ww, xx, yy, zz);
    let r11 = d(ww, yy, xx, zz);
    let r22 = d(ww, zz, xx, yy);
    let mut o = |a: Val, b: Val, plus: bool| {
        let s = if plus { t.add(a, b) } else { t.sub(a, b) };
        t.mul(two, s)
    };
    [
        [r00, o(xy, wz, false), o(xz, wy, true)],
        [o(xy, wz, true), r11, o(yz, wx, false)],
        [o(xz, wy, false), o(yz, wx, true), r22],
    ]
}

/// A floating base's spatial vector from Pinocchio's order (linear;
/// angular), and the joints' part after it; a fixed base's: none, all.
fn split(floating: bool, x: &[Val]) -> (Sv, &[Val]) {
    if floating {
        (
            Sv {
                w: [x[3], x[4], x[5]],
                v: [x[0], x[1], x[2]],
            },
            &x[6..],
        )
    } else {
        (SV0, x)
    }
}

/// A base's spatial vector then the joints', in Pinocchio's order.
fn join(base: Option<Sv>, joints: Vec<Val>) -> Vec<Val> {
    match base {
        Some(b) => b.v.into_iter().chain(b.w).chain(joints).collect(),
        None => joints,
    }
}

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

/// A rigid body's (or a rigid composite's) spatial inertia by its ten
/// parameters: the mass, the first moment `h = m c` and the inertia `Ī`
/// about the frame's origin (symmetric). The mass matrix's composites are
/// rigid, so CRBA carries these instead of a general [`Si`]: `C = m 1`
/// stays one scalar and `B = [h]×` a vector through every transform.
#[derive(Clone, Copy)]
struct Rigid {
    m: Val,
    h: V3,
    i: M3,
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
    /// A rigid inertia in the child's frame, in its parent's: `h' = E h +
    /// m r`, `Ī' = E Ī Eᵀ + 2 (r·g) 1 − r gᵀ − g rᵀ + m (|r|² 1 − r rᵀ)` with
    /// `g = E h` (the parallel-axis theorem about the parent's origin;
    /// [`Self::inertia_up`] on `rigid`'s matrices, in fewer operations).
    fn rigid_up(&mut self, x: &Xf, b: &Rigid) -> Rigid {
        let g = self.up(x, b.h);
        let rot = self.congruence_up(x, &b.i, true);
        let r = x.r;
        let mr = self.scale3(b.m, r);
        let h = self.add3(g, mr);
        let mut i = [[ZERO; 3]; 3];
        for k in 0..3 {
            for l in k..3 {
                let x = if k == l {
                    // 2 Σ_{j≠k} r_j g_j + m Σ_{j≠k} r_j².
                    let (a, c) = ((k + 1) % 3, (k + 2) % 3);
                    let rg = self.t.dot(&[r[a], r[c]], &[g[a], g[c]]);
                    let rg2 = self.t.add(rg, rg);
                    let rr = self.t.dot(&[r[a], r[c]], &[mr[a], mr[c]]);
                    let y = self.t.add(rot[k][k], rg2);
                    self.t.add(y, rr)
                } else {
                    // −(r_k g_l + g_k r_l + m r_k r_l).
                    let a = self.t.mul(r[k], g[l]);
                    let c = self.t.mul(g[k], r[l]);
                    let d = self.t.mul(mr[k], r[l]);
                    let y = self.t.sub(rot[k][l], a);
                    let y = self.t.sub(y, c);
                    self.t.sub(y, d)
                };
                i[k][l] = x;
                i[l][k] = x;
            }
        }
        Rigid { m: b.m, h, i }
    }
    fn rigid_add(&mut self, x: &Rigid, y: &Rigid) -> Rigid {
        let mut i = x.i;
        for k in 0..3 {
            for l in k..3 {
                i[k][l] = self.t.add(x.i[k][l], y.i[k][l]);
                i[l][k] = i[k][l];
            }
        }
        Rigid {
            m: self.t.add(x.m, y.m),
            h: self.add3(x.h, y.h),
            i,
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

fn rigid(t: &mut Trace, b: &Body) -> Si {
    spatial(&rigid10_body(t, b))
}

fn rigid_mass(t: &mut Trace, b: &Mass) -> Si {
    spatial(&rigid10(t, b))
}

/// A body's ten parameters: its constants, or where `parameters(..)` names
/// it, the struct field's `[S; 10]` (Pinocchio's order: `m`, `h`, `Ixx,
/// Ixy, Iyy, Ixz, Iyz, Izz`) read as inputs.
fn rigid10(t: &mut Trace, b: &Mass) -> Rigid {
    match &b.param {
        None => Rigid {
            m: Val::K(b.mass),
            h: k3(b.h),
            i: km3(b.inertia),
        },
        Some(field) => {
            let field = quote::format_ident!("{}", field);
            let mut p = [ZERO; 10];
            for (k, x) in p.iter_mut().enumerate() {
                *x = t.input_once(quote::quote!(self.#field[#k]));
            }
            let i = [[p[4], p[5], p[7]], [p[5], p[6], p[8]], [p[7], p[8], p[9]]];
            Rigid {
                m: p[0],
                h: [p[1], p[2], p[3]],
                i,
            }
        }
    }
}

fn rigid10_body(t: &mut Trace, b: &Body) -> Rigid {
    rigid10(
        t,
        &Mass {
            mass: b.mass,
            h: b.h,
            inertia: b.inertia,
            param: b.param.clone(),
        },
    )
}

/// A rigid inertia as a spatial one: `A = Ī`, `B = [h]×`, `C = m 1`.
fn spatial(b: &Rigid) -> Si {
    let m = b.m;
    Si {
        a: b.i,
        b: Cx::skew(b.h),
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

/// Gravity's acceleration upwards in a floating base's axes, `Rᵀ ẑ g`.
fn gravity_in_base(cx: &mut Cx, fb: &Floating) -> Sv {
    let up = [fb.rot[2][0], fb.rot[2][1], fb.rot[2][2]];
    Sv {
        w: [ZERO; 3],
        v: cx.scale3(Val::K(GRAVITY), up),
    }
}

/// RNEA: the joint forces `τ(q, q̇, q̈)` (gravity included when `gravity`);
/// with a floating base, `q̇`, `q̈` and `τ` start with the base's six.
pub fn rnea(
    t: &mut Trace,
    bodies: &[Body],
    fb: Option<&Floating>,
    q: &[Val],
    qd: &[Val],
    qdd: &[Val],
    gravity: bool,
) -> Vec<Val> {
    let xs = transforms(t, bodies, q);
    let mut cx = Cx { t };
    let n = bodies.len();
    let (vb, qd) = split(fb.is_some(), qd);
    let (ab, qdd) = split(fb.is_some(), qdd);
    let mut v = vec![SV0; n];
    let mut a = vec![SV0; n];
    let mut f = vec![SV0; n];
    let a0 = if gravity { base_acceleration() } else { SV0 };
    // The base: its acceleration the joint's plus gravity's, its force
    // `I a + v ×* I v`.
    let root = fb.map(|fb| {
        let ab = if gravity {
            let g = gravity_in_base(&mut cx, fb);
            cx.sv_add(ab, g)
        } else {
            ab
        };
        let inertia = rigid_mass(cx.t, fb.mass);
        let ia = cx.inertia_times(&inertia, ab);
        let iv = cx.inertia_times(&inertia, vb);
        let vf = cx.cross_force(vb, iv);
        (ab, cx.sv_add(ia, vf))
    });
    let (v_root, a_root) = match root {
        Some((ab, _)) => (vb, ab),
        None => (SV0, a0),
    };
    let mut f_root = root.map(|(_, f)| f);
    for i in 0..n {
        let s = subspace(&bodies[i]);
        let (vp, ap) = match bodies[i].parent {
            Some(p) => (v[p], a[p]),
            None => (v_root, a_root),
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
        let inertia = rigid(cx.t, &bodies[i]);
        let ia = cx.inertia_times(&inertia, a[i]);
        let iv = cx.inertia_times(&inertia, v[i]);
        let vf = cx.cross_force(v[i], iv);
        f[i] = cx.sv_add(ia, vf);
    }
    let mut tau = vec![ZERO; n];
    for i in (0..n).rev() {
        let s = subspace(&bodies[i]);
        tau[i] = cx.sv_dot(s, f[i]);
        match (bodies[i].parent, f_root) {
            (Some(p), _) => {
                let fp = cx.force(&xs[i], f[i]);
                f[p] = cx.sv_add(f[p], fp);
            }
            (None, Some(fr)) => {
                let fp = cx.force(&xs[i], f[i]);
                f_root = Some(cx.sv_add(fr, fp));
            }
            (None, None) => {}
        }
    }
    join(f_root, tau)
}

/// CRBA: the mass matrix, row-major, symmetric; with a floating base, its
/// first six rows and columns the base's.
pub fn crba(t: &mut Trace, bodies: &[Body], fb: Option<&Floating>, q: &[Val]) -> Vec<Vec<Val>> {
    let xs = transforms(t, bodies, q);
    let mut cx = Cx { t };
    let n = bodies.len();
    let mut ic: Vec<Rigid> = bodies.iter().map(|b| rigid10_body(cx.t, b)).collect();
    let mut ic_root = fb.map(|fb| rigid10(cx.t, fb.mass));
    for i in (0..n).rev() {
        match (bodies[i].parent, ic_root) {
            (Some(p), _) => {
                let up = cx.rigid_up(&xs[i], &ic[i]);
                ic[p] = cx.rigid_add(&ic[p], &up);
            }
            (None, Some(root)) => {
                let up = cx.rigid_up(&xs[i], &ic[i]);
                ic_root = Some(cx.rigid_add(&root, &up));
            }
            (None, None) => {}
        }
    }
    let ic: Vec<Si> = ic.iter().map(spatial).collect();
    let ic_root = ic_root.as_ref().map(spatial);
    let o = if fb.is_some() { 6 } else { 0 };
    let mut m = vec![vec![ZERO; n + o]; n + o];
    for i in 0..n {
        let mut f = cx.inertia_times(&ic[i], subspace(&bodies[i]));
        m[o + i][o + i] = cx.sv_dot(subspace(&bodies[i]), f);
        let mut j = i;
        while let Some(p) = bodies[j].parent {
            f = cx.force(&xs[j], f);
            j = p;
            let mij = cx.sv_dot(subspace(&bodies[j]), f);
            m[o + i][o + j] = mij;
            m[o + j][o + i] = mij;
        }
        if fb.is_some() {
            // The base's column: the joint's force at the base, (f; n).
            let f = cx.force(&xs[j], f);
            for (k, x) in f.v.into_iter().chain(f.w).enumerate() {
                m[k][o + i] = x;
                m[o + i][k] = x;
            }
        }
    }
    if let Some(root) = ic_root {
        // The composite inertia of the whole robot in (linear; angular)
        // order: [[C, Bᵀ], [B, A]].
        for k in 0..3 {
            for l in 0..3 {
                m[k][l] = root.c[k][l];
                m[k][3 + l] = root.b[l][k];
                m[3 + k][l] = root.b[k][l];
                m[3 + k][3 + l] = root.a[k][l];
            }
        }
    }
    m
}

/// `x` solving `A x = b`, `A` symmetric positive definite (a floating
/// base's articulated inertia), by `LDLᵀ` without pivots (stable on a
/// positive definite matrix).
fn solve_spd(cx: &mut Cx, a: &[[Val; 6]; 6], b: [Val; 6]) -> [Val; 6] {
    let mut l = [[ZERO; 6]; 6];
    let mut d_inv = [ONE; 6];
    let mut d = [ZERO; 6];
    for j in 0..6 {
        let mut djj = a[j][j];
        for k in 0..j {
            let ld = cx.t.mul(l[j][k], d[k]);
            let x = cx.t.mul(ld, l[j][k]);
            djj = cx.t.sub(djj, x);
        }
        d[j] = djj;
        d_inv[j] = cx.t.recip(djj);
        for i in j + 1..6 {
            let mut x = a[i][j];
            for k in 0..j {
                let ld = cx.t.mul(l[i][k], d[k]);
                let y = cx.t.mul(ld, l[j][k]);
                x = cx.t.sub(x, y);
            }
            l[i][j] = cx.t.mul(x, d_inv[j]);
        }
    }
    let mut y = b;
    for i in 0..6 {
        for k in 0..i {
            let p = cx.t.mul(l[i][k], y[k]);
            y[i] = cx.t.sub(y[i], p);
        }
    }
    let mut x = [ZERO; 6];
    for i in (0..6).rev() {
        let mut xi = cx.t.mul(y[i], d_inv[i]);
        for k in i + 1..6 {
            let p = cx.t.mul(l[k][i], x[k]);
            xi = cx.t.sub(xi, p);
        }
        x[i] = xi;
    }
    x
}

/// ABA: the accelerations `q̈(q, q̇, τ)`, gravity included; with a
/// floating base, `q̇`, `τ` and `q̈` start with the base's six.
pub fn aba(
    t: &mut Trace,
    bodies: &[Body],
    fb: Option<&Floating>,
    q: &[Val],
    qd: &[Val],
    tau: &[Val],
) -> Vec<Val> {
    let xs = transforms(t, bodies, q);
    let mut cx = Cx { t };
    let n = bodies.len();
    let (vb, qd) = split(fb.is_some(), qd);
    let (tau_b, tau) = split(fb.is_some(), tau);
    let mut v = vec![SV0; n];
    let mut c = vec![SV0; n];
    let mut ia: Vec<Si> = bodies.iter().map(|b| rigid(cx.t, b)).collect();
    let mut pa = vec![SV0; n];
    // The base's articulated inertia and bias force, from its own body.
    let mut root = fb.map(|fb| {
        let inertia = rigid_mass(cx.t, fb.mass);
        let iv = cx.inertia_times(&inertia, vb);
        (inertia, cx.cross_force(vb, iv))
    });
    for i in 0..n {
        let s = subspace(&bodies[i]);
        let vj = Sv {
            w: cx.scale3(qd[i], s.w),
            v: cx.scale3(qd[i], s.v),
        };
        let vp = bodies[i].parent.map_or(vb, |p| v[p]);
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
        if bodies[i].parent.is_some() || root.is_some() {
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
            let p_up = cx.force(&xs[i], p_art);
            match (bodies[i].parent, root) {
                (Some(p), _) => {
                    ia[p] = cx.si_add(&ia[p], &i_up);
                    pa[p] = cx.sv_add(pa[p], p_up);
                }
                (None, Some((ri, rp))) => {
                    root = Some((cx.si_add(&ri, &i_up), cx.sv_add(rp, p_up)));
                }
                (None, None) => {}
            }
        }
    }
    // The base: `a = Iᴬ⁻¹ (τ − pᴬ)`, its spatial acceleration with gravity's
    // (the world's upwards); its `q̈` that less gravity's.
    let mut base_qdd = None;
    let a_root = match (fb, root) {
        (Some(fb), Some((ri, rp))) => {
            let mut m = [[ZERO; 6]; 6];
            for k in 0..3 {
                for l in 0..3 {
                    m[k][l] = ri.a[k][l];
                    m[k][3 + l] = ri.b[k][l];
                    m[3 + k][l] = ri.b[l][k];
                    m[3 + k][3 + l] = ri.c[k][l];
                }
            }
            let r = [0, 1, 2].map(|k| cx.t.sub(tau_b.w[k], rp.w[k]));
            let r2 = [0, 1, 2].map(|k| cx.t.sub(tau_b.v[k], rp.v[k]));
            let x = solve_spd(&mut cx, &m, [r[0], r[1], r[2], r2[0], r2[1], r2[2]]);
            let a = Sv {
                w: [x[0], x[1], x[2]],
                v: [x[3], x[4], x[5]],
            };
            let g = gravity_in_base(&mut cx, fb);
            base_qdd = Some(Sv {
                w: a.w,
                v: cx.sub3(a.v, g.v),
            });
            a
        }
        _ => base_acceleration(),
    };
    let mut a = vec![SV0; n];
    let mut qdd = vec![ZERO; n];
    for i in 0..n {
        let ap = bodies[i].parent.map_or(a_root, |p| a[p]);
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
    join(base_qdd, qdd)
}

/// The kinetic energy `½ Σ vᵢᵀ Iᵢ vᵢ` (the base's among them when it
/// floats, `q̇` then its velocity and the joints').
pub fn kinetic(
    t: &mut Trace,
    bodies: &[Body],
    fb: Option<&Floating>,
    q: &[Val],
    qd: &[Val],
) -> Val {
    let xs = transforms(t, bodies, q);
    let mut cx = Cx { t };
    let (vb, qd) = split(fb.is_some(), qd);
    let mut v = vec![SV0; bodies.len()];
    let mut twice = ZERO;
    if let Some(fb) = fb {
        let inertia = rigid_mass(cx.t, fb.mass);
        let iv = cx.inertia_times(&inertia, vb);
        twice = cx.sv_dot(vb, iv);
    }
    for (i, b) in bodies.iter().enumerate() {
        let s = subspace(b);
        let vj = Sv {
            w: cx.scale3(qd[i], s.w),
            v: cx.scale3(qd[i], s.v),
        };
        let vp = b.parent.map_or(vb, |p| v[p]);
        let vx = cx.motion(&xs[i], vp);
        v[i] = cx.sv_add(vx, vj);
        let inertia = rigid(cx.t, b);
        let iv = cx.inertia_times(&inertia, v[i]);
        let e = cx.sv_dot(v[i], iv);
        twice = cx.t.add(twice, e);
    }
    cx.t.mul(Val::K(0.5), twice)
}

/// The potential energy `g Σ (mᵢ zᵢ + ẑ · hᵢ)`, with `ẑ` the world's up
/// in each body's axes and `zᵢ` its origin's height (the base's among
/// them when it floats).
pub fn potential(t: &mut Trace, bodies: &[Body], fb: Option<&Floating>, q: &[Val]) -> Val {
    let xs = transforms(t, bodies, q);
    let mut cx = Cx { t };
    let n = bodies.len();
    let mut up = vec![[ZERO; 3]; n];
    let mut height = vec![ZERO; n];
    let mut sum = ZERO;
    let (z_root, h_root) = match fb {
        Some(fb) => {
            let zb = [fb.rot[2][0], fb.rot[2][1], fb.rot[2][2]];
            let b = rigid10(cx.t, fb.mass);
            let mz = cx.t.mul(b.m, fb.pos[2]);
            let zh = cx.dot3(zb, b.h);
            sum = cx.t.add(mz, zh);
            (zb, fb.pos[2])
        }
        None => ([ZERO, ZERO, ONE], ZERO),
    };
    for (i, b) in bodies.iter().enumerate() {
        let (zp, hp) = b.parent.map_or((z_root, h_root), |p| (up[p], height[p]));
        let dz = cx.dot3(zp, xs[i].r);
        height[i] = cx.t.add(hp, dz);
        up[i] = cx.down(&xs[i], zp);
        let b = rigid10_body(cx.t, b);
        let mz = cx.t.mul(b.m, height[i]);
        let zh = cx.dot3(up[i], b.h);
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
