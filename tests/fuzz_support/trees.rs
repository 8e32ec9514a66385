//! The random mechanisms of `fuzz.rs`: one description ([`Tree`]) written two ways, as a
//! `mechanism!` declaration for the compiler ([`Tree::declaration`]) and as the runtime
//! `ModelBuilder` calls of the same bodies, joints and loads ([`Tree::builder`]), with the
//! inertia forms and rotations computed here (the table of the language reference) rather
//! than by the compiler.
//!
//! A tree has 1 to 12 joints (`Features::joints`) and, as its features say: fixed joints
//! anywhere (at the root, between moving joints, at leaves, in chains), a free base (and
//! sometimes a second free body) with branches, bodies hung from the ground beside it,
//! parameters in masses, mass centres, inertias, placements, armatures, dampings and load
//! points, shapes (point, sphere, box, rod, cylinder) besides full, diagonal and principal
//! inertias, massless bodies (mostly welded), loads (forces, couples, wrenches, in body or
//! world axes) on bodies merged through fixed joints, armature and damping, forward
//! dynamics by both methods, joints declared in shuffled order. Every number is printed
//! with `{:?}`, which reads back as the same `f64`.

use dynamics_runtime::{BodySpec, Inertia, JointSpec, LoadSpec, ModelBuilder, GROUND};
use dynamics_tests::random::SplitMix;
use dynamics_tests::DEFAULT_FUNCTIONS;
use nalgebra::{Matrix3, Rotation3, Unit, Vector3};
use std::fmt::Write as _;

/// What a random tree may have. Proptest shrinks each flag to `false` and `joints` towards
/// 1, so a failure comes with the fewest features that still fail.
#[derive(Clone, Copy, Debug)]
pub struct Features {
    /// Number of joints (and of bodies), 1 to 12.
    pub joints: usize,
    /// Body 0 on a free joint, the others mostly below it.
    pub free_base: bool,
    /// Fixed joints, anywhere in the tree.
    pub fixed: bool,
    /// Symbolic parameters, used in several places.
    pub parameters: bool,
    /// Shapes (and not only inertia matrices).
    pub shapes: bool,
    /// Massless bodies.
    pub massless: bool,
    /// Loads.
    pub loads: bool,
    /// Armature and damping.
    pub friction: bool,
    /// `forward_dynamics_aba` and `forward_dynamics_ldlt` besides the default outputs.
    pub both_methods: bool,
    /// The joints declared in a shuffled order (the same order on both sides).
    pub shuffled: bool,
}

/// A number: a constant, or a parameter scaled (`c * pk`) or divided (`pk / d`).
#[derive(Clone, Copy, Debug)]
enum Num {
    Const(f64),
    Scaled(f64, usize),
    Divided(usize, f64),
}

impl Num {
    fn text(self) -> String {
        match self {
            Num::Const(c) => format!("{c:?}"),
            Num::Scaled(c, k) => format!("{c:?} * p{k}"),
            Num::Divided(k, d) => format!("p{k} / {d:?}"),
        }
    }

    fn at(self, p: &[f64]) -> f64 {
        match self {
            Num::Const(c) => c,
            Num::Scaled(c, k) => c * p[k],
            Num::Divided(k, d) => p[k] / d,
        }
    }

    fn parameter(self) -> Option<usize> {
        match self {
            Num::Const(_) => None,
            Num::Scaled(_, k) | Num::Divided(k, _) => Some(k),
        }
    }
}

fn vector_text(v: &[Num; 3]) -> String {
    format!("[{}, {}, {}]", v[0].text(), v[1].text(), v[2].text())
}

fn vector_at(v: &[Num; 3], p: &[f64]) -> [f64; 3] {
    v.map(|x| x.at(p))
}

fn f64s_text(v: [f64; 3]) -> String {
    format!("[{:?}, {:?}, {:?}]", v[0], v[1], v[2])
}

fn rows(m: &Matrix3<f64>) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
}

/// A rotation, in one of the language's forms.
#[derive(Clone, Copy, Debug)]
enum Rot {
    Rpy([f64; 3]),
    AxisAngle([f64; 3], f64),
    Matrix([[f64; 3]; 3]),
}

