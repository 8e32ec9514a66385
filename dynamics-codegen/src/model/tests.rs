//! Unit tests of the front half: `quote!{}` in, validated model or spanned errors out.

use super::*;
use quote::quote;

fn lower_tokens(tokens: proc_macro2::TokenStream) -> Result<Model, syn::Error> {
    let mechanism: syntax::Mechanism = syn::parse2(tokens)?;
    lower(&mechanism)
}

fn errors(tokens: proc_macro2::TokenStream) -> Vec<String> {
    match lower_tokens(tokens) {
        Ok(_) => Vec::new(),
        Err(e) => e.into_iter().map(|e| e.to_string()).collect(),
    }
}

#[test]
fn falling_rod_lowers() {
    let m = lower_tokens(quote! {
        pub struct FallingRod;
        gravity: [0.0, -9.81, 0.0];
        body rod { mass: 2.0, com: [0.0, -0.3, 0.0], shape: rod(length: 0.6, axis: y) }
        joint pivot: revolute(ground -> rod) { axis: z }
    })
    .expect("valid");
    assert_eq!((m.nq, m.nv), (1, 1));
    let i = value::nominal33(&m.bodies[0].parts[0].inertia_com_in_body, &[]);
    assert!((i[0][0] - 0.06).abs() < 1e-15 && i[1][1] == 0.0 && (i[2][2] - 0.06).abs() < 1e-15);
    assert_eq!(m.outputs, Outputs::all());
}

/// No `gravity:` means (0, 0, −9.81), as in Pinocchio, MuJoCo and Drake; `gravity: none;`
/// means zero; a vector is taken as written.
#[test]
fn gravity_defaults_to_minus_z_and_none_is_zero() {
    let gravity = |setting: proc_macro2::TokenStream| {
        lower_tokens(quote! {
            pub struct P;
            #setting
            body bob { mass: 1.0, com: [0.0, -0.5, 0.0], shape: point }
            joint pivot: revolute(ground -> bob) { axis: z }
        })
        .expect("valid")
        .gravity_in_world
    };
    assert_eq!(gravity(quote! {}), [0.0, 0.0, -9.81]);
    assert_eq!(gravity(quote! { gravity: none; }), [0.0; 3]);
    assert_eq!(gravity(quote! { gravity: [0.0, 0.0, 0.0]; }), [0.0; 3]);
    assert_eq!(
        gravity(quote! { gravity: [0.0, -9.81, 0.0]; }),
        [0.0, -9.81, 0.0]
    );
}

/// Each setting is given once: the second is an error at the second, naming the first.
#[test]
fn a_setting_given_twice_is_an_error() {
    for (first, second) in [
        (
            quote! { gravity: none; },
            quote! { gravity: [0.0, 0.0, -1.0]; },
        ),
        (quote! { outputs: [energy]; }, quote! { outputs: [energy]; }),
        (
            quote! { parameters: [a = 1.0]; },
            quote! { parameters: [a = 1.0]; },
        ),
        (quote! { allow: []; }, quote! { allow: []; }),
        (quote! { urdf: "a.urdf"; }, quote! { urdf: "a.urdf"; }),
        (
            quote! { floating_base: true; },
            quote! { floating_base: false; },
        ),
        (
            quote! { urdf_damping: true; },
            quote! { urdf_damping: false; },
        ),
        (
            quote! { force_analysis: planar; },
            quote! { force_analysis: spatial; },
        ),
        (quote! { isa: baseline; }, quote! { isa: dispatch; }),
        (
            quote! { rotation_tolerance: 1e-10; },
            quote! { rotation_tolerance: 1e-12; },
        ),
    ] {
        let setting = first.to_string();
        let name = setting.split(' ').next().unwrap_or_default().to_string();
        let e = errors(quote! {
            pub struct P;
            #first
            #second
            body bob { mass: 1.0, com: [0.0, -0.5, 0.0], shape: point }
            joint pivot: revolute(ground -> bob) { axis: z }
        });
        assert_eq!(
            e,
            [
                format!("`{name}` is given twice; a setting is given once"),
                format!("the first `{name}` is here"),
            ],
            "{setting}"
        );
    }
}

