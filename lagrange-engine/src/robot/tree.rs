//! The URDF's links and joints as a tree of moving bodies: what is fixed
//! (or locked) to a body merged into it, its inertia expressed about the
//! body's joint frame.

use super::urdf::{Joint, JointKind, Placement, Refusal, Urdf, rotation};

/// The most moving joints a robot may have: the generated `M` has `N²`
/// entries, and the code grows with them.
pub const MAX_JOINTS: usize = 64;

/// One moving body: the child of one revolute or prismatic joint.
#[derive(Clone, Debug)]
pub struct Body {
    /// The joint's name: the coordinate's.
    pub name: String,
    /// The parent body, `None` for the fixed base.
    pub parent: Option<usize>,
    /// The joint frame at zero motion, in the parent body's frame.
    pub placement: Placement,
    /// Rotation or translation.
    pub kind: JointKind,
    /// The unit axis in the body's frame.
    pub axis: [f64; 3],
    /// The mass carried (the body and what is fixed to it).
    pub mass: f64,
    /// The first moment `m c` in the body's frame.
    pub h: [f64; 3],
    /// The inertia about the body's origin, in its axes.
    pub inertia: [[f64; 3]; 3],
    /// The struct's field holding its ten inertial parameters, where
    /// `parameters(..)` names its link: the code reads them there instead
    /// of the three constants above (which `new()` writes into it).
    pub param: Option<String>,
}

/// The mass of the root link and of what is fixed to it: a floating base's
/// body (in the root link's frame).
#[derive(Clone, Debug, Default)]
pub struct Mass {
    /// The mass.
    pub mass: f64,
    /// The first moment `m c`.
    pub h: [f64; 3],
    /// The inertia about the origin.
    pub inertia: [[f64; 3]; 3],
    /// As [`Body::param`].
    pub param: Option<String>,
}

/// A joint locked at a value: an angle, or a displacement.
#[derive(Clone, Debug)]
pub struct Lock {
    /// The joint's name.
    pub joint: String,
    /// The value it is held at.
    pub value: f64,
}

/// Why a lock was refused: the index of the lock, and the message.
pub enum TreeError {
    /// The file's fault, at a line.
    File(Refusal),
    /// Lock `usize` of the list is wrong.
    Lock(usize, String),
}

/// The placement a joint that does not move gives its child: a fixed
/// joint's identity, a locked revolute or prismatic joint's turn or shift
/// by its locked value; `None` for a joint that moves (a body of its own).
pub fn rigid_motion(joint: &Joint, locked: Option<f64>) -> Option<Placement> {
    match (joint.kind, locked) {
        (JointKind::Fixed, _) => Some(Placement::IDENTITY),
        (JointKind::Revolute, Some(v)) => Some(Placement {
            rot: rotation(joint.axis, v),
            pos: [0.0; 3],
        }),
        (JointKind::Prismatic, Some(v)) => Some(Placement {
            rot: Placement::IDENTITY.rot,
            pos: joint.axis.map(|a| a * v),
        }),
        _ => None,
    }
}