impl Rot {
    fn random(rng: &mut SplitMix) -> Rot {
        match rng.below(3) {
            0 => Rot::Rpy(rng.vector(-3.0, 3.0)),
            1 => Rot::AxisAngle(nonzero_vector(rng), rng.uniform(-3.0, 3.0)),
            _ => {
                let [r, p, y] = rng.vector(-3.0, 3.0);
                Rot::Matrix(rows(Rotation3::from_euler_angles(r, p, y).matrix()))
            }
        }
    }

    fn text(self) -> String {
        match self {
            Rot::Rpy([r, p, y]) => format!("rpy({r:?}, {p:?}, {y:?})"),
            Rot::AxisAngle(axis, angle) => format!("axis_angle({}, {angle:?})", f64s_text(axis)),
            Rot::Matrix(m) => format!(
                "[{}, {}, {}]",
                f64s_text(m[0]),
                f64s_text(m[1]),
                f64s_text(m[2])
            ),
        }
    }

    /// R = Rz(yaw) Ry(pitch) Rx(roll) for `rpy`, Rodrigues' for `axis_angle`.
    fn matrix(self) -> Matrix3<f64> {
        match self {
            Rot::Rpy([r, p, y]) => *Rotation3::from_euler_angles(r, p, y).matrix(),
            Rot::AxisAngle(axis, angle) => {
                let axis = Unit::new_normalize(Vector3::from(axis));
                *Rotation3::from_axis_angle(&axis, angle).matrix()
            }
            Rot::Matrix(m) => Matrix3::from_fn(|i, j| m[i][j]),
        }
    }
}

fn nonzero_vector(rng: &mut SplitMix) -> [f64; 3] {
    loop {
        let v = rng.vector(-1.0, 1.0);
        if v.iter().map(|x| x * x).sum::<f64>() > 0.04 {
            return v;
        }
    }
}

/// A uniform solid's shape (dimensions are constants in the language).
#[derive(Clone, Copy, Debug)]
enum Shape {
    Point,
    Sphere(f64),
    Box([f64; 3]),
    Rod(f64, usize),
    Cylinder(f64, f64, usize),
}

const AXES: [&str; 3] = ["x", "y", "z"];

impl Shape {
    fn text(self) -> String {
        match self {
            Shape::Point => "point".into(),
            Shape::Sphere(r) => format!("sphere(radius: {r:?})"),
            Shape::Box(s) => format!("box(size: {})", f64s_text(s)),
            Shape::Rod(l, a) => format!("rod(length: {l:?}, axis: {})", AXES[a]),
            Shape::Cylinder(r, l, a) => {
                format!("cylinder(radius: {r:?}, length: {l:?}, axis: {})", AXES[a])
            }
        }
    }

    /// The principal moments about the body axes, for mass `m` (the language reference's
    /// table).
    fn moments(self, m: f64) -> [f64; 3] {
        let about = |axis: usize, along: f64, across: f64| {
            std::array::from_fn(|k| if k == axis { along } else { across })
        };
        match self {
            Shape::Point => [0.0; 3],
            Shape::Sphere(r) => [0.4 * m * r * r; 3],
            Shape::Box([a, b, c]) => [
                m * (b * b + c * c) / 12.0,
                m * (a * a + c * c) / 12.0,
                m * (a * a + b * b) / 12.0,
            ],
            Shape::Rod(l, axis) => about(axis, 0.0, m * l * l / 12.0),
            Shape::Cylinder(r, l, axis) => {
                about(axis, m * r * r / 2.0, m * (3.0 * r * r + l * l) / 12.0)
            }
        }
    }
}

/// A body's inertia, in one of the language's forms. The matrix forms may be scaled by a
/// parameter (`Some(k)`: every entry times p_k, positive, so still physical).
#[derive(Clone, Copy, Debug)]
enum InertiaForm {
    Shape(Shape),
    Matrix([[f64; 3]; 3], Option<usize>),
    Diag([f64; 3], Option<usize>),
    Principal([f64; 3], Option<usize>, Rot),
}

#[derive(Clone, Debug)]
struct Body {
    mass: Num,
    com: Option<[Num; 3]>,
    inertia: InertiaForm,
}