/// A quarter turn written to 11 decimals (as HyQ's and ANYmal's URDFs write it) leaves
/// 4.9e-12 in its cosine: kept by default, as Pinocchio keeps it; `rotation_tolerance:
/// 1e-10` makes it exact. A tolerance that is not a small constant is an error at it.
#[test]
fn a_rotation_tolerance_makes_written_quarter_turns_exact() {
    let declare = |setting: proc_macro2::TokenStream| {
        quote! {
            struct Leg;
            #setting
            body a { mass: 1.0, com: [0.1, 0.0, 0.0], inertia: [[0.01, 0.0, 0.0], [0.0, 0.02, 0.0], [0.0, 0.0, 0.03]] }
            body b { mass: 1.0, com: [0.1, 0.0, 0.0], inertia: [[0.01, 0.0, 0.0], [0.0, 0.02, 0.0], [0.0, 0.0, 0.03]] }
            joint j1: revolute(ground -> a) { axis: z }
            joint j2: revolute(a -> b) { axis: z, at: [0.2, 0.0, 0.0], rotation: rpy(1.57079632679, 0.0, 0.0) }
        }
    };
    let kept = lower_tokens(declare(quote! {})).expect("valid");
    let cosine = kept.bodies[1].joint.rotation_in_parent[1][1];
    assert!(cosine != 0.0 && cosine.abs() < 1e-11, "{cosine}");
    // What the CLI's `--ops` and the generated type's docs tell the user.
    let residues = kept.rotation_residues().expect("the cosines' residues");
    assert_eq!((residues.count, residues.tolerance), (2, 1e-11));
    assert!(
        (residues.largest - 4.9e-12).abs() < 1e-13,
        "{}",
        residues.largest
    );
    let exact = lower_tokens(declare(quote! { rotation_tolerance: 1e-10; })).expect("valid");
    assert_eq!(exact.rotation_residues(), None);
    assert_eq!(
        exact.bodies[1].joint.rotation_in_parent,
        [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]]
    );
    for bad in [quote! { 1e-3 }, quote! { 0.0 }, quote! { -1e-10 }] {
        let e = errors(declare(quote! { rotation_tolerance: #bad; }));
        assert!(
            e.iter()
                .any(|m| m.contains("must lie between 1e-15 (the default) and 1e-4")),
            "{e:?}"
        );
    }
    // Written to four decimals (the xarm7's 1.5708, 3.7e-6 off) beside a general angle:
    // the angle is taken as the quarter turn, so the rotation stays orthonormal.
    let four_decimals = lower_tokens(quote! {
        struct Twisted;
        rotation_tolerance: 1e-5;
        body a { mass: 1.0, com: [0.1, 0.0, 0.0], inertia: [[0.01, 0.0, 0.0], [0.0, 0.02, 0.0], [0.0, 0.0, 0.03]] }
        joint j: revolute(ground -> a) { axis: z, rotation: rpy(1.5708, 0.0, 0.3) }
    })
    .expect("valid");
    let r = four_decimals.declared_joints[0].rotation;
    let (s, c) = 0.3_f64.sin_cos();
    assert_eq!(r, [[c, 0.0, s], [s, 0.0, -c], [0.0, 1.0, 0.0]]);
    let e = errors(declare(
        quote! { parameters: [t = 1e-10]; rotation_tolerance: t; },
    ));
    assert!(
        e.iter()
            .any(|m| m.contains("cannot be used in a rotation tolerance")),
        "{e:?}"
    );
}

/// ANYmal's hip: the joint frame turned by 150° about the joint's axis x, the link turned
/// back by −150° through a weld. The tree turns the body's frame about x so that the hip's
/// placement and the knee's are signed permutations, and keeps the turn for the outputs
/// that report the joint frame; the physics (the mass matrix at the reference) is checked
/// by the generated-vs-reference tests of turned models.
#[test]
fn a_frame_turned_about_its_axis_and_back_is_placed_by_a_signed_permutation() {
    let m = lower_tokens(quote! {
        struct Hip;
        body hip { mass: 1.0, com: [0.05, 0.01, 0.0], inertia: [[0.01, 0.0, 0.0], [0.0, 0.02, 0.0], [0.0, 0.0, 0.03]] }
        body hip_fixed { mass: 0.0, com: [0.0, 0.0, 0.0], inertia: [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]] }
        body thigh { mass: 2.0, com: [0.0, 0.0, -0.1], inertia: [[0.03, 0.0, 0.0], [0.0, 0.03, 0.0], [0.0, 0.0, 0.01]] }
        joint haa: revolute(ground -> hip) { axis: x, at: [0.3, 0.1, 0.0], rotation: rpy(2.61799387799, 0.0, 0.0) }
        joint turn_back: fixed(hip -> hip_fixed) { rotation: rpy(-2.61799387799, 0.0, 0.0) }
        joint hfe: revolute(hip_fixed -> thigh) { axis: x, at: [0.06, 0.08, 0.0], rotation: rpy(0.0, 0.0, pi / 2.0) }
    })
    .expect("valid");
    let signed_permutation =
        |r: [[f64; 3]; 3]| r.iter().flatten().all(|&x| x == 0.0 || x.abs() == 1.0);
    let hip = &m.bodies[0].joint;
    assert!(hip.joint_frame_in_body.is_some());
    assert!(
        signed_permutation(hip.rotation_in_parent),
        "{:?}",
        hip.rotation_in_parent
    );
    let knee = &m.bodies[1].joint;
    assert!(
        signed_permutation(knee.rotation_in_parent),
        "{:?}",
        knee.rotation_in_parent
    );
    // The hip's mass centre, turned with the frame, keeps its length.
    let c = value::nominal3(&m.bodies[0].parts[0].com_in_body, &[]);
    assert!(
        (c.iter().map(|x| x * x).sum::<f64>() - (0.05f64.powi(2) + 0.01f64.powi(2))).abs() < 1e-15
    );
}

/// A joint declared about a coordinate axis the negative way (−y here) turns its body's
/// frame by a half turn about the next axis (z), so that the tree's axis is +y: the
/// placement and everything on the body change signs only, and the joint frame as
/// declared is the half turn back. A joint about +y, or about a general axis, keeps its
/// frame.
#[test]
fn an_axis_declared_the_negative_way_is_turned_to_point_the_positive_way() {
    let m = lower_tokens(quote! {
            struct Legs;
            body a { mass: 1.0, com: [0.05, 0.01, 0.02], inertia: [[0.01, 0.001, 0.0], [0.001, 0.02, 0.0], [0.0, 0.0, 0.03]] }
            body b { mass: 1.0, com: [0.05, 0.01, 0.02], inertia: diag([0.01, 0.02, 0.03]) }
            body c { mass: 1.0, com: [0.05, 0.01, 0.02], inertia: diag([0.01, 0.02, 0.03]) }
            joint ja: revolute(ground -> a) { axis: [0.0, -1.0, 0.0], at: [0.3, 0.1, 0.0] }
            joint jb: revolute(a -> b) { axis: y, at: [0.0, 0.2, 0.1] }
            joint jc: revolute(b -> c) { axis: [0.0, -0.6, 0.8], at: [0.0, 0.0, 0.3] }
    })
    .expect("valid");
    let half_turn_about_z = [[-1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]];
    let a = &m.bodies[0];
    assert_eq!(
        a.joint.kind,
        JointKind::Revolute {
            axis_in_body: [0.0, 1.0, 0.0]
        }
    );
    assert_eq!(a.joint.joint_frame_in_body, Some(half_turn_about_z));
    assert_eq!(a.joint.rotation_in_parent, half_turn_about_z);
    assert_eq!(
        value::nominal3(&a.parts[0].com_in_body, &[]),
        [-0.05, -0.01, 0.02]
    );
    // b's joint, on a's frame, is placed by the same half turn; b's own frame is kept.
    let b = &m.bodies[1].joint;
    assert_eq!(b.rotation_in_parent, half_turn_about_z);
    assert_eq!(
        value::nominal3(&b.translation_in_parent, &[]),
        [0.0, -0.2, 0.1]
    );
    assert_eq!(b.joint_frame_in_body, None);
    assert_eq!(
        m.bodies[2].joint.kind,
        JointKind::Revolute {
            axis_in_body: [0.0, -0.6, 0.8]
        }
    );
}

/// A matrix printed by a tool that computed a quarter turn from angles (Pinocchio's Panda):
/// its 2.2e-16 residues become exact zeros, other entries stay as written (j2 turns about
/// x, so no turn of its frame about its axis could clear them).
#[test]
fn explicit_rotations_lose_their_rounding_residue() {
    let m = lower_tokens(quote! {
        struct Arm;
        body a { mass: 1.0, shape: sphere(radius: 0.1) }
        body b { mass: 1.0, shape: sphere(radius: 0.1) }
        joint j1: revolute(ground -> a) {
            axis: z,
            rotation: [[1.0, 0.0, 0.0], [0.0, 2.220446049250313e-16, 1.0], [0.0, -1.0, 2.220446049250313e-16]]
        }
        joint j2: revolute(a -> b) {
            axis: x,
            rotation: [[0.6, 0.8, 0.0], [-0.8, 0.6, 0.0], [0.0, 0.0, 1.0]]
        }
    })
    .expect("valid");
    assert_eq!(
        m.bodies[0].joint.rotation_in_parent,
        [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]]
    );
    assert_eq!(
        m.bodies[1].joint.rotation_in_parent,
        [[0.6, 0.8, 0.0], [-0.8, 0.6, 0.0], [0.0, 0.0, 1.0]]
    );
}