/// The moving bodies, parents before children (depth first, children in the
/// file's order), and the root's mass (what a floating base carries; a
/// fixed base's is never read). A floating base may carry no joint (a
/// free body); a fixed one needs one.
pub fn bodies(urdf: &Urdf, locks: &[Lock], floating: bool) -> Result<(Vec<Body>, Mass), TreeError> {
    for (k, lock) in locks.iter().enumerate() {
        match urdf.joints.iter().find(|j| j.name == lock.joint) {
            None => {
                return Err(TreeError::Lock(
                    k,
                    format!("the robot has no joint `{}`", lock.joint),
                ));
            }
            Some(j) if j.kind == JointKind::Fixed => {
                return Err(TreeError::Lock(
                    k,
                    format!("joint `{}` is fixed already", lock.joint),
                ));
            }
            _ => {}
        }
        if locks[..k].iter().any(|l| l.joint == lock.joint) {
            return Err(TreeError::Lock(
                k,
                format!("joint `{}` is locked twice", lock.joint),
            ));
        }
    }
    let locked = |name: &str| locks.iter().find(|l| l.joint == name).map(|l| l.value);
    let mut bodies: Vec<Body> = Vec::new();
    let mut root = Mass::default();
    // (the joint reaching the link, none for the root; the link; the body
    // the joint's parent is fixed to; the joint frame in that body's frame)
    let mut stack = vec![(None::<usize>, urdf.root, None::<usize>, Placement::IDENTITY)];
    while let Some((joint, link, parent, at)) = stack.pop() {
        let (body, frame) = match joint {
            None => (None, Placement::IDENTITY),
            Some(j) => {
                let joint = &urdf.joints[j];
                let child_link = &urdf.links[link];
                let motion = rigid_motion(joint, locked(&joint.name));
                match motion {
                    Some(motion) => (parent, at.then(&motion)),
                    None => {
                        if let Some(line) = joint.mimic {
                            return Err(TreeError::File(Refusal {
                                line: Some(line),
                                message: format!(
                                    "joint `{}` mimics another: a mimic joint is not supported, lock it \
                                     (`locked: {} = value;`)",
                                    joint.name, joint.name
                                ),
                            }));
                        }
                        if child_link.inertial.is_none() {
                            return Err(TreeError::File(Refusal {
                                line: Some(child_link.line),
                                message: format!(
                                    "link `{}` has no `<inertial>`: the joint `{}` moving it needs its mass and inertia",
                                    child_link.name, joint.name
                                ),
                            }));
                        }
                        if bodies.len() == MAX_JOINTS {
                            return Err(TreeError::File(Refusal {
                                line: Some(joint.line),
                                message: format!(
                                    "the robot has more than {MAX_JOINTS} moving joints, the most a model from URDF may have"
                                ),
                            }));
                        }
                        bodies.push(Body {
                            name: joint.name.clone(),
                            parent,
                            placement: at,
                            kind: joint.kind,
                            axis: joint.axis,
                            mass: 0.0,
                            h: [0.0; 3],
                            inertia: [[0.0; 3]; 3],
                            param: None,
                        });
                        (Some(bodies.len() - 1), Placement::IDENTITY)
                    }
                }
            }
        };
        if let Some(inertial) = urdf.links[link].inertial {
            // Into the body's frame: c' = R c + p, I' = R I Rᵀ, then about
            // the origin: I' + m (|c'|² 1 − c' c'ᵀ).
            let c = frame.apply(inertial.com);
            let r = frame.rot;
            let m = inertial.mass;
            let target = match body {
                Some(b) => {
                    let b = &mut bodies[b];
                    (&mut b.mass, &mut b.h, &mut b.inertia)
                }
                None => (&mut root.mass, &mut root.h, &mut root.inertia),
            };
            let (mass, h, inertia) = target;
            let cc: f64 = c.iter().map(|x| x * x).sum();
            for i in 0..3 {
                h[i] += m * c[i];
                for j in 0..3 {
                    let rot: f64 = (0..3)
                        .flat_map(|k| (0..3).map(move |l| (k, l)))
                        .map(|(k, l)| r[i][k] * inertial.inertia[k][l] * r[j][l])
                        .sum();
                    let delta = if i == j { cc } else { 0.0 };
                    inertia[i][j] += rot + m * (delta - c[i] * c[j]);
                }
            }
            *mass += m;
        }
        // Children in the file's order: pushed in reverse. A link without
        // `<inertial>` fixed to the base or a body is a frame (the world, a
        // tool frame): only a moved link needs a mass.
        for (j, joint) in urdf.joints.iter().enumerate().rev() {
            if joint.parent == link {
                stack.push((Some(j), joint.child, body, frame.then(&joint.origin)));
            }
        }
    }
    if bodies.is_empty() && !floating {
        return Err(TreeError::File(Refusal {
            line: None,
            message:
                "the robot has no moving joint (revolute, continuous or prismatic, not locked)"
                    .to_string(),
        }));
    }
    Ok((bodies, root))
}
