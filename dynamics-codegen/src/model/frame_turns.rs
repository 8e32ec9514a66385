//! Body frames turned about their joint axes, where that makes the placements sparser.
//!
//! A revolute or prismatic joint moves its body by Rot(s, q) (or a slide along s) after the
//! placement R_p. Turning the body's frame about s by a constant angle φ changes nothing of
//! the motion, because turns about the same axis commute:
//!
//! ```text
//! R_p Rot(s, q) Rot(s, φ) = (R_p Rot(s, φ)) Rot(s, q)
//! ```
//!
//! so the tree may use the turned frame B' (x_B = Rot(s, φ) x_B') with the placement
//! R_p Rot(s, φ), while everything fixed on the body (its mass centre c, I_G, its children's
//! placements S, welded parts, load points, frames) is re-expressed as Rot(s, φ)ᵀ (·). A
//! URDF that turns a link by 150° about its joint's axis and its child back by −150°
//! (ANYmal's hips) then places both with zeros and ones, which fold in the expansion, as an
//! axis-aligned description would.
//!
//! The angle is chosen by counting entries: a placement entry costs 2 when general, 1 when
//! ±1 and 0 when zero; a translation entry (a child's origin, the body's first moment
//! h = m c) 1 when nonzero; the body's I_P 1 per nonzero diagonal entry and 2 per nonzero
//! pair off it. Candidates are the angles that zero one entry of the joint's placement, of
//! h or of a child's placement or origin (each entry is a + b cos φ + c sin φ); a child
//! that turns too is scored at its own best angle. The turn is taken only when it lowers
//! the count, so a description that is already sparse keeps its frames.

use super::linear::{self, Matrix3, Vector3, IDENTITY};
use super::value::snapped;

/// A moving joint below a body (directly, or through bodies welded to it), as the body's
/// frame sees it before any turn.
pub(crate) struct ChildPlacement {
    /// The child joint frame's rotation in the body frame (rows).
    pub rotation_in_body: Matrix3,
    /// Its origin in the body frame (at the parameters' nominal values).
    pub origin_in_body: [f64; 3],
    /// The child joint's axis when it may turn too (revolute or prismatic).
    pub axis: Option<[f64; 3]>,
}

/// The body's inertia about its origin, summed over the declared bodies it carries, as the
/// body's frame sees it before any turn (at the parameters' nominal values).
pub(crate) struct MassProperties {
    /// h = Σ m c.
    pub first_moment: [f64; 3],
    /// I_P = Σ (I_G + m (|c|² 1 − c cᵀ)).
    pub inertia_about_origin: Matrix3,
}

/// Rot(s, φ) for the best angle φ ≠ 0, or `None` when no turn lowers the cost of the
/// placement `rotation_in_parent`, the children's placements and the body's inertia.
pub(crate) fn best_turn(
    axis: [f64; 3],
    rotation_in_parent: &Matrix3,
    children: &[ChildPlacement],
    body: &MassProperties,
) -> Option<Matrix3> {
    let cost = |turn: &Matrix3| -> usize {
        let back = linear::transpose(turn);
        let inertia = linear::mul(&back, &linear::mul(&body.inertia_about_origin, turn));
        let own = entries_cost(&snapped(&linear::mul(rotation_in_parent, turn)))
            + translation_cost(&linear::mul_vector(&back, &body.first_moment))
            + inertia_cost(&inertia);
        let below: usize = children
            .iter()
            .map(|c| {
                let rotation = linear::mul(&back, &c.rotation_in_body);
                let origin = linear::mul_vector(&back, &c.origin_in_body);
                child_rotation_cost(&rotation, c.axis) + translation_cost(&origin)
            })
            .sum();
        own + below
    };
    let mut candidates = placement_angles(axis, rotation_in_parent);
    candidates.extend(vector_angles(axis, &body.first_moment));
    for c in children {
        candidates.extend(child_angles(axis, &c.rotation_in_body));
        candidates.extend(vector_angles(axis, &c.origin_in_body));
    }
    let mut best = (cost(&IDENTITY), None);
    for angle in distinct(candidates) {
        let turn = rotation_about(axis, angle);
        let c = cost(&turn);
        if c < best.0 {
            best = (c, Some(turn));
        }
    }
    best.1
}

