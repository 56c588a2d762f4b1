//! The robot's frames: every URDF link's, on the body it is fixed to, and
//! their placements in the world at `q` (forward kinematics, traced like
//! the recursions so that the robot's constants fold). The Jacobians are
//! assembled from these placements by the generated code (one column per
//! joint the frame's body hangs from), so this module writes the
//! kinematics once for all frames.

use super::{Cx, Floating, transforms};
use crate::robot::trace::{Trace, Val};
use crate::robot::tree::{Body, Lock, rigid_motion};
use crate::robot::urdf::{Placement, Urdf};

/// A frame of the robot: a URDF link.
#[derive(Clone, Debug)]
pub struct Frame {
    /// The link's name.
    pub name: String,
    /// The body it is fixed to, `None` for the fixed base.
    pub body: Option<usize>,
    /// Its placement in that body's frame (the base's: the world).
    pub placement: Placement,
}

/// Every link of the file as a frame, in the bodies' order (depth first,
/// children in the file's order), each on the moving body it is fixed or
/// locked to. `bodies` are [`super::super::tree::bodies`] of the same file
/// and locks: the walk is the same, each moving joint's child link is its
/// body's frame.
pub fn frames(urdf: &Urdf, locks: &[Lock], bodies: &[Body]) -> Vec<Frame> {
    let locked = |name: &str| locks.iter().find(|l| l.joint == name).map(|l| l.value);
    let mut out = Vec::new();
    // (the joint reaching the link; the link; its body; the link's frame in
    // the body's frame)
    let mut stack = vec![(None::<usize>, urdf.root, None::<usize>, Placement::IDENTITY)];
    while let Some((joint, link, parent, at)) = stack.pop() {
        let (body, frame) = match joint {
            None => (None, Placement::IDENTITY),
            Some(j) => {
                let joint = &urdf.joints[j];
                let motion = rigid_motion(joint, locked(&joint.name));
                match motion {
                    Some(motion) => (parent, at.then(&motion)),
                    None => (
                        bodies.iter().position(|b| b.name == joint.name),
                        Placement::IDENTITY,
                    ),
                }
            }
        };
        out.push(Frame {
            name: urdf.links[link].name.clone(),
            body,
            placement: frame,
        });
        for (j, joint) in urdf.joints.iter().enumerate().rev() {
            if joint.parent == link {
                stack.push((Some(j), joint.child, body, frame.then(&joint.origin)));
            }
        }
    }
    out
}

/// A placement at `q`: the rotation (frame axes in world coordinates) and
/// the origin, row-major.
pub struct Pose {
    /// `R[i][j]`.
    pub rot: [[Val; 3]; 3],
    /// The origin in the world.
    pub pos: [Val; 3],
}

fn constant(p: &Placement) -> Pose {
    Pose {
        rot: p.rot.map(|r| r.map(Val::K)),
        pos: p.pos.map(Val::K),
    }
}

/// `a ∘ b`, `b` constant.
fn then_k(cx: &mut Cx, a: &Pose, b: &Placement) -> Pose {
    let rot = [0, 1, 2].map(|i| {
        [0, 1, 2].map(|j| {
            let col = [b.rot[0][j], b.rot[1][j], b.rot[2][j]].map(Val::K);
            cx.t.dot(&a.rot[i], &col)
        })
    });
    let d = cx.mv(&a.rot, b.pos.map(Val::K));
    Pose {
        rot,
        pos: cx.add3(a.pos, d),
    }
}

/// The world placement of every body's frame at `q` (the joints'
/// coordinates), under a floating base where it is where `fb` says.
pub fn body_poses(t: &mut Trace, bodies: &[Body], fb: Option<&Floating>, q: &[Val]) -> Vec<Pose> {
    let xs = transforms(t, bodies, q);
    let mut cx = Cx { t };
    let mut poses: Vec<Pose> = Vec::with_capacity(bodies.len());
    for (i, b) in bodies.iter().enumerate() {
        let x = &xs[i];
        let parent = match b.parent {
            Some(p) => Pose {
                rot: poses[p].rot,
                pos: poses[p].pos,
            },
            None => match fb {
                Some(fb) => Pose {
                    rot: fb.rot,
                    pos: fb.pos,
                },
                None => constant(&Placement::IDENTITY),
            },
        };
        // R = R_p R_o R_j, p = p_p + R_p r.
        let ro = Placement {
            rot: x.ro,
            pos: [0.0; 3],
        };
        let mut pose = then_k(&mut cx, &parent, &ro);
        if let Some(rj) = &x.rj {
            let rot = [0, 1, 2].map(|i| {
                [0, 1, 2].map(|j| {
                    let col = [rj[0][j], rj[1][j], rj[2][j]];
                    cx.t.dot(&pose.rot[i], &col)
                })
            });
            pose.rot = rot;
        }
        let d = cx.mv(&parent.rot, x.r);
        pose.pos = cx.add3(parent.pos, d);
        poses.push(pose);
    }
    poses
}
