//! What robotics code calls beside the dynamics: the frames' placements,
//! Jacobians and velocities, and the inertial-parameter regressor. One
//! more `impl` block on the robot's struct, written here.
//!
//! The frames are the URDF's links, every one (a tool frame is a link
//! fixed to the last body): the kinematics are traced once for all the
//! bodies (`body_placements`, the robot's constants folded), and a frame's
//! placement, Jacobian and velocity are assembled from them at run time
//! from constant tables (its body, its placement on it, the joints it
//! hangs from), so the code does not grow with the frames. Jacobians
//! follow Pinocchio's `LOCAL_WORLD_ALIGNED`: rows the linear velocity of
//! the frame's origin then the angular velocity, both in world axes.

use super::algorithms::{frames::Frame, regressor};
use super::function;
use super::tree::Body;
use super::urdf::JointKind;
use proc_macro2::{Literal, TokenStream};
use quote::quote;

fn lit(x: f64) -> Literal {
    Literal::f64_suffixed(x)
}

fn option(x: Option<usize>) -> TokenStream {
    match x {
        Some(i) => quote!(::core::option::Option::Some(#i)),
        None => quote!(::core::option::Option::None),
    }
}

/// The constant tables the frames' functions read: the frames' names,
/// bodies and placements on them, the bodies' parents, axes and kinds.
struct Tables {
    frame_names: Vec<String>,
    frame_body: Vec<TokenStream>,
    frame_rot: Vec<TokenStream>,
    frame_pos: Vec<TokenStream>,
    parent: Vec<TokenStream>,
    axis: Vec<TokenStream>,
    prismatic: Vec<bool>,
}

fn tables(bodies: &[Body], frames: &[Frame]) -> Tables {
    Tables {
        frame_names: frames.iter().map(|f| f.name.clone()).collect(),
        frame_body: frames.iter().map(|f| option(f.body)).collect(),
        frame_rot: frames
            .iter()
            .map(|f| {
                let r = f.placement.rot.iter().flatten().map(|&x| lit(x));
                quote!([#(#r),*])
            })
            .collect(),
        frame_pos: frames
            .iter()
            .map(|f| {
                let p = f.placement.pos.iter().map(|&x| lit(x));
                quote!([#(#p),*])
            })
            .collect(),
        parent: bodies.iter().map(|b| option(b.parent)).collect(),
        axis: bodies
            .iter()
            .map(|b| {
                let a = b.axis.iter().map(|&x| lit(x));
                quote!([#(#a),*])
            })
            .collect(),
        prismatic: bodies
            .iter()
            .map(|b| b.kind == JointKind::Prismatic)
            .collect(),
    }
}

/// Twelve traced values per placement (rotation row-major, then the
/// origin) as `(Matrix3, Vector3)` expressions.
fn placements(outs: &[TokenStream]) -> Vec<TokenStream> {
    outs.chunks(12)
        .map(|c| {
            let (r, p) = (&c[..9], &c[9..]);
            quote!((
                ::lagrange::nalgebra::Matrix3::<S>::new(#(#r),*),
                ::lagrange::nalgebra::Vector3::<S>::new(#(#p),*)
            ))
        })
        .collect()
}

/// The `impl` block of the frames and the regressor.
pub fn emit(name: &syn::Ident, bodies: &[Body], frames: &[Frame], regressor: bool) -> TokenStream {
    let n = bodies.len();
    let nf = frames.len();
    let (poses_body, poses_out) = function(bodies, &["q"], |t, x| {
        algorithms_body_poses(t, bodies, None, &x[0])
    });
    let poses = placements(&poses_out);
    let Tables {
        frame_names,
        frame_body,
        frame_rot,
        frame_pos,
        parent,
        axis,
        prismatic,
    } = tables(bodies, frames);
    // The regressor and its parameters, where `#[lagrange(regressor)]`
    // asks for them: `10 n` columns, the largest item of a large robot.
    let regressor_items = if regressor {
        let sv = quote!(::lagrange::nalgebra::SVector<S, #n>);
        let np = regressor::PER_BODY * n;
        let params: Vec<Literal> = bodies
            .iter()
            .flat_map(regressor::parameters)
            .map(lit)
            .collect();
        let (y_body, y_out) = function(bodies, &["q", "qdot", "qddot"], |t, x| {
            let y = regressor::regressor(t, bodies, None, &x[0], &x[1], &x[2], true);
            // Column-major, as nalgebra stores it.
            (0..np)
                .flat_map(|c| y.iter().map(move |row| row[c]))
                .collect()
        });
        let y_cols: Vec<TokenStream> = y_out.chunks(n).map(|c| quote!([#(#c),*])).collect();
        quote! {
            /// The inertial parameters `π` of the file, ten per body in
            /// the coordinates' order: `m`, the first moment `m c` (3), and
            /// the inertia about the joint frame `Ixx, Ixy, Iyy, Ixz, Iyz,
            /// Izz`, in the body's axes (what is fixed or locked to a
            /// body included): [`regressor`](Self::regressor)` · π = τ`.
            pub const PARAMETERS: [f64; #np] = [#(#params),*];

            /// The inertial-parameter regressor `Y(q, q̇, q̈)`: `Y π` is
            /// [`inverse_dynamics`](Self::inverse_dynamics)`(q, q̇, q̈)` for
            /// every `π` (ten per body, as
            /// [`PARAMETERS`](Self::PARAMETERS)), gravity included: what
            /// identifies masses and inertias from measured torques by
            /// least squares.
            #[inline]
            pub fn regressor(&self, q: &#sv, qdot: &#sv, qddot: &#sv) -> ::lagrange::nalgebra::SMatrix<S, #n, #np> {
                #y_body
                ::lagrange::nalgebra::SMatrix::<S, #n, #np>::from_array_storage(
                    ::lagrange::nalgebra::ArrayStorage([#(#y_cols),*])
                )
            }
        }
    } else {
        TokenStream::new()
    };
    let simd = quote! {
        S: ::lagrange::nalgebra::SimdRealField + ::core::marker::Copy,
        S::Element: ::lagrange::nalgebra::RealField + ::core::marker::Copy,
    };
    let sv = quote!(::lagrange::nalgebra::SVector<S, #n>);
    let placement = quote!((
        ::lagrange::nalgebra::Matrix3<S>,
        ::lagrange::nalgebra::Vector3<S>
    ));
    quote! {
        #[allow(unused_variables, unused_parens, non_snake_case, clippy::all, clippy::pedantic)]
        impl<S> #name<S> where #simd {
            /// Names of the frames: the URDF's links, every one, parents
            /// first (a frame is fixed to a moving body or to the base).
            pub const FRAMES: [&'static str; #nf] = [#(#frame_names),*];
            const FRAME_BODY: [::core::option::Option<usize>; #nf] = [#(#frame_body),*];
            const FRAME_ROT: [[f64; 9]; #nf] = [#(#frame_rot),*];
            const FRAME_POS: [[f64; 3]; #nf] = [#(#frame_pos),*];
            const BODY_PARENT: [::core::option::Option<usize>; #n] = [#(#parent),*];
            const BODY_AXIS: [[f64; 3]; #n] = [#(#axis),*];
            const BODY_PRISMATIC: [bool; #n] = [#(#prismatic),*];

            /// The index of the frame named `name` in
            /// [`FRAMES`](Self::FRAMES), if there is one.
            pub fn frame_index(name: &str) -> ::core::option::Option<usize> {
                Self::FRAMES.iter().position(|f| *f == name)
            }

            /// Every moving body's frame (its joint's, the child link's)
            /// in the world at `q`: the rotation (the frame's axes in world
            /// coordinates) and the origin.
            #[inline]
            pub fn body_placements(&self, q: &#sv) -> [#placement; #n] {
                #poses_body
                [#(#poses),*]
            }

            fn placement_from(bodies: &[#placement; #n], frame: usize) -> #placement {
                let k = |x: f64| ::lagrange::nalgebra::convert::<f64, S>(x);
                let r = &Self::FRAME_ROT[frame];
                let p = &Self::FRAME_POS[frame];
                let r = ::lagrange::nalgebra::Matrix3::<S>::new(
                    k(r[0]), k(r[1]), k(r[2]), k(r[3]), k(r[4]), k(r[5]), k(r[6]), k(r[7]), k(r[8]),
                );
                let p = ::lagrange::nalgebra::Vector3::<S>::new(k(p[0]), k(p[1]), k(p[2]));
                match Self::FRAME_BODY[frame] {
                    ::core::option::Option::Some(b) => {
                        let (rb, pb) = &bodies[b];
                        (rb * r, pb + rb * p)
                    }
                    ::core::option::Option::None => (r, p),
                }
            }

            /// The placement of frame `frame` (an index of
            /// [`FRAMES`](Self::FRAMES)) in the world at `q`: rotation and
            /// origin. Panics if `frame` is out of range.
            #[inline]
            pub fn frame_placement(&self, q: &#sv, frame: usize) -> #placement {
                Self::placement_from(&self.body_placements(q), frame)
            }

            /// The geometric Jacobian of frame `frame` at `q`, Pinocchio's
            /// `LOCAL_WORLD_ALIGNED`: `J q̇` is the linear velocity of the
            /// frame's origin (rows 0–2) and its angular velocity (rows
            /// 3–5), both in world axes. Columns of joints the frame does
            /// not hang from are zero. Panics if `frame` is out of range.
            pub fn frame_jacobian(&self, q: &#sv, frame: usize) -> ::lagrange::nalgebra::SMatrix<S, 6, #n> {
                let bodies = self.body_placements(q);
                let (_, origin) = Self::placement_from(&bodies, frame);
                let k = |x: f64| ::lagrange::nalgebra::convert::<f64, S>(x);
                let mut j = ::lagrange::nalgebra::SMatrix::<S, 6, #n>::zeros();
                let mut at = Self::FRAME_BODY[frame];
                while let ::core::option::Option::Some(b) = at {
                    let (rb, pb) = &bodies[b];
                    let a = &Self::BODY_AXIS[b];
                    let axis = rb * ::lagrange::nalgebra::Vector3::<S>::new(k(a[0]), k(a[1]), k(a[2]));
                    if Self::BODY_PRISMATIC[b] {
                        j.fixed_view_mut::<3, 1>(0, b).copy_from(&axis);
                    } else {
                        let arm = origin - pb;
                        j.fixed_view_mut::<3, 1>(0, b).copy_from(&axis.cross(&arm));
                        j.fixed_view_mut::<3, 1>(3, b).copy_from(&axis);
                    }
                    at = Self::BODY_PARENT[b];
                }
                j
            }

            /// The velocity of frame `frame` at `(q, q̇)`: `J q̇`, the linear
            /// velocity of its origin then its angular velocity, in world
            /// axes (see [`frame_jacobian`](Self::frame_jacobian)).
            #[inline]
            pub fn frame_velocity(&self, q: &#sv, qdot: &#sv, frame: usize) -> ::lagrange::nalgebra::SVector<S, 6> {
                self.frame_jacobian(q, frame) * qdot
            }


            #regressor_items
        }
    }
}

fn algorithms_body_poses(
    t: &mut super::trace::Trace,
    bodies: &[Body],
    fb: Option<&super::algorithms::Floating>,
    q: &[super::trace::Val],
) -> Vec<super::trace::Val> {
    super::algorithms::frames::body_poses(t, bodies, fb, q)
        .into_iter()
        .flat_map(|p| {
            let mut v: Vec<super::trace::Val> = p.rot.iter().flatten().copied().collect();
            v.extend(p.pos);
            v
        })
        .collect()
}

/// The `impl` block of the frames and the regressor on a floating base:
/// the configuration `q` has the base's 7 first (position, quaternion),
/// the velocities `ν` its 6 (linear, angular, in its frame), as
/// [`super::floating`] writes them. A frame on no moving body is on the
/// base's.
pub fn emit_floating(
    name: &syn::Ident,
    bodies: &[Body],
    frames: &[Frame],
    mass: &super::tree::Mass,
    regressor: bool,
) -> TokenStream {
    let n = bodies.len();
    let (nq, nv) = (7 + n, 6 + n);
    let nf = frames.len();
    let (poses_body, poses_out) = super::function_of(&[("q", nq)], |t, x| {
        let fb = super::floating::base(t, mass, &x[0]);
        let mut out: Vec<super::trace::Val> = fb.rot.iter().flatten().copied().collect();
        out.extend(fb.pos);
        out.extend(algorithms_body_poses(t, bodies, Some(&fb), &x[0][7..]));
        out
    });
    let poses = placements(&poses_out);
    let (base_pose, poses) = (&poses[0], &poses[1..]);
    let Tables {
        frame_names,
        frame_body,
        frame_rot,
        frame_pos,
        parent,
        axis,
        prismatic,
    } = tables(bodies, frames);
    // The regressor and its parameters, where `#[lagrange(regressor)]`
    // asks for them: `10 n` columns, the largest item of a large robot.
    let regressor_items = if regressor {
        let sq = quote!(::lagrange::nalgebra::SVector<S, #nq>);
        let sv = quote!(::lagrange::nalgebra::SVector<S, #nv>);
        let np = regressor::PER_BODY * (n + 1);
        let params: Vec<Literal> = regressor::base_parameters(mass)
            .into_iter()
            .chain(bodies.iter().flat_map(regressor::parameters))
            .map(lit)
            .collect();
        let (y_body, y_out) = super::function_of(&[("q", nq), ("v", nv), ("a", nv)], |t, x| {
            let fb = super::floating::base(t, mass, &x[0]);
            let y = regressor::regressor(t, bodies, Some(&fb), &x[0][7..], &x[1], &x[2], true);
            // Column-major, as nalgebra stores it.
            (0..np)
                .flat_map(|c| y.iter().map(move |row| row[c]))
                .collect()
        });
        let y_cols: Vec<TokenStream> = y_out.chunks(nv).map(|c| quote!([#(#c),*])).collect();
        quote! {
            /// The inertial parameters `π` of the file, ten per body, the
            /// floating base's body first, then the joints' bodies in the
            /// coordinates' order: `m`, the first moment `m c` (3), and the
            /// inertia about the body's frame `Ixx, Ixy, Iyy, Ixz, Iyz, Izz`,
            /// in the body's axes (what is fixed or locked to a body
            /// included): [`regressor`](Self::regressor)` · π = τ`.
            pub const PARAMETERS: [f64; #np] = [#(#params),*];

            /// The inertial-parameter regressor `Y(q, ν, ν̇)`: `Y π` is
            /// [`inverse_dynamics`](Self::inverse_dynamics)`(q, ν, ν̇)` for
            /// every `π` (ten per body, the base's first, as
            /// [`PARAMETERS`](Self::PARAMETERS)), gravity included; its
            /// first six rows are the base's wrench.
            #[inline]
            pub fn regressor(&self, q: &#sq, v: &#sv, a: &#sv) -> ::lagrange::nalgebra::SMatrix<S, #nv, #np> {
                #y_body
                ::lagrange::nalgebra::SMatrix::<S, #nv, #np>::from_array_storage(
                    ::lagrange::nalgebra::ArrayStorage([#(#y_cols),*])
                )
            }
        }
    } else {
        TokenStream::new()
    };
    let simd = quote! {
        S: ::lagrange::nalgebra::SimdRealField + ::core::marker::Copy,
        S::Element: ::lagrange::nalgebra::RealField + ::core::marker::Copy,
    };
    let sq = quote!(::lagrange::nalgebra::SVector<S, #nq>);
    let sv = quote!(::lagrange::nalgebra::SVector<S, #nv>);
    let placement = quote!((
        ::lagrange::nalgebra::Matrix3<S>,
        ::lagrange::nalgebra::Vector3<S>
    ));
    quote! {
        #[allow(unused_variables, unused_parens, non_snake_case, clippy::all, clippy::pedantic)]
        impl<S> #name<S> where #simd {
            /// Names of the frames: the URDF's links, every one, parents
            /// first (a frame is fixed to a moving body or to the base's).
            pub const FRAMES: [&'static str; #nf] = [#(#frame_names),*];
            const FRAME_BODY: [::core::option::Option<usize>; #nf] = [#(#frame_body),*];
            const FRAME_ROT: [[f64; 9]; #nf] = [#(#frame_rot),*];
            const FRAME_POS: [[f64; 3]; #nf] = [#(#frame_pos),*];
            const BODY_PARENT: [::core::option::Option<usize>; #n] = [#(#parent),*];
            const BODY_AXIS: [[f64; 3]; #n] = [#(#axis),*];
            const BODY_PRISMATIC: [bool; #n] = [#(#prismatic),*];

            /// The index of the frame named `name` in
            /// [`FRAMES`](Self::FRAMES), if there is one.
            pub fn frame_index(name: &str) -> ::core::option::Option<usize> {
                Self::FRAMES.iter().position(|f| *f == name)
            }

            /// The base's placement and every moving body's frame (its
            /// joint's, the child link's) in the world at `q`: rotations
            /// (the frame's axes in world coordinates) and origins.
            #[inline]
            fn placements(q: &#sq) -> (#placement, [#placement; #n]) {
                #poses_body
                (#base_pose, [#(#poses),*])
            }

            /// The floating base's placement in the world at `q`: its
            /// rotation (of the quaternion, `|q|²` times a rotation off the
            /// unit sphere) and its origin.
            #[inline]
            pub fn base_placement(&self, q: &#sq) -> #placement {
                Self::placements(q).0
            }

            /// Every moving body's frame (its joint's, the child link's)
            /// in the world at `q`: the rotation and the origin.
            #[inline]
            pub fn body_placements(&self, q: &#sq) -> [#placement; #n] {
                Self::placements(q).1
            }

            fn placement_from(base: &#placement, bodies: &[#placement; #n], frame: usize) -> #placement {
                let k = |x: f64| ::lagrange::nalgebra::convert::<f64, S>(x);
                let r = &Self::FRAME_ROT[frame];
                let p = &Self::FRAME_POS[frame];
                let r = ::lagrange::nalgebra::Matrix3::<S>::new(
                    k(r[0]), k(r[1]), k(r[2]), k(r[3]), k(r[4]), k(r[5]), k(r[6]), k(r[7]), k(r[8]),
                );
                let p = ::lagrange::nalgebra::Vector3::<S>::new(k(p[0]), k(p[1]), k(p[2]));
                let (rb, pb) = match Self::FRAME_BODY[frame] {
                    ::core::option::Option::Some(b) => &bodies[b],
                    ::core::option::Option::None => base,
                };
                (rb * r, pb + rb * p)
            }

            /// The placement of frame `frame` (an index of
            /// [`FRAMES`](Self::FRAMES)) in the world at `q`: rotation and
            /// origin. Panics if `frame` is out of range.
            #[inline]
            pub fn frame_placement(&self, q: &#sq, frame: usize) -> #placement {
                let (base, bodies) = Self::placements(q);
                Self::placement_from(&base, &bodies, frame)
            }

            /// The geometric Jacobian of frame `frame` at `q` in the
            /// velocities `ν`, Pinocchio's `LOCAL_WORLD_ALIGNED`: `J ν` is
            /// the linear velocity of the frame's origin (rows 0–2) and its
            /// angular velocity (rows 3–5), both in world axes. The base's
            /// six columns come first (its linear then angular velocity in
            /// its own frame), then the joints'; columns of joints the frame
            /// does not hang from are zero. Panics if `frame` is out of
            /// range.
            pub fn frame_jacobian(&self, q: &#sq, frame: usize) -> ::lagrange::nalgebra::SMatrix<S, 6, #nv> {
                let (base, bodies) = Self::placements(q);
                let (_, origin) = Self::placement_from(&base, &bodies, frame);
                let k = |x: f64| ::lagrange::nalgebra::convert::<f64, S>(x);
                let mut j = ::lagrange::nalgebra::SMatrix::<S, 6, #nv>::zeros();
                let (r0, p0) = &base;
                let arm = origin - p0;
                for c in 0..3 {
                    let axis: ::lagrange::nalgebra::Vector3<S> = r0.column(c).into_owned();
                    j.fixed_view_mut::<3, 1>(0, c).copy_from(&axis);
                    j.fixed_view_mut::<3, 1>(0, 3 + c).copy_from(&axis.cross(&arm));
                    j.fixed_view_mut::<3, 1>(3, 3 + c).copy_from(&axis);
                }
                let mut at = Self::FRAME_BODY[frame];
                while let ::core::option::Option::Some(b) = at {
                    let (rb, pb) = &bodies[b];
                    let a = &Self::BODY_AXIS[b];
                    let axis = rb * ::lagrange::nalgebra::Vector3::<S>::new(k(a[0]), k(a[1]), k(a[2]));
                    if Self::BODY_PRISMATIC[b] {
                        j.fixed_view_mut::<3, 1>(0, 6 + b).copy_from(&axis);
                    } else {
                        let arm = origin - pb;
                        j.fixed_view_mut::<3, 1>(0, 6 + b).copy_from(&axis.cross(&arm));
                        j.fixed_view_mut::<3, 1>(3, 6 + b).copy_from(&axis);
                    }
                    at = Self::BODY_PARENT[b];
                }
                j
            }

            /// The velocity of frame `frame` at `(q, ν)`: `J ν`, the linear
            /// velocity of its origin then its angular velocity, in world
            /// axes (see [`frame_jacobian`](Self::frame_jacobian)).
            #[inline]
            pub fn frame_velocity(&self, q: &#sq, v: &#sv, frame: usize) -> ::lagrange::nalgebra::SVector<S, 6> {
                self.frame_jacobian(q, frame) * v
            }


            #regressor_items
        }
    }
}
