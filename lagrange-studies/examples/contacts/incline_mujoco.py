"""MuJoCo (PyPI `mujoco`) on the block that must stay put on an incline: a 1 kg box (0.2 m
cube) on a plane with mu = 1, gravity tilted by 20 and 30 degrees (below the friction angle of
45 degrees). After 1 s of settling, how far it creeps in 10 s and how deep it sinks, at
MuJoCo's defaults and with its anti-slip settings (elliptic friction cone, impratio = 10,
noslip_iterations = 10). The same script as ../shared/peers/mujoco/incline_creep.py, printing
one line per case for `contacts.rs`: `settings;degrees;creep;penetration`."""
import math
import mujoco

settings = {
    "MuJoCo, defaults": "",
    "MuJoCo, elliptic cone, impratio 10, noslip 10": 'cone="elliptic" impratio="10" noslip_iterations="10"',
}
for label, opts in settings.items():
    for degrees in (20, 30):
        a = math.radians(degrees)
        g = 9.81
        xml = f'''<mujoco><option timestep="0.002" gravity="{g*math.sin(a)} 0 {-g*math.cos(a)}" {opts}/>
        <worldbody><geom type="plane" size="5 5 .1" friction="1 0.005 0.0001"/>
        <body pos="0 0 0.1"><freejoint/><geom type="box" size=".1 .1 .1" mass="1"/></body></worldbody></mujoco>'''
        m = mujoco.MjModel.from_xml_string(xml)
        d = mujoco.MjData(m)
        for _ in range(500):
            mujoco.mj_step(m, d)
        x0 = d.qpos[0]
        for _ in range(5000):
            mujoco.mj_step(m, d)
        print(f"{label};{degrees};{d.qpos[0] - x0:.3e};{-(d.qpos[2] - 0.1):.3e}")
