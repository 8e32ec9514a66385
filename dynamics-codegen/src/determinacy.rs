//! The numeric rank of the force analysis, of the loop closures and of the mass matrix, at
//! compile time.
//!
//! The model's rules check the force analysis structurally: as many unknowns as balance
//! equations, and a matching between them body by body (`model::statics`). That cannot see
//! geometry: a roller whose normal is the direction a prismatic joint already holds, or a
//! support placed on the pivot it should brace, passes the count and the matching, and
//! A(q) is singular at every configuration (the generated solve then divides by zero and
//! returns infinities). Here the assembled matrices are evaluated with the model's numbers
//! (parameters at their nominal values) at a few pseudo-random configurations (a fixed
//! seed: the same verdict on every build):
//!
//! - **Φ_q**, the loop-closure Jacobian (one row per closure equation), when constraints are
//!   declared: rank below its number of rows at every configuration means redundant
//!   closure equations: their constraint forces cannot be found (from equilibrium, or as
//!   the closure's Lagrange multipliers). Reported first, naming the equations, and which
//!   of them change with no coordinate at all (the joints already keep them satisfied).
//! - **A(q)** of the force analysis otherwise: rank below its number of unknowns at every
//!   configuration is an error naming the unknowns that cannot be found (the columns that
//!   are combinations of the others: exactly the unknowns some null vector of A moves) and
//!   the bodies whose balance equations depend on the others (they move with no input).
//! - **M(q)**, whenever the mechanism asks for dynamics, independently of the two above:
//!   singular at every configuration means joint coordinates dependent in inertia (a
//!   massless free base carrying one body), which the model's per-coordinate rule cannot
//!   see. [`mass`] factors it and names the joints.
//!
//! A matrix singular at only some configurations (a toggle, a dead centre) has full rank at
//! random ones and compiles; there the generated `force_analysis` reports it at run time
//! (`ForceAnalysis::checked` gives `IllConditioned`). Sampling q with the closure
//! unsatisfied is sound: every entry is analytic in q, so a rank lost at random points is
//! lost everywhere, on the closed loop too.
//!
//! The rank of Φ_q and A is Gaussian elimination with complete pivoting on the matrix equilibrated
//! (columns to unit length, then rows to unit largest entry, which makes forces and
//! couples, metres and radians comparable), pivots below [`TOLERANCE`] times the first
//! counted as zero. The matrices are small (6 rows per body at most), and the dependent
//! columns and rows, one rank each, are computed only for an error.

mod mass;

use crate::expand::{self, statics};
use crate::model::statics::{Component, Statics};
use crate::model::value::nominal3;
use crate::model::{Diagnostics, JointKind, Model};
use crate::sym::{Array, InputRef, Node};
use crate::syntax::{self, SpanRange};

/// Configurations tried.
const SAMPLES: usize = 5;
/// A pivot below this fraction of the largest is zero.
const TOLERANCE: f64 = 1e-9;

/// Checks the force analysis and the loop closures of a validated model, and that its mass
/// matrix is regular ([`mass`]); every error at the declaration it concerns.
///
/// # Errors
/// A closure Jacobian, a force analysis or a mass matrix singular at every configuration
/// tried.
pub(crate) fn check(mechanism: &syntax::Mechanism, model: &Model) -> syn::Result<()> {
    let configurations = configurations(model);
    let mut d = Diagnostics::default();
    if let Some(statics) = &model.statics {
        check_statics(mechanism, model, statics, &configurations, &mut d);
    }
    mass::check(mechanism, model, &configurations, &mut d);
    d.take_result()
}