/// The half turn H about e_(k+1) for an axis s = −e_k along a coordinate axis the negative
/// way, `None` for any other axis. H is its own inverse and H s = e_k, so
///
/// ```text
/// R_p Rot(s, q) H = (R_p H) Rot(e_k, q)        (H Rot(e_k, q) Hᵀ = Rot(H e_k, q) = Rot(s, q))
/// ```
///
/// and a prismatic joint's slide R_p s q = (R_p H) e_k q: the body may use the frame B'
/// (x_B = H x_B') with the placement R_p H and the axis e_k, everything on it re-expressed
/// by Hᵀ, and the coordinate is the same. H only changes signs, so no entry that was zero
/// becomes nonzero. Limbs that are mirror images (ANYmal's legs turn about +x and −x) then
/// have the same joints and are packed side by side (`expand::slots`).
pub(crate) fn axis_half_turn(axis: [f64; 3]) -> Option<Matrix3> {
    let mut nonzero = axis.iter().enumerate().filter(|(_, a)| **a != 0.0);
    let (k, &along) = nonzero.next()?;
    if nonzero.next().is_some() || along > 0.0 {
        return None;
    }
    let mut half_turn = [[0.0; 3]; 3];
    for (i, row) in half_turn.iter_mut().enumerate() {
        row[i] = if i == (k + 1) % 3 { 1.0 } else { -1.0 };
    }
    Some(half_turn)
}

/// Rot(s, φ) for a unit axis s: the explicit matrix for a coordinate axis (so that the
/// entry on s is exactly 1), Rodrigues' formula otherwise. The same rotation as
/// `linear::rotation_from_axis_angle`, rounded differently about a general axis; the turns
/// were chosen, and the generated code's constants computed, with this one.
fn rotation_about(axis: Vector3, angle: f64) -> Matrix3 {
    let (sin, cos) = angle.sin_cos();
    if axis.iter().filter(|a| **a != 0.0).count() == 1 {
        let k = axis.iter().position(|a| *a != 0.0).unwrap_or(2);
        let s = sin * axis[k].signum();
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        let mut m = IDENTITY;
        m[i][i] = cos;
        m[j][j] = cos;
        m[i][j] = -s;
        m[j][i] = s;
        return m;
    }
    let [x, y, z] = axis;
    let c1 = 1.0 - cos;
    [
        [cos + x * x * c1, x * y * c1 - z * sin, x * z * c1 + y * sin],
        [y * x * c1 + z * sin, cos + y * y * c1, y * z * c1 - x * sin],
        [z * x * c1 - y * sin, z * y * c1 + x * sin, cos + z * z * c1],
    ]
}

/// The cost of a child's placement, at the child's own best turn when it may turn.
fn child_rotation_cost(rotation: &Matrix3, axis: Option<[f64; 3]>) -> usize {
    let fixed = entries_cost(&snapped(rotation));
    let Some(axis) = axis else {
        return fixed;
    };
    distinct(placement_angles(axis, rotation))
        .into_iter()
        .map(|angle| {
            let turn = rotation_about(axis, angle);
            entries_cost(&snapped(&linear::mul(rotation, &turn)))
        })
        .fold(fixed, usize::min)
}

/// 2 per general entry, 1 per ±1, 0 per zero.
fn entries_cost(m: &Matrix3) -> usize {
    m.iter()
        .flatten()
        .map(|&x| match x {
            0.0 => 0,
            1.0 | -1.0 => 1,
            _ => 2,
        })
        .sum()
}

/// 1 per entry that is not zero (relative to the largest, as `value::snapped_vector`
/// drops them).
fn translation_cost(t: &[f64; 3]) -> usize {
    let scale = t.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    t.iter()
        .filter(|x| x.abs() >= 1e-14 * scale && **x != 0.0)
        .count()
}

