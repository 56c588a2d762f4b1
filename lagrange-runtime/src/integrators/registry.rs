//! The registry's machinery: from one line per integrator (in
//! `integrators/mod.rs`), its module, [`Method`] with [`Method::ALL`] and the table of methods in its docs,
//! [`AnyIntegrator`] (every method with its settings, itself a method a
//! [`Stepper`](crate::stepper::Stepper) can drive) and the names the
//! prelude exports. (Each is an [`Integrator`] through one blanket
//! implementation over [`StepMethod`](super::StepMethod).)
//!
//! [`Integrator`]: super::Integrator
//! [`Method`]: super::Method
//! [`Method::ALL`]: super::Method::ALL
//! [`AnyIntegrator`]: super::AnyIntegrator

/// `adaptive` or `fixed`, as a `bool`.
macro_rules! is_adaptive {
    (adaptive) => {
        true
    };
    (fixed) => {
        false
    };
}

/// An adaptive method `$m` with tolerances `$rtol`, `$atol`; a fixed-step
/// one as it is.
macro_rules! with_tolerances {
    (adaptive, $m:expr, $rtol:expr, $atol:expr) => {
        $m.rtol($rtol).atol($atol)
    };
    (fixed, $m:expr, $rtol:expr, $atol:expr) => {{
        let _ = ($rtol, $atol);
        $m
    }};
}

