//! A ball bouncing on a floor written as a contact: its bounces
//! accumulate in finite time and end in a persistent contact.

use crate::lagrangian;

lagrangian! {
    /// A ball of mass `m` in the vertical plane, `x` along a frictionless
    /// floor it cannot pass and `z` its height above it, under gravity
    /// `g`, bouncing with restitution `e`.
    ///
    /// ```
    /// use lagrange::contact::{self, ContactSettings, Mode};
    /// use lagrange::models::BallOnFloor;
    /// use lagrange::prelude::*;
    /// use lagrange::nalgebra::Vector2;
    ///
    /// let ball = BallOnFloor::new(1.0, 9.81, 0.5);
    /// let run = contact::integrate(
    ///     &Dop853::new().rtol(1e-12).atol(1e-12), &ball, 0.0,
    ///     Vector2::new(0.0, 1.0), Vector2::new(0.5, 0.0), &[2.0], ContactSettings::default(),
    /// )?;
    /// let rest = run.switches().last().unwrap();
    /// assert_eq!(rest.to, Mode::Closed);
    /// assert!((rest.t - ball.rest_time(1.0)).abs() < 1e-9);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub struct BallOnFloor {
        coordinates: x, z;
        parameters: m, g, e;
        kinetic: m/2*(dot(x)^2 + dot(z)^2);
        potential: m*g*z;
        contacts: floor: z >= 0 { restitution: e };
    }
}

impl BallOnFloor<f64> {
    /// The first landing after a release from rest at height `h`, `t₁ =
    /// √(2h/g)`.
    pub fn first_landing(&self, h: f64) -> f64 {
        (2.0 * h / self.g).sqrt()
    }

    /// The time the bounces accumulate at, released from rest at height
    /// `h`: `t₁ (1 + e)/(1 − e)`, the sum of the flights `2 t₁ eᵏ`.
    pub fn rest_time(&self, h: f64) -> f64 {
        self.first_landing(h) * (1.0 + self.e) / (1.0 - self.e)
    }
}