/// 1 per nonzero diagonal entry, 2 per nonzero pair off the diagonal (relative to the
/// largest, as `value::snapped_matrix` drops them).
fn inertia_cost(m: &Matrix3) -> usize {
    let scale = m.iter().flatten().fold(0.0_f64, |a, x| a.max(x.abs()));
    let nonzero = |x: f64| x.abs() >= 1e-14 * scale && x != 0.0;
    (0..3)
        .flat_map(|i| (i..3).map(move |j| (i, j)))
        .filter(|&(i, j)| nonzero(m[i][j]))
        .map(|(i, j)| if i == j { 1 } else { 2 })
        .sum()
}

/// The angles that zero an entry of R Rot(s, φ) = R s sᵀ + cos φ R (1 − s sᵀ) + sin φ R ŝ.
fn placement_angles(axis: [f64; 3], rotation: &Matrix3) -> Vec<f64> {
    let (along, across, cross) = split(axis);
    let a = linear::mul(rotation, &along);
    let b = linear::mul(rotation, &across);
    let c = linear::mul(rotation, &cross);
    (0..9)
        .flat_map(|k| zeroing_angles(a[k / 3][k % 3], b[k / 3][k % 3], c[k / 3][k % 3]))
        .collect()
}

/// The angles that zero an entry of Rot(s, φ)ᵀ S = s sᵀ S + cos φ (1 − s sᵀ) S − sin φ ŝ S.
fn child_angles(axis: [f64; 3], rotation: &Matrix3) -> Vec<f64> {
    let (along, across, cross) = split(axis);
    let a = linear::mul(&along, rotation);
    let b = linear::mul(&across, rotation);
    let c = linear::mul(&cross, rotation);
    (0..9)
        .flat_map(|k| zeroing_angles(a[k / 3][k % 3], b[k / 3][k % 3], -c[k / 3][k % 3]))
        .collect()
}

/// The angles that zero an entry of Rot(s, φ)ᵀ t, the same way.
fn vector_angles(axis: [f64; 3], t: &Vector3) -> Vec<f64> {
    let (along, across, cross) = split(axis);
    let a = linear::mul_vector(&along, t);
    let b = linear::mul_vector(&across, t);
    let c = linear::mul_vector(&cross, t);
    (0..3)
        .flat_map(|k| zeroing_angles(a[k], b[k], -c[k]))
        .collect()
}

/// s sᵀ, 1 − s sᵀ and ŝ: Rot(s, φ) = s sᵀ + cos φ (1 − s sᵀ) + sin φ ŝ.
fn split(s: [f64; 3]) -> (Matrix3, Matrix3, Matrix3) {
    let along = linear::outer(&s, &s);
    let across = linear::sub(&IDENTITY, &along);
    let cross = [[0.0, -s[2], s[1]], [s[2], 0.0, -s[0]], [-s[1], s[0], 0.0]];
    (along, across, cross)
}

/// The angles φ in (−π, π] with a + b cos φ + c sin φ = 0, where the entry varies with φ.
fn zeroing_angles(a: f64, b: f64, c: f64) -> Vec<f64> {
    let r = b.hypot(c);
    if r < 1e-12 || a.abs() > r * (1.0 + 1e-12) {
        return Vec::new();
    }
    let base = c.atan2(b);
    let spread = (-a / r).clamp(-1.0, 1.0).acos();
    vec![wrap(base + spread), wrap(base - spread)]
}

/// An angle in (−π, π].
fn wrap(angle: f64) -> f64 {
    let mut a = angle % std::f64::consts::TAU;
    if a <= -std::f64::consts::PI {
        a += std::f64::consts::TAU;
    } else if a > std::f64::consts::PI {
        a -= std::f64::consts::TAU;
    }
    a
}