#[test]
fn fixed_joints_merge_into_parts_in_the_parent_frame() {
    let m = lower_tokens(quote! {
        struct Arm;
        body link { mass: 1.0, shape: point }
        body tool { mass: 0.5, com: [0.0, 0.0, 0.1], shape: point }
        joint j: revolute(ground -> link) { axis: z }
        joint weld: fixed(link -> tool) { at: [1.0, 0.0, 0.0], rotation: rpy(0.0, 0.0, pi / 2.0) }
        load push: force on tool at [0.0, 0.0, 0.2];
    })
    .expect("valid");
    assert_eq!(m.bodies.len(), 1);
    assert_eq!(m.bodies[0].parts.len(), 2);
    assert_eq!(
        value::nominal3(&m.bodies[0].parts[1].com_in_body, &[]),
        [1.0, 0.0, 0.1]
    );
    assert_eq!(m.loads[0].body, 0);
    assert_eq!(
        value::nominal3(&m.loads[0].point_in_body, &[]),
        [1.0, 0.0, 0.2]
    );
    assert_eq!(m.declared_joints.len(), 2);
}

#[test]
fn parameters_stay_symbolic() {
    let m = lower_tokens(quote! {
        struct P;
        parameters: [payload = 2.0];
        body b { mass: payload, shape: sphere(radius: 0.1) }
        joint j: prismatic(ground -> b) { axis: x }
    })
    .expect("valid");
    let part = &m.bodies[0].parts[0];
    assert_eq!(part.mass, Value::parameter(0, 1.0));
    assert_eq!(
        part.inertia_com_in_body[0][0],
        Value::parameter(0, 0.004000000000000001)
    );
    assert_eq!(m.declared_bodies[0].mass.nominal(&[2.0]), 2.0);
}