/// The registry: for each integrator, its module and type, then each of
/// its named settings (a [`Method`](super::Method) variant: its id, order,
/// kind, whether its Newton iterations use the model's Jacobians, how it
/// is built from a step `h`, and its row of the table of methods).
macro_rules! registry {
    ($(
        $module:ident :: $ty:ident {
            $(
                $variant:ident = $id:literal, order $order:literal, $kind:ident,
                jacobians $jac:literal, |$h:ident| $build:expr,
                $row:literal;
            )+
        }
    )+) => {
        // The modules are declared beside the registry, outside any macro,
        // so that rustfmt reaches them; a module left out fails here.
        $(
            pub use $module::$ty;
        )+

        /// Every integrator of the runtime by name, without its settings:
        /// a study that runs them all lists them once, and a method added
        /// to the registry is run everywhere [`Method::ALL`] is.
        ///
        /// | method | order | kind | cost per step | when to use it |
        /// |---|---|---|---|---|
        $($(
            #[doc = concat!("| [`", stringify!($variant), "`](Method::", stringify!($variant), ") | ", $order, " | ", $row, " |")]
        )+)+
        ///
        /// Costs are right-hand side evaluations (one `M q̈ = f` solve
        /// each). The implicit Runge–Kutta methods are symmetric and
        /// conserve quadratic invariants; they are symplectic for a
        /// constant mass matrix, and for `M(q)` they keep the energy from
        /// drifting on reversible models without being symplectic
        /// ([the crate's docs](crate#implicit-methods-symmetric-and-when-symplectic)).
        ///
        /// ```
        /// use lagrange::models::Oscillator;
        /// use lagrange_runtime::integrators::Method;
        /// use lagrange_runtime::Integrator;
        /// use lagrange_runtime::nalgebra::Vector1;
        ///
        /// let spring = Oscillator::new(1.0, 1.0, 0.0);
        /// for method in Method::ALL {
        ///     // Fixed-step methods at h = 0.01, adaptive ones at rtol = atol = 1e-8.
        ///     let run = method
        ///         .integrator(0.01, 1e-8)
        ///         .integrate(&spring, 0.0, Vector1::new(1.0), Vector1::new(0.0), &[1.0])?;
        ///     // x = cos t; explicit Euler, first order, errs most: ≈ h t / 2.
        ///     let x = run.last().unwrap().q[0];
        ///     assert!((x - 1f64.cos()).abs() < 1e-2, "{method:?}");
        /// }
        /// # Ok::<(), Box<dyn std::error::Error>>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        #[non_exhaustive]
        pub enum Method {
            $($(
                #[doc = concat!("[`", stringify!($ty), "`]: ", $row)]
                $variant,
            )+)+
        }

        impl Method {
            /// Every method, in the registry's order.
            pub const ALL: [Method; 0 $($( + { let _ = stringify!($variant); 1 } )+)+] =
                [$($(Method::$variant,)+)+];

            /// Its name in lower case, as in file names and tables
            /// (`explicit_euler`, `gauss_legendre_2`).
            pub const fn id(self) -> &'static str {
                match self {
                    $($(Method::$variant => $id,)+)+
                }
            }

            /// The order of its steps.
            pub const fn order(self) -> usize {
                match self {
                    $($(Method::$variant => $order,)+)+
                }
            }

            /// Whether it chooses its own steps to meet a tolerance.
            pub const fn is_adaptive(self) -> bool {
                match self {
                    $($(Method::$variant => is_adaptive!($kind),)+)+
                }
            }

            /// Whether it solves its stages by Newton's method on
            /// `M q̈ − f`, with the model's exact Jacobians or, without
            /// them, by differences.
            pub const fn uses_jacobians(self) -> bool {
                match self {
                    $($(Method::$variant => $jac,)+)+
                }
            }

            /// The fixed-step methods with step `h`; the adaptive ones at
            /// their default tolerances (they have no step to set).
            pub fn with_step<S: RealField + Copy>(self, h: S) -> AnyIntegrator<S> {
                match self {
                    $($(Method::$variant => {
                        let $h = h;
                        let _ = $h;
                        AnyIntegrator::$variant($build)
                    })+)+
                }
            }
        }

        /// Any of the runtime's integrators with its settings: an
        /// [`Integrator`] itself, so that code written once runs any of
        /// them (each through the run loop of its kind), and a method a
        /// [`Stepper`](crate::stepper::Stepper) steps.
        #[derive(Clone, Copy, Debug, PartialEq)]
        #[allow(missing_docs)]
        #[non_exhaustive]
        pub enum AnyIntegrator<S: RealField + Copy> {
            $($( $variant($ty<S>), )+)+
        }

        impl<S: RealField + Copy> AnyIntegrator<S> {
            /// The method by name.
            pub fn method(&self) -> Method {
                match self {
                    $($(Self::$variant(_) => Method::$variant,)+)+
                }
            }

            /// The step budget (see each method's `max_steps`).
            pub fn max_steps(self, max_steps: usize) -> Self {
                match self {
                    $($(Self::$variant(m) => Self::$variant(m.max_steps(max_steps)),)+)+
                }
            }

            /// The tolerances of an adaptive method; a fixed-step one has
            /// none and is returned unchanged.
            pub fn tolerances(self, rtol: S, atol: S) -> Self {
                match self {
                    $($(Self::$variant(m) => Self::$variant(with_tolerances!($kind, m, rtol, atol)),)+)+
                }
            }
        }

        impl<S: RealField + Copy> StepMethod<S> for AnyIntegrator<S> {
            type Walker<const N: usize> = AnyWalker<S, N>;

            fn walker<const N: usize>(&self) -> Result<AnyWalker<S, N>, InvalidInput<S>> {
                Ok(match self {
                    $($(Self::$variant(m) => AnyWalker::$variant(m.walker::<N>()?),)+)+
                })
            }
        }

        /// The walker of [`AnyIntegrator`]: its method's.
        #[doc(hidden)]
        pub enum AnyWalker<S: RealField + Copy, const N: usize> {
            $($( $variant(<$ty<S> as StepMethod<S>>::Walker<N>), )+)+
        }

        impl<S: RealField + Copy, const N: usize> Walk<S, N> for AnyWalker<S, N> {
            fn advance<L: Lagrangian<N, Scalar = S>>(
                &mut self,
                run: &mut Run<'_, S, N>,
                model: &L,
                target: S,
            ) -> Result<Advanced, IntegrationError<S, N>> {
                match self {
                    $($(Self::$variant(w) => w.advance(run, model, target),)+)+
                }
            }
        }

        /// Every integrator's type: what the prelude exports.
        pub mod all {
            pub use super::{$($ty),+};
        }
    };
}

pub(super) use {is_adaptive, registry, with_tolerances};
