//! A robot on a floating base (`#[lagrange(urdf = "..", floating)]`): the
//! items, in two sets of coordinates.
//!
//! The configuration `q` is the base's position `(x, y, z)` in the world,
//! its orientation the unit quaternion `(w, x, y, z)` (base to world), then
//! the joints: `7 + n` coordinates. The recursions run in the velocities
//! `ν` of Pinocchio's free flyer, `6 + n`: the base's spatial velocity in
//! its own frame, linear `v = Rᵀ ṗ` then angular `ω = 2 Im(q̄ q̇)`, then the
//! joint rates (`inverse_dynamics`, `forward_dynamics`, `velocity_mass_matrix`,
//! ...). The `Lagrangian` is in the coordinates' rates `q̇`, `7 + n` of
//! them, its unit-norm constraint `|q|² = 1` a `Holonomic` one, as a free
//! body in quaternions is: with `ν = J q̇`, `J = diag(Rᵀ, 2E(q), 1)`,
//! `M_q = Jᵀ M_ν J` (singular along the quaternion itself, regular on the
//! rates the constraint allows) and `f_q = −Jᵀ RNEA(q, ν, J̇ q̇)`, where
//! `J̇ q̇ = (−ω × v, 0, 0)` (`ω̇ = 2 Im(q̄ q̈)` exactly, since `q̄̇ q̇` is
//! real). On the sphere and for rates along it, `M_q q̈ = f_q + Gᵀλ` with
//! `G q̈ = −γ` is the same motion as Pinocchio's `M ν̇ + nle = τ`:
//! `f_q` is the Euler–Lagrange forcing up to a multiple of `Gᵀ`, which the
//! multiplier takes.
//!
//! The recursions are traced and unrolled (`inverse_dynamics`,
//! `forward_dynamics`, `velocity_mass_matrix`, `gravity_torques`, the
//! energies, the maps, `solve_velocity_mass_matrix` of [`super::solve`]);
//! what is built from them (`unforced_accelerations`, `mass_matrix`,
//! `forcing`) calls them and applies `J`'s 6 × 7 base block in loops, so
//! that each recursion's code is written once: romeo's items are half the
//! size they were with each traced apart, and its crate builds in half the
//! time. `nonlinear_effects` calls `inverse_dynamics` at `ν̇ = 0`: RNEA
//! traced a second time with the zeros folded had 2 % fewer operations
//! (romeo's 3134 multiplications against 3199), measured slower on the
//! Go2 (about 340 against 320 ns: more code beside `M` and the solve in
//! the instruction cache), and added a third to the floating robots'
//! expansions (202 kB of tokens on romeo).

use super::algorithms::{self, Floating, M3};
use super::trace::{ONE, Trace, Val, ZERO};
use super::tree::{Body, Mass};
use super::{Input, function_of};
use proc_macro2::TokenStream;
use quote::quote;

/// The names of the base's seven coordinates.
pub const BASE: [&str; 7] = [
    "base_x", "base_y", "base_z", "base_qw", "base_qx", "base_qy", "base_qz",
];

/// The base read from the configuration's first seven inputs.
pub(super) fn base<'a>(t: &mut Trace, mass: &'a Mass, q: &[Val]) -> Floating<'a> {
    let rot = algorithms::quaternion_rotation(t, [q[3], q[4], q[5], q[6]]);
    Floating {
        mass,
        rot,
        pos: [q[0], q[1], q[2]],
    }
}

/// `E(q)`: the base rates `ω = 2E q̇` of the quaternion's rates.
fn e_of(q: &[Val]) -> [[Val; 4]; 3] {
    let [w, x, y, z] = [q[3], q[4], q[5], q[6]];
    let n = |v: Val| v.negated();
    [[n(x), w, z, n(y)], [n(y), n(z), w, x], [n(z), y, n(x), w]]
}

