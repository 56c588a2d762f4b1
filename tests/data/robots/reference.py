"""The reference values the robot tests compare against, computed once with Pinocchio.

For each robot of this folder, at 100 random states (seeded): M (CRBA), the nonlinear effects
(RNEA at zero acceleration), q'' (ABA at a random tau) and tau (RNEA at a random q''); at the
first 20 of them the placement of every link frame (rotation row-major, then the origin), the
tool frame's Jacobian and velocity in LOCAL_WORLD_ALIGNED (linear rows first) and the gravity
torques, and at the first 5 the joint-torque regressor (10 parameters per joint: m, m c, the
inertia about the joint frame; on a floating base the free flyer's body first, its rows the
base's wrench), for the robots with a tool frame named in ROBOTS. Writes `reference_NAME.json` beside this script. The tests
read the JSON and need no Python.

Fixed bases: the UR5, the Panda (fingers locked at 0 as Pinocchio's `buildReducedModel` at
its neutral configuration) and the xArm7 from example-robot-data; the tree of this
repository. Floating bases (the Go2 and romeo_small from example-robot-data): Pinocchio's
free-flyer root joint, its configuration (x, y, z, qx, qy, qz, qw, joints), the quaternion
random and unit; its velocity the base's spatial velocity in the base frame (linear,
angular, joints), as are the accelerations and the base's wrench (force, moment) in `tau`.
The Go2's tool frame is its front left foot, `FL_foot`. For these M is stored as its upper triangle, row by row (M is symmetric): romeo's 37 x 37
matrices at 100 states would double the file otherwise.

    pip install pin          # Pinocchio (4.1 wrote the files in the repository)
    python3 tests/data/robots/reference.py
"""
import json, os, numpy as np, pinocchio as pin

here = os.path.dirname(os.path.abspath(__file__))
# (name, file, locked joints, tool frame whose placements and Jacobians are stored or None,
# floating base)
ROBOTS = [
    ("ur5", "ur5.urdf", [], "tool0", False),
    ("panda", "panda.urdf", ["panda_finger_joint1", "panda_finger_joint2"], "panda_hand_tcp", False),
    ("tree", "tree.urdf", [], "tool", False),
    ("xarm7", "xarm7.urdf", [], None, False),
    ("go2", "go2.urdf", [], "FL_foot", True),
    ("romeo", "romeo_small.urdf", [], None, True),
]
STATES = 100
FRAME_STATES = 20
REGRESSOR_STATES = 5
LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED

for name, file, locked, tool, floating in ROBOTS:
    path = os.path.join(here, file)
    model = pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer()) if floating else pin.buildModelFromUrdf(path)
    if locked:
        model = pin.buildReducedModel(model, [model.getJointId(j) for j in locked], pin.neutral(model))
    data = model.createData()
    rng = np.random.default_rng(46)
    first = 2 if floating else 1  # the joints after the free flyer
    prismatic = np.array([model.joints[j].shortname().startswith("JointModelP") for j in range(first, model.njoints)])
    nj = model.nq - (7 if floating else 0)
    links = [f.name for f in model.frames if f.type == pin.FrameType.BODY]
    states = []
    for k in range(STATES):
        qj = np.where(prismatic, rng.uniform(-0.3, 0.3, nj), rng.uniform(-np.pi, np.pi, nj))
        if floating:
            quat = rng.normal(size=4)
            quat /= np.linalg.norm(quat)
            q = np.concatenate([rng.uniform(-1.0, 1.0, 3), quat, qj])
        else:
            q = qj
        v = rng.uniform(-2.0, 2.0, model.nv)
        a = rng.uniform(-5.0, 5.0, model.nv)
        tau = rng.uniform(-10.0, 10.0, model.nv)
        M = pin.crba(model, data, q)
        M = np.triu(M) + np.triu(M, 1).T
        nle = pin.nonLinearEffects(model, data, q, v)
        qdd = pin.aba(model, data, q, v, tau)
        rnea = pin.rnea(model, data, q, v, a)
        state = {"q": q.tolist(), "v": v.tolist(), "a": a.tolist(), "tau": tau.tolist()}
        if floating:
            state["mass_matrix_upper"] = M[np.triu_indices(model.nv)].tolist()
        else:
            state["mass_matrix"] = M.tolist()
        state.update({"nonlinear_effects": nle.tolist(), "aba": qdd.tolist(), "rnea": rnea.tolist()})
        states.append(state)
        if tool is not None and k < FRAME_STATES:
            tool_id = model.getFrameId(tool)
            pin.forwardKinematics(model, data, q, v)
            pin.updateFramePlacements(model, data)
            pin.computeJointJacobians(model, data, q)
            placements = {}
            for f in links:
                oMf = data.oMf[model.getFrameId(f)]
                placements[f] = oMf.rotation.flatten().tolist() + oMf.translation.tolist()
            state.update({
                "placements": placements,
                "jacobian": pin.getFrameJacobian(model, data, tool_id, LWA).tolist(),
                "frame_velocity": pin.getFrameVelocity(model, data, tool_id, LWA).vector.tolist(),
                "gravity": pin.computeGeneralizedGravity(model, data, q).tolist(),
            })
        if tool is not None and k < REGRESSOR_STATES:
            state["regressor"] = pin.computeJointTorqueRegressor(model, data, q, v, a).tolist()
    out = {
        "pinocchio": pin.__version__,
        "joints": [model.names[j] for j in range(first, model.njoints)],
    }
    if tool is not None:
        out.update({"links": links, "tool": tool})
    out["states"] = states
    with open(os.path.join(here, f"reference_{name}.json"), "w") as f:
        json.dump(out, f, separators=(",", ":"))
    print(name, model.nq, model.nv, out["joints"])
