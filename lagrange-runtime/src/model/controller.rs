//! [`Controller`]: the layer that drives a model's control inputs, and
//! [`Controlled`], a model under it.

use core::cell::Cell;

use nalgebra::{SMatrix, SVector};

use super::inputs::{Actuated, Inputs, Visitor as InputVisitor};
use crate::model::constraints::{Holonomic, Visitor as ConstraintVisitor};
use crate::model::layer::{At, Joined};
use crate::model::settings::ConstraintSettings;
use crate::model::{Layer, Layered};

/// The layer that sets a model's `K` inputs to `controller(t, q, q̇)` at
/// every evaluation: the model is copied, its inputs set, and the
/// evaluation made by the copy. Built by [`WithLayers::with_controller`](crate::model::WithLayers::with_controller).
///
/// The controller is called once per right-hand side
/// ([`mass_matrix_and_forcing`](crate::model::Lagrangian::mass_matrix_and_forcing);
/// the variational integrator, which asks for `∂L/∂q` and the
/// non-conservative forces apart, calls it twice per residual), and
/// [`controller_calls`](Controlled::controller_calls) counts the calls.
/// Where it returns a NaN or an infinity, the evaluation returns NaN,
/// which the integrators report as
/// [`NonFiniteValue::Inputs`](crate::error::NonFiniteValue::Inputs) at that `t`
/// and state; the inputs are never passed on.
///
/// What takes no `q̇` cannot call the controller: `mass_matrix` and
/// `momentum` need none (inputs are kept out of them), and
/// `potential_energy` is the model's with the inputs it holds (NaN unless
/// set by `with_inputs`): an input-dependent potential has no value
/// without the velocities the controller reads. The exact residual
/// Jacobians are not passed on: they hold the inputs fixed, while `u`
/// depends on the state through the controller, so implicit methods take
/// finite differences, which see the controller too.
pub struct Controller<F, const K: usize> {
    controller: F,
    calls: Cell<usize>,
}

impl<F, const K: usize> Controller<F, K> {
    /// The layer of `controller`.
    pub fn new(controller: F) -> Self {
        Self {
            controller,
            calls: Cell::new(0),
        }
    }
}

impl<F: Clone, const K: usize> Clone for Controller<F, K> {
    fn clone(&self) -> Self {
        Self {
            controller: self.controller.clone(),
            calls: Cell::new(self.calls.get()),
        }
    }
}

impl<F, const K: usize> core::fmt::Debug for Controller<F, K> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Controller")
            .field("calls", &self.calls.get())
            .finish_non_exhaustive()
    }
}

/// A model whose `K` inputs are `controller(t, q, q̇)` at every
/// evaluation: the model under the [`Controller`] layer. Build it with
/// [`WithLayers::with_controller`](crate::model::WithLayers::with_controller) and integrate it like the model itself.
pub type Controlled<M, F, const K: usize> = Layered<M, Controller<F, K>>;

impl<M, F, const K: usize> Layered<M, Controller<F, K>> {
    /// How many times the controller was called so far (by every
    /// integration of this value).
    pub fn controller_calls(&self) -> usize {
        self.layer().calls.get()
    }
}

impl<F, const K: usize> Controller<F, K> {
    /// The controller's inputs at `(t, q, q̇)`, counted.
    fn inputs<S, const N: usize>(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> SVector<S, K>
    where
        F: Fn(S, &SVector<S, N>, &SVector<S, N>) -> SVector<S, K>,
    {
        self.calls.set(self.calls.get() + 1);
        (self.controller)(t, q, qdot)
    }
}

impl<M, F, const N: usize, const K: usize> Layer<M, N> for Controller<F, K>
where
    M: Actuated<N, K> + Copy,
    F: Fn(M::Scalar, &SVector<M::Scalar, N>, &SVector<M::Scalar, N>) -> SVector<M::Scalar, K>,
{
    #[inline]
    fn at<'m>(
        &self,
        model: &'m M,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> At<'m, M> {
        let u = self.inputs(t, q, qdot);
        if !crate::linalg::all_finite(u.as_slice()) {
            return At::NotFinite;
        }
        let mut driven = *model;
        driven.set_inputs(&u);
        At::Changed(driven)
    }

    #[inline]
    fn residual_jacobians(
        &self,
        _: &M,
        _: M::Scalar,
        _: &SVector<M::Scalar, N>,
        _: &SVector<M::Scalar, N>,
        _: &SVector<M::Scalar, N>,
    ) -> Option<(SMatrix<M::Scalar, N, N>, SMatrix<M::Scalar, N, N>)> {
        None
    }

    /// The model's constraints (which hold no input), joined to the
    /// controlled dynamics.
    #[inline]
    fn visit_constrained<V, H, const C: usize>(
        layered: &Layered<M, Self>,
        constraints: &H,
        settings: ConstraintSettings<M::Scalar>,
        visitor: V,
    ) -> V::Output
    where
        V: ConstraintVisitor<M::Scalar, N>,
        H: Holonomic<N, C, Scalar = M::Scalar> + ?Sized,
    {
        let joined = Joined::<_, H, M::Scalar, C> {
            dynamics: layered,
            constraints,
            settings,
        };
        visitor.visit::<_, C>(&joined, settings)
    }

    /// The controlled model's inputs: the controller's, none held.
    #[inline]
    fn visit_inputs<V>(layered: &Layered<M, Self>, visitor: V) -> Option<V::Output>
    where
        V: InputVisitor<M::Scalar, N>,
    {
        Some(visitor.visit::<_, K>(layered))
    }
}

impl<M, F, const N: usize, const K: usize> Inputs<N, K> for Layered<M, Controller<F, K>>
where
    M: Actuated<N, K> + Copy,
    F: Fn(M::Scalar, &SVector<M::Scalar, N>, &SVector<M::Scalar, N>) -> SVector<M::Scalar, K>,
{
    const NAMES: [&'static str; K] = M::INPUTS;

    #[inline]
    fn inputs_at(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> SVector<M::Scalar, K> {
        self.layer().inputs(t, q, qdot)
    }

    #[inline]
    fn held_inputs(&self) -> Option<SVector<M::Scalar, K>> {
        None
    }
}