/// `J`, `(6 + n) × (7 + n)`: `ν = J q̇`.
fn jacobian(t: &mut Trace, rot: &M3, q: &[Val], n: usize) -> Vec<Vec<Val>> {
    let mut j = vec![vec![ZERO; 7 + n]; 6 + n];
    for a in 0..3 {
        for b in 0..3 {
            j[a][b] = rot[b][a];
        }
    }
    let e = e_of(q);
    for a in 0..3 {
        for b in 0..4 {
            j[3 + a][3 + b] = t.mul(Val::K(2.0), e[a][b]);
        }
    }
    for k in 0..n {
        j[6 + k][7 + k] = ONE;
    }
    j
}

fn times(t: &mut Trace, j: &[Vec<Val>], x: &[Val]) -> Vec<Val> {
    j.iter().map(|row| t.dot(row, x)).collect()
}

/// `q̇` of the velocities: `ṗ = R v`, `q̇ = ½ q (0, ω)`.
fn rates(t: &mut Trace, rot: &M3, q: &[Val], v: &[Val]) -> Vec<Val> {
    let mut out: Vec<Val> = (0..3).map(|a| t.dot(&rot[a], &v[0..3])).collect();
    let [w, x, y, z] = [q[3], q[4], q[5], q[6]];
    let [o1, o2, o3] = [v[3], v[4], v[5]];
    let half = Val::K(0.5);
    let mut lin = |terms: &[(Val, Val, bool)]| {
        let mut acc = ZERO;
        for &(a, b, plus) in terms {
            let p = t.mul(a, b);
            acc = if plus { t.add(acc, p) } else { t.sub(acc, p) };
        }
        t.mul(half, acc)
    };
    out.push(lin(&[(x, o1, false), (y, o2, false), (z, o3, false)]));
    out.push(lin(&[(w, o1, true), (y, o3, true), (z, o2, false)]));
    out.push(lin(&[(w, o2, true), (z, o1, true), (x, o3, false)]));
    out.push(lin(&[(w, o3, true), (x, o2, true), (y, o1, false)]));
    out.extend_from_slice(&v[6..]);
    out
}