/// The rank checks of the loop closures and of the force analysis.
fn check_statics(
    mechanism: &syntax::Mechanism,
    model: &Model,
    statics: &Statics,
    configurations: &[Vec<f64>],
    d: &mut Diagnostics,
) {
    let (g, transforms, _) = expand::fresh_graph(model);
    let a = statics::balance_matrix(&g, model, statics, &transforms);
    let balance = Sampled::new(
        evaluate(&g, &a, model, configurations),
        statics.unknowns.len(),
        Full::Columns,
    );
    let closure = (statics.closure_count() > 0).then(|| {
        let phi = statics::closure_residual(&g, model, statics, &transforms);
        let jacobian = statics::closure_jacobian(&g, model, &phi);
        Sampled::new(
            evaluate(&g, &jacobian, model, configurations),
            model.nv,
            Full::Rows,
        )
    });
    if let Some(closure) = closure.filter(Sampled::deficient) {
        redundant_closure(mechanism, model, statics, &closure, &balance, d);
    } else if balance.deficient() {
        singular_force_analysis(mechanism, model, statics, &balance, d);
    }
}

/// Which rank is full: the number of columns (A: every unknown found) or of rows (Φ_q:
/// independent equations).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Full {
    Columns,
    Rows,
}

/// A matrix evaluated at every configuration: the ranks of the finite ones and the one of
/// highest rank (the most regular, the one the names are read from).
struct Sampled {
    matrices: Vec<Vec<Vec<f64>>>,
    columns: usize,
    full: Full,
    ranks: Vec<Option<usize>>,
}

impl Sampled {
    fn new(matrices: Vec<Vec<Vec<f64>>>, columns: usize, full: Full) -> Self {
        let ranks = matrices
            .iter()
            .map(|m| {
                m.iter()
                    .flatten()
                    .all(|x| x.is_finite())
                    .then(|| rank(m, columns))
            })
            .collect();
        Sampled {
            matrices,
            columns,
            full,
            ranks,
        }
    }

    fn rows(&self) -> usize {
        self.matrices.first().map_or(0, Vec::len)
    }

    /// The rank that would be full.
    fn wanted(&self) -> usize {
        match self.full {
            Full::Columns => self.columns,
            Full::Rows => self.rows(),
        }
    }

    /// The finite sample of highest rank.
    fn best(&self) -> Option<(usize, usize)> {
        self.ranks
            .iter()
            .enumerate()
            .filter_map(|(k, r)| r.map(|r| (k, r)))
            .max_by_key(|&(k, r)| (r, std::cmp::Reverse(k)))
    }

    /// Whether the rank is below full at every configuration tried (and some evaluation was
    /// finite: a non-finite one decides nothing).
    fn deficient(&self) -> bool {
        self.best().is_some_and(|(_, r)| r < self.wanted())
    }

    /// The columns some null vector moves: each column whose removal leaves the rank as it
    /// is, at the most regular sample.
    fn dependent_columns(&self) -> Vec<usize> {
        let Some((k, r)) = self.best() else {
            return Vec::new();
        };
        let m = &self.matrices[k];
        (0..self.columns)
            .filter(|&j| {
                let without: Vec<Vec<f64>> = m
                    .iter()
                    .map(|row| {
                        row.iter()
                            .enumerate()
                            .filter(|&(c, _)| c != j)
                            .map(|(_, x)| *x)
                            .collect()
                    })
                    .collect();
                rank(&without, self.columns - 1) == r
            })
            .collect()
    }

    /// The rows some left null vector moves: each row whose removal leaves the rank as it
    /// is, at the most regular sample.
    fn dependent_rows(&self) -> Vec<usize> {
        let Some((k, r)) = self.best() else {
            return Vec::new();
        };
        let m = &self.matrices[k];
        (0..m.len())
            .filter(|&i| {
                let without: Vec<Vec<f64>> = m
                    .iter()
                    .enumerate()
                    .filter(|&(c, _)| c != i)
                    .map(|(_, row)| row.clone())
                    .collect();
                rank(&without, self.columns) == r
            })
            .collect()
    }

