//! The cart-pole: a cart on a rail driven by a motor force, a pole hinged on
//! it. The problem of control inputs (`inputs:`): constant inputs, a
//! prescribed force `u(t)`, a feedback controller.

use crate::lagrangian;

lagrangian! {
    /// A cart of mass `mc` on a horizontal rail, pushed by the control
    /// input `force`, carrying a point bob of mass `mp` on a massless rod
    /// of length `l`; `θ` from the **upright** vertical (θ = 0 is the
    /// inverted pole, unstable without control).
    ///
    /// `M = [[mc + mp, mp l cos θ], [mp l cos θ, mp l²]]`,
    /// `f = (force + mp l sin θ θ̇², mp g l sin θ)`, so `∂f/∂u = (1, 0)`.
    ///
    /// ```
    /// use lagrange::models::CartPole;
    /// use lagrange::nalgebra::{Vector1, Vector2};
    /// use lagrange::prelude::*;
    /// use lagrange::InvalidInput;
    ///
    /// let cart = CartPole::<f64>::new(1.0, 0.1, 0.5, 9.81);
    /// let (q0, v0) = (Vector2::new(0.0, 0.1), Vector2::zeros());
    /// let times = [0.0, 0.5, 1.0];
    ///
    /// // Inputs start unset: integrating is refused, not run on NaN or zero.
    /// let refused = Rk4::new(1e-3).integrate(&cart, 0.0, q0, v0, &times).unwrap_err();
    /// assert!(matches!(
    ///     refused.error,
    ///     IntegrationError::InvalidInput(InvalidInput::InputsNotSet { .. })
    /// ));
    ///
    /// // Constant inputs.
    /// let pushed = cart.with_inputs(&Vector1::new(2.0));
    /// assert!(Rk4::new(1e-3).integrate(&pushed, 0.0, q0, v0, &times).is_ok());
    ///
    /// // A prescribed force u(t): a controller that ignores the state.
    /// let shaken = cart.with_controller(|t: f64, _, _| Vector1::new((3.0 * t).sin()));
    /// assert!(Rk4::new(1e-3).integrate(&shaken, 0.0, q0, v0, &times).is_ok());
    ///
    /// // Feedback: a PD law on θ and x that holds the pole upright.
    /// let balanced = cart.with_controller(|_, q: &Vector2<f64>, v: &Vector2<f64>| {
    ///     Vector1::new(40.0 * q[1] + 10.0 * v[1] + 1.0 * q[0] + 2.0 * v[0])
    /// });
    /// let run = Rk4::new(1e-3).integrate(&balanced, 0.0, q0, v0, &times).unwrap();
    /// assert!(balanced.controller_calls() >= 4 * 1000); // 4 stages per step
    /// assert!(run.last().unwrap().q[1].abs() < 0.1);
    /// ```
    #[lagrange(jacobians)]
    pub struct CartPole {
        coordinates: x, theta;
        parameters: mc, mp, l, g;
        inputs: force;
        let xb = x + l*sin(theta);
        let yb = l*cos(theta);
        kinetic: mc/2*dot(x)^2 + mp/2*(dot(xb)^2 + dot(yb)^2);
        potential: mp*g*yb;
        forces: x = force;
    }
}
