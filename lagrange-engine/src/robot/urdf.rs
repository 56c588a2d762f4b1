//! A URDF file read into links and joints, every number checked.
//!
//! Only what the dynamics needs is read: each link's `<inertial>`, each
//! joint's type, parent, child, `<origin>` and `<axis>`. Visuals,
//! collisions, limits and transmissions are ignored. Every refusal names
//! the element and its line in the file.

use roxmltree::{Document, Node, ParsingOptions};

/// The largest URDF read (bytes): a robot's file is tens of kilobytes.
pub const MAX_FILE: u64 = 4 << 20;
/// The most XML nodes read.
const MAX_NODES: u32 = 200_000;

/// A rigid placement: `x_parent = rot · x_child + pos`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// The child's axes in the parent's coordinates (columns).
    pub rot: [[f64; 3]; 3],
    /// The child's origin in the parent's coordinates.
    pub pos: [f64; 3],
}

impl Placement {
    /// The identity.
    pub const IDENTITY: Placement = Placement {
        rot: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        pos: [0.0; 3],
    };

    /// `self ∘ other`: `other` given in `self`'s child frame.
    pub fn then(&self, other: &Placement) -> Placement {
        let mut rot = [[0.0; 3]; 3];
        let mut pos = self.pos;
        for i in 0..3 {
            for j in 0..3 {
                rot[i][j] = (0..3).map(|k| self.rot[i][k] * other.rot[k][j]).sum();
            }
            pos[i] += (0..3).map(|k| self.rot[i][k] * other.pos[k]).sum::<f64>();
        }
        Placement { rot, pos }
    }

    /// A point given in the child frame, in the parent's.
    pub fn apply(&self, x: [f64; 3]) -> [f64; 3] {
        let mut y = self.pos;
        for (i, yi) in y.iter_mut().enumerate() {
            *yi += (0..3).map(|k| self.rot[i][k] * x[k]).sum::<f64>();
        }
        y
    }
}

/// A rotation by `angle` about the unit `axis` (Rodrigues).
pub fn rotation(axis: [f64; 3], angle: f64) -> [[f64; 3]; 3] {
    let (s, c) = angle.sin_cos();
    let [x, y, z] = axis;
    let t = 1.0 - c;
    [
        [c + x * x * t, x * y * t - z * s, x * z * t + y * s],
        [y * x * t + z * s, c + y * y * t, y * z * t - x * s],
        [z * x * t - y * s, z * y * t + x * s, c + z * z * t],
    ]
}

/// A link's mass, centre of mass and inertia about it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inertial {
    /// Mass.
    pub mass: f64,
    /// The centre of mass in the link's frame.
    pub com: [f64; 3],
    /// The inertia about the centre of mass, in the link's axes.
    pub inertia: [[f64; 3]; 3],
}

/// A link.
#[derive(Clone, Debug)]
pub struct Link {
    /// Its name.
    pub name: String,
    /// Its line in the file.
    pub line: u32,
    /// Its `<inertial>`, if it has one.
    pub inertial: Option<Inertial>,
}

/// What a joint lets its child do.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// A rotation about the axis (`revolute` or `continuous`).
    Revolute,
    /// A translation along the axis.
    Prismatic,
    /// Nothing.
    Fixed,
}

/// A joint.
#[derive(Clone, Debug)]
pub struct Joint {
    /// Its name.
    pub name: String,
    /// Its line in the file.
    pub line: u32,
    /// What it lets move.
    pub kind: JointKind,
    /// The parent link (an index into the links).
    pub parent: usize,
    /// The child link.
    pub child: usize,
    /// The joint frame in the parent link's frame.
    pub origin: Placement,
    /// The unit axis in the joint frame.
    pub axis: [f64; 3],
    /// The line of its `<mimic>`, if it has one.
    pub mimic: Option<u32>,
}

/// A robot as read: links, joints, the root link.
#[derive(Clone, Debug)]
pub struct Urdf {
    /// The robot's name.
    pub name: String,
    /// The links, in the file's order.
    pub links: Vec<Link>,
    /// The joints, in the file's order.
    pub joints: Vec<Joint>,
    /// The one link that is no joint's child.
    pub root: usize,
}

