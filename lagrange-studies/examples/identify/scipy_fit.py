"""The damped double pendulum of `identify/main.rs` fitted with SciPy, as a
user without lagrange would: the equations written by hand, `solve_ivp`
(DOP853, rtol = atol = 1e-10) for the motion, `least_squares` (method
"lm", MINPACK's Levenberg-Marquardt; Jacobian by forward differences of
whole runs) for the fit, standard errors from the final Jacobian as
sigma^2 (J^T J)^-1 with sigma^2 = |r|^2 / (m - D).

Arguments: the data CSV (t, theta1, theta2), the starting parameters
[m1, m2, l1, l2, g, c1, c2] and the initial state [q1, q2, v1, v2].
Fits m2, l1, l2, c1, c2. Prints one line: the five values, the five
standard errors, the seconds the fit took and the number of solve_ivp
runs.

Before fitting it checks its own hand-written equations: that its
right-hand side satisfies the Euler-Lagrange equations of the same T, V
and R, by central differences of the Lagrangian at a random state (to
1e-6, the differences' own error being about 1e-8).
"""

import ast
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import least_squares

FITTED = [1, 2, 3, 5, 6]


def rhs(p, y):
    m1, m2, l1, l2, g, c1, c2 = p
    th1, th2, w1, w2 = y
    d = th1 - th2
    m = np.array(
        [
            [(m1 + m2) * l1 * l1, m2 * l1 * l2 * np.cos(d)],
            [m2 * l1 * l2 * np.cos(d), m2 * l2 * l2],
        ]
    )
    f = np.array(
        [
            -m2 * l1 * l2 * np.sin(d) * w2 * w2
            - (m1 + m2) * g * l1 * np.sin(th1)
            - (c1 * w1 - c2 * (w2 - w1)),
            m2 * l1 * l2 * np.sin(d) * w1 * w1
            - m2 * g * l2 * np.sin(th2)
            - c2 * (w2 - w1),
        ]
    )
    a = np.linalg.solve(m, f)
    return np.array([w1, w2, a[0], a[1]])


def check_equations(p):
    """M qdd - f against d/dt dL/dqd - dL/dq + dR/dqd by differences."""
    m1, m2, l1, l2, g, c1, c2 = p

    def lagrangian(q, v):
        x1, y1 = l1 * np.sin(q[0]), -l1 * np.cos(q[0])
        x2, y2 = x1 + l2 * np.sin(q[1]), y1 - l2 * np.cos(q[1])
        vx1, vy1 = l1 * np.cos(q[0]) * v[0], l1 * np.sin(q[0]) * v[0]
        vx2, vy2 = vx1 + l2 * np.cos(q[1]) * v[1], vy1 + l2 * np.sin(q[1]) * v[1]
        t = m1 / 2 * (vx1**2 + vy1**2) + m2 / 2 * (vx2**2 + vy2**2)
        return t - (m1 * g * y1 + m2 * g * y2)

    rng = np.random.default_rng(0)
    q, v = rng.uniform(-2, 2, 2), rng.uniform(-2, 2, 2)
    a = rhs(p, np.concatenate([q, v]))[2:]
    h = 1e-4

    def dl_dv(q, v):
        return np.array(
            [
                (lagrangian(q, v + h * e) - lagrangian(q, v - h * e)) / (2 * h)
                for e in np.eye(2)
            ]
        )

    # d/dt dL/dqd along (q, v, a), by a central difference in time.
    dt = 1e-4
    ddt = (dl_dv(q + dt * v, v + dt * a) - dl_dv(q - dt * v, v - dt * a)) / (2 * dt)
    dl_dq = np.array(
        [(lagrangian(q + h * e, v) - lagrangian(q - h * e, v)) / (2 * h) for e in np.eye(2)]
    )
    dr_dv = np.array([c1 * v[0] - c2 * (v[1] - v[0]), c2 * (v[1] - v[0])])
    residual = ddt - dl_dq + dr_dv
    assert np.max(np.abs(residual)) < 1e-6, residual


def main():
    path, guess, state = sys.argv[1], ast.literal_eval(sys.argv[2]), ast.literal_eval(sys.argv[3])
    data = np.loadtxt(path, delimiter=",", skiprows=1)
    times, measured = data[:, 0], data[:, 1:3]
    guess = np.array(guess, dtype=float)
    check_equations(guess)
    runs = 0

    def residuals(x):
        nonlocal runs
        runs += 1
        p = guess.copy()
        p[FITTED] = x
        sol = solve_ivp(
            lambda t, y: rhs(p, y),
            (0.0, times[-1]),
            np.array(state, dtype=float),
            method="DOP853",
            rtol=1e-10,
            atol=1e-10,
            t_eval=times,
        )
        if not sol.success or sol.y.shape[1] != len(times):
            return np.full(2 * len(times), 1e3)
        return (sol.y[0:2].T - measured).ravel()

    start = time.perf_counter()
    result = least_squares(residuals, guess[FITTED], method="lm", xtol=1e-10, ftol=1e-12)
    seconds = time.perf_counter() - start
    m, d = 2 * len(times), len(FITTED)
    sigma2 = np.sum(result.fun**2) / (m - d)
    cov = sigma2 * np.linalg.inv(result.jac.T @ result.jac)
    values = list(result.x) + list(np.sqrt(np.diag(cov))) + [seconds, runs]
    print(" ".join(repr(float(v)) for v in values))


if __name__ == "__main__":
    main()
