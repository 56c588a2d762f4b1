"""MuJoCo's side of `benches/mujoco.rs` (lagrange's Stepper beside MuJoCo).

The models of the Rust side, in MJCF: every link a point mass 1 at the end of a
massless rod 1 on a hinge, gravity 9.81, no contact, no constraint solver, no
damping; released from rest with the first hinge at 0.5 rad (the chain's other
hinges at 0: every absolute angle 0.5 rad), to T = 2 s. MuJoCo integrates in
relative joint angles; the chain's are summed to absolute ones to compare with
the Rust model's coordinates, the tree's are compared as they are.

  python mujoco_chain.py errors REFERENCE.json   per model, step and method: the final
                                                 state's error against the Rust side's
                                                 Dop853 at 1e-13
  python mujoco_chain.py time REFERENCE.json     per model and method: ns per step at the
                                                 timed step, one rollout of T / h steps

Methods: MuJoCo's RK4 beside lagrange's RK4, MuJoCo's default (semi-implicit
Euler) beside lagrange's symplectic Euler. Timing by `mujoco.rollout` (its own C
loop, one thread), after a short warm-up rollout. Prints one JSON object.
"""
import json
import sys
import time

import mujoco
import numpy as np
from mujoco import rollout

METHODS = {"RK4": "RK4", "SymplecticEuler": "Euler"}


def link(name, pos, inner=""):
    # A hinge about -y turns (0, 0, -1) to (sin a, 0, -cos a): the Rust model's (x, y).
    return (f'<body name="{name}" pos="{pos}"><joint type="hinge" axis="0 -1 0"/>'
            f'<inertial pos="0 0 -1" mass="1" diaginertia="1e-12 1e-12 1e-12"/>{inner}</body>')


def branch(prefix, count, pos, after_first=""):
    # `count` links, each hanging from the end of the one before; `after_first` goes
    # inside the first link, after the rest of its branch (MuJoCo numbers the joints
    # depth first, as written: the whole branch, then `after_first`).
    inner = ""
    for i in reversed(range(1, count)):
        inner = link(f"{prefix}{i}", "0 0 -1", inner)
    return link(f"{prefix}0", pos, inner + after_first)


def mjcf(case, h, integrator):
    n = case["n"]
    if case["absolute"]:
        body = branch("c", n, "0 0 0")
    else:
        b = n // 2
        body = branch("a", b, "0 0 0", after_first=branch("b", b, "0 0 -1"))
    return (f'<mujoco><option timestep="{h}" integrator="{integrator}" gravity="0 0 -9.81">'
            f'<flag contact="disable" constraint="disable"/></option>'
            f'<worldbody>{body}</worldbody></mujoco>')


def start(model, n):
    data = mujoco.MjData(model)
    data.qpos[:] = 0.0
    data.qpos[0] = 0.5
    data.qvel[:] = 0.0
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    state = np.zeros(mujoco.mj_stateSize(model, spec))
    mujoco.mj_getState(model, data, state, spec)
    return data, state


def simulate(case, h, method):
    model = mujoco.MjModel.from_xml_string(mjcf(case, h, METHODS[method]))
    data, state = start(model, case["n"])
    return model, data, state


def errors(reference):
    out = {}
    for name, case in reference.items():
        if not isinstance(case, dict):
            continue
        n = case["n"]
        rq, rv = np.array(case["q_ref"]), np.array(case["qdot_ref"])
        rows = []
        for row in case["ours"]:
            h, method = row["h"], row["method"]
            model, data, state = simulate(case, h, method)
            steps = int(round(reference["T"] / h))
            states, _ = rollout.rollout(model, data, state[None, :], nstep=steps)
            last = states[0, -1]
            q, v = last[1:1 + n], last[1 + n:1 + 2 * n]
            if case["absolute"]:
                q, v = np.cumsum(q), np.cumsum(v)
            e = float(max(np.max(np.abs(q - rq)), np.max(np.abs(v - rv))))
            rows.append({"method": method, "h": h, "error": e})
        out[name] = rows
    return out


def timings(reference):
    h = reference["h_timed"]
    steps = int(round(reference["T"] / h))
    out = {}
    for name, case in reference.items():
        if not isinstance(case, dict):
            continue
        out[name] = {}
        for method in METHODS:
            model, data, state = simulate(case, h, method)
            rollout.rollout(model, data, state[None, :], nstep=10)
            clock = time.perf_counter()
            rollout.rollout(model, data, state[None, :], nstep=steps)
            out[name][method] = (time.perf_counter() - clock) / steps * 1e9
    return out


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] not in ("errors", "time"):
        sys.exit(__doc__)
    reference = json.load(open(sys.argv[2]))
    result = errors(reference) if sys.argv[1] == "errors" else timings(reference)
    print(json.dumps({"mujoco": mujoco.__version__, **result}))