/// Why a file was refused: a message and the line it is about.
#[derive(Clone, Debug, PartialEq)]
pub struct Refusal {
    /// The line in the file (1-based), if the refusal is about one.
    pub line: Option<u32>,
    /// What is wrong, in words.
    pub message: String,
}

fn refuse(line: u32, message: String) -> Refusal {
    Refusal {
        line: Some(line),
        message,
    }
}

fn line_of(doc: &Document, node: Node) -> u32 {
    doc.text_pos_at(node.range().start).row
}

/// `n` numbers from a whitespace-separated attribute, each finite.
fn numbers<const K: usize>(
    doc: &Document,
    node: Node,
    attr: &str,
    default: Option<[f64; K]>,
) -> Result<[f64; K], Refusal> {
    let line = line_of(doc, node);
    let element = node.tag_name().name();
    let Some(text) = node.attribute(attr) else {
        return default
            .ok_or_else(|| refuse(line, format!("`<{element}>` has no `{attr}` attribute")));
    };
    let mut out = [0.0; K];
    let mut count = 0;
    for word in text.split_whitespace() {
        let value = word.parse::<f64>().ok().filter(|v| v.is_finite());
        match (value, out.get_mut(count)) {
            (Some(v), Some(slot)) => *slot = v,
            (None, _) => {
                return Err(refuse(
                    line,
                    format!("`<{element} {attr}=\"{text}\">`: `{word}` is not a finite number"),
                ));
            }
            (_, None) => break,
        }
        count += 1;
    }
    if count != K {
        return Err(refuse(
            line,
            format!("`<{element} {attr}=\"{text}\">` needs {K} numbers"),
        ));
    }
    Ok(out)
}

fn child<'a, 'i>(node: Node<'a, 'i>, name: &str) -> Option<Node<'a, 'i>> {
    node.children()
        .find(|c| c.is_element() && c.tag_name().name() == name)
}

/// Rotation entries this close to 0 are taken as 0: `rpy` angles of
/// ±π/2 leave 6e-17 where a permutation has 0, and the exact zero lets the
/// generated code skip those products (a change of 1e-16 relative).
pub const SNAP: f64 = 4.0 * f64::EPSILON;

/// The rotation `Rz(y) Ry(p) Rx(r)` of an `rpy`, snapped ([`snapped`]).
pub fn rpy(r: f64, p: f64, y: f64) -> [[f64; 3]; 3] {
    placement([0.0; 3], [r, p, y]).rot
}

/// The placement of `xyz` and `rpy`: `Rz(y) Ry(p) Rx(r)` snapped.
fn placement(pos: [f64; 3], [r, p, y]: [f64; 3]) -> Placement {
    let rx = rotation([1.0, 0.0, 0.0], r);
    let ry = rotation([0.0, 1.0, 0.0], p);
    let rz = rotation([0.0, 0.0, 1.0], y);
    let z = Placement { rot: rz, pos };
    let place = z
        .then(&Placement {
            rot: ry,
            pos: [0.0; 3],
        })
        .then(&Placement {
            rot: rx,
            pos: [0.0; 3],
        });
    Placement {
        rot: snapped(place.rot),
        pos: place.pos,
    }
}

/// A rotation's entries within [`SNAP`] of zero set to zero.
pub fn snapped(mut rot: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    for x in rot.iter_mut().flatten() {
        if x.abs() < SNAP {
            *x = 0.0;
        }
    }
    rot
}

/// `<origin xyz rpy>`: the placement `Rz(y) Ry(p) Rx(r)`, `xyz`.
fn origin(doc: &Document, node: Node) -> Result<Placement, Refusal> {
    let Some(o) = child(node, "origin") else {
        return Ok(Placement::IDENTITY);
    };
    let pos = numbers::<3>(doc, o, "xyz", Some([0.0; 3]))?;
    let angles = numbers::<3>(doc, o, "rpy", Some([0.0; 3]))?;
    Ok(placement(pos, angles))
}

/// An inertia given in axes `r` expressed in the link's: `R I Rᵀ`.
pub fn rotated_inertia(r: &[[f64; 3]; 3], local: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut inertia = [[0.0; 3]; 3];
    for (i, row) in inertia.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = (0..3)
                .flat_map(|k| (0..3).map(move |l| (k, l)))
                .map(|(k, l)| r[i][k] * local[k][l] * r[j][l])
                .sum();
        }
    }
    inertia
}

