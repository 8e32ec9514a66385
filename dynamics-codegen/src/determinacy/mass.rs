//! M(q) positive definite, at compile time: the joint coordinates independent in inertia.
//!
//! The model's rule `coordinate_has_inertia` checks each coordinate alone: its motion moves
//! some inertia. It cannot see coordinates that are dependent together: a massless body on
//! a free joint carrying one revolute body has 7 coordinates, each moving the child, but the
//! child alone has 6 inertial degrees of freedom (turning the base and the joint oppositely
//! moves no mass); three revolute joints on massless links ending at a point mass off their
//! common point, or two coaxial revolute joints whose first body has no inertia about the
//! axis, likewise. M(q) is then singular at every configuration and forward dynamics
//! divides by zero.
//!
//! Here M(q) (armature included) is built by the compiler's own composite-rigid-body
//! expansion ([`expand::crba::mass_matrix`]) and evaluated with the parameters at their
//! nominal values at the stage's seeded configurations (the same as the rank checks of the
//! force analysis). It is equilibrated by its diagonal (S M S, S = diag(M_ii^-1/2), so
//! that a light wrist and a heavy base are alike) and factored as LDLᵀ with symmetric
//! (diagonal) pivoting, the largest remaining diagonal first; a pivot below
//! [`TOLERANCE`] ends the factorization, and its index is the rank. Full rank at any one
//! finite configuration and the mechanism compiles: a matrix singular at special
//! configurations only (a gimbal lock) has full rank at random ones; an analytic matrix that
//! loses rank at random configurations loses it everywhere. Singular at every finite one
//! is an error at the first joint some null vector of M moves (the trailing block's null
//! vectors, [−L₁₁⁻ᵀ L₂₁ᵀ e; e], at the sample of highest rank), naming those joints and
//! the massless bodies they move.
//!
//! Only when the mechanism asks for dynamics and has coordinates (as the per-joint rule),
//! and not when that rule already failed: its errors end `model::lower` before this stage,
//! so a coordinate without inertia is reported once. The work is bounded: M's graph has
//! O(nv²) nodes and the factorization costs nv³/3 per configuration, so above
//! [`MAX_COORDINATES`] coordinates (a 1000-joint chain) the check is skipped, and it stops at
//! the first configuration where M is regular (the first, for a well-posed mechanism). A
//! graph past the node budget decides nothing either. It only reads the model: no generated
//! code changes.

use super::{coordinate_joints, evaluate, quoted, SAMPLES};
use crate::expand::{self, crba};
use crate::model::{Diagnostics, Model};
use crate::syntax::{self, SpanRange};

/// A pivot of the equilibrated M (whose diagonal is 1) below this is zero.
const TOLERANCE: f64 = 1e-10;

/// Above this many velocity coordinates the check is skipped: M's expansion grows as nv²
/// nodes and its factorization as nv³. At the bound, a spatial chain of 200 revolute joints,
/// the check takes 0.1 s and 35 MB in the optimised command-line compiler (0.3 s and 170 MB
/// at 300 joints); no robot comes near it, and a 1000-joint chain costs nothing more.
const MAX_COORDINATES: usize = 200;

/// A component of a null vector below this fraction of its largest is not a motion.
const MOVES: f64 = 1e-6;

/// Checks that M(q) is regular at some configuration of `configurations`; the error at the
/// first joint whose coordinate a null vector moves.
pub(super) fn check(
    mechanism: &syntax::Mechanism,
    model: &Model,
    configurations: &[Vec<f64>],
    d: &mut Diagnostics,
) {
    if model.nv == 0 || model.nv > MAX_COORDINATES || !model.outputs.any_dynamics() {
        return;
    }
    let (g, transforms, inertias) = expand::fresh_graph(model);
    let m = crba::mass_matrix(&g, model, &transforms, &inertias);
    if g.is_exhausted() {
        return;
    }
    let mut most_regular: Option<Factored> = None;
    for q in configurations {
        let Some(values) = evaluate(&g, &m, model, std::slice::from_ref(q)).pop() else {
            continue;
        };
        if !values.iter().flatten().all(|x| x.is_finite()) {
            continue;
        }
        let factored = Factored::new(values);
        if factored.rank == model.nv {
            return;
        }
        if most_regular.as_ref().is_none_or(|f| factored.rank > f.rank) {
            most_regular = Some(factored);
        }
    }
    if let Some(factored) = most_regular {
        singular(mechanism, model, &factored, d);
    }
}

