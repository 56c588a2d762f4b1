"""MuJoCo (PyPI `mujoco`) on the die that `contacts_3d.rs` throws onto a table: a uniform cube
(side 0.016 m, 0.01 kg) on a plane with mu = 0.4, dropped from 10 cm at the orientation given
on the command line (w x y z, the same quaternion as the project's run), drifting at
(0.5, 0.2, 0) m/s and turning at body rates (8, -5, 12) rad/s, for 12 s at MuJoCo's default
time step (2 ms). At MuJoCo's defaults and with its anti-slip settings (elliptic friction cone,
impratio = 10, noslip_iterations = 10): how far it creeps from 2 s to 12 s (the largest
displacement of a corner along the table), how deep a
corner sinks below the table (the deepest, and at the end), the most its energy rises in one step (relative to the start's),
and its energy at the end. MuJoCo has no restitution coefficient: its contacts are soft
(solref), so its bounces are not the project's e = 0.3. One line per case:
`settings;creep;deepest;sunk at the end;rise;energy`."""
import math
import sys

import mujoco
import numpy as np

qw, qx, qy, qz = (float(a) for a in sys.argv[1:5])
m_die, side, g, mu = 0.01, 0.016, 9.81, 0.4
h = side / 2
inertia = m_die * side * side / 6
settings = {
    "MuJoCo, defaults": "",
    "MuJoCo, elliptic cone, impratio 10, noslip 10":
        'cone="elliptic" impratio="10" noslip_iterations="10"',
}
corners = np.array([[sx, sy, sz] for sx in (h, -h) for sy in (h, -h) for sz in (h, -h)])


def rotation(q):
    r = np.zeros(9)
    mujoco.mju_quat2Mat(r, q)
    return r.reshape(3, 3)


def energy(d):
    v, w = d.qvel[:3], d.qvel[3:6]
    return 0.5 * m_die * v @ v + 0.5 * inertia * w @ w + m_die * g * d.qpos[2]


for label, opts in settings.items():
    xml = f'''<mujoco><option timestep="0.002" gravity="0 0 {-g}" {opts}/>
    <worldbody><geom type="plane" size="5 5 .1" friction="{mu} 0.005 0.0001"/>
    <body pos="0 0 0.1"><freejoint/>
    <geom type="box" size="{h} {h} {h}" mass="{m_die}"/></body></worldbody></mujoco>'''
    m = mujoco.MjModel.from_xml_string(xml)
    d = mujoco.MjData(m)
    d.qpos[:] = [0.0, 0.0, 0.1, qw, qx, qy, qz]
    d.qvel[:] = [0.5, 0.2, 0.0, 8.0, -5.0, 12.0]
    e0 = energy(d)
    previous, rise, deepest = e0, 0.0, 0.0
    creep, first = 0.0, None
    steps = int(round(12.0 / m.opt.timestep))
    for k in range(1, steps + 1):
        mujoco.mj_step(m, d)
        e = energy(d)
        rise = max(rise, e - previous)
        previous = e
        r = rotation(d.qpos[3:7])
        deepest = min(deepest, float(np.min(d.qpos[2] + corners @ r.T[:, 2])))
        if k * m.opt.timestep >= 2.0 - 1e-12:
            now = d.qpos[:3] + corners @ r.T
            if first is None:
                first = now
            creep = max(creep, float(np.max(np.linalg.norm((now - first)[:, :2], axis=1))))
    r = rotation(d.qpos[3:7])
    sunk = -float(np.min(d.qpos[2] + corners @ r.T[:, 2]))
    print(f"{label};{creep:.3e};{-deepest:.3e};{sunk:.3e};{rise / e0:.3e};{previous:.6e}")