fn inertial(doc: &Document, link: Node, name: &str) -> Result<Option<Inertial>, Refusal> {
    let Some(node) = child(link, "inertial") else {
        return Ok(None);
    };
    let line = line_of(doc, node);
    let place = origin(doc, node)?;
    let mass_node = child(node, "mass").ok_or_else(|| {
        refuse(
            line,
            format!("link `{name}`'s `<inertial>` has no `<mass>`"),
        )
    })?;
    let [mass] = numbers::<1>(doc, mass_node, "value", None)?;
    let i_node = child(node, "inertia").ok_or_else(|| {
        refuse(
            line,
            format!("link `{name}`'s `<inertial>` has no `<inertia>`"),
        )
    })?;
    let get = |a: &str| numbers::<1>(doc, i_node, a, None).map(|[v]| v);
    let (xx, xy, xz, yy, yz, zz) = (
        get("ixx")?,
        get("ixy")?,
        get("ixz")?,
        get("iyy")?,
        get("iyz")?,
        get("izz")?,
    );
    let i_line = line_of(doc, i_node);
    if mass < 0.0 {
        return Err(refuse(
            line_of(doc, mass_node),
            format!("link `{name}` has a negative mass, {mass}"),
        ));
    }
    let local = [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]];
    if mass == 0.0 {
        if local.iter().flatten().any(|&v| v != 0.0) {
            return Err(refuse(
                i_line,
                format!(
                    "link `{name}` has no mass but an inertia: a massless link's inertia is zero"
                ),
            ));
        }
    } else {
        // Positive definite: the leading minors positive (Sylvester).
        let d2 = xx * yy - xy * xy;
        let d3 = xx * (yy * zz - yz * yz) - xy * (xy * zz - yz * xz) + xz * (xy * yz - yy * xz);
        if !(xx > 0.0 && d2 > 0.0 && d3 > 0.0) {
            return Err(refuse(
                i_line,
                format!(
                    "link `{name}`'s inertia is not positive definite (ixx = {xx}, leading minors {d2:e} and {d3:e}): \
                     a body of mass {mass} has a positive moment about every axis"
                ),
            ));
        }
    }
    // Into the link's axes: R I Rᵀ.
    let inertia = rotated_inertia(&place.rot, &local);
    Ok(Some(Inertial {
        mass,
        com: place.pos,
        inertia,
    }))
}