fn scaled_text(x: f64, by: Option<usize>) -> String {
    match by {
        Some(k) => format!("{x:?} * p{k}"),
        None => format!("{x:?}"),
    }
}

impl Body {
    fn text(&self, name: &str) -> String {
        let mut fields = vec![format!("mass: {}", self.mass.text())];
        if let Some(c) = &self.com {
            fields.push(format!("com: {}", vector_text(c)));
        }
        let list = |v: [f64; 3], by| {
            format!(
                "[{}, {}, {}]",
                scaled_text(v[0], by),
                scaled_text(v[1], by),
                scaled_text(v[2], by)
            )
        };
        fields.push(match self.inertia {
            InertiaForm::Shape(s) => format!("shape: {}", s.text()),
            InertiaForm::Matrix(m, by) => format!(
                "inertia: [{}, {}, {}]",
                list(m[0], by),
                list(m[1], by),
                list(m[2], by)
            ),
            InertiaForm::Diag(d, by) => format!("inertia: diag({})", list(d, by)),
            InertiaForm::Principal(d, by, r) => {
                format!(
                    "inertia: principal({}, rotation: {})",
                    list(d, by),
                    r.text()
                )
            }
        });
        format!("body {name} {{ {} }}", fields.join(", "))
    }

    /// Mass, mass centre and I_G at parameter values `p`.
    fn inertia_at(&self, p: &[f64]) -> Inertia {
        let m = self.mass.at(p);
        let com = self.com.as_ref().map_or([0.0; 3], |c| vector_at(c, p));
        let scale = |by: Option<usize>| by.map_or(1.0, |k| p[k]);
        let i_g = match self.inertia {
            InertiaForm::Shape(s) => Matrix3::from_diagonal(&Vector3::from(s.moments(m))),
            InertiaForm::Matrix(rows, by) => Matrix3::from_fn(|i, j| rows[i][j] * scale(by)),
            InertiaForm::Diag(d, by) => {
                Matrix3::from_diagonal(&Vector3::from(d.map(|x| x * scale(by))))
            }
            InertiaForm::Principal(d, by, r) => {
                let r = r.matrix();
                let i = r
                    * Matrix3::from_diagonal(&Vector3::from(d.map(|x| x * scale(by))))
                    * r.transpose();
                // Exactly symmetric, as the compiler's.
                (i + i.transpose()) * 0.5
            }
        };
        Inertia::new(m, com, rows(&i_g))
    }