/// The items of a robot on a floating base.
pub(super) fn emit(input: &Input, bodies: &[Body], mass: &Mass) -> TokenStream {
    let n = bodies.len();
    let (nq, nv) = (7 + n, 6 + n);
    let name = &input.name;
    let rel = input.path.value();
    let names: Vec<&str> = BASE
        .iter()
        .copied()
        .chain(bodies.iter().map(|b| b.name.as_str()))
        .collect();
    let velocity_names: Vec<String> = [
        "base_vx", "base_vy", "base_vz", "base_wx", "base_wy", "base_wz",
    ]
    .iter()
    .map(|s| s.to_string())
    .chain(bodies.iter().map(|b| b.name.clone()))
    .collect();
    let vector = |len: usize, outs: Vec<TokenStream>| {
        quote!(::lagrange::nalgebra::SVector::<S, #len>::from_array_storage(
            ::lagrange::nalgebra::ArrayStorage([[#(#outs),*]])
        ))
    };
    let matrix = |len: usize, outs: Vec<TokenStream>| {
        let columns: Vec<TokenStream> = outs.chunks(len).map(|col| quote!([#(#col),*])).collect();
        quote!(::lagrange::nalgebra::SMatrix::<S, #len, #len>::from_array_storage(
            ::lagrange::nalgebra::ArrayStorage([#(#columns),*])
        ))
    };
    let zero = vec![ZERO; nv];
    let (rnea_body, out) = function_of(&[("q", nq), ("v", nv), ("a", nv)], |t, x| {
        let fb = base(t, mass, &x[0]);
        algorithms::rnea(t, bodies, Some(&fb), &x[0][7..], &x[1], &x[2], true)
    });
    let rnea_out = vector(nv, out);
    let parents: Vec<Option<usize>> = bodies.iter().map(|b| b.parent).collect();
    let (solve_body, _) = super::solve::emit(&super::solve::parent_table(&parents, 6));
    let (grav_body, out) = function_of(&[("q", nq)], |t, x| {
        let fb = base(t, mass, &x[0]);
        algorithms::rnea(t, bodies, Some(&fb), &x[0][7..], &zero, &zero, true)
    });
    let grav_out = vector(nv, out);
    let (aba_body, out) = function_of(&[("q", nq), ("v", nv), ("tau", nv)], |t, x| {
        let fb = base(t, mass, &x[0]);
        algorithms::aba(t, bodies, Some(&fb), &x[0][7..], &x[1], &x[2])
    });
    let aba_out = vector(nv, out);
    let (crba_body, out) = function_of(&[("q", nq)], |t, x| {
        let fb = base(t, mass, &x[0]);
        // Column-major for nalgebra: M is symmetric, its rows are its columns.
        algorithms::crba(t, bodies, Some(&fb), &x[0][7..])
            .into_iter()
            .flatten()
            .collect()
    });
    let crba_out = matrix(nv, out);
    let (nu_body, out) = function_of(&[("q", nq), ("qdot", nq)], |t, x| {
        let fb = base(t, mass, &x[0]);
        let j = jacobian(t, &fb.rot, &x[0], n);
        times(t, &j, &x[1])
    });
    let nu_out = vector(nv, out);
    let (rates_body, out) = function_of(&[("q", nq), ("v", nv)], |t, x| {
        let fb = base(t, mass, &x[0]);
        rates(t, &fb.rot, &x[0], &x[1])
    });
    let rates_out = vector(nq, out);
    let (ke_body, out) = function_of(&[("q", nq), ("qdot", nq)], |t, x| {
        let fb = base(t, mass, &x[0]);
        let j = jacobian(t, &fb.rot, &x[0], n);
        let nu = times(t, &j, &x[1]);
        vec![algorithms::kinetic(t, bodies, Some(&fb), &x[0][7..], &nu)]
    });
    let ke = &out[0];
    let ke = quote!(#ke);
    let (pe_body, out) = function_of(&[("q", nq)], |t, x| {
        let fb = base(t, mass, &x[0]);
        vec![algorithms::potential(t, bodies, Some(&fb), &x[0][7..])]
    });
    let pe = &out[0];
    let pe = quote!(#pe);
    let doc_n = format!(
        "Number of coordinates: the floating base's 7 (position, unit quaternion) and the moving joints of `{rel}`."
    );
    let doc_v = format!("Number of velocities: the base's 6 and the moving joints of `{rel}`.");
    let simd = quote! {
        S: ::lagrange::nalgebra::SimdRealField + ::core::marker::Copy,
        S::Element: ::lagrange::nalgebra::RealField + ::core::marker::Copy,
    };
    let sq = quote!(::lagrange::nalgebra::SVector<S, #nq>);
    let sv = quote!(::lagrange::nalgebra::SVector<S, #nv>);
    let include = input.include();
    let holonomic = quote!(::lagrange::Holonomic<#nq, 1>);
    let (item, new) = super::robot_struct(input, bodies, mass);
    quote! {
        #item

        // The URDF read at compile time: rebuilt when it changes.
        #include

        #[allow(unused_variables, unused_parens, non_snake_case, clippy::all, clippy::pedantic)]
        impl<S> #name<S> where #simd {
            #[doc = #doc_n]
            pub const DOF: usize = #nq;
            #[doc = #doc_v]
            pub const VELOCITIES: usize = #nv;
            /// Names of the coordinates: the base's position and quaternion
            /// `(w, x, y, z)`, then the moving joints, parents first.
            pub const COORDINATES: [&'static str; #nq] = [#(#names),*];
            /// Names of the velocities `ν`: the base's linear then angular
            /// velocity in its own frame, then the joints' rates.
            pub const VELOCITY_NAMES: [&'static str; #nv] = [#(#velocity_names),*];
            /// The names of the constraints: the quaternion's unit norm.
            pub const CONSTRAINTS: [&'static str; 1] = ["unit_quaternion"];
            #new
            /// Inverse dynamics by RNEA: the forces `τ(q, ν, ν̇)` that give
            /// the accelerations `ν̇`, gravity included: the wrench on the
            /// base (force, moment, in its frame), then the joints'.
            #[inline]
            pub fn inverse_dynamics(&self, q: &#sq, v: &#sv, a: &#sv) -> #sv {
                #rnea_body
                #rnea_out
            }
            /// The nonlinear effects (RNEA at `ν̇ = 0`): `M ν̇ + nle = τ`.
            #[inline]
            pub fn nonlinear_effects(&self, q: &#sq, v: &#sv) -> #sv {
                self.inverse_dynamics(q, v, &<#sv>::zeros())
            }
            /// The gravity forces (RNEA at rest), the base's wrench first.
            #[inline]
            pub fn gravity_torques(&self, q: &#sq) -> #sv {
                #grav_body
                #grav_out
            }
            /// Forward dynamics by ABA: `ν̇(q, ν, τ)`, without forming `M`.
            #[inline]
            pub fn forward_dynamics(&self, q: &#sq, v: &#sv, tau: &#sv) -> #sv {
                #aba_body
                #aba_out
            }
            /// `ν̇(q, ν)` unforced (ABA at `τ = 0`).
            #[inline]
            pub fn unforced_accelerations(&self, q: &#sq, v: &#sv) -> #sv {
                self.forward_dynamics(q, v, &<#sv>::zeros())
            }
            /// The mass matrix in the velocities `ν` by CRBA: `M ν̇ + nle = τ`.
            #[inline]
            pub fn velocity_mass_matrix(&self, q: &#sq) -> ::lagrange::nalgebra::SMatrix<S, #nv, #nv> {
                #crba_body
                #crba_out
            }
            /// The velocities `ν = J q̇` of the coordinates' rates: `v = Rᵀ ṗ`,
            /// `ω = 2 Im(q̄ q̇)`, the joints' rates.
            #[inline]
            pub fn velocities(&self, q: &#sq, qdot: &#sq) -> #sv {
                #nu_body
                #nu_out
            }
            /// The coordinates' rates of the velocities: `ṗ = R v`,
            /// `q̇ = ½ q (0, ω)`, the joints' rates (along the unit sphere).
            #[inline]
            pub fn rates(&self, q: &#sq, v: &#sv) -> #sq {
                #rates_body
                #rates_out
            }
            /// The mass matrix in the coordinates' rates, `Jᵀ M J`: singular
            /// along the quaternion, regular on the rates `|q| = 1` allows.
            #[inline]
            pub fn mass_matrix(&self, t: S, q: &#sq) -> ::lagrange::nalgebra::SMatrix<S, #nq, #nq> {
                // J's base block only (the joints' is the identity): `M J`,
                // then `Jᵀ (M J)`, its upper triangle mirrored.
                let m = self.velocity_mass_matrix(q);
                let j = Self::base_jacobian(q);
                let zero = ::lagrange::nalgebra::zero::<S>();
                let mut mj = ::lagrange::nalgebra::SMatrix::<S, #nv, #nq>::zeros();
                for r in 0..#nv {
                    for c in 0..7 {
                        let mut s = zero;
                        for k in 0..6 {
                            s += m[(r, k)] * j[k][c];
                        }
                        mj[(r, c)] = s;
                    }
                    for c in 7..#nq {
                        mj[(r, c)] = m[(r, c - 1)];
                    }
                }
                let mut out = ::lagrange::nalgebra::SMatrix::<S, #nq, #nq>::zeros();
                for c in 0..#nq {
                    for r in 0..=c {
                        let x = if r < 7 {
                            let mut s = zero;
                            for k in 0..6 {
                                s += j[k][r] * mj[(k, c)];
                            }
                            s
                        } else {
                            mj[(r - 1, c)]
                        };
                        out[(r, c)] = x;
                        out[(c, r)] = x;
                    }
                }
                out
            }
            /// The base's block of `J` (`ν = J q̇`, the joints' block the
            /// identity): `Rᵀ` over the position's rates, `2E(q)` over the
            /// quaternion's.
            #[inline]
            fn base_jacobian(q: &#sq) -> [[S; 7]; 6] {
                let (w, x, y, z) = (q[3], q[4], q[5], q[6]);
                let two = ::lagrange::nalgebra::convert::<f64, S>(2.0);
                let r = [
                    [w * w + x * x - y * y - z * z, two * (x * y - w * z), two * (x * z + w * y)],
                    [two * (x * y + w * z), w * w - x * x + y * y - z * z, two * (y * z - w * x)],
                    [two * (x * z - w * y), two * (y * z + w * x), w * w - x * x - y * y + z * z],
                ];
                let e = [[-x, w, z, -y], [-y, -z, w, x], [-z, y, -x, w]];
                let mut j = [[::lagrange::nalgebra::zero::<S>(); 7]; 6];
                for a in 0..3 {
                    for b in 0..3 {
                        j[a][b] = r[b][a];
                    }
                    for b in 0..4 {
                        j[3 + a][3 + b] = two * e[a][b];
                    }
                }
                j
            }
            /// The forcing of `M q̈ = f + Gᵀλ`: `f = −Jᵀ RNEA(q, J q̇, J̇ q̇)`.
            #[inline]
            pub fn forcing(&self, t: S, q: &#sq, qdot: &#sq) -> #sq {
                let nu = self.velocities(q, qdot);
                // J̇ q̇ = (−ω × v, 0, 0).
                let mut jd = <#sv>::zeros();
                for a in 0..3 {
                    let (b, c) = ((a + 1) % 3, (a + 2) % 3);
                    jd[a] = nu[3 + c] * nu[b] - nu[3 + b] * nu[c];
                }
                let tau = self.inverse_dynamics(q, &nu, &jd);
                let j = Self::base_jacobian(q);
                let mut f = <#sq>::zeros();
                for c in 0..7 {
                    let mut s = ::lagrange::nalgebra::zero::<S>();
                    for k in 0..6 {
                        s += j[k][c] * tau[k];
                    }
                    f[c] = -s;
                }
                for c in 7..#nq {
                    f[c] = -tau[c - 1];
                }
                f
            }
            /// The kinetic energy `½ Σ vᵢᵀ Iᵢ vᵢ` (the base's included).
            #[inline]
            pub fn kinetic_energy(&self, t: S, q: &#sq, qdot: &#sq) -> S {
                #ke_body
                #ke
            }
            /// The potential energy in gravity `9.81` along `−z`.
            #[inline]
            pub fn potential_energy(&self, t: S, q: &#sq) -> S {
                #pe_body
                #pe
            }
        }

        #[allow(unused_variables, clippy::all)]
        impl<S: ::lagrange::nalgebra::RealField + ::core::marker::Copy> ::lagrange::Lagrangian<#nq> for #name<S> {
            type Scalar = S;
            const COORDINATES: [&'static str; #nq] = [#(#names),*];
            #[inline]
            fn mass_matrix(&self, t: S, q: &#sq) -> ::lagrange::nalgebra::SMatrix<S, #nq, #nq> {
                #name::mass_matrix(self, t, q)
            }
            #[inline]
            fn forcing(&self, t: S, q: &#sq, qdot: &#sq) -> #sq {
                #name::forcing(self, t, q, qdot)
            }
            #[inline]
            fn kinetic_energy(&self, t: S, q: &#sq, qdot: &#sq) -> S {
                #name::kinetic_energy(self, t, q, qdot)
            }
            #[inline]
            fn potential_energy(&self, t: S, q: &#sq) -> S {
                #name::potential_energy(self, t, q)
            }
            #[inline]
            fn visit_constraints<V: ::lagrange::constraints::Visitor<S, #nq>>(&self, visitor: V) -> ::core::option::Option<V::Output> {
                ::core::option::Option::Some(visitor.visit::<Self, 1>(self, ::core::default::Default::default()))
            }
        }

        #[allow(unused_variables, unused_parens, non_snake_case, clippy::all, clippy::pedantic)]
        impl<S: ::lagrange::nalgebra::RealField + ::core::marker::Copy> #name<S> {
            /// `M⁻¹ b` for the mass matrix `m` in the velocities `ν` of
            /// [`velocity_mass_matrix`](Self::velocity_mass_matrix):
            /// Featherstone's sparse `M = Lᵀ D L`, unrolled over this robot's
            /// tree (the base's six velocities a chain at its root), then its
            /// two substitutions (`Σ depth²` operations, not a dense
            /// Cholesky's `N³ / 6`). Reads only the lower triangle's entries
            /// `(i, j)` with `j` an ancestor of `i` (the others are zero in
            /// any `M` of this tree). `None` where a pivot of `D` is not
            /// finite or not above `N ε` times the largest (`m` not positive
            /// definite, or too ill-conditioned), or `x` is not finite: never
            /// a NaN. `M ν̇ = τ − nle` is
            /// `solve_velocity_mass_matrix(&m, &(tau - nle))`.
            #[inline]
            pub fn solve_velocity_mass_matrix(
                &self,
                m: &::lagrange::nalgebra::SMatrix<S, #nv, #nv>,
                b: &#sv,
            ) -> ::core::option::Option<#sv> {
                #solve_body
            }
        }

        // The quaternion's unit norm, `φ = w² + x² + y² + z² − 1`.
        #[allow(clippy::all)]
        impl<S: ::lagrange::nalgebra::RealField + ::core::marker::Copy> #holonomic for #name<S> {
            const CONSTRAINTS: [&'static str; 1] = ["unit_quaternion"];
            #[inline]
            fn constraints(&self, t: S, q: &#sq) -> ::lagrange::nalgebra::SVector<S, 1> {
                ::lagrange::nalgebra::SVector::<S, 1>::new(
                    q[3] * q[3] + q[4] * q[4] + q[5] * q[5] + q[6] * q[6] - S::one(),
                )
            }
            #[inline]
            fn constraint_jacobian(&self, t: S, q: &#sq) -> ::lagrange::nalgebra::SMatrix<S, 1, #nq> {
                let mut g = ::lagrange::nalgebra::SMatrix::<S, 1, #nq>::zeros();
                let two = S::one() + S::one();
                for k in 3..7 {
                    g[k] = two * q[k];
                }
                g
            }
            #[inline]
            fn constraint_velocities(&self, t: S, q: &#sq, qdot: &#sq) -> ::lagrange::nalgebra::SVector<S, 1> {
                let two = S::one() + S::one();
                ::lagrange::nalgebra::SVector::<S, 1>::new(
                    two * (q[3] * qdot[3] + q[4] * qdot[4] + q[5] * qdot[5] + q[6] * qdot[6]),
                )
            }
            #[inline]
            fn constraint_bias(&self, t: S, q: &#sq, qdot: &#sq) -> ::lagrange::nalgebra::SVector<S, 1> {
                let two = S::one() + S::one();
                ::lagrange::nalgebra::SVector::<S, 1>::new(
                    two * (qdot[3] * qdot[3] + qdot[4] * qdot[4] + qdot[5] * qdot[5] + qdot[6] * qdot[6]),
                )
            }
            #[inline]
            fn mass_regular_on_constraints_only(&self) -> bool {
                true
            }
        }
    }
}
