//! The compiler's rules and the runtime's `ModelBuilder` agree: whatever the compiler accepts
//! the runtime accepts too, so a generated `Mechanism::model()` never panics.
//!
//! The two check the inertia and rotation rules with different code (a closed-form
//! eigenvalue routine at compile time, nalgebra's at run time), so the properties bisect each
//! rule's edge: at every probe on the way to the edge where the compiler accepts, the
//! runtime, given the same numbers, must accept as well.

use dynamics_runtime::{BodySpec, Inertia, JointSpec, ModelBuilder};
use proptest::prelude::*;
use std::path::Path;

type M3 = [[f64; 3]; 3];

/// The declaration of a one-body pendulum with this inertia and placement rotation; `{:?}`
/// prints every f64 in a form that parses back to the same number.
fn declaration(inertia: &M3, rotation: &M3) -> String {
    let m = |a: &M3| {
        format!(
            "[[{:?}, {:?}, {:?}], [{:?}, {:?}, {:?}], [{:?}, {:?}, {:?}]]",
            a[0][0], a[0][1], a[0][2], a[1][0], a[1][1], a[1][2], a[2][0], a[2][1], a[2][2]
        )
    };
    format!(
        "pub struct P; outputs: [mass_matrix];
         body b {{ mass: 1.0, com: [0.0, 0.0, 0.1], inertia: {} }}
         joint j: revolute(ground -> b) {{ axis: z, rotation: {} }}",
        m(inertia),
        m(rotation)
    )
}

/// Whether the compiler accepts the pendulum.
fn compiler_accepts(inertia: &M3, rotation: &M3) -> bool {
    let source = declaration(inertia, rotation);
    match syn::parse_str::<dynamics_codegen::Mechanism>(&source) {
        Ok(mechanism) => dynamics_codegen::compile(mechanism, Path::new(".")).is_ok(),
        Err(e) => panic!("the test's declaration does not parse: {e}\n{source}"),
    }
}

/// Whether the runtime's `ModelBuilder` accepts the same pendulum.
fn runtime_accepts(inertia: &M3, rotation: &M3) -> bool {
    ModelBuilder::new()
        .body(BodySpec::new(
            "b",
            Inertia::new(1.0, [0.0, 0.0, 0.1], *inertia),
        ))
        .joint(JointSpec::revolute("j", "ground", "b", [0.0, 0.0, 1.0]).placed([0.0; 3], *rotation))
        .build()
        .is_ok()
}

/// A rotation matrix from a (not necessarily unit) quaternion.
fn rotation(q: [f64; 4]) -> M3 {
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    let [w, x, y, z] = q.map(|c| c / n);
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

/// R diag(p) Rᵀ, exactly symmetric (the upper triangle mirrored).
fn inertia(p: [f64; 3], r: &M3) -> M3 {
    let mut m = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in i..3 {
            let v = (0..3).map(|k| r[i][k] * p[k] * r[j][k]).sum();
            m[i][j] = v;
            m[j][i] = v;
        }
    }
    m
}

/// Bisects `t` on [lo, hi] towards the compiler's edge (accepted at `lo`, rejected at `hi`),
/// asserting at every probe the compiler accepts that the runtime accepts too.
fn bisect(mut lo: f64, mut hi: f64, case: impl Fn(f64) -> (M3, M3)) -> Result<(), TestCaseError> {
    let (i, r) = case(lo);
    prop_assume!(compiler_accepts(&i, &r));
    let (i, r) = case(hi);
    prop_assume!(!compiler_accepts(&i, &r));
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        let (i, r) = case(mid);
        if compiler_accepts(&i, &r) {
            prop_assert!(
                runtime_accepts(&i, &r),
                "the compiler accepts but the runtime rejects inertia {i:?}, rotation {r:?}"
            );
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(())
}

fn quaternion() -> impl Strategy<Value = [f64; 4]> {
    prop::array::uniform4(-1.0..1.0_f64).prop_filter("not near zero", |q| {
        q.iter().map(|x| x * x).sum::<f64>() > 0.01
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// I3 grows from I1 + I2 until the triangle rule rejects; I1 from 0 (a rod) to I2.
    #[test]
    fn triangle_edge(q in quaternion(), exponent in -12.0..0.0_f64, b in 0.01..10.0_f64) {
        let a = b * 10f64.powf(exponent);
        let r = rotation(q);
        bisect(0.0, 1e-7, |t| (inertia([a, b, (a + b) * (1.0 + t)], &r), rotation([1.0, 0.0, 0.0, 0.0])))?;
    }

    /// The smallest moment falls below zero until the positivity rule rejects.
    #[test]
    fn positive_edge(q in quaternion(), c in 0.01..10.0_f64) {
        let r = rotation(q);
        bisect(0.0, 1e-7, |t| (inertia([-t * c, c, c], &r), rotation([1.0, 0.0, 0.0, 0.0])))?;
    }

    /// One product of inertia drifts from its mirror until the symmetry rule rejects.
    #[test]
    fn symmetric_edge(q in quaternion(), p in prop::array::uniform3(0.5..1.0_f64)) {
        let r = rotation(q);
        let base = inertia(p, &r);
        bisect(0.0, 1e-7, |t| {
            let mut i = base;
            i[1][0] += t * (1.0 + base[1][0].abs());
            (i, rotation([1.0, 0.0, 0.0, 0.0]))
        })?;
    }

    /// A placement rotation is stretched until the orthonormality rule rejects.
    #[test]
    fn rotation_edge(q in quaternion()) {
        let r = rotation(q);
        bisect(0.0, 1e-5, |t| (inertia([1.0, 1.0, 1.0], &r), r.map(|row| row.map(|x| x * (1.0 + t)))))?;
    }
}

dynamics_runtime::mechanism! {
    /// The issue's example: a rotated principal inertia whose I1 + I2 − I3 misses the
    /// triangle threshold by 2.6e-17; it compiled and `model()` panicked.
    pub struct NearTriangleEdge;
    outputs: [mass_matrix];
    body b {
        mass: 1.0,
        com: [0.0, 0.0, 0.1],
        inertia: principal([0.5248131666072078, 0.6685078166917041, 1.193320985685554],
            rotation: rpy(-1.7705890092073469, -0.042064885231845484, 0.08037669793289659)),
    }
    joint j: revolute(ground -> b) { axis: z }
}

#[test]
fn issue_example_model_builds() {
    use dynamics_runtime::Mechanism;
    assert_eq!(NearTriangleEdge::model().bodies().len(), 1);
}

dynamics_runtime::mechanism! {
    /// Kinematics only, with a massless link (a URDF link without `<inertial>`): the
    /// compiler checks coordinates for inertia only when an output needs M(q), and
    /// `model()` panicked, the runtime checking them always (found by `tests/fuzz.rs`).
    pub struct MasslessKinematics;
    outputs: [joint_placements, center_of_mass];
    body link { mass: 0.0, shape: point }
    body tip { mass: 1.0, shape: point }
    joint shoulder: revolute(ground -> link) { axis: z }
    joint elbow: revolute(link -> tip) { axis: z, at: [0.5, 0.0, 0.0] }
    joint spin: revolute(tip -> tool) { axis: x }
    body tool { mass: 0.0, shape: point }
}

#[test]
fn kinematics_only_model_builds() {
    use dynamics_runtime::Mechanism;
    assert_eq!(MasslessKinematics::model().nv(), 3);
}