/// M at one configuration, equilibrated and factored as far as its rank.
struct Factored {
    /// The numeric rank: the pivots above [`TOLERANCE`].
    rank: usize,
    /// A basis of the null space (as many vectors as nv − rank), in the equilibrated
    /// coordinates, in the coordinates' order.
    null: Vec<Vec<f64>>,
}

impl Factored {
    /// P S M S Pᵀ = L D Lᵀ, the outer-product form with the largest remaining diagonal as
    /// pivot, L below the diagonal of the working matrix.
    fn new(mut a: Vec<Vec<f64>>) -> Self {
        let n = a.len();
        // S = diag(M_ii^-1/2); a coordinate with no inertia (M_ii ≤ 0) keeps its row, whose
        // zero pivot then counts.
        let s: Vec<f64> = (0..n)
            .map(|i| {
                if a[i][i] > 0.0 {
                    a[i][i].sqrt().recip()
                } else {
                    1.0
                }
            })
            .collect();
        for (i, row) in a.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x *= s[i] * s[j];
            }
        }
        let mut order: Vec<usize> = (0..n).collect();
        let mut rank = n;
        for k in 0..n {
            let (pivot_at, pivot) =
                (k..n)
                    .map(|i| (i, a[i][i]))
                    .fold(
                        (k, f64::NEG_INFINITY),
                        |best, c| {
                            if c.1 > best.1 {
                                c
                            } else {
                                best
                            }
                        },
                    );
            if pivot.is_nan() || pivot <= TOLERANCE {
                rank = k;
                break;
            }
            a.swap(k, pivot_at);
            for row in &mut a {
                row.swap(k, pivot_at);
            }
            order.swap(k, pivot_at);
            let l: Vec<f64> = (k + 1..n).map(|i| a[i][k] / pivot).collect();
            for (i, li) in (k + 1..n).zip(&l) {
                for j in k + 1..n {
                    a[i][j] -= li * a[k][j];
                }
            }
            for (i, li) in (k + 1..n).zip(l) {
                a[i][k] = li;
            }
        }
        // Each trailing index t: x_t = 1, the other trailing entries 0, and L₁₁ᵀ x₁ =
        // −L₂₁ᵀ e_t by back substitution (L₁₁ unit lower triangular).
        let null = (rank..n)
            .map(|t| {
                let mut x = vec![0.0; n];
                x[t] = 1.0;
                for i in (0..rank).rev() {
                    let below: f64 = (i + 1..rank).map(|j| a[j][i] * x[j]).sum();
                    x[i] = -a[t][i] - below;
                }
                let mut unpermuted = vec![0.0; n];
                for (k, &coordinate) in order.iter().enumerate() {
                    unpermuted[coordinate] = x[k];
                }
                unpermuted
            })
            .collect();
        Factored { rank, null }
    }

    /// The coordinates some null vector moves, in order.
    fn moved(&self) -> Vec<usize> {
        let n = self.null.first().map_or(0, Vec::len);
        (0..n)
            .filter(|&i| {
                self.null.iter().any(|x| {
                    let largest = x.iter().fold(0.0_f64, |s, v| s.max(v.abs()));
                    x[i].abs() > MOVES * largest
                })
            })
            .collect()
    }
}