/// Reads a URDF document.
pub fn read(text: &str) -> Result<Urdf, Refusal> {
    let options = ParsingOptions {
        allow_dtd: false,
        nodes_limit: MAX_NODES,
        ..ParsingOptions::default()
    };
    let doc = Document::parse_with_options(text, options).map_err(|e| {
        let pos = e.pos();
        Refusal {
            line: Some(pos.row),
            message: format!("not well-formed XML: {e}"),
        }
    })?;
    let robot = doc.root_element();
    if robot.tag_name().name() != "robot" {
        return Err(refuse(
            line_of(&doc, robot),
            format!(
                "the root element is `<{}>`, not `<robot>`",
                robot.tag_name().name()
            ),
        ));
    }
    let name = robot.attribute("name").unwrap_or("").to_string();
    let elements = || robot.children().filter(|c| c.is_element());
    let mut links: Vec<Link> = Vec::new();
    for node in elements().filter(|c| c.tag_name().name() == "link") {
        let line = line_of(&doc, node);
        let name = node
            .attribute("name")
            .ok_or_else(|| refuse(line, "a `<link>` has no name".to_string()))?;
        if let Some(other) = links.iter().find(|l| l.name == name) {
            return Err(refuse(
                line,
                format!(
                    "link `{name}` is defined twice (first on line {})",
                    other.line
                ),
            ));
        }
        links.push(Link {
            name: name.to_string(),
            line,
            inertial: inertial(&doc, node, name)?,
        });
    }
    let find = |joint: &str, node: Node, which: &str| -> Result<usize, Refusal> {
        let line = line_of(&doc, node);
        let n = child(node, which)
            .ok_or_else(|| refuse(line, format!("joint `{joint}` has no `<{which}>`")))?;
        let link = n.attribute("link").ok_or_else(|| {
            refuse(
                line_of(&doc, n),
                format!("joint `{joint}`'s `<{which}>` names no link"),
            )
        })?;
        links.iter().position(|l| l.name == link).ok_or_else(|| {
            refuse(
                line_of(&doc, n),
                format!("joint `{joint}`'s {which} `{link}` is no link of the robot"),
            )
        })
    };
    let mut joints: Vec<Joint> = Vec::new();
    for node in elements().filter(|c| c.tag_name().name() == "joint") {
        let line = line_of(&doc, node);
        let name = node
            .attribute("name")
            .ok_or_else(|| refuse(line, "a `<joint>` has no name".to_string()))?;
        let kind = match node.attribute("type").unwrap_or("") {
            "revolute" | "continuous" => JointKind::Revolute,
            "prismatic" => JointKind::Prismatic,
            "fixed" => JointKind::Fixed,
            other @ ("planar" | "floating") => {
                return Err(refuse(
                    line,
                    format!(
                        "joint `{name}` is `{other}`: a robot from URDF takes revolute, continuous, prismatic \
                         and fixed joints (a floating base is not read from URDF)"
                    ),
                ));
            }
            other => {
                return Err(refuse(
                    line,
                    format!(
                        "joint `{name}` has type `{other}`: expected revolute, continuous, prismatic or fixed"
                    ),
                ));
            }
        };
        if let Some(other) = joints.iter().find(|j| j.name == name) {
            return Err(refuse(
                line,
                format!(
                    "joint `{name}` is defined twice (first on line {})",
                    other.line
                ),
            ));
        }
        let parent = find(name, node, "parent")?;
        let child_link = find(name, node, "child")?;
        let origin = origin(&doc, node)?;
        let mut axis = [1.0, 0.0, 0.0];
        if kind != JointKind::Fixed {
            if let Some(a) = child(node, "axis") {
                axis = numbers::<3>(&doc, a, "xyz", Some(axis))?;
                let norm = axis.iter().map(|x| x * x).sum::<f64>().sqrt();
                if norm.is_nan() || norm < 1e-12 {
                    return Err(refuse(
                        line_of(&doc, a),
                        format!(
                            "joint `{name}`'s axis is zero: a joint moves about or along a direction"
                        ),
                    ));
                }
                for x in &mut axis {
                    *x /= norm;
                }
            }
        }
        joints.push(Joint {
            name: name.to_string(),
            line,
            kind,
            parent,
            child: child_link,
            origin,
            axis,
            mimic: child(node, "mimic").map(|m| line_of(&doc, m)),
        });
    }
    // A tree: each link the child of at most one joint, one root, all reached.
    let mut parent_joint: Vec<Option<usize>> = vec![None; links.len()];
    for (j, joint) in joints.iter().enumerate() {
        if let Some(first) = parent_joint[joint.child] {
            return Err(refuse(
                joint.line,
                format!(
                    "link `{}` is attached twice: by joint `{}` (line {}) and by joint `{}`",
                    links[joint.child].name, joints[first].name, joints[first].line, joint.name
                ),
            ));
        }
        parent_joint[joint.child] = Some(j);
    }
    let roots: Vec<usize> = (0..links.len())
        .filter(|&l| parent_joint[l].is_none())
        .collect();
    let root = match roots.as_slice() {
        [r] => *r,
        [] => {
            return Err(Refusal {
                line: None,
                message: if links.is_empty() {
                    "the robot has no links".to_string()
                } else {
                    "every link is some joint's child: the joints form a loop".to_string()
                },
            });
        }
        [a, b, ..] => {
            return Err(refuse(
                links[*b].line,
                format!(
                    "links `{}` and `{}` are both roots (no joint's child): a robot is one tree",
                    links[*a].name, links[*b].name
                ),
            ));
        }
    };
    // Every link reached from the root (else a loop hangs apart from it).
    let mut reached = vec![false; links.len()];
    reached[root] = true;
    let mut stack = vec![root];
    while let Some(l) = stack.pop() {
        for j in joints.iter().filter(|j| j.parent == l) {
            if !reached[j.child] {
                reached[j.child] = true;
                stack.push(j.child);
            }
        }
    }
    if let Some(l) = (0..links.len()).find(|&l| !reached[l]) {
        return Err(refuse(
            links[l].line,
            format!(
                "link `{}` lies on a loop of joints: a robot is a tree",
                links[l].name
            ),
        ));
    }
    Ok(Urdf {
        name,
        links,
        joints,
        root,
    })
}
