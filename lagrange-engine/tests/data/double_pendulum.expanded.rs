#[derive(Clone, Copy, Debug, PartialEq)]
#[allow(non_snake_case)]
pub struct DoublePendulum<S = f64> {
    /// The parameter `m1`.
    pub m1: S,
    /// The parameter `m2`.
    pub m2: S,
    /// The parameter `l1`.
    pub l1: S,
    /// The parameter `l2`.
    pub l2: S,
    /// The parameter `g`.
    pub g: S,
}
/// The parameters of [`DoublePendulum`] by name, for [`DoublePendulum::from_parameters`]: each field the parameter of that name (with its domain, where it declares one).
#[derive(Clone, Copy, Debug, PartialEq)]
#[allow(non_snake_case)]
pub struct DoublePendulumParameters<S = f64> {
    /// `m1`.
    pub m1: S,
    /// `m2`.
    pub m2: S,
    /// `l1`.
    pub l1: S,
    /// `l2`.
    pub l2: S,
    /// `g`.
    pub g: S,
}
#[allow(non_snake_case, clippy::all)]
impl<S: ::lagrange::nalgebra::RealField + ::core::marker::Copy> DoublePendulum<S> {
    /// `new`, each parameter checked against its declared domain: the first
    /// outside it is the error, named with its value.
    pub fn try_new(
        m1: S,
        m2: S,
        l1: S,
        l2: S,
        g: S,
    ) -> ::core::result::Result<Self, ::lagrange::ParameterError> {
        let model = Self::new(m1, m2, l1, l2, g);
        model.check_parameters()?;
        ::core::result::Result::Ok(model)
    }
    /// The model from its parameters by name, each checked against its declared
    /// domain (as `try_new`).
    pub fn from_parameters(
        parameters: DoublePendulumParameters<S>,
    ) -> ::core::result::Result<Self, ::lagrange::ParameterError> {
        Self::try_new(
            parameters.m1,
            parameters.m2,
            parameters.l1,
            parameters.l2,
            parameters.g,
        )
    }
    /// Whether every parameter lies inside its declared domain: the first that
    /// does not is the error (after a field was set, or a model was read back).
    pub fn check_parameters(
        &self,
    ) -> ::core::result::Result<(), ::lagrange::ParameterError> {
        ::core::result::Result::Ok(())
    }
}
#[allow(non_snake_case, clippy::all)]
impl<S: ::core::marker::Copy> DoublePendulum<S> {
    /// The model's parameters by name: with `..model.parameters()`, a model that
    /// differs from this one in the parameters named.
    pub fn parameters(&self) -> DoublePendulumParameters<S> {
        DoublePendulumParameters {
            m1: self.m1,
            m2: self.m2,
            l1: self.l1,
            l2: self.l2,
            g: self.g,
        }
    }
}
#[allow(unused_variables, unused_parens, non_snake_case, clippy::all, clippy::pedantic)]
impl<S: ::lagrange::nalgebra::SimdRealField + ::core::marker::Copy> DoublePendulum<S>
where
    S::Element: ::lagrange::nalgebra::RealField + ::core::marker::Copy,
{
    /// Number of degrees of freedom (generalized coordinates).
    pub const DOF: usize = 2;
    /// Names of the generalized coordinates, in the order of `q`.
    pub const COORDINATES: [&'static str; 2] = ["theta1", "theta2"];
    /// Names of the runtime parameters (the struct's fields; an
    /// indexed parameter `m[N]` is one field `m: [S; N]`), in
    /// declaration order.
    pub const PARAMETERS: [&'static str; 5] = ["m1", "m2", "l1", "l2", "g"];
    /// Names of the `let` values, in the order of `lets` (an indexed
    /// `let x[i in 0..N]` is `x[0]` … `x[N-1]`).
    pub const LETS: [&'static str; 4] = ["x1", "y1", "x2", "y2"];
    ///The derived equations `M q̈ = f`, readable: shared subexpressions first, then each entry.
    pub const EQUATIONS: &'static str = "e0 = m1 + m2\ne1 = cos(theta1)\ne2 = cos(theta2)\ne3 = sin(theta1)\ne4 = sin(theta2)\ne5 = e3*e2 - e1*e4\nM[theta1, theta1] = l1^2*e0\nM[theta1, theta2] = l1*l2*m2*(e1*e2 + e3*e4)\nM[theta2, theta2] = m2*l2^2\nf[theta1] = -l1*(e3*g*e0 + l2*m2*e5*dot(theta2)^2)\nf[theta2] = -l2*m2*(e4*g - l1*dot(theta1)^2*e5)\n";
    ///The derived equations as LaTeX: one `aligned` block, the same entries as `EQUATIONS`.
    pub const LATEX: &'static str = "\\begin{aligned}\ne_{0} &= m_{1} + m_{2} \\\\\ne_{1} &= \\cos\\left(\\theta_{1}\\right) \\\\\ne_{2} &= \\cos\\left(\\theta_{2}\\right) \\\\\ne_{3} &= \\sin\\left(\\theta_{1}\\right) \\\\\ne_{4} &= \\sin\\left(\\theta_{2}\\right) \\\\\ne_{5} &= e_{3} \\, e_{2} - e_{1} \\, e_{4} \\\\\nM_{\\theta_{1} \\, \\theta_{1}} &= l_{1}^{2} \\, e_{0} \\\\\nM_{\\theta_{1} \\, \\theta_{2}} &= l_{1} \\, l_{2} \\, m_{2} \\, \\left(e_{1} \\, e_{2} + e_{3} \\, e_{4}\\right) \\\\\nM_{\\theta_{2} \\, \\theta_{2}} &= m_{2} \\, l_{2}^{2} \\\\\nf_{\\theta_{1}} &= -l_{1} \\, \\left(e_{3} \\, g \\, e_{0} + l_{2} \\, m_{2} \\, e_{5} \\, \\dot{\\theta}_{2}^{2}\\right) \\\\\nf_{\\theta_{2}} &= -l_{2} \\, m_{2} \\, \\left(e_{4} \\, g - l_{1} \\, \\dot{\\theta}_{1}^{2} \\, e_{5}\\right) \\\\\n\\end{aligned}\n";
    ///A `DoublePendulum` with the given parameters (`m1`, `m2`, `l1`, `l2`, `g`).
    #[inline]
    pub const fn new(m1: S, m2: S, l1: S, l2: S, g: S) -> Self {
        Self { m1, m2, l1, l2, g }
    }
    /// The mass matrix `M(t, q) = ∂²T/∂q̇²`.
    #[inline]
    pub fn mass_matrix(
        &self,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> ::lagrange::nalgebra::SMatrix<S, 2, 2> {
        let [theta1, theta2] = [q[0], q[1]];
        let Self { m1, m2, l1, l2, .. } = *self;
        #[inline(always)]
        fn fma<S: ::lagrange::nalgebra::SimdRealField + ::core::marker::Copy>(
            a: S,
            b: S,
            c: S,
        ) -> S {
            #[cfg(target_feature = "fma")]
            { ::lagrange::nalgebra::SimdComplexField::simd_mul_add(a, b, c) }
            #[cfg(not(target_feature = "fma"))] { a * b + c }
        }
        let ([e0, e2], [e1, e3]) = ::lagrange::trig::sin_cos_array([theta1, theta2]);
        let e4 = l1 * l2 * m2 * fma(e0, e2, e1 * e3);
        ::lagrange::nalgebra::SMatrix::<
            S,
            2,
            2,
        >::from_array_storage(
            ::lagrange::nalgebra::ArrayStorage([
                [(l1 * l1) * (m1 + m2), e4],
                [e4, m2 * (l2 * l2)],
            ]),
        )
    }
    /// The forcing `f(t, q, q̇)` of `M q̈ = f`.
    #[inline]
    pub fn forcing(
        &self,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
        qdot: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> ::lagrange::nalgebra::SVector<S, 2> {
        let ([theta1, theta2], [theta1_dot, theta2_dot]) = (
            [q[0], q[1]],
            [qdot[0], qdot[1]],
        );
        let Self { m1, m2, l1, l2, g, .. } = *self;
        #[inline(always)]
        fn fma<S: ::lagrange::nalgebra::SimdRealField + ::core::marker::Copy>(
            a: S,
            b: S,
            c: S,
        ) -> S {
            #[cfg(target_feature = "fma")]
            { ::lagrange::nalgebra::SimdComplexField::simd_mul_add(a, b, c) }
            #[cfg(not(target_feature = "fma"))] { a * b + c }
        }
        let ([e0, e2], [e1, e3]) = ::lagrange::trig::sin_cos_array([theta1, theta2]);
        let e4 = fma(-e1, e2, e0 * e3);
        ::lagrange::nalgebra::SVector::<
            S,
            2,
        >::from_array_storage(
            ::lagrange::nalgebra::ArrayStorage([
                [
                    -l1 * fma(l2 * m2 * e4, theta2_dot * theta2_dot, e0 * g * (m1 + m2)),
                    -l2 * m2 * fma(-l1 * (theta1_dot * theta1_dot), e4, e2 * g),
                ],
            ]),
        )
    }
    /// `M` and `f` together, sharing their common subexpressions.
    #[inline]
    pub fn mass_matrix_and_forcing(
        &self,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
        qdot: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> (::lagrange::nalgebra::SMatrix<S, 2, 2>, ::lagrange::nalgebra::SVector<S, 2>) {
        let ([theta1, theta2], [theta1_dot, theta2_dot]) = (
            [q[0], q[1]],
            [qdot[0], qdot[1]],
        );
        let Self { m1, m2, l1, l2, g, .. } = *self;
        #[inline(always)]
        fn fma<S: ::lagrange::nalgebra::SimdRealField + ::core::marker::Copy>(
            a: S,
            b: S,
            c: S,
        ) -> S {
            #[cfg(target_feature = "fma")]
            { ::lagrange::nalgebra::SimdComplexField::simd_mul_add(a, b, c) }
            #[cfg(not(target_feature = "fma"))] { a * b + c }
        }
        let e0 = m1 + m2;
        let ([e1, e3], [e2, e4]) = ::lagrange::trig::sin_cos_array([theta1, theta2]);
        let e5 = l1 * l2 * m2 * fma(e1, e3, e2 * e4);
        let e6 = fma(-e2, e3, e1 * e4);
        (
            ::lagrange::nalgebra::SMatrix::<
                S,
                2,
                2,
            >::from_array_storage(
                ::lagrange::nalgebra::ArrayStorage([
                    [(l1 * l1) * e0, e5],
                    [e5, m2 * (l2 * l2)],
                ]),
            ),
            ::lagrange::nalgebra::SVector::<
                S,
                2,
            >::from_array_storage(
                ::lagrange::nalgebra::ArrayStorage([
                    [
                        -l1 * fma(l2 * m2 * e6, theta2_dot * theta2_dot, e1 * g * e0),
                        -l2 * m2 * fma(-l1 * (theta1_dot * theta1_dot), e6, e3 * g),
                    ],
                ]),
            ),
        )
    }
    /// Kinetic energy `T(t, q, q̇)`.
    #[inline]
    pub fn kinetic_energy(
        &self,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
        qdot: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> S {
        let ([theta1, theta2], [theta1_dot, theta2_dot]) = (
            [q[0], q[1]],
            [qdot[0], qdot[1]],
        );
        let Self { m1, m2, l1, l2, .. } = *self;
        #[inline(always)]
        fn fma<S: ::lagrange::nalgebra::SimdRealField + ::core::marker::Copy>(
            a: S,
            b: S,
            c: S,
        ) -> S {
            #[cfg(target_feature = "fma")]
            { ::lagrange::nalgebra::SimdComplexField::simd_mul_add(a, b, c) }
            #[cfg(not(target_feature = "fma"))] { a * b + c }
        }
        let k0: S = ::lagrange::nalgebra::convert::<f64, S>(0.5f64);
        let ([e0, e2], [e1, e3]) = ::lagrange::trig::sin_cos_array([theta1, theta2]);
        let e4 = fma(l2 * e3, theta2_dot, l1 * e1 * theta1_dot);
        let e5 = fma(l2 * e2, theta2_dot, l1 * e0 * theta1_dot);
        fma(k0 * m2, e4 * e4 + e5 * e5, k0 * m1 * (l1 * l1) * (theta1_dot * theta1_dot))
    }
    /// Potential energy `V(t, q)`.
    #[inline]
    pub fn potential_energy(&self, t: S, q: &::lagrange::nalgebra::SVector<S, 2>) -> S {
        let [theta1, theta2] = [q[0], q[1]];
        let Self { m1, m2, l1, l2, g, .. } = *self;
        #[inline(always)]
        fn fma<S: ::lagrange::nalgebra::SimdRealField + ::core::marker::Copy>(
            a: S,
            b: S,
            c: S,
        ) -> S {
            #[cfg(target_feature = "fma")]
            { ::lagrange::nalgebra::SimdComplexField::simd_mul_add(a, b, c) }
            #[cfg(not(target_feature = "fma"))] { a * b + c }
        }
        let ([_, _], [e0, e1]) = ::lagrange::trig::sin_cos_array([theta1, theta2]);
        fma(-m2 * g, fma(l1, e0, l2 * e1), -l1 * e0 * m1 * g)
    }
    /// Total energy `T + V`.
    #[inline]
    pub fn energy(
        &self,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
        qdot: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> S {
        let ([theta1, theta2], [theta1_dot, theta2_dot]) = (
            [q[0], q[1]],
            [qdot[0], qdot[1]],
        );
        let Self { m1, m2, l1, l2, g, .. } = *self;
        #[inline(always)]
        fn fma<S: ::lagrange::nalgebra::SimdRealField + ::core::marker::Copy>(
            a: S,
            b: S,
            c: S,
        ) -> S {
            #[cfg(target_feature = "fma")]
            { ::lagrange::nalgebra::SimdComplexField::simd_mul_add(a, b, c) }
            #[cfg(not(target_feature = "fma"))] { a * b + c }
        }
        let k0: S = ::lagrange::nalgebra::convert::<f64, S>(0.5f64);
        let ([e0, e2], [e1, e3]) = ::lagrange::trig::sin_cos_array([theta1, theta2]);
        let e4 = fma(l2 * e3, theta2_dot, l1 * e1 * theta1_dot);
        let e5 = fma(l2 * e2, theta2_dot, l1 * e0 * theta1_dot);
        fma(
            -m2 * g,
            fma(l1, e1, l2 * e3),
            fma(
                -l1 * e1 * m1,
                g,
                fma(
                    k0 * m2,
                    e4 * e4 + e5 * e5,
                    k0 * m1 * (l1 * l1) * (theta1_dot * theta1_dot),
                ),
            ),
        )
    }
    /// The generalized momenta `p = ∂L/∂q̇`.
    #[inline]
    pub fn momentum(
        &self,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
        qdot: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> ::lagrange::nalgebra::SVector<S, 2> {
        let ([theta1, theta2], [theta1_dot, theta2_dot]) = (
            [q[0], q[1]],
            [qdot[0], qdot[1]],
        );
        let Self { m1, m2, l1, l2, .. } = *self;
        #[inline(always)]
        fn fma<S: ::lagrange::nalgebra::SimdRealField + ::core::marker::Copy>(
            a: S,
            b: S,
            c: S,
        ) -> S {
            #[cfg(target_feature = "fma")]
            { ::lagrange::nalgebra::SimdComplexField::simd_mul_add(a, b, c) }
            #[cfg(not(target_feature = "fma"))] { a * b + c }
        }
        let ([e0, e2], [e1, e3]) = ::lagrange::trig::sin_cos_array([theta1, theta2]);
        let e4 = fma(l2 * e3, theta2_dot, l1 * e1 * theta1_dot);
        let e5 = fma(l2 * e2, theta2_dot, l1 * e0 * theta1_dot);
        ::lagrange::nalgebra::SVector::<
            S,
            2,
        >::from_array_storage(
            ::lagrange::nalgebra::ArrayStorage([
                [
                    fma(l1 * m2, fma(e0, e5, e1 * e4), m1 * theta1_dot * (l1 * l1)),
                    l2 * m2 * fma(e2, e5, e3 * e4),
                ],
            ]),
        )
    }
    /// `∂L/∂q`.
    #[inline]
    pub fn lagrangian_gradient(
        &self,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
        qdot: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> ::lagrange::nalgebra::SVector<S, 2> {
        let ([theta1, theta2], [theta1_dot, theta2_dot]) = (
            [q[0], q[1]],
            [qdot[0], qdot[1]],
        );
        let Self { m1, m2, l1, l2, g, .. } = *self;
        #[inline(always)]
        fn fma<S: ::lagrange::nalgebra::SimdRealField + ::core::marker::Copy>(
            a: S,
            b: S,
            c: S,
        ) -> S {
            #[cfg(target_feature = "fma")]
            { ::lagrange::nalgebra::SimdComplexField::simd_mul_add(a, b, c) }
            #[cfg(not(target_feature = "fma"))] { a * b + c }
        }
        let ([e0, e2], [e1, e3]) = ::lagrange::trig::sin_cos_array([theta1, theta2]);
        let e4 = fma(l2 * e3, theta2_dot, l1 * e1 * theta1_dot);
        let e5 = fma(l2 * e2, theta2_dot, l1 * e0 * theta1_dot);
        ::lagrange::nalgebra::SVector::<
            S,
            2,
        >::from_array_storage(
            ::lagrange::nalgebra::ArrayStorage([
                [
                    fma(
                        -l1 * e0 * g,
                        m1 + m2,
                        -l1 * theta1_dot * m2 * fma(-e1, e5, e0 * e4),
                    ),
                    fma(-l2 * e2 * m2, g, -l2 * m2 * theta2_dot * fma(-e3, e5, e2 * e4)),
                ],
            ]),
        )
    }
    /// Every `let` of the model at `(t, q, q̇)`, in the order of `LETS`:
    /// the positions (and any other quantity) the model names, for
    /// drawing a trajectory without writing the kinematics again.
    #[inline]
    pub fn lets(
        &self,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
        qdot: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> [S; 4] {
        let [theta1, theta2] = [q[0], q[1]];
        let Self { l1, l2, .. } = *self;
        #[inline(always)]
        fn fma<S: ::lagrange::nalgebra::SimdRealField + ::core::marker::Copy>(
            a: S,
            b: S,
            c: S,
        ) -> S {
            #[cfg(target_feature = "fma")]
            { ::lagrange::nalgebra::SimdComplexField::simd_mul_add(a, b, c) }
            #[cfg(not(target_feature = "fma"))] { a * b + c }
        }
        let ([e0, e2], [e1, e3]) = ::lagrange::trig::sin_cos_array([theta1, theta2]);
        let e4 = l1 * e0;
        [e4, -l1 * e1, fma(l2, e2, e4), fma(-l1, e1, -l2 * e3)]
    }
    /// The value of the `let` named `name` (as `LETS` writes it: `x1`,
    /// `x[2]`) at `(t, q, q̇)`; `None` where the model has no such `let`.
    #[inline]
    pub fn let_value(
        &self,
        name: &str,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
        qdot: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> ::core::option::Option<S> {
        let index = Self::LETS.iter().position(|l| *l == name)?;
        ::core::option::Option::Some(self.lets(t, q, qdot)[index])
    }
}
impl<S: ::lagrange::nalgebra::RealField + ::core::marker::Copy> ::lagrange::Lagrangian<2>
for DoublePendulum<S> {
    type Scalar = S;
    const COORDINATES: [&'static str; 2] = Self::COORDINATES;
    #[inline]
    fn mass_matrix(
        &self,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> ::lagrange::nalgebra::SMatrix<S, 2, 2> {
        DoublePendulum::mass_matrix(self, t, q)
    }
    #[inline]
    fn forcing(
        &self,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
        qdot: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> ::lagrange::nalgebra::SVector<S, 2> {
        DoublePendulum::forcing(self, t, q, qdot)
    }
    #[inline]
    fn mass_matrix_and_forcing(
        &self,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
        qdot: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> (::lagrange::nalgebra::SMatrix<S, 2, 2>, ::lagrange::nalgebra::SVector<S, 2>) {
        DoublePendulum::mass_matrix_and_forcing(self, t, q, qdot)
    }
    #[inline]
    fn kinetic_energy(
        &self,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
        qdot: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> S {
        DoublePendulum::kinetic_energy(self, t, q, qdot)
    }
    #[inline]
    fn potential_energy(&self, t: S, q: &::lagrange::nalgebra::SVector<S, 2>) -> S {
        DoublePendulum::potential_energy(self, t, q)
    }
    #[inline]
    fn energy(
        &self,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
        qdot: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> S {
        DoublePendulum::energy(self, t, q, qdot)
    }
    #[inline]
    fn momentum(
        &self,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
        qdot: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> ::core::option::Option<::lagrange::nalgebra::SVector<S, 2>> {
        ::core::option::Option::Some(DoublePendulum::momentum(self, t, q, qdot))
    }
    #[inline]
    fn lagrangian_gradient(
        &self,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
        qdot: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> ::core::option::Option<::lagrange::nalgebra::SVector<S, 2>> {
        ::core::option::Option::Some(
            DoublePendulum::lagrangian_gradient(self, t, q, qdot),
        )
    }
    #[inline]
    fn nonconservative_forces(
        &self,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
        qdot: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> ::core::option::Option<::lagrange::nalgebra::SVector<S, 2>> {
        let _ = (t, q, qdot);
        ::core::option::Option::Some(::lagrange::nalgebra::SVector::zeros())
    }
    #[inline]
    fn parameters_are_finite(&self) -> bool {
        ::lagrange::nalgebra::ComplexField::is_finite(&self.m1)
            && ::lagrange::nalgebra::ComplexField::is_finite(&self.m2)
            && ::lagrange::nalgebra::ComplexField::is_finite(&self.l1)
            && ::lagrange::nalgebra::ComplexField::is_finite(&self.l2)
            && ::lagrange::nalgebra::ComplexField::is_finite(&self.g)
    }
    #[inline]
    fn visit_lets<V: ::lagrange::lets::Visitor<S, 2>>(
        &self,
        visitor: V,
    ) -> ::core::option::Option<V::Output> {
        ::core::option::Option::Some(visitor.visit::<Self, 4>(self))
    }
}
impl<
    S: ::lagrange::nalgebra::RealField + ::core::marker::Copy,
> ::lagrange::lets::Lets<2, 4> for DoublePendulum<S> {
    const LETS: [&'static str; 4] = Self::LETS;
    #[inline]
    fn lets(
        &self,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
        qdot: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> [S; 4] {
        DoublePendulum::lets(self, t, q, qdot)
    }
}
impl<
    S: ::lagrange::nalgebra::SimdRealField + ::core::marker::Copy,
> ::lagrange::ensemble::LaneModel<2> for DoublePendulum<S>
where
    S::Element: ::lagrange::nalgebra::RealField + ::core::marker::Copy,
{
    type Lanes = S;
    const COORDINATES: [&'static str; 2] = Self::COORDINATES;
    #[inline(always)]
    fn mass_matrix_and_forcing(
        &self,
        t: S,
        q: &::lagrange::nalgebra::SVector<S, 2>,
        qdot: &::lagrange::nalgebra::SVector<S, 2>,
    ) -> (::lagrange::nalgebra::SMatrix<S, 2, 2>, ::lagrange::nalgebra::SVector<S, 2>) {
        DoublePendulum::mass_matrix_and_forcing(self, t, q, qdot)
    }
}