/// Error: M(q) singular at every configuration tried.
fn singular(
    mechanism: &syntax::Mechanism,
    model: &Model,
    factored: &Factored,
    d: &mut Diagnostics,
) {
    let joints = coordinate_joints(model, factored.moved());
    let p: Vec<f64> = model.parameters.iter().map(|p| p.nominal).collect();
    let massless: Vec<&str> = model
        .bodies
        .iter()
        .filter(|b| joints.contains(&b.joint.name.as_str()))
        .filter(|b| {
            b.parts
                .iter()
                .map(|part| part.mass.nominal(&p))
                .sum::<f64>()
                == 0.0
        })
        .map(|b| b.name.as_str())
        .collect();
    let span = joints
        .iter()
        .find_map(|name| mechanism.joints.iter().find(|j| j.name.text == *name))
        .map_or_else(
            || SpanRange::from(mechanism.name.span()),
            |j| SpanRange::from(j.name.span),
        );
    let which = if joints.len() == 1 {
        format!(
            "the coordinates of joint {}",
            quoted(joints.iter().copied())
        )
    } else {
        format!(
            "the coordinates of joints {}",
            quoted(joints.iter().copied())
        )
    };
    let massless = match massless.as_slice() {
        [] => String::new(),
        [one] => format!("; the body `{one}` is massless"),
        many => format!("; the bodies {} are massless", quoted(many.iter().copied())),
    };
    d.error(
        span,
        format!(
            "the mass matrix M(q) is singular at every configuration: {which} are not \
             independent in inertia, some motion of them together moves no mass and no \
             inertia (M has rank at most {} for {} coordinates in the {SAMPLES} \
             configurations tried){massless}, so forward dynamics cannot be solved. Give the \
             bodies these joints move mass and inertia (enough that every such motion moves \
             some), or make one of the joints fixed",
            factored.rank, model.nv,
        ),
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use quote::quote;

    /// Every error of the pipeline up to this check, `lower:` before those of the model.
    fn checked(tokens: proc_macro2::TokenStream) -> Result<(), Vec<String>> {
        let mechanism: syntax::Mechanism = syn::parse2(tokens).expect("parses");
        let all = |e: syn::Error| e.into_iter().map(|e| e.to_string()).collect::<Vec<_>>();
        let model = crate::model::lower(&mechanism).map_err(|e| {
            all(e)
                .into_iter()
                .map(|m| format!("lower: {m}"))
                .collect::<Vec<_>>()
        })?;
        super::super::check(&mechanism, &model).map_err(all)
    }

    /// The fuzzer's finding: each of the 7 coordinates moves the arm, but a massless body on
    /// a free joint and one revolute child have 7 coordinates for the child's 6 inertial
    /// degrees of freedom.
    #[test]
    fn a_massless_free_base_carrying_one_body_is_an_error() {
        let e = checked(quote! {
            pub struct FloatingMassless;
            body base { mass: 0.0, shape: point }
            body arm { mass: 1.0, com: [0.5, 0.0, 0.0], shape: box(size: [1.0, 0.1, 0.1]) }
            joint float: free(ground -> base);
            joint hinge: revolute(base -> arm) { axis: z, at: [0.1, 0.2, 0.0] }
        })
        .expect_err("singular");
        assert_eq!(e.len(), 1, "{e:?}");
        assert!(
            e[0].starts_with(
                "the mass matrix M(q) is singular at every configuration: the coordinates of \
                 joints `float` and `hinge` are not independent in inertia"
            ),
            "{e:?}"
        );
        assert!(
            e[0].contains("M has rank at most 6 for 7 coordinates"),
            "{e:?}"
        );
        assert!(e[0].contains("the body `base` is massless"), "{e:?}");
        // Armature on the hinge makes M regular: the check sees it.
        checked(quote! {
            pub struct FloatingMassless;
            body base { mass: 0.0, shape: point }
            body arm { mass: 1.0, com: [0.5, 0.0, 0.0], shape: box(size: [1.0, 0.1, 0.1]) }
            joint float: free(ground -> base);
            joint hinge: revolute(base -> arm) { axis: z, at: [0.1, 0.2, 0.0], armature: 0.01 }
        })
        .expect("regular with armature");
    }

    /// Only the joints some null vector moves are named: a regular branch beside is not.
    #[test]
    fn only_the_dependent_joints_are_named() {
        let e = checked(quote! {
            pub struct Branches;
            body hub { mass: 2.0, shape: point }
            body wheel { mass: 1.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
            body other { mass: 1.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
            joint a: revolute(ground -> hub) { axis: z }
            joint b: revolute(hub -> wheel) { axis: z }
            joint c: revolute(ground -> other) { axis: y }
        })
        .expect_err("coaxial joints on a hub with no inertia about the axis");
        assert!(e[0].contains("joints `a` and `b` are not"), "{e:?}");
        assert!(e[0].contains("rank at most 2 for 3 coordinates"), "{e:?}");
    }

    /// A planar two-link arm, the first link massless, the mass at the tip: M = m Jᵀ J is
    /// singular where the arm is stretched or folded (q2 = 0, π) only, so it compiles.
    #[test]
    fn singular_at_special_configurations_only_compiles() {
        checked(quote! {
            pub struct TipMass;
            gravity: [0.0, -9.81, 0.0];
            body upper { mass: 0.0, shape: point }
            body lower { mass: 1.0, com: [1.0, 0.0, 0.0], shape: point }
            joint shoulder: revolute(ground -> upper) { axis: z }
            joint elbow: revolute(upper -> lower) { axis: z, at: [1.0, 0.0, 0.0] }
        })
        .expect("regular at random configurations");
    }

    /// A coordinate without inertia is the model's error alone: not a second time here.
    #[test]
    fn a_coordinate_without_inertia_is_reported_once() {
        let e = checked(quote! {
            pub struct MasslessLeaf;
            body arm { mass: 1.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
            body tip { mass: 0.0, shape: point }
            joint shoulder: revolute(ground -> arm) { axis: z }
            joint wrist: revolute(arm -> tip) { axis: z, at: [1.0, 0.0, 0.0] }
        })
        .expect_err("no inertia");
        assert_eq!(e.len(), 1, "{e:?}");
        assert!(
            e[0].starts_with("lower: the coordinate of joint `wrist` has no inertia"),
            "{e:?}"
        );
    }

    /// Without dynamics outputs M is not needed, and not judged (as the per-joint rule).
    #[test]
    fn kinematics_only_is_not_judged() {
        checked(quote! {
            pub struct FloatingMassless;
            outputs: [energy];
            body base { mass: 0.0, shape: point }
            body arm { mass: 1.0, com: [0.5, 0.0, 0.0], shape: box(size: [1.0, 0.1, 0.1]) }
            joint float: free(ground -> base);
            joint hinge: revolute(base -> arm) { axis: z }
        })
        .expect("no dynamics asked");
    }

    fn factored(rows: &[&[f64]]) -> Factored {
        Factored::new(rows.iter().map(|r| r.to_vec()).collect())
    }

    #[test]
    fn rank_and_null_vectors_of_small_matrices() {
        assert_eq!(factored(&[&[2.0, 0.0], &[0.0, 1e-9]]).rank, 2);
        let f = factored(&[&[1.0, 2.0], &[2.0, 4.0]]);
        assert_eq!(f.rank, 1);
        // (2, −1) up to scale in M's coordinates, (1, −1) equilibrated (S = diag(1, 1/2)).
        let x = &f.null[0];
        assert!((x[0] + x[1]).abs() < 1e-12 && x[0] != 0.0, "{x:?}");
        assert_eq!(f.moved(), [0, 1]);
        // A coordinate with no inertia at all, beside a regular one.
        let f = factored(&[&[0.0, 0.0, 0.0], &[0.0, 3.0, 1.0], &[0.0, 1.0, 3.0]]);
        assert_eq!((f.rank, f.moved()), (2, vec![0]));
        // Badly scaled but regular: a heavy base and a light wrist.
        assert_eq!(factored(&[&[1e6, 1.0], &[1.0, 1e-5]]).rank, 2);
    }
}
