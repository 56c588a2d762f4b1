"""The reference values the robot tests compare against, computed once with Pinocchio.

For each robot of this folder (the UR5 and the Panda from example-robot-data, the Panda's
fingers locked at 0 as Pinocchio's `buildReducedModel` at its neutral configuration; the
tree of this repository), at 100 random states (seeded): M (CRBA), the nonlinear effects
(RNEA at zero acceleration), q'' (ABA at a random tau) and tau (RNEA at a random q''); at the
first 20 of them the placement of every link frame (rotation row-major, then the origin), the
tool frame's Jacobian and velocity in LOCAL_WORLD_ALIGNED (linear rows first) and the gravity
torques; at the first 5 the joint-torque regressor (10 parameters per joint: m, m c, the
inertia about the joint frame). Writes `reference_NAME.json` beside this script. The tests
read the JSON and need no Python.

    pip install pin          # Pinocchio (4.1 wrote the files in the repository)
    python3 tests/data/robots/reference.py
"""
import json, os, numpy as np, pinocchio as pin

here = os.path.dirname(os.path.abspath(__file__))
ROBOTS = [
    ("ur5", "ur5.urdf", [], "tool0"),
    ("panda", "panda.urdf", ["panda_finger_joint1", "panda_finger_joint2"], "panda_hand_tcp"),
    ("tree", "tree.urdf", [], "tool"),
]
STATES = 100
FRAME_STATES = 20
REGRESSOR_STATES = 5
LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED

for name, file, locked, tool in ROBOTS:
    model = pin.buildModelFromUrdf(os.path.join(here, file))
    if locked:
        model = pin.buildReducedModel(model, [model.getJointId(j) for j in locked], pin.neutral(model))
    data = model.createData()
    rng = np.random.default_rng(46)
    prismatic = np.array([model.joints[j].shortname().startswith("JointModelP") for j in range(1, model.njoints)])
    links = [f.name for f in model.frames if f.type == pin.FrameType.BODY]
    tool_id = model.getFrameId(tool)
    states = []
    for k in range(STATES):
        q = np.where(prismatic, rng.uniform(-0.3, 0.3, model.nq), rng.uniform(-np.pi, np.pi, model.nq))
        v = rng.uniform(-2.0, 2.0, model.nv)
        a = rng.uniform(-5.0, 5.0, model.nv)
        tau = rng.uniform(-10.0, 10.0, model.nv)
        M = pin.crba(model, data, q)
        M = np.triu(M) + np.triu(M, 1).T
        nle = pin.nonLinearEffects(model, data, q, v)
        qdd = pin.aba(model, data, q, v, tau)
        rnea = pin.rnea(model, data, q, v, a)
        states.append({
            "q": q.tolist(), "v": v.tolist(), "a": a.tolist(), "tau": tau.tolist(),
            "mass_matrix": M.tolist(), "nonlinear_effects": nle.tolist(),
            "aba": qdd.tolist(), "rnea": rnea.tolist(),
        })
        if k < FRAME_STATES:
            pin.forwardKinematics(model, data, q, v)
            pin.updateFramePlacements(model, data)
            pin.computeJointJacobians(model, data, q)
            placements = {}
            for f in links:
                oMf = data.oMf[model.getFrameId(f)]
                placements[f] = oMf.rotation.flatten().tolist() + oMf.translation.tolist()
            states[-1].update({
                "placements": placements,
                "jacobian": pin.getFrameJacobian(model, data, tool_id, LWA).tolist(),
                "frame_velocity": pin.getFrameVelocity(model, data, tool_id, LWA).vector.tolist(),
                "gravity": pin.computeGeneralizedGravity(model, data, q).tolist(),
            })
        if k < REGRESSOR_STATES:
            states[-1]["regressor"] = pin.computeJointTorqueRegressor(model, data, q, v, a).tolist()
    out = {
        "pinocchio": pin.__version__,
        "joints": [model.names[j] for j in range(1, model.njoints)],
        "links": links,
        "tool": tool,
        "states": states,
    }
    with open(os.path.join(here, f"reference_{name}.json"), "w") as f:
        json.dump(out, f, separators=(",", ":"))
    print(name, model.nv, out["joints"])