#[test]
fn errors_are_collected_not_stopped_at_the_first() {
    let e = errors(quote! {
        struct Bad;
        outputs: [inverse_dynamics, jacobian];
        body a { mass: -1.0, shape: point }
        body b { mass: 1.0, inertia: [[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] }
        joint j1: revolute(ground -> a) { axis: [0, 0, 0] }
        joint j2: revolute(nowhere -> b) { axis: z }
    });
    let joined = e.join("\n");
    assert!(joined.contains("unknown output `jacobian`"), "{joined}");
    assert!(joined.contains("mass -1 kg"), "{joined}");
    assert!(joined.contains("not symmetric"), "{joined}");
    assert!(joined.contains("zero length"), "{joined}");
    assert!(joined.contains("unknown parent `nowhere`"), "{joined}");
    assert_eq!(e.len(), 5, "{joined}");
}

#[test]
fn structural_rules() {
    let e = errors(quote! {
        struct S;
        body a { mass: 1.0, shape: point }
        body b { mass: 1.0, shape: point }
        body c { mass: 1.0, shape: point }
        body lonely { mass: 1.0, shape: point }
        joint j1: revolute(b -> a) { axis: z }
        joint j2: revolute(a -> b) { axis: z }
        joint j3: revolute(ground -> c) { axis: z }
        joint j4: revolute(ground -> c) { axis: z }
    })
    .join("\n");
    assert!(e.contains("cycle through bodies"), "{e}");
    assert!(e.contains("`lonely` is not connected"), "{e}");
    assert!(e.contains("already has a parent through joint `j3`"), "{e}");
}

#[test]
fn physical_rules() {
    let e = errors(quote! {
        struct S;
        allow: [everything];
        body a { mass: 1.0, inertia: diag([1.0, 1.0, 3.0]) }
        body b { mass: 1.0, inertia: diag([-1.0, 1.0, 1.0]) }
        joint j1: revolute(ground -> a) { axis: z, rotation: [[1, 0, 0], [0, 1, 0], [0, 0, -1]] }
        joint j2: revolute(a -> b) { axis: z, armature: -0.1, at: [1.0 / 0.0, 0, 0] }
    })
    .join("\n");
    assert!(e.contains("triangle inequality"), "{e}");
    assert!(e.contains("not positive semi-definite"), "{e}");
    assert!(e.contains("determinant -1"), "{e}");
    assert!(e.contains("armature -0.1"), "{e}");
    assert!(e.contains("evaluates to inf"), "{e}");
    assert!(e.contains("unknown check `everything`"), "{e}");
}

#[test]
fn coordinate_without_inertia_is_rejected() {
    // A point mass on the axis of its own revolute joint: no moment of inertia about z.
    let e = errors(quote! {
        struct S;
        body a { mass: 1.0, com: [0.0, 0.0, 0.5], shape: point }
        joint spin: revolute(ground -> a) { axis: z }
    })
    .join("\n");
    assert!(
        e.contains("coordinate of joint `spin` has no inertia"),
        "{e}"
    );
    assert!(
        e.contains("total mass 1 kg) have a moment of inertia about its axis of 0 kg·m² in every configuration tried"),
        "{e}"
    );
    // The same point mass off the axis is fine.
    assert!(errors(quote! {
        struct S;
        body a { mass: 1.0, com: [0.1, 0.0, 0.5], shape: point }
        joint spin: revolute(ground -> a) { axis: z }
    })
    .is_empty());
}

#[test]
fn parameter_rules() {
    let e = errors(quote! {
        struct S;
        parameters: [unused = 1.0, length = 0.5];
        body a { mass: missing, shape: rod(length: length, axis: x) }
        joint j: revolute(ground -> a) { axis: z }
    })
    .join("\n");
    assert!(e.contains("`missing` is not a declared parameter"), "{e}");
    assert!(
        e.contains("parameter `unused` is declared but never used"),
        "{e}"
    );
    assert!(e.contains("cannot be used in a shape dimension"), "{e}");
}

#[test]
fn no_degree_of_freedom() {
    let e = errors(quote! {
        struct S;
        outputs: [mass_matrix];
        body a { mass: 1.0, shape: point }
        joint weld: fixed(ground -> a);
    })
    .join("\n");
    assert!(e.contains("no degree of freedom"), "{e}");
}

#[test]
fn quarter_turns_are_exact() {
    let m = lower_tokens(quote! {
        struct S;
        body a { mass: 1.0, com: [0.1, 0.0, 0.0], shape: point }
        joint j: revolute(ground -> a) { axis: z, rotation: rpy(-pi / 2.0, 0.0, pi / 2.0) }
    })
    .expect("valid");
    let r = m.bodies[0].joint.rotation_in_parent;
    assert!(
        r.iter().flatten().all(|x| [0.0, 1.0, -1.0].contains(x)),
        "{r:?}"
    );
    assert_eq!(r, [[0.0, 0.0, -1.0], [1.0, 0.0, 0.0], [0.0, -1.0, 0.0]]);
}

#[test]
fn coordinate_without_mass_says_what_was_measured() {
    let e = errors(quote! {
        struct S;
        body a { mass: 0.0, shape: sphere(radius: 0.1) }
        joint slide: prismatic(ground -> a) { axis: x }
    });
    assert_eq!(e.len(), 1, "{e:?}");
    assert!(
        e[0].contains("joint `slide` has no inertia: the bodies it moves have total mass 0 kg"),
        "{e:?}"
    );
    let e = errors(quote! {
        struct S;
        body a { mass: 2.0, shape: point }
        joint float: free(ground -> a);
    });
    assert_eq!(e.len(), 1, "{e:?}");
    assert!(
        e[0].contains(
            "(total mass 2 kg) have a smallest principal moment of inertia about their centre \
             of mass of 0 kg·m² in every configuration tried"
        ),
        "{e:?}"
    );
}

/// A huge mass far from the axis: m |c|² overflows to infinity and the measured moments to
/// NaN, which `max` passed over, so the rule reported "a moment of inertia of 0" (found by
/// `tests/fuzz.rs`). With an infinite scale every moment looked negligible too. Now the
/// overflow is said as such, for every kind of joint.
#[test]
fn an_overflowing_inertia_is_not_called_zero() {
    for joint in [
        quote!(joint spin: revolute(ground -> a) { axis: z }),
        quote!(joint spin: revolute(ground -> a) { axis: [0.0, 0.6, 0.8] }),
        quote!(joint spin: free(ground -> a);),
    ] {
        let e = errors(quote! {
            struct S;
            body a { mass: 1e300, com: [1e5, 2.0, 0.0], shape: point }
            #joint
        });
        assert_eq!(e.len(), 1, "{e:?}");
        assert!(
            e[0].contains(
                "the inertia that the coordinate of joint `spin` moves overflows: the bodies it \
                 moves (total mass 1e300 kg) have"
            ) && e[0].contains("that is not a finite number"),
            "{e:?}"
        );
    }
    // Huge but finite: accepted.
    lower_tokens(quote! {
        struct S;
        body a { mass: 1e300, com: [1.0, 0.0, 0.0], shape: point }
        joint spin: revolute(ground -> a) { axis: z }
    })
    .expect("finite");
}

/// A free body's rotations meet the inertia about its centre of mass, not about the joint
/// origin: a rod off the origin spins about its own axis moving no mass, so M(q) is
/// singular (found by `tests/fuzz.rs`; the parallel-axis term about the origin hid it).
#[test]
fn free_body_inertia_is_judged_about_its_centre_of_mass() {
    let e = errors(quote! {
        struct S;
        body a { mass: 7.0, com: [0.03, 0.24, -0.13], shape: rod(length: 0.4, axis: y) }
        joint float: free(ground -> a) { at: [0.4, -0.3, 0.2] }
    });
    assert_eq!(e.len(), 1, "{e:?}");
    assert!(
        e[0].contains(
            "joint `float` has no inertia: the bodies it moves (total mass 7 kg) have a smallest \
             principal moment of inertia about their centre of mass of"
        ),
        "{e:?}"
    );
    // Two welded rods crossing: inertia about every axis through their centre of mass.
    assert!(errors(quote! {
        struct S;
        body a { mass: 7.0, com: [0.03, 0.24, -0.13], shape: rod(length: 0.4, axis: y) }
        body b { mass: 1.0, shape: rod(length: 0.4, axis: x) }
        joint float: free(ground -> a);
        joint weld: fixed(a -> b) { at: [0.03, 0.24, -0.13] }
    })
    .is_empty());
    // A rod carrying a point mass off its axis on a joint: the bodies the free joint moves
    // have inertia about every axis through their centre of mass.
    assert!(errors(quote! {
        struct S;
        body a { mass: 7.0, com: [0.0, 0.2, 0.0], shape: rod(length: 0.4, axis: y) }
        body b { mass: 1.0, com: [0.1, 0.0, 0.0], shape: point }
        joint float: free(ground -> a);
        joint hinge: revolute(a -> b) { axis: z, at: [0.0, 0.4, 0.0] }
    })
    .is_empty());
}

#[test]
fn one_mistake_is_one_error() {
    // A joint from a body to itself: not also "a second parent" nor "a cycle".
    let e = errors(quote! {
        struct S;
        body bob { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
        joint pivot: revolute(ground -> bob) { axis: z }
        joint hinge: revolute(bob -> bob) { axis: x }
    });
    assert_eq!(e, vec!["joint `hinge` attaches body `bob` to itself"]);
    // Nor "not connected" when the self-joint is the body's only joint.
    let e = errors(quote! {
        struct S;
        body bob { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
        joint hinge: revolute(bob -> bob) { axis: x }
    });
    assert_eq!(e, vec!["joint `hinge` attaches body `bob` to itself"]);
    // A body named `ground`: not also "body `ground` is not connected to the ground".
    let e = errors(quote! {
        struct S;
        body ground { mass: 1.0, shape: sphere(radius: 0.1) }
        body bob { mass: 1.0, com: [0.0, -0.5, 0.0], shape: point }
        joint pivot: revolute(ground -> bob) { axis: z }
    });
    assert_eq!(
        e,
        vec!["`ground` is the fixed world frame; a body cannot be named `ground`"]
    );
    // A negative mass with a shape (or a parameter whose nominal value makes it negative):
    // not also "the inertia is not positive semi-definite", which the shape's I_G, scaled
    // by the mass, only inherits.
    let with_parameter = quote!(parameters: [m = 0.5];);
    for (parameters, mass) in [(quote!(), quote!(-1.0)), (with_parameter, quote!(-2.0 * m))] {
        let e = errors(quote! {
            struct S;
            #parameters
            body bob { mass: #mass, com: [0.0, -0.5, 0.0], shape: box(size: [0.1, 0.2, 0.3]) }
            joint pivot: revolute(ground -> bob) { axis: z }
        });
        assert_eq!(e.len(), 1, "{e:?}");
        assert!(e[0].starts_with("body `bob` has mass -1 kg"), "{e:?}");
    }
}

#[test]
fn duplicate_names_point_at_the_first_declaration() {
    let e = errors(quote! {
        struct S;
        parameters: [k = 1.0, k = 2.0];
        body link { mass: k, shape: point }
        body link { mass: 1.0, shape: point }
        joint j: revolute(ground -> link) { axis: z, at: [1.0, 0.0, 0.0] }
    });
    assert_eq!(
        e,
        vec![
            "a body named `link` is already declared",
            "body `link` is first declared here",
            "a parameter named `k` is already declared",
            "parameter `k` is first declared here",
        ]
    );
}

#[test]
fn missing_fields_name_the_item_and_hint_in_code() {
    let e = errors(quote! {
        struct S;
        body bob { com: [0.0, -0.5, 0.0] }
        joint pivot: revolute(ground -> bob);
    });
    assert_eq!(
        e,
        vec![
            "body `bob` has no `mass`; add for example `mass: 1.0`",
            "body `bob` has no `inertia`; add for example `inertia: [[..], [..], [..]]`, or \
             `shape: point` for a point mass",
            "joint `pivot` has no `axis`; add for example `axis: z`",
        ]
    );
}

#[test]
fn computed_numbers_have_six_significant_digits() {
    use super::rules::computed;
    assert_eq!(computed(0.30000000000000004), "0.3");
    assert_eq!(computed(-0.09999999999999998), "-0.1");
    assert_eq!(computed(3.0), "3");
    assert_eq!(computed(-0.0), "0");
    assert_eq!(computed(2.9999999999999996e-17), "3e-17");
    assert_eq!(computed(1234567.0), "1.23457e6");
    assert_eq!(computed(0.000123456789), "0.000123457");
    assert_eq!(computed(f64::INFINITY), "inf");
    let e = errors(quote! {
        struct S;
        parameters: [k = 0.3];
        body bob { mass: 1.0, inertia: [[0.1, 0.2, 0.0], [0.2, 0.1, 0.0], [0.0, 0.0, 0.1]] }
        joint pivot: revolute(ground -> bob) {
            axis: z,
            rotation: [[1.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 1.0]],
            armature: -0.1 * k,
            damping: -0.25,
        }
    })
    .join("\n");
    assert!(
        e.contains("principal moments are -0.1, 0.1, 0.3 kg·m²"),
        "{e}"
    );
    assert!(e.contains("|RᵀR − 1| is 3 (at most 1e-6"), "{e}");
    // A parameter at its nominal value is computed; a number as written stays as written.
    assert!(e.contains("armature -0.03;"), "{e}");
    assert!(e.contains("damping -0.25;"), "{e}");
}

/// Issue 21 (item 13's leftovers): a number as written keeps its shortest round-trip
/// digits, in scientific notation when very small or large (`1e-300` was printed with 300
/// digits).
#[test]
fn written_numbers_are_short() {
    use super::rules::written;
    assert_eq!(written(-2.0), "-2");
    assert_eq!(written(0.1), "0.1");
    assert_eq!(written(0.30000000000000004), "0.30000000000000004");
    assert_eq!(written(-1e-300), "-1e-300");
    assert_eq!(written(1.5e-5), "1.5e-5");
    assert_eq!(written(0.0001), "0.0001");
    assert_eq!(written(123456.5), "123456.5");
    assert_eq!(written(2.5e6), "2.5e6");
    assert_eq!(written(1e300), "1e300");
    assert_eq!(written(0.0), "0");
    let e = errors(quote! {
        struct S;
        body bob { mass: -1e-300, com: [0.0, -0.5, 0.0], shape: rod(length: -2e-9, axis: x) }
        joint pivot: revolute(ground -> bob) { axis: z, damping: -1e20 }
    })
    .join("\n");
    assert!(e.contains("has mass -1e-300 kg"), "{e}");
    assert!(e.contains("a shape dimension is -2e-9 m"), "{e}");
    assert!(e.contains("damping -1e20;"), "{e}");
    assert!(e.len() < 1000, "{e}");
}

#[test]
fn an_output_with_into_asks_for_its_twin_too() {
    let mut outputs = Outputs::default();
    assert!(outputs.enable("mass_matrix_into"));
    assert!(outputs.enable("energy_into"));
    assert!(outputs.enable("inverse_dynamics"));
    assert!(outputs.mass_matrix && outputs.energy && outputs.inverse_dynamics);
    assert!(outputs.wants_into("mass_matrix"));
    assert!(outputs.wants_into("kinetic_energy"));
    assert!(!outputs.wants_into("potential_energy"));
    assert!(!outputs.wants_into("inverse_dynamics"));
    assert!(!outputs.enable("mass_matirx_into"));
    assert!(!outputs.enable("_into"));
    assert!(!outputs.wants_sparse_into("mass_matrix"));
    assert!(outputs.enable("coriolis_sparse_into"));
    assert!(outputs.coriolis && outputs.wants_sparse_into("coriolis_matrix"));
    assert!(!outputs.wants_into("coriolis_matrix"));
    assert!(!outputs.enable("mass_matirx_sparse_into"));
    assert!(!outputs.enable("_sparse_into"));
    let e = errors(quote! {
        struct Bad;
        outputs: [mass_matirx_into];
        body a { mass: 1.0, com: [0.1, 0.0, 0.0], shape: point }
        joint j: revolute(ground -> a) { axis: z }
    })
    .join("\n");
    assert!(e.contains("unknown output `mass_matirx_into`"), "{e}");
    assert!(e.contains("each also with `_into`"), "{e}");
}

#[test]
fn an_unknown_output_suggests_the_closest_name() {
    let e = errors(quote! {
        struct Bad;
        outputs: [mass_matirx, reaction, jacobian];
        body a { mass: 1.0, com: [0.1, 0.0, 0.0], shape: point }
        joint j: revolute(ground -> a) { axis: z }
    })
    .join("\n");
    assert!(
        e.contains("unknown output `mass_matirx`; did you mean `mass_matrix`?"),
        "{e}"
    );
    assert!(
        e.contains("unknown output `reaction`; did you mean `reactions`?"),
        "{e}"
    );
    assert!(
        e.contains("unknown output `jacobian`. The outputs are"),
        "{e}"
    );
    assert_eq!(
        crate::syntax::closest("bodi", &["body", "joint"]),
        Some("body")
    );
    assert_eq!(
        crate::syntax::closest("jiont", &["body", "joint"]),
        Some("joint")
    );
    assert_eq!(crate::syntax::closest("wheel", &["body", "joint"]), None);
}

/// Issue item 2: every number of the declaration is finite, load and constraint points
/// included (they bypassed the rule; a roller at a NaN point made the residual NaN).
#[test]
fn load_and_constraint_points_must_be_finite() {
    let e = errors(quote! {
        struct P;
        body b { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
        joint j: revolute(ground -> b) { axis: z }
        load l: force on b at [1e400, 0.0 / 0.0, 0.0];
    });
    assert_eq!(
        e,
        [
            "this number evaluates to inf; every number must be finite",
            "this number evaluates to NaN; every number must be finite"
        ]
    );
    let e = errors(quote! {
        struct P;
        body a { mass: 1.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
        joint pin: revolute(ground -> a) { axis: z }
        constraint rest: roller(ground at [1.0, 0.0, 0.0], a at [0.0 / 0.0, 0.0, 0.0]) { normal: y };
    });
    assert_eq!(
        e,
        ["this number evaluates to NaN; every number must be finite"]
    );
}

/// A parameter's number is finite too: its coefficient (`m / 0.0`) and its value at the
/// nominal parameters (`1e308 * m` with m = 1e308), which `Mechanism::model()` hands the
/// runtime's `ModelBuilder`. An infinite load point got through and `model()` panicked;
/// others were reported as a coordinate without inertia (found by `tests/fuzz.rs`).
#[test]
fn parameter_numbers_must_be_finite() {
    let e = errors(quote! {
        struct P;
        parameters: [m = 1.0];
        body b { mass: 1.0, com: [0.1, 0.1, 0.0], shape: point }
        joint j: revolute(ground -> b) { axis: z }
        load f: force on b at [m / 0.0, 0.0, 0.0];
    });
    assert_eq!(
        e,
        ["this number evaluates to inf; every number must be finite"]
    );
    let e = errors(quote! {
        struct P;
        parameters: [m = 1e308, k = 2.0];
        body b { mass: 1.0, com: [0.1, 0.1, 0.0], inertia: diag([k * (0.0 / 0.0), 1.0, 1.0]) }
        joint j: revolute(ground -> b) { axis: z, at: [1e308 * m, 0.0, 0.0] }
    });
    assert_eq!(
        e,
        [
            "this number evaluates to NaN; every number must be finite",
            "this number evaluates to inf; every number must be finite"
        ]
    );
    // A non-finite nominal value is one error, not one more per use.
    let e = errors(quote! {
        struct P;
        parameters: [m = 1e400];
        body b { mass: m, com: [0.1, 0.1, 0.0], shape: point }
        joint j: revolute(ground -> b) { axis: z }
    });
    assert_eq!(
        e,
        ["this number evaluates to inf; every number must be finite"]
    );
}

/// Issue item 9: a parameter used only in a load point is used; one not declared is
/// reported once, as not declared.
#[test]
fn a_parameter_in_a_load_point_is_a_use() {
    let e = errors(quote! {
        struct P;
        parameters: [reach = 0.5];
        body b { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
        joint j: revolute(ground -> b) { axis: z }
        load l: force on b at [reach, 0.0, 0.0];
    });
    assert!(e.is_empty(), "{e:?}");
    let e = errors(quote! {
        struct P;
        body b { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
        joint j: revolute(ground -> b) { axis: z }
        load l: force on b at [reach, 0.0, 0.0];
    });
    assert_eq!(e.len(), 1, "{e:?}");
    assert!(
        e[0].starts_with("`reach` is not a declared parameter"),
        "{e:?}"
    );
}

/// Issue item 8: an axis component above 1.4e154 overflowed |a|² and the axis became zero
/// ("has no inertia"); it is normalized by its largest component first.
#[test]
fn a_huge_axis_is_a_unit_axis() {
    let m = lower_tokens(quote! {
        struct P;
        body b { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
        joint j: revolute(ground -> b) { axis: [0.0, 1e300, 1e300] }
    })
    .expect("valid");
    let h = std::f64::consts::FRAC_1_SQRT_2;
    match m.bodies[0].joint.kind {
        JointKind::Revolute { axis_in_body } => {
            assert!(
                axis_in_body[0] == 0.0 && (axis_in_body[1] - h).abs() < 1e-15,
                "{axis_in_body:?}"
            );
            assert_eq!(axis_in_body[1], axis_in_body[2]);
        }
        ref other => panic!("{other:?}"),
    }
}

/// Issue item 9: armature is inertia of the coordinate, M = [armature] for a massless slider.
#[test]
fn armature_gives_a_coordinate_inertia() {
    let e = errors(quote! {
        struct S;
        body carriage { mass: 0.0, shape: point }
        joint slide: prismatic(ground -> carriage) { axis: x, armature: 0.5 }
    });
    assert!(e.is_empty(), "{e:?}");
}

/// Issue item 9: the force analysis names unknowns after joints and constraints (`A.x`), so
/// a constraint named like a joint or another constraint is an error at its name.
#[test]
fn constraint_names_collide_with_no_joint_or_constraint() {
    let e = errors(quote! {
        struct P;
        body a { mass: 1.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
        joint A: revolute(ground -> a) { axis: z }
        constraint A: roller(ground at [1.0, 0.0, 0.0], a at [1.0, 0.0, 0.0]) { normal: y };
    });
    assert!(
        e.iter()
            .any(|m| m.starts_with("a joint named `A` is already declared")),
        "{e:?}"
    );
    assert!(
        e.iter().any(|m| m == "joint `A` is first declared here"),
        "{e:?}"
    );
    let e = errors(quote! {
        struct P;
        body a { mass: 1.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
        joint pin: revolute(ground -> a) { axis: z }
        constraint B: roller(ground at [1.0, 0.0, 0.0], a at [1.0, 0.0, 0.0]) { normal: y };
        constraint B: roller(ground at [1.0, 0.0, 0.0], a at [1.0, 0.0, 0.0]) { normal: x };
    });
    assert!(
        e.iter()
            .any(|m| m.starts_with("a constraint named `B` is already declared")),
        "{e:?}"
    );
}

/// Issue item 11: a type named like the generic parameter, an argument of the generated
/// functions or a primitive type broke the generated code; it is an error at the name.
#[test]
fn reserved_type_names_are_errors_at_the_name() {
    for name in [
        "T", "q", "v", "a", "tau", "p", "loads", "f64", "u8", "bool", "usize",
    ] {
        let name = proc_macro2::Ident::new(name, proc_macro2::Span::call_site());
        let e = errors(quote! {
            struct #name;
            body b { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
            joint j: revolute(ground -> b) { axis: z }
        });
        assert_eq!(e.len(), 1, "{e:?}");
        assert!(
            e[0].starts_with(&format!("the mechanism's type cannot be named `{name}`")),
            "{e:?}"
        );
    }
}

/// `floating_base` and `urdf_damping` apply to a URDF file: without `urdf:` they are an
/// error at the setting; their value is `true` or `false`.
#[test]
fn urdf_settings_need_a_urdf_file_and_a_flag() {
    for setting in [
        quote! { urdf_damping: false; },
        quote! { floating_base: true; },
    ] {
        let name = setting.to_string();
        let name = name.split(' ').next().unwrap_or_default().to_string();
        let e = errors(quote! {
            pub struct P;
            #setting
            body bob { mass: 1.0, com: [0.0, -0.5, 0.0], shape: point }
            joint pivot: revolute(ground -> bob) { axis: z }
        });
        assert_eq!(
            e,
            [format!(
                "`{name}` applies to a URDF file, and this mechanism imports none; add `urdf: \
                 \"path/to/robot.urdf\";` or remove `{name}`"
            )]
        );
    }
    let e = errors(quote! { pub struct P; urdf: "a.urdf"; urdf_damping: maybe; });
    assert_eq!(e, ["expected `true` or `false` after `urdf_damping:`"]);
}

/// A joint's `limits: { .. }` and `friction:` reach the model, each limit unbounded where
/// absent; a joint without them is unbounded and frictionless.
#[test]
fn declared_limits_and_friction_reach_the_model() {
    let m = lower_tokens(quote! {
        pub struct P;
        body a { mass: 1.0, com: [0.5, 0.0, 0.0], shape: point }
        body b { mass: 1.0, com: [0.5, 0.0, 0.0], shape: point }
        joint j1: revolute(ground -> a) {
            axis: z,
            friction: 0.5,
            limits: { lower: -pi / 2, upper: pi / 2, effort: 40.0 },
        }
        joint j2: prismatic(a -> b) { axis: x }
    })
    .expect("valid");
    let j1 = &m.bodies[0].joint;
    assert_eq!(
        j1.limits,
        JointLimits {
            lower: -std::f64::consts::FRAC_PI_2,
            upper: std::f64::consts::FRAC_PI_2,
            velocity: f64::INFINITY,
            effort: 40.0,
        }
    );
    assert_eq!(j1.friction, 0.5);
    assert_eq!(m.bodies[1].joint.limits, JointLimits::UNBOUNDED);
    assert_eq!(m.bodies[1].joint.friction, 0.0);
}

/// Limits are constants on a revolute or prismatic joint, ordered and not negative.
#[test]
fn limits_and_friction_are_checked() {
    let e = errors(quote! {
        pub struct P;
        parameters: [top = 1.0];
        body a { mass: 1.0, com: [0.5, 0.0, 0.0], shape: point }
        body b { mass: 1.0, shape: point }
        body c { mass: 1.0, com: [0.5, 0.0, 0.0], shape: point }
        joint j1: revolute(ground -> a) {
            axis: z,
            friction: -0.1,
            limits: { lower: 1.0, upper: 0.5, velocity: -2.0 },
        }
        joint j2: fixed(a -> b) { limits: { effort: 1.0 }, friction: 0.2 }
        joint j3: revolute(a -> c) { axis: z, limits: { upper: top } }
    });
    assert_eq!(
        e,
        [
            "parameter `top` cannot be used in joint limits: axes, rotations, gravity, shape \
             dimensions, joint limits and friction must be constants",
            "joint `j1` has lower limit 1 above its upper limit 0.5; the lower limit must be ≤ \
             the upper",
            "joint `j1` has velocity limit -2; it must be ≥ 0",
            "joint `j1` has friction -0.1; it must be ≥ 0",
            "joint `j2` is a fixed joint, which has no limits; remove `limits`",
            "joint `j2` is a fixed joint, which has no friction; remove `friction`",
        ]
    );
    let e = errors(quote! {
        pub struct P;
        body a { mass: 1.0, com: [0.5, 0.0, 0.0], shape: point }
        joint j1: revolute(ground -> a) { axis: z, limits: { lowr: 1.0 } }
    });
    assert_eq!(
        e,
        ["unknown limit `lowr`; the limits are lower, upper, velocity, effort"]
    );
}

/// The inertia rules judge bodies merged through fixed joints: a placeholder inertia that
/// alone violates the triangle inequality is accepted welded to a physical body (and the
/// body's docs say so), a merged body that is unphysical is an error at the body it is
/// welded to, naming the merged bodies.
#[test]
fn inertia_rules_judge_the_merged_body() {
    let m = lower_tokens(quote! {
        pub struct Quadruped;
        body base { mass: 0.001, inertia: diag([1e-6, 1e-6, 1e-5]) }
        body trunk { mass: 6.0, com: [0.01, 0.0, 0.02], inertia: diag([0.05, 0.12, 0.14]) }
        joint root: free(ground -> base);
        joint weld: fixed(base -> trunk) { at: [0.02, 0.0, 0.01], rotation: rpy(0.0, 0.0, 0.1) }
    })
    .expect("the merged body is physical");
    let docs = m.bodies[0].documented(&[], m.skip_triangle_inequality);
    assert_eq!(
        docs,
        [
            " Note: the inertia of `base` alone violates the triangle inequality I1 + I2 ≥ I3 \
          (principal moments 1e-6, 1e-6, 1e-5 kg·m²), as a placeholder inertia in a URDF \
          file may; the inertia rules judge the body merged with `trunk` (welded to it \
          through fixed joints), which is physical."
        ]
    );
    let e = errors(quote! {
        pub struct Quadruped;
        body base { mass: 0.001, inertia: diag([1e-6, 1e-6, 1e-5]) }
        body trunk { mass: 6.0, inertia: diag([0.1, 0.1, 0.3]) }
        body lamp { mass: 0.1, shape: point }
        joint root: free(ground -> base);
        joint weld: fixed(base -> trunk);
        joint mount: fixed(trunk -> lamp) { at: [0.0, 0.0, 0.1] }
    });
    assert_eq!(
        e,
        [
            "the principal moments of body `base` merged with `trunk`, `lamp` (welded to it \
          through fixed joints) (0.100985, 0.100985, 0.30001 kg·m²) violate the triangle \
          inequality I1 + I2 ≥ I3 (0.201969 < 0.30001): no mass distribution has this inertia \
          (`allow: [triangle_inequality];` accepts it anyway)"
        ]
    );
    // The bodies welded to the ground are merged too; a body alone is judged as declared.
    let ground = |weld: proc_macro2::TokenStream| {
        errors(quote! {
            pub struct P;
            body stand { mass: 0.001, inertia: diag([1e-6, 1e-6, 1e-5]) }
            body plate { mass: 2.0, inertia: diag([0.1, 0.1, 0.15]) }
            body arm { mass: 1.0, com: [0.5, 0.0, 0.0], shape: point }
            joint weld: fixed(ground -> stand);
            #weld
            joint shoulder: revolute(plate -> arm) { axis: z }
        })
    };
    assert_eq!(
        ground(quote! { joint bolt: fixed(stand -> plate); }),
        Vec::<String>::new()
    );
    assert_eq!(
        ground(quote! { joint bolt: fixed(ground -> plate); }),
        Vec::<String>::new()
    );
    let e = ground(quote! { joint bolt: revolute(ground -> plate) { axis: z } });
    assert_eq!(e.len(), 1, "{e:?}");
    assert!(
        e[0].starts_with("the principal moments of body `stand` (1e-6, 1e-6, 1e-5 kg·m²)"),
        "{e:?}"
    );
}

/// The same arm, a revolute, a prismatic (with a θ offset) and a revolute joint, declared
/// with a standard DH table (the inertial data, a load point, a frame and a welded tool in
/// the DH link frames) and with the same table in Craig's convention (row i takes a and α
/// from standard row i − 1; the data carried into Craig's frames by C = Tx(a) Rx(α), which
/// with quarter-turn twists permutes axes exactly). The trees are the same, number for
/// number.
#[test]
fn standard_and_modified_dh_tables_lower_to_the_same_tree() {
    let standard = lower_tokens(quote! {
        pub struct Arm;
        body l1 { mass: 2.0, com: [-0.05, 0.01, 0.02], inertia: diag([0.01, 0.02, 0.03]) }
        body l2 { mass: 1.0, com: [0.0, 0.03, -0.1], inertia: diag([0.004, 0.005, 0.006]) }
        body l3 { mass: 0.5, com: [-0.1, 0.0, 0.0], inertia: diag([0.001, 0.002, 0.002]) }
        body tool { mass: 0.1, shape: point }
        joint j1: revolute(ground -> l1) { placement: dh(a: 0.1, alpha: pi / 2, d: 0.3, theta: 0.2) }
        joint j2: prismatic(l1 -> l2) { placement: dh(alpha: -pi / 2, d: 0.25, theta: -pi / 2) }
        joint j3: revolute(l2 -> l3) { placement: dh(a: 0.2, d: 0.05) }
        joint weld: fixed(l3 -> tool) { at: [0.1, 0.0, 0.0] }
        load push: force on l2 at [0.01, 0.02, 0.03];
        frame tcp: on l3 at [0.05, 0.0, 0.0];
    })
    .expect("valid");
    let modified = lower_tokens(quote! {
        pub struct Arm;
        // Rx(π/2) takes (x, y, z) to (x, −z, y), Rx(−π/2) to (x, z, −y); then + (a, 0, 0).
        body l1 { mass: 2.0, com: [0.1 - 0.05, -0.02, 0.01], inertia: diag([0.01, 0.03, 0.02]) }
        body l2 { mass: 1.0, com: [0.0, -0.1, -0.03], inertia: diag([0.004, 0.006, 0.005]) }
        body l3 { mass: 0.5, com: [0.2 - 0.1, 0.0, 0.0], inertia: diag([0.001, 0.002, 0.002]) }
        body tool { mass: 0.1, shape: point }
        joint j1: revolute(ground -> l1) { placement: mdh(a: 0.0, alpha: 0.0, d: 0.3, theta: 0.2) }
        joint j2: prismatic(l1 -> l2) { placement: mdh(a: 0.1, alpha: pi / 2, d: 0.25, theta: -pi / 2) }
        joint j3: revolute(l2 -> l3) { placement: mdh(alpha: -pi / 2, d: 0.05) }
        joint weld: fixed(l3 -> tool) { at: [0.1 + 0.2, 0.0, 0.0] }
        load push: force on l2 at [0.01, 0.03, -0.02];
        frame tcp: on l3 at [0.05 + 0.2, 0.0, 0.0];
    })
    .expect("valid");
    assert_eq!(standard.bodies.len(), 3);
    for (s, m) in standard.bodies.iter().zip(&modified.bodies) {
        assert_eq!(s.joint.kind, m.joint.kind, "{}", s.name);
        assert_eq!(
            s.joint.rotation_in_parent, m.joint.rotation_in_parent,
            "{}",
            s.name
        );
        assert_eq!(
            s.joint.translation_in_parent, m.joint.translation_in_parent,
            "{}",
            s.name
        );
        assert_eq!(s.parts.len(), m.parts.len());
        for (sp, mp) in s.parts.iter().zip(&m.parts) {
            assert_eq!(sp.com_in_body, mp.com_in_body, "{}", sp.name);
            assert_eq!(
                sp.inertia_com_in_body, mp.inertia_com_in_body,
                "{}",
                sp.name
            );
        }
    }
    assert_eq!(
        standard.bodies[1].joint.kind,
        JointKind::Prismatic {
            axis_in_body: [0.0, 0.0, 1.0]
        }
    );
    assert_eq!(
        standard.loads[0].point_in_body,
        modified.loads[0].point_in_body
    );
    // In body axes, the standard declaration's load is in the DH link frame's axes.
    let rx_minus = [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]];
    assert_eq!(standard.loads[0].rotation_in_body, rx_minus);
    assert_eq!(modified.loads[0].rotation_in_body, linear::IDENTITY);
    let tcp = |m: &Model| {
        let f = m.frames.iter().find(|f| f.name == "tcp").expect("tcp");
        (f.body, f.rotation_in_body, f.origin_in_body.clone())
    };
    assert_eq!(tcp(&standard), tcp(&modified));
    // The runtime model gets the child frames of the standard rows (each has a ≠ 0 or
    // α ≠ 0), none for the weld.
    let child_frames: Vec<bool> = standard
        .declared_joints
        .iter()
        .map(|j| j.child_frame.is_some())
        .collect();
    assert_eq!(child_frames, [true, true, true, false]);
    assert!(modified
        .declared_joints
        .iter()
        .all(|j| j.child_frame.is_none()));
}

/// A DH row fixes the joint frame and the axis: `at`, `rotation` and `axis` with it are
/// errors at their tokens; fixed and free joints take no DH row; the angles are constants,
/// the lengths may be parameters.
#[test]
fn dh_placements_are_checked() {
    let e = errors(quote! {
        pub struct P;
        body b { mass: 1.0, com: [0.1, 0.0, 0.0], shape: point }
        joint j: revolute(ground -> b) {
            axis: z, at: [0.0, 0.0, 0.1], rotation: rpy(0, 0, 1), placement: dh(a: 0.1)
        }
    });
    assert_eq!(
        e,
        [
            "`axis` cannot be given with `placement: dh(..)`: `dh(..)` fixes the axis: the joint \
             moves about or along z of its DH frame; remove `axis`",
            "`at` cannot be given with `placement: dh(..)`: `dh(..)` places the joint frame; \
             remove `at`",
            "`rotation` cannot be given with `placement: dh(..)`: `dh(..)` places the joint \
             frame; remove `rotation`",
        ]
    );
    // A parameter in the field given with the row is not also reported as unused.
    let e = errors(quote! {
        pub struct P;
        parameters: [offset = 0.1];
        body b { mass: 1.0, com: [0.1, 0.0, 0.0], shape: point }
        joint j: revolute(ground -> b) { at: [0.0, 0.0, offset], placement: dh(a: 0.1) }
    });
    assert_eq!(e.len(), 1, "{e:?}");
    assert!(e[0].starts_with("`at` cannot be given with"), "{e:?}");
    let e = errors(quote! {
        pub struct P;
        body a { mass: 1.0, com: [0.1, 0.0, 0.0], shape: point }
        body b { mass: 1.0, shape: point }
        joint j: revolute(ground -> a) { axis: z }
        joint w: fixed(a -> b) { placement: mdh(a: 0.1, alpha: pi / 2) }
    });
    assert_eq!(
        e,
        [
            "a fixed joint cannot be placed by `mdh(..)`: a Denavit–Hartenberg row places the \
          axis of a revolute or prismatic joint; place a fixed joint with `at` and `rotation`"
        ]
    );
    let e = errors(quote! {
        pub struct P;
        parameters: [twist = 0.1];
        body b { mass: 1.0, com: [0.1, 0.0, 0.0], shape: point }
        joint j: revolute(ground -> b) { placement: dh(alpha: twist) }
    });
    assert_eq!(e.len(), 1, "{e:?}");
    assert!(
        e[0].starts_with("parameter `twist` cannot be used in a DH angle (`alpha` or `theta`)"),
        "{e:?}"
    );
    // Lengths stay symbolic: the link length moves the child's mass centre and its child's
    // joint.
    let m = lower_tokens(quote! {
        pub struct P;
        parameters: [reach = 0.4, lift = 0.2];
        body b { mass: 1.0, com: [-0.1, 0.0, 0.0], shape: point }
        body c { mass: 1.0, com: [0.1, 0.0, 0.0], shape: point }
        joint j: revolute(ground -> b) { placement: dh(a: reach, alpha: pi / 2, d: lift) }
        joint k: revolute(b -> c) { placement: dh(d: 0.1) }
    })
    .expect("valid");
    let p = [0.4, 0.2];
    assert_eq!(
        value::nominal3(&m.bodies[0].joint.translation_in_parent, &p),
        [0.0, 0.0, 0.2]
    );
    let com = &m.bodies[0].parts[0].com_in_body;
    assert_eq!(com[0].terms, [(0, 1.0)]);
    assert!((com[0].nominal(&p) - 0.3).abs() < 1e-15);
    // k's joint frame: d = 0.1 along z of b's DH link frame, carried by b's
    // C = Tx(reach) Rx(π/2): Rx(π/2) [0, 0, 0.1] + [reach, 0, 0] = [reach, −0.1, 0].
    let t = value::nominal3(&m.bodies[1].joint.translation_in_parent, &p);
    assert!(
        (t[0] - 0.4).abs() < 1e-15 && (t[1] + 0.1).abs() < 1e-15 && t[2] == 0.0,
        "{t:?}"
    );
}