/// The angles without repeats (within 1e-12) and without 0, in the order first met.
fn distinct(angles: Vec<f64>) -> Vec<f64> {
    let mut kept: Vec<f64> = Vec::new();
    for a in angles {
        let seen = |b: &f64| (a - b).abs() < 1e-12;
        if a.abs() > 1e-12 && !kept.iter().any(seen) {
            kept.push(a);
        }
    }
    kept
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rx(angle: f64) -> Matrix3 {
        rotation_about([1.0, 0.0, 0.0], angle)
    }

    fn rz(angle: f64) -> Matrix3 {
        rotation_about([0.0, 0.0, 1.0], angle)
    }

    /// A unit mass at c with I_G = 0.01 · 1.
    fn point_mass(c: [f64; 3]) -> MassProperties {
        MassProperties {
            first_moment: c,
            inertia_about_origin: linear::add(
                &linear::scale(&IDENTITY, 0.01),
                &linear::parallel_axis(&c),
            ),
        }
    }

    #[test]
    fn a_link_turned_about_its_axis_and_back_is_placed_by_the_identity() {
        // ANYmal's hip: placed by Rx(150°), its child by Rx(−150°) Rz(90°).
        let turn = 150_f64.to_radians();
        let child = ChildPlacement {
            rotation_in_body: linear::mul(&rx(-turn), &rz(std::f64::consts::FRAC_PI_2)),
            origin_in_body: linear::mul_vector(&rx(-turn), &[0.0599, 0.08381, 0.0]),
            axis: Some([1.0, 0.0, 0.0]),
        };
        let chosen = best_turn(
            [1.0, 0.0, 0.0],
            &rx(turn),
            &[child],
            &point_mass([0.0, 0.0, -0.1]),
        );
        let Some(t) = chosen else {
            panic!("no turn chosen")
        };
        // Both placements become signed permutations: Rx(150°) Rx(−150°) = 1 (or a half
        // turn about x, which costs the same), and the child's Rz(90°).
        let signed_permutation =
            |m: Matrix3| m.iter().flatten().all(|&x| x == 0.0 || x.abs() == 1.0);
        assert!(signed_permutation(snapped(&linear::mul(&rx(turn), &t))));
        let child_rotation = snapped(&linear::mul(
            &linear::transpose(&t),
            &linear::mul(&rx(-turn), &rz(std::f64::consts::FRAC_PI_2)),
        ));
        assert!(signed_permutation(child_rotation));
        assert_eq!(entries_cost(&child_rotation), 3);
    }

    #[test]
    fn a_sparse_description_keeps_its_frames() {
        let child = ChildPlacement {
            rotation_in_body: rz(std::f64::consts::FRAC_PI_2),
            origin_in_body: [0.1, 0.0, 0.3],
            axis: Some([0.0, 1.0, 0.0]),
        };
        assert!(best_turn(
            [0.0, 0.0, 1.0],
            &IDENTITY,
            &[child],
            &point_mass([0.1, 0.0, 0.0])
        )
        .is_none());
    }

    #[test]
    fn a_turn_that_only_moves_a_general_rotation_to_the_children_is_not_taken() {
        // Placed by Rz(0.3) about its own axis, with two axis-aligned children: turning
        // would clear the placement but load the same rotation onto both children.
        let children: Vec<ChildPlacement> = (0..2)
            .map(|_| ChildPlacement {
                rotation_in_body: IDENTITY,
                origin_in_body: [0.2, 0.0, 0.0],
                axis: Some([1.0, 0.0, 0.0]),
            })
            .collect();
        assert!(best_turn(
            [0.0, 0.0, 1.0],
            &rz(0.3),
            &children,
            &point_mass([0.1, 0.0, 0.0])
        )
        .is_none());
    }

    #[test]
    fn a_general_axis_turns_by_rodrigues_formula() {
        let s = [2.0_f64.sqrt() / 2.0, 0.0, 2.0_f64.sqrt() / 2.0];
        let r = rotation_about(s, 0.7);
        let back = rotation_about(s, -0.7);
        let m = snapped(&linear::mul(&r, &back));
        assert_eq!(m, IDENTITY);
        // The axis is fixed by the turn.
        let turned = linear::mul_vector(&r, &s);
        assert!((0..3).all(|k| (turned[k] - s[k]).abs() < 1e-15));
    }
}