    fn parameters(&self, used: &mut [bool]) {
        let mut mark = |k: Option<usize>| k.into_iter().for_each(|k| used[k] = true);
        mark(self.mass.parameter());
        self.com.iter().flatten().for_each(|c| mark(c.parameter()));
        match self.inertia {
            InertiaForm::Shape(_) => {}
            InertiaForm::Matrix(_, by)
            | InertiaForm::Diag(_, by)
            | InertiaForm::Principal(_, by, _) => mark(by),
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Revolute,
    Prismatic,
    Fixed,
    Free,
}

#[derive(Clone, Copy, Debug)]
enum Axis {
    /// A coordinate axis, negated when `true`.
    Coordinate(usize, bool),
    Vector([f64; 3]),
}

impl Axis {
    fn text(self) -> String {
        match self {
            Axis::Coordinate(k, negative) => {
                format!("{}{}", if negative { "-" } else { "" }, AXES[k])
            }
            Axis::Vector(v) => f64s_text(v),
        }
    }

    fn vector(self) -> [f64; 3] {
        match self {
            Axis::Coordinate(k, negative) => std::array::from_fn(|i| {
                if i != k {
                    0.0
                } else if negative {
                    -1.0
                } else {
                    1.0
                }
            }),
            Axis::Vector(v) => v,
        }
    }
}

/// Joint k moves body k.
#[derive(Clone, Debug)]
struct Joint {
    kind: Kind,
    /// `None`: the ground.
    parent: Option<usize>,
    axis: Axis,
    at: Option<[Num; 3]>,
    rotation: Option<Rot>,
    armature: Option<Num>,
    damping: Option<Num>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum LoadKind {
    Force,
    Couple,
    Wrench,
}

#[derive(Clone, Debug)]
struct Load {
    kind: LoadKind,
    body: usize,
    point: Option<[Num; 3]>,
    /// `Some(true)`: `in world`; `Some(false)`: `in body`; `None`: neither (body axes).
    world: Option<bool>,
}

#[derive(Clone, Copy, Debug)]
enum Gravity {
    /// No `gravity:` setting: (0, 0, −9.81).
    Default,
    /// `gravity: none;`.
    Zero,
    Vector([f64; 3]),
}

/// One random mechanism; see the module's docs.
#[derive(Clone, Debug)]
pub struct Tree {
    gravity: Gravity,
    /// Nominal values of p0, p1, ...
    nominal: Vec<f64>,
    bodies: Vec<Body>,
    joints: Vec<Joint>,
    /// The order the joints are declared in.
    order: Vec<usize>,
    loads: Vec<Load>,
    both_methods: bool,
}

impl Tree {
    /// The tree `seed` draws with `features`.
    pub fn generate(seed: u64, f: Features) -> Tree {
        let mut rng = SplitMix(seed);
        let n = f.joints.clamp(1, 12);
        let nominal: Vec<f64> = if f.parameters {
            (0..1 + rng.below(3))
                .map(|_| rng.uniform(0.5, 2.0))
                .collect()
        } else {
            Vec::new()
        };
        let np = nominal.len();
        // A number in [lo, hi), sometimes a parameter times a constant.
        let number = |rng: &mut SplitMix, lo: f64, hi: f64, chance: f64| -> Num {
            let x = rng.uniform(lo, hi);
            if np > 0 && rng.chance(chance) {
                let k = rng.below(np);
                if rng.chance(0.5) {
                    Num::Scaled(x, k)
                } else if x.abs() > 1e-3 {
                    Num::Divided(k, 1.0 / x)
                } else {
                    Num::Scaled(x, k)
                }
            } else {
                Num::Const(x)
            }
        };
        let mut kinds: Vec<Kind> = (0..n)
            .map(|k| {
                if f.free_base && (k == 0 || rng.chance(0.08)) {
                    Kind::Free
                } else if f.fixed && rng.chance(0.35) {
                    Kind::Fixed
                } else if rng.chance(0.25) {
                    Kind::Prismatic
                } else {
                    Kind::Revolute
                }
            })
            .collect();
        // Never a free body: a massless free base carrying a body on a revolute joint has a
        // singular M(q) (turning the base and the joint oppositely moves no mass), which the
        // compiler rejects; most such trees would be rejected.
        let mut massless: Vec<bool> = (0..n)
            .map(|k| f.massless && kinds[k] != Kind::Free && rng.chance(0.3))
            .collect();
        // A massless body is welded most of the time (a massless leaf on a moving joint
        // would make M singular, which the compiler rejects).
        for k in 0..n {
            if massless[k] && kinds[k] != Kind::Free && rng.chance(0.7) {
                kinds[k] = Kind::Fixed;
            }
        }
        if kinds.iter().all(|&k| k == Kind::Fixed) {
            kinds[n - 1] = Kind::Revolute;
        }
        let joints: Vec<Joint> = (0..n)
            .map(|k| {
                let kind = kinds[k];
                let parent = if k == 0 || kind == Kind::Free {
                    None
                } else if rng.chance(0.5) {
                    Some(k - 1)
                } else if f.free_base && !rng.chance(0.15) {
                    Some(rng.below(k))
                } else {
                    rng.below(k + 1).checked_sub(1)
                };
                let axis = if rng.chance(0.4) {
                    Axis::Coordinate(rng.below(3), rng.chance(0.3))
                } else {
                    Axis::Vector(nonzero_vector(&mut rng))
                };
                let at = rng
                    .chance(0.85)
                    .then(|| std::array::from_fn(|_| number(&mut rng, -0.5, 0.5, 0.15)));
                let rotation = rng.chance(0.75).then(|| Rot::random(&mut rng));
                let moving = matches!(kind, Kind::Revolute | Kind::Prismatic);
                let armature = (f.friction && moving && rng.chance(0.8))
                    .then(|| number(&mut rng, 0.0, 0.2, 0.2));
                let damping = (f.friction && moving && rng.chance(0.8))
                    .then(|| number(&mut rng, 0.0, 0.5, 0.2));
                Joint {
                    kind,
                    parent,
                    axis,
                    at,
                    rotation,
                    armature,
                    damping,
                }
            })
            .collect();
        let bodies: Vec<Body> = (0..n)
            .map(|k| {
                if massless[k] {
                    let inertia = if rng.chance(0.5) {
                        InertiaForm::Shape(Shape::Point)
                    } else {
                        InertiaForm::Diag([0.0; 3], None)
                    };
                    return Body {
                        mass: Num::Const(0.0),
                        com: rng
                            .chance(0.3)
                            .then(|| rng.vector(-0.1, 0.1).map(Num::Const)),
                        inertia,
                    };
                }
                let mass = number(&mut rng, 0.1, 5.0, 0.3);
                let com = rng
                    .chance(0.8)
                    .then(|| std::array::from_fn(|_| number(&mut rng, -0.3, 0.3, 0.1)));
                let by = (np > 0 && rng.chance(0.2)).then(|| rng.below(np));
                // ∫x² dm, ∫y² dm, ∫z² dm: the moments satisfy the triangle inequality.
                let [d1, d2, d3] = rng.vector(0.0005, 0.05);
                let moments = [d2 + d3, d1 + d3, d1 + d2];
                let inertia = if f.shapes && rng.chance(0.6) {
                    let axis = rng.below(3);
                    InertiaForm::Shape(match rng.below(5) {
                        0 => Shape::Point,
                        1 => Shape::Sphere(rng.uniform(0.01, 0.3)),
                        2 => Shape::Box(rng.vector(0.01, 0.5)),
                        3 => Shape::Rod(rng.uniform(0.05, 1.0), axis),
                        _ => Shape::Cylinder(rng.uniform(0.01, 0.2), rng.uniform(0.01, 0.8), axis),
                    })
                } else {
                    match rng.below(3) {
                        0 => {
                            let r = Rot::random(&mut rng).matrix();
                            let i =
                                r * Matrix3::from_diagonal(&Vector3::from(moments)) * r.transpose();
                            // Exactly symmetric: the upper triangle mirrored.
                            let m: [[f64; 3]; 3] = std::array::from_fn(|a| {
                                std::array::from_fn(|b| i[(a.min(b), a.max(b))])
                            });
                            InertiaForm::Matrix(m, by)
                        }
                        1 => InertiaForm::Diag(moments, by),
                        _ => InertiaForm::Principal(moments, by, Rot::random(&mut rng)),
                    }
                };
                Body { mass, com, inertia }
            })
            .collect();
        let mut tree = Tree {
            gravity: match rng.below(6) {
                0 | 1 => Gravity::Default,
                2 => Gravity::Zero,
                _ => Gravity::Vector(rng.vector(-10.0, 10.0)),
            },
            nominal,
            bodies,
            joints,
            order: (0..n).collect(),
            loads: Vec::new(),
            both_methods: f.both_methods,
        };
        if f.loads {
            // Loads act on bodies that move: welded to the ground they do no work (an
            // error). Half of them on bodies welded to a moving body, when there are some.
            let moving: Vec<usize> = (0..n).filter(|&b| tree.moves(b)).collect();
            let merged: Vec<usize> = moving
                .iter()
                .copied()
                .filter(|&b| tree.joints[b].kind == Kind::Fixed)
                .collect();
            for _ in 0..1 + rng.below(3) {
                let body = if !merged.is_empty() && rng.chance(0.5) {
                    merged[rng.below(merged.len())]
                } else {
                    moving[rng.below(moving.len())]
                };
                let kind = [LoadKind::Force, LoadKind::Couple, LoadKind::Wrench][rng.below(3)];
                let point = (kind != LoadKind::Couple && rng.chance(0.8))
                    .then(|| std::array::from_fn(|_| number(&mut rng, -0.3, 0.3, 0.15)));
                let world = [None, Some(true), Some(false)][rng.below(3)];
                tree.loads.push(Load {
                    kind,
                    body,
                    point,
                    world,
                });
            }
        }
        // Every declared parameter is used (an unused one is an error): each one left takes
        // the place of a constant mass or mass centre coordinate of a body with mass (or
        // gives a massless body a mass).
        let mut used = vec![false; np];
        tree.mark_parameters(&mut used);
        for k in (0..np).filter(|&k| !used[k]) {
            // (body, None for the mass or Some(coordinate)).
            let mut slots: Vec<(usize, Option<usize>)> = Vec::new();
            for (b, body) in tree
                .bodies
                .iter()
                .enumerate()
                .filter(|&(b, _)| !massless[b])
            {
                if matches!(body.mass, Num::Const(_)) {
                    slots.push((b, None));
                }
                let com = body.com.unwrap_or([Num::Const(0.0); 3]);
                slots.extend(
                    (0..3)
                        .filter(|&i| matches!(com[i], Num::Const(_)))
                        .map(|i| (b, Some(i))),
                );
            }
            let body_count = tree.bodies.len();
            let (b, slot) = if slots.is_empty() {
                (rng.below(body_count), None)
            } else {
                slots[rng.below(slots.len())]
            };
            massless[b] = false;
            let body = &mut tree.bodies[b];
            match slot {
                None => body.mass = Num::Scaled(rng.uniform(0.1, 3.0), k),
                Some(i) => {
                    let mut com = body.com.unwrap_or([Num::Const(0.0); 3]);
                    com[i] = Num::Scaled(rng.uniform(0.05, 0.3), k);
                    body.com = Some(com);
                }
            }
        }
        let mut used = vec![false; np];
        tree.mark_parameters(&mut used);
        assert!(used.iter().all(|&u| u), "every parameter is used: {used:?}");
        if f.shuffled {
            for k in (1..n).rev() {
                tree.order.swap(k, rng.below(k + 1));
            }
        }
        tree
    }

    /// Whether body `b` moves: a joint other than fixed is on its path from the ground.
    fn moves(&self, mut b: usize) -> bool {
        loop {
            let joint = &self.joints[b];
            if joint.kind != Kind::Fixed {
                return true;
            }
            match joint.parent {
                Some(parent) => b = parent,
                None => return false,
            }
        }
    }

    fn mark_parameters(&self, used: &mut [bool]) {
        for body in &self.bodies {
            body.parameters(used);
        }
        let mut mark = |n: &Num| n.parameter().into_iter().for_each(|k| used[k] = true);
        for joint in &self.joints {
            joint.at.iter().flatten().for_each(&mut mark);
            joint.armature.iter().for_each(&mut mark);
            joint.damping.iter().for_each(&mut mark);
        }
        for load in &self.loads {
            load.point.iter().flatten().for_each(&mut mark);
        }
    }

    /// The parameters' nominal values.
    pub fn nominal(&self) -> &[f64] {
        &self.nominal
    }

    /// Number of parameters.
    pub fn num_parameters(&self) -> usize {
        self.nominal.len()
    }

    /// The names of the functions the compiler should generate, in the order it emits
    /// them.
    pub fn functions(&self) -> Vec<&'static str> {
        let mut functions = DEFAULT_FUNCTIONS.to_vec();
        if self.both_methods {
            functions.splice(6..6, ["forward_dynamics_aba", "forward_dynamics_ldlt"]);
        }
        functions
    }

    /// The `mechanism!` declaration (the macro's input, without `mechanism! { }`).
    pub fn declaration(&self) -> String {
        let mut s = String::from("pub struct RandomTree;\n");
        let mut line = |text: String| {
            writeln!(s, "{text}").expect("writing to a String");
        };
        match self.gravity {
            Gravity::Default => {}
            Gravity::Zero => line("gravity: none;".into()),
            Gravity::Vector(g) => line(format!("gravity: {};", f64s_text(g))),
        }
        if !self.nominal.is_empty() {
            let list: Vec<String> = self
                .nominal
                .iter()
                .enumerate()
                .map(|(k, v)| format!("p{k} = {v:?}"))
                .collect();
            line(format!("parameters: [{}];", list.join(", ")));
        }
        if self.both_methods {
            let mut outputs = self.functions();
            // In another order than the generated functions', with a short form.
            outputs.reverse();
            outputs.retain(|&f| f != "coriolis_matrix");
            outputs.push("coriolis");
            line(format!("outputs: [{}];", outputs.join(", ")));
        }
        for (k, body) in self.bodies.iter().enumerate() {
            line(body.text(&format!("b{k}")));
        }
        for &k in &self.order {
            let joint = &self.joints[k];
            let parent = joint.parent.map_or(GROUND.to_owned(), |p| format!("b{p}"));
            let kind = match joint.kind {
                Kind::Revolute => "revolute",
                Kind::Prismatic => "prismatic",
                Kind::Fixed => "fixed",
                Kind::Free => "free",
            };
            let mut fields = Vec::new();
            if matches!(joint.kind, Kind::Revolute | Kind::Prismatic) {
                fields.push(format!("axis: {}", joint.axis.text()));
            }
            if let Some(at) = &joint.at {
                fields.push(format!("at: {}", vector_text(at)));
            }
            if let Some(r) = joint.rotation {
                fields.push(format!("rotation: {}", r.text()));
            }
            if let Some(a) = joint.armature {
                fields.push(format!("armature: {}", a.text()));
            }
            if let Some(d) = joint.damping {
                fields.push(format!("damping: {}", d.text()));
            }
            let head = format!("joint j{k}: {kind}({parent} -> b{k})");
            if fields.is_empty() {
                line(format!("{head};"));
            } else {
                line(format!("{head} {{ {} }}", fields.join(", ")));
            }
        }
        for (k, load) in self.loads.iter().enumerate() {
            let kind = match load.kind {
                LoadKind::Force => "force",
                LoadKind::Couple => "couple",
                LoadKind::Wrench => "wrench",
            };
            let mut text = format!("load l{k}: {kind} on b{}", load.body);
            if let Some(point) = &load.point {
                write!(text, " at {}", vector_text(point)).expect("writing to a String");
            }
            match load.world {
                Some(true) => text.push_str(" in world"),
                Some(false) => text.push_str(" in body"),
                None => {}
            }
            line(format!("{text};"));
        }
        s
    }

    /// The same mechanism for the runtime, at parameter values `p`: the bodies, joints (in
    /// the declaration's order) and loads, every number as the declaration gives it.
    pub fn builder(&self, p: &[f64]) -> ModelBuilder {
        let gravity = match self.gravity {
            Gravity::Default => [0.0, 0.0, -9.81],
            Gravity::Zero => [0.0; 3],
            Gravity::Vector(g) => g,
        };
        let mut builder = ModelBuilder::new().gravity(gravity);
        for (k, body) in self.bodies.iter().enumerate() {
            builder = builder.body(BodySpec::new(format!("b{k}"), body.inertia_at(p)));
        }
        for &k in &self.order {
            let joint = &self.joints[k];
            let (name, child) = (format!("j{k}"), format!("b{k}"));
            let parent = joint.parent.map_or(GROUND.to_owned(), |p| format!("b{p}"));
            let axis = joint.axis.vector();
            let mut spec = match joint.kind {
                Kind::Revolute => JointSpec::revolute(&name, &parent, &child, axis),
                Kind::Prismatic => JointSpec::prismatic(&name, &parent, &child, axis),
                Kind::Fixed => JointSpec::fixed(&name, &parent, &child),
                Kind::Free => JointSpec::free_flyer(&name, &child),
            };
            let at = joint.at.as_ref().map_or([0.0; 3], |v| vector_at(v, p));
            let rotation = joint.rotation.map_or(Matrix3::identity(), Rot::matrix);
            spec = spec.placed(at, rows(&rotation));
            if let Some(a) = joint.armature {
                spec = spec.with_armature(a.at(p));
            }
            if let Some(d) = joint.damping {
                spec = spec.with_damping(d.at(p));
            }
            builder = builder.joint(spec);
        }
        for (k, load) in self.loads.iter().enumerate() {
            let (name, body) = (format!("l{k}"), format!("b{}", load.body));
            let mut spec = match load.kind {
                LoadKind::Force => LoadSpec::force(&name, &body),
                LoadKind::Couple => LoadSpec::couple(&name, &body),
                LoadKind::Wrench => LoadSpec::wrench(&name, &body),
            };
            if let Some(point) = &load.point {
                spec = spec.at(vector_at(point, p));
            }
            if load.world == Some(true) {
                spec = spec.in_world();
            }
            builder = builder.load(spec);
        }
        builder
    }
}