    /// Whether row `i` is zero at every finite sample (relative to the largest entry).
    fn row_is_zero(&self, i: usize) -> bool {
        self.matrices
            .iter()
            .zip(&self.ranks)
            .filter(|(_, r)| r.is_some())
            .all(|(m, _)| {
                let scale = m.iter().flatten().fold(0.0_f64, |s, x| s.max(x.abs()));
                m[i].iter().all(|x| x.abs() <= TOLERANCE * scale)
            })
    }

    /// The columns with an entry in one of `rows`, at the most regular sample.
    fn columns_touched(&self, rows: &[usize]) -> Vec<usize> {
        let Some((k, _)) = self.best() else {
            return Vec::new();
        };
        let m = &self.matrices[k];
        let scale = m.iter().flatten().fold(0.0_f64, |s, x| s.max(x.abs()));
        (0..self.columns)
            .filter(|&j| rows.iter().any(|&i| m[i][j].abs() > TOLERANCE * scale))
            .collect()
    }
}

/// The numeric rank of an `m × columns` matrix (rows given), equilibrated, by Gaussian
/// elimination with complete pivoting.
fn rank(matrix: &[Vec<f64>], columns: usize) -> usize {
    let mut a: Vec<Vec<f64>> = matrix.to_vec();
    for j in 0..columns {
        let norm = a.iter().map(|row| row[j] * row[j]).sum::<f64>().sqrt();
        if norm > 0.0 {
            a.iter_mut().for_each(|row| row[j] /= norm);
        }
    }
    for row in &mut a {
        let largest = row.iter().fold(0.0_f64, |s, x| s.max(x.abs()));
        if largest > 0.0 {
            row.iter_mut().for_each(|x| *x /= largest);
        }
    }
    let (m, n) = (a.len(), columns);
    let mut largest_pivot = None;
    for k in 0..m.min(n) {
        let (mut pi, mut pj, mut largest) = (k, k, 0.0_f64);
        for (i, row) in a.iter().enumerate().skip(k) {
            for (j, x) in row.iter().enumerate().skip(k) {
                if x.abs() > largest {
                    (pi, pj, largest) = (i, j, x.abs());
                }
            }
        }
        let first = *largest_pivot.get_or_insert(largest);
        if largest == 0.0 || largest <= TOLERANCE * first {
            return k;
        }
        a.swap(k, pi);
        for row in &mut a {
            row.swap(k, pj);
        }
        let pivot_row = a[k].clone();
        for row in a.iter_mut().skip(k + 1) {
            let factor = row[k] / pivot_row[k];
            if factor != 0.0 {
                for (x, p) in row.iter_mut().zip(&pivot_row).skip(k) {
                    *x -= factor * p;
                }
            }
        }
    }
    m.min(n)
}

/// A pseudo-random generator (SplitMix64) with a fixed seed: uniform numbers in [−1, 1).
struct Random(u64);

impl Random {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        // 53 random bits to [0, 1), then to [−1, 1).
        2.0 * ((z >> 11) as f64 / (1u64 << 53) as f64) - 1.0
    }
}

/// [`SAMPLES`] configurations q: revolute angles in (−π, π), prismatic displacements and free
/// positions within the mechanism's size, free orientations unit quaternions.
fn configurations(model: &Model) -> Vec<Vec<f64>> {
    let p: Vec<f64> = model.parameters.iter().map(|p| p.nominal).collect();
    let size = model
        .bodies
        .iter()
        .map(|b| nominal3(&b.joint.translation_in_parent, &p))
        .map(|t| t.iter().map(|x| x * x).sum::<f64>().sqrt())
        .filter(|x| x.is_finite())
        .fold(0.0_f64, f64::max);
    let size = if size > 0.0 { size } else { 1.0 };
    let mut random = Random(0x5eed_0f21);
    (0..SAMPLES)
        .map(|_| {
            let mut q = vec![0.0; model.nq];
            for body in &model.bodies {
                let at = body.joint.idx_q;
                match body.joint.kind {
                    JointKind::Revolute { .. } => q[at] = std::f64::consts::PI * random.next(),
                    JointKind::Prismatic { .. } => q[at] = size * random.next(),
                    JointKind::Free => {
                        for k in 0..3 {
                            q[at + k] = size * random.next();
                        }
                        let quaternion: [f64; 4] = std::array::from_fn(|_| random.next());
                        let norm = quaternion.iter().map(|x| x * x).sum::<f64>().sqrt();
                        for k in 0..4 {
                            q[at + 3 + k] = if norm > 1e-3 {
                                quaternion[k] / norm
                            } else {
                                [0.0, 0.0, 0.0, 1.0][k]
                            };
                        }
                    }
                }
            }
            q
        })
        .collect()
}

/// Evaluates `rows` (a matrix of nodes of `graph`) at each configuration: q from it,
/// parameters nominal, every other input zero (neither matrix reads them).
fn evaluate(
    graph: &crate::sym::Graph,
    rows: &[Vec<Node>],
    model: &Model,
    configurations: &[Vec<f64>],
) -> Vec<Vec<Vec<f64>>> {
    let flat: Vec<Node> = rows.iter().flatten().copied().collect();
    let width = rows.first().map_or(0, Vec::len);
    configurations
        .iter()
        .map(|q| {
            let input = |r: InputRef| match r.array {
                Array::Q => q[r.index as usize],
                Array::P => model.parameters[r.index as usize].nominal,
                _ => 0.0,
            };
            let values = graph.eval(input, &flat);
            if width == 0 {
                vec![Vec::new(); rows.len()]
            } else {
                values.chunks(width).map(<[f64]>::to_vec).collect()
            }
        })
        .collect()
}

/// `a`, `b` and `c`, each in backticks.
fn quoted<'a>(names: impl IntoIterator<Item = &'a str>) -> String {
    let names: Vec<String> = names.into_iter().map(|n| format!("`{n}`")).collect();
    match names.as_slice() {
        [] => String::new(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
    }
}

/// `1 equation`, `2 equations`.
fn counted(n: usize, word: &str) -> String {
    if n == 1 {
        format!("{n} {word}")
    } else {
        format!("{n} {word}s")
    }
}

/// The span of the declared constraint named `name`, if one is.
fn constraint_span(mechanism: &syntax::Mechanism, name: &str) -> Option<SpanRange> {
    mechanism
        .constraints
        .iter()
        .find(|c| c.name.text == name)
        .map(|c| SpanRange::from(c.name.span))
}

/// The unknowns the force analysis cannot find (`None` when it can find them all).
fn undetermined(balance: &Sampled) -> Option<Vec<usize>> {
    balance.deficient().then(|| balance.dependent_columns())
}

/// Error: closure equations redundant at every configuration.
fn redundant_closure(
    mechanism: &syntax::Mechanism,
    model: &Model,
    statics: &Statics,
    closure: &Sampled,
    balance: &Sampled,
    d: &mut Diagnostics,
) {
    let equations: Vec<&crate::model::statics::Unknown> = statics.closure_components().collect();
    let redundant = closure.dependent_rows();
    let rank = closure.best().map_or(0, |(_, r)| r);
    let name = |i: usize| equations[i].name.as_str();
    let (still, moving): (Vec<usize>, Vec<usize>) =
        redundant.iter().partition(|&&i| closure.row_is_zero(i));
    let mut why = Vec::new();
    if !still.is_empty() {
        let (verb, it) = if still.len() == 1 {
            ("changes", "it")
        } else {
            ("change", "them")
        };
        why.push(format!(
            "{} {verb} with no coordinate (the joints already keep {it} satisfied)",
            quoted(still.iter().map(|&i| name(i)))
        ));
    }
    if !moving.is_empty() {
        let joints = coordinate_joints(model, closure.columns_touched(&moving));
        why.push(format!(
            "{} depend on one another through the coordinates of {}",
            quoted(moving.iter().map(|&i| name(i))),
            quoted(joints)
        ));
    }
    let forces = match undetermined(balance) {
        Some(columns) if !columns.is_empty() => {
            let moving: Vec<&str> = moving_bodies(statics, balance)
                .into_iter()
                .map(|(b, _)| model.bodies[b].name.as_str())
                .collect();
            let moving = if moving.is_empty() {
                String::new()
            } else {
                format!(", and {} can move with no input", quoted(moving))
            };
            format!(
                " (the force analysis cannot find {}{moving})",
                quoted(columns.iter().map(|&j| statics.unknowns[j].name.as_str()))
            )
        }
        _ => String::new(),
    };
    let span = redundant
        .iter()
        .find_map(|&i| {
            let connection = &statics.connections[equations[i].connection];
            constraint_span(mechanism, &connection.name)
        })
        .unwrap_or_else(|| SpanRange::from(mechanism.name.span()));
    let these = if redundant.len() == 1 {
        "the constraint equation"
    } else {
        "the constraint equations"
    };
    d.error(
        span,
        format!(
            "{these} {} {} redundant at every configuration: the loop-closure Jacobian Φ_q has \
             rank at most {rank} for its {} in the {SAMPLES} configurations tried; {}. \
             Equilibrium cannot find {}{forces}: remove the constraint, or release the \
             components that the joints or the other constraints already hold",
            quoted(redundant.iter().map(|&i| name(i))),
            if redundant.len() == 1 { "is" } else { "are" },
            counted(equations.len(), "equation"),
            why.join("; "),
            if redundant.len() == 1 {
                "its reaction"
            } else {
                "their reactions"
            },
        ),
    );
}

/// The joints of the velocity coordinates `coordinates`, each named once, in the order met.
fn coordinate_joints(model: &Model, coordinates: impl IntoIterator<Item = usize>) -> Vec<&str> {
    let mut names = Vec::new();
    for name in coordinates
        .into_iter()
        .filter_map(|j| coordinate_joint(model, j))
    {
        if !names.contains(&name) {
            names.push(name);
        }
    }
    names
}

/// The joint whose coordinate is velocity coordinate `j`.
fn coordinate_joint(model: &Model, j: usize) -> Option<&str> {
    model
        .bodies
        .iter()
        .find(|b| (b.joint.idx_v..b.joint.idx_v + b.joint.kind.dofs()).contains(&j))
        .map(|b| b.joint.name.as_str())
}

/// The bodies whose balance equations depend on the others (they can move with no input),
/// each with those equations (`force x`, `moment z`).
fn moving_bodies(statics: &Statics, balance: &Sampled) -> Vec<(usize, Vec<&'static str>)> {
    let rows = statics.rows_per_body();
    let mut bodies: Vec<(usize, Vec<&str>)> = Vec::new();
    for i in balance.dependent_rows() {
        let (body, (kind, axis)) = (i / rows.len(), rows[i % rows.len()]);
        let label = match (kind, axis) {
            (Component::Force, 0) => "force x",
            (Component::Force, 1) => "force y",
            (Component::Force, _) => "force z",
            (Component::Couple, 0) => "moment x",
            (Component::Couple, 1) => "moment y",
            (Component::Couple, _) => "moment z",
        };
        match bodies.iter_mut().find(|(b, _)| *b == body) {
            Some((_, labels)) => labels.push(label),
            None => bodies.push((body, vec![label])),
        }
    }
    bodies
}

/// Error: the force analysis singular at every configuration.
fn singular_force_analysis(
    mechanism: &syntax::Mechanism,
    model: &Model,
    statics: &Statics,
    balance: &Sampled,
    d: &mut Diagnostics,
) {
    let columns = balance.dependent_columns();
    let rank = balance.best().map_or(0, |(_, r)| r);
    let bodies = moving_bodies(statics, balance);
    let moving = if bodies.is_empty() {
        String::new()
    } else {
        let list: Vec<String> = bodies
            .iter()
            .map(|(b, labels)| format!("`{}` ({})", model.bodies[*b].name, labels.join(", ")))
            .collect();
        let pronoun = if bodies.len() == 1 { "it" } else { "they" };
        format!(
            "; the balance equations of {} depend on the others: {pronoun} can move with no \
             input",
            list.join(", ")
        )
    };
    let involved = |j: &usize| &statics.connections[statics.unknowns[*j].connection];
    let span = columns
        .iter()
        .filter(|j| involved(j).closes_loop)
        .find_map(|j| constraint_span(mechanism, &involved(j).name))
        .or_else(|| mechanism.analysis.map(|(_, span)| SpanRange::from(span)))
        .or_else(|| {
            mechanism
                .outputs
                .iter()
                .flatten()
                .find(|n| n.text == "force_analysis")
                .map(|n| SpanRange::from(n.span))
        })
        .unwrap_or_else(|| SpanRange::from(mechanism.name.span()));
    d.error(
        span,
        format!(
            "the force analysis is singular at every configuration: its balance equations \
             A(q) x = b have rank at most {rank} for {} in the {SAMPLES} configurations \
             tried, so the unknowns {} cannot be found: the equations do not determine them \
             at any configuration{moving}. A reaction along the line of another, or one through \
             the pivot it should brace, adds an unknown and no equation: move or turn the \
             support, or drive another joint",
            counted(statics.unknowns.len(), "unknown"),
            quoted(columns.iter().map(|&j| statics.unknowns[j].name.as_str())),
        ),
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use quote::quote;

    fn checked(tokens: proc_macro2::TokenStream) -> Result<(), String> {
        let mechanism: syntax::Mechanism = syn::parse2(tokens).expect("parses");
        let model = crate::model::lower(&mechanism).map_err(|e| format!("lower: {e}"))?;
        check(&mechanism, &model).map_err(|e| e.to_string())
    }

    #[test]
    fn rank_of_small_matrices() {
        let m = |rows: &[&[f64]]| rows.iter().map(|r| r.to_vec()).collect::<Vec<_>>();
        assert_eq!(rank(&m(&[&[1.0, 0.0], &[0.0, 1.0]]), 2), 2);
        assert_eq!(rank(&m(&[&[1.0, 2.0], &[2.0, 4.0]]), 2), 1);
        assert_eq!(rank(&m(&[&[0.0, 0.0], &[0.0, 0.0]]), 2), 0);
        // Badly scaled but regular: forces in newtons, couples in newton-millimetres.
        assert_eq!(rank(&m(&[&[1e-6, 0.0], &[1.0, 1e6]]), 2), 2);
        // Singular up to rounding.
        let t = 0.3_f64;
        let rows = m(&[&[t.cos(), t.sin()], &[3.0 * t.cos(), 3.0 * t.sin()]]);
        assert_eq!(rank(&rows, 2), 1);
        assert_eq!(rank(&m(&[&[1.0, 2.0, 3.0]]), 3), 1);
    }

    /// The second example: a roller placed on the pin it should brace.
    #[test]
    fn a_support_on_the_pivot_is_an_error() {
        let e = checked(quote! {
            pub struct OnPivot;
            gravity: [0.0, -9.81, 0.0];
            body beam { mass: 2.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
            joint A: revolute(ground -> beam) { axis: z }
            constraint B: roller(ground at [0.0, 0.0, 0.0], beam at [0.0, 0.0, 0.0]) { normal: x };
        })
        .expect_err("singular");
        assert!(
            e.contains("the constraint equation `B.normal` is redundant"),
            "{e}"
        );
        assert!(e.contains("`B.normal` changes with no coordinate"), "{e}");
        assert!(
            e.contains("cannot find `A.x` and `B.normal`, and `beam` can move"),
            "{e}"
        );
    }

    /// A support at the tip of a second link, on its hinge: the closure is regular, the
    /// force analysis is not (the second link turns freely).
    #[test]
    fn a_singular_force_analysis_names_its_unknowns() {
        let e = checked(quote! {
            pub struct Prop;
            gravity: [0.0, -9.81, 0.0];
            body arm { mass: 1.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
            body flap { mass: 0.5, com: [0.25, 0.0, 0.0], shape: rod(length: 0.5, axis: x) }
            joint shoulder: revolute(ground -> arm) { axis: z, driven: true }
            joint hinge: revolute(arm -> flap) { axis: z, at: [1.0, 0.0, 0.0] }
            constraint prop: roller(ground at [1.0, 0.0, 0.0], flap at [0.0, 0.0, 0.0]) { normal: y };
        })
        .expect_err("singular");
        assert!(e.starts_with("the force analysis is singular"), "{e}");
        assert!(
            e.contains("the unknowns `shoulder.y`, `shoulder.torque`, `hinge.x`, `hinge.y` and `prop.normal` cannot be found"),
            "{e}"
        );
        assert!(e.contains("`flap` (moment z)"), "{e}");
    }

    /// Singular at special configurations only (a dead centre; a roller whose line passes
    /// the pin at one angle): accepted.
    #[test]
    fn singular_at_special_configurations_only_compiles() {
        checked(quote! {
            pub struct SupportedBeam;
            gravity: none;
            body beam { mass: 4.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
            joint A: revolute(ground -> beam) { axis: z }
            constraint B: roller(ground at [1.0, 0.0, 0.0], beam at [1.0, 0.0, 0.0]) { normal: y };
        })
        .expect("regular at random configurations");
        checked(quote! {
            pub struct FourBarRockerDriven;
            gravity: [0.0, -9.81, 0.0];
            body crank { mass: 0.5, com: [0.05, 0.0, 0.0], shape: rod(length: 0.1, axis: x) }
            body coupler { mass: 1.2, com: [0.175, 0.0, 0.0], shape: rod(length: 0.35, axis: x) }
            body rocker { mass: 1.0, com: [0.15, 0.0, 0.0], shape: rod(length: 0.3, axis: x) }
            joint O2: revolute(ground -> crank) { axis: z }
            joint A: revolute(crank -> coupler) { at: [0.1, 0.0, 0.0], axis: z }
            joint O4: revolute(ground -> rocker) { at: [0.3, 0.0, 0.0], axis: z, driven: true }
            constraint B: pin(coupler at [0.35, 0.0, 0.0], rocker at [0.3, 0.0, 0.0]);
        })
        .expect("regular at random configurations");
    }

    /// Two constraints closing the same loop at one point: the roller repeats the pin's x.
    #[test]
    fn redundant_closure_equations_are_named() {
        let e = checked(quote! {
            pub struct TwiceClosed;
            gravity: [0.0, -9.81, 0.0];
            body crank { mass: 0.5, com: [0.05, 0.0, 0.0], shape: rod(length: 0.1, axis: x) }
            body coupler { mass: 1.2, com: [0.175, 0.0, 0.0], shape: rod(length: 0.35, axis: x) }
            body rocker { mass: 1.0, com: [0.15, 0.0, 0.0], shape: rod(length: 0.3, axis: x) }
            joint O2: revolute(ground -> crank) { axis: z }
            joint A: revolute(crank -> coupler) { at: [0.1, 0.0, 0.0], axis: z }
            joint O4: revolute(ground -> rocker) { at: [0.3, 0.0, 0.0], axis: z }
            constraint B: pin(coupler at [0.35, 0.0, 0.0], rocker at [0.3, 0.0, 0.0]);
            constraint C: roller(coupler at [0.35, 0.0, 0.0], rocker at [0.3, 0.0, 0.0]) { normal: x };
        })
        .expect_err("redundant");
        assert!(
            e.contains("the constraint equations `B.x` and `C.normal` are redundant"),
            "{e}"
        );
        assert!(
            e.contains("depend on one another through the coordinates of `O2`, `A` and `O4`"),
            "{e}"
        );
    }
}
