//! Loads declared `in world` (components in the world's fixed axes, the point fixed on the
//! body) against loads in the body's axes, on a spatial arm with non-parallel revolute axes
//! and a tool welded on at an angle, and on a free-floating tree with a slider and a welded
//! tip. At random states, with random load inputs:
//! - the generated inverse dynamics, forward dynamics and joint reactions against the runtime
//!   reference, to 1e-12: τ = ID(q, v, a) − Q and q̈ = FD(q, v, τ + Q), Q = Σ J_Pᵀ F + J_ωᵀ M
//!   computed by virtual power (`Reference::generalized_load_forces`) from the loads of
//!   `Mechanism::model()`, and the joint reactions under the loads turned into body wrenches
//!   by hand;
//! - by virtual work, load by load: τ(q, v, a, 0) − τ(q, v, a, L) = J_Pᵀ F + J_ωᵀ M with F and
//!   M in world axes (turned by hand from the body's axes, read from `frame_placements`, for a
//!   body-frame load) and J_P, J_ω the rows of the generated `frame_jacobians` of a frame
//!   declared at the load's point, themselves checked against central differences of
//!   `frame_placements`;
//! - the same physical load declared `in body` and fed the world components turned by hand
//!   into the body's axes gives the same τ, q̈ and joint reactions as declared `in world`.

use dynamics_runtime::{mechanism, LoadFrame, LoadType, Mechanism, Model, Reference, Wrench};
use dynamics_tests::random::{integrate, random_state, SplitMix};
use dynamics_tests::{assert_close, condition_number};
use nalgebra::{DMatrix, Matrix3, Vector3};

/// The arm, with its load `push` on the forearm in the axes `$($axes)*` names.
macro_rules! loaded_arm {
    ($(#[$doc:meta])* $name:ident, $($axes:tt)*) => {
        mechanism! {
            $(#[$doc])*
            pub struct $name;
            outputs: [inverse_dynamics, forward_dynamics, joint_reactions, frame_placements, frame_jacobians];
            body upper { mass: 2.0, com: [0.02, 0.01, 0.15], inertia: [[0.03, 0.001, 0.002], [0.001, 0.035, 0.003], [0.002, 0.003, 0.01]] }
            body fore { mass: 1.2, com: [0.12, 0.0, 0.01], shape: rod(length: 0.25, axis: x) }
            body hand { mass: 0.5, com: [0.04, 0.01, 0.0], shape: box(size: [0.08, 0.05, 0.03]) }
            body tool { mass: 0.2, com: [0.02, 0.0, 0.0], shape: sphere(radius: 0.02) }
            joint shoulder: revolute(ground -> upper) { axis: z, at: [0.0, 0.0, 0.1] }
            joint elbow: revolute(upper -> fore) { axis: [0.3, 1.0, 0.2], at: [0.0, 0.02, 0.3], rotation: rpy(0.2, 0.0, 0.4) }
            joint wrist: revolute(fore -> hand) { axis: x, at: [0.25, 0.05, 0.0], rotation: rpy(0.0, 0.3, 0.0) }
            joint flex: revolute(hand -> tool) { axis: [0.0, 1.0, 1.0], at: [0.08, 0.0, 0.0] }
            joint mount: fixed(tool -> tip) { at: [0.1, 0.0, 0.02], rotation: rpy(0.0, 0.5, -0.3) }
            body tip { mass: 0.1, shape: point }
            /// A force in the tip's own axes.
            load grip: force on tip at [0.05, 0.01, 0.0];
            /// A wrench on the forearm.
            load push: wrench on fore at [0.1, 0.02, -0.03] $($axes)*;
            frame grip_point: on tip at [0.05, 0.01, 0.0];
            frame push_point: on fore at [0.1, 0.02, -0.03];
        }
    };
}

loaded_arm!(
    /// The arm pushed in world axes.
    WorldPushArm, in world
);
loaded_arm!(
    /// The arm pushed in the forearm's axes, said explicitly.
    BodyPushArm, in body
);

mechanism! {
    /// A free-floating base with two branches, one ending in a slider, a tip welded to the
    /// other; a couple on the base and forces on the branches in world axes, a wrench on the
    /// welded tip in its own axes.
    pub struct FreeTreeLoads;
    outputs: [inverse_dynamics, forward_dynamics, joint_reactions, frame_placements, frame_jacobians];
    body base { mass: 3.0, com: [0.01, 0.02, -0.03], inertia: [[0.1, 0.01, 0.0], [0.01, 0.12, 0.02], [0.0, 0.02, 0.09]] }
    body left { mass: 1.0, com: [0.1, 0.0, 0.0], shape: rod(length: 0.2, axis: x) }
    body right { mass: 0.7, com: [0.0, 0.05, 0.01], shape: box(size: [0.05, 0.1, 0.02]) }
    body slider { mass: 0.4, com: [0.02, 0.0, 0.01], shape: sphere(radius: 0.03) }
    body tip { mass: 0.1, shape: point }
    joint float: free(ground -> base);
    joint hip_left: revolute(base -> left) { axis: [0.3, 0.2, 1.0], at: [0.1, 0.1, 0.0], rotation: rpy(0.1, 0.2, 0.3) }
    joint hip_right: revolute(base -> right) { axis: y, at: [0.1, -0.1, 0.0] }
    joint slide: prismatic(left -> slider) { axis: x, at: [0.2, 0.0, 0.0] }
    joint weld: fixed(right -> tip) { at: [0.0, 0.1, 0.05], rotation: rpy(0.4, 0.0, -0.2) }
    load spin: couple on base in world;
    load kick: force on left at [0.15, 0.02, 0.0] in world;
    load grip: wrench on tip at [0.02, 0.0, 0.01];
    load shove: wrench on slider in world at [0.01, 0.02, 0.0];
    frame base_point: on base;
    frame kick_point: on left at [0.15, 0.02, 0.0];
    frame grip_point: on tip at [0.02, 0.0, 0.01];
    frame shove_point: on slider at [0.01, 0.02, 0.0];
}

type Placements<const NF: usize> = [([[f64; 3]; 3], [f64; 3]); NF];
/// A generated function of (q, v, a or τ, loads).
type OfStateAndLoads<const NQ: usize, const NV: usize, const NL: usize, Out> =
    fn(&[f64; NQ], &[f64; NV], &[f64; NV], &[f64; NL]) -> Out;
type Jacobians<const NV: usize, const NF: usize> = [[[f64; NV]; 6]; NF];

/// The generated functions of one mechanism, in f64, and where its loads act.
struct Loaded<const NQ: usize, const NV: usize, const NL: usize, const NB: usize, const NF: usize> {
    name: &'static str,
    model: fn() -> Model,
    inverse_dynamics: OfStateAndLoads<NQ, NV, NL, [f64; NV]>,
    forward_dynamics: OfStateAndLoads<NQ, NV, NL, [f64; NV]>,
    joint_reactions: OfStateAndLoads<NQ, NV, NL, [[f64; 6]; NB]>,
    frame_placements: fn(&[f64; NQ]) -> Placements<NF>,
    frame_jacobians: fn(&[f64; NQ]) -> Jacobians<NV, NF>,
    /// For each load (by its index in `Model::loads`), the frame declared at its point on
    /// the same body, with that body's axes.
    frame_at_load: &'static [usize],
}

macro_rules! loaded {
    ($m:ty, $frames:expr) => {
        Loaded {
            name: <$m as Mechanism>::NAME,
            model: <$m as Mechanism>::model,
            inverse_dynamics: <$m>::inverse_dynamics::<f64>,
            forward_dynamics: <$m>::forward_dynamics::<f64>,
            joint_reactions: <$m>::joint_reactions::<f64>,
            frame_placements: <$m>::frame_placements::<f64>,
            frame_jacobians: <$m>::frame_jacobians::<f64>,
            frame_at_load: $frames,
        }
    };
}

fn world_push_arm() -> Loaded<4, 4, 9, 4, 3> {
    loaded!(
        WorldPushArm,
        &[
            WorldPushArm::FRAME_GRIP_POINT,
            WorldPushArm::FRAME_PUSH_POINT
        ]
    )
}

fn body_push_arm() -> Loaded<4, 4, 9, 4, 3> {
    loaded!(
        BodyPushArm,
        &[BodyPushArm::FRAME_GRIP_POINT, BodyPushArm::FRAME_PUSH_POINT]
    )
}

fn free_tree() -> Loaded<10, 9, 18, 4, 5> {
    loaded!(
        FreeTreeLoads,
        &[
            FreeTreeLoads::FRAME_BASE_POINT,
            FreeTreeLoads::FRAME_KICK_POINT,
            FreeTreeLoads::FRAME_GRIP_POINT,
            FreeTreeLoads::FRAME_SHOVE_POINT,
        ]
    )
}

/// States per mechanism and test.
const STATES: usize = 25;

/// A random state and random load inputs in ±20, as arrays.
fn random_inputs<const NQ: usize, const NV: usize, const NL: usize>(
    model: &Model,
    rng: &mut SplitMix,
) -> ([f64; NQ], [f64; NV], [f64; NV], [f64; NL]) {
    let (q, v, a) = random_state(model, rng);
    let loads = std::array::from_fn(|_| rng.uniform(-20.0, 20.0));
    let sizes = "the model's sizes";
    (
        q.try_into().expect(sizes),
        v.try_into().expect(sizes),
        a.try_into().expect(sizes),
        loads,
    )
}

fn rotation(rows: &[[f64; 3]; 3]) -> Matrix3<f64> {
    Matrix3::from_fn(|r, c| rows[r][c])
}

/// Entries `offset..offset + 3` of the load inputs.
fn three(loads: &[f64], offset: usize) -> Vector3<f64> {
    Vector3::new(loads[offset], loads[offset + 1], loads[offset + 2])
}

/// A load's force and couple in world axes, from its inputs: as given for a load `in
/// world`, turned by `body_in_world` (its declared body's axes in the world) otherwise.
fn force_and_couple_in_world(
    kind: LoadType,
    frame: LoadFrame,
    loads: &[f64],
    offset: usize,
    body_in_world: &Matrix3<f64>,
) -> (Vector3<f64>, Vector3<f64>) {
    let turn = |given: Vector3<f64>| match frame {
        LoadFrame::World => given,
        LoadFrame::Body => body_in_world * given,
    };
    match kind {
        LoadType::Force => (turn(three(loads, offset)), Vector3::zeros()),
        LoadType::Couple => (Vector3::zeros(), turn(three(loads, offset))),
        LoadType::Wrench => (turn(three(loads, offset)), turn(three(loads, offset + 3))),
    }
}

/// The generated inverse dynamics, forward dynamics and joint reactions against the
/// runtime reference, whose loads act through Q = Σ J_Pᵀ F + J_ωᵀ M.
fn check_against_reference<
    const NQ: usize,
    const NV: usize,
    const NL: usize,
    const NB: usize,
    const NF: usize,
>(
    m: &Loaded<NQ, NV, NL, NB, NF>,
    seed: u64,
) {
    let model = (m.model)();
    assert_eq!(model.num_load_inputs(), NL);
    let mut reference = Reference::<f64>::new(&model);
    let mut rng = SplitMix(seed);
    for state in 0..STATES {
        let (q, v, a, loads) = random_inputs::<NQ, NV, NL>(&model, &mut rng);
        let what = |item: &str| format!("{} state {state}: {item}", m.name);
        let mut q_loads = [0.0; NV];
        reference
            .generalized_load_forces(&q, &loads, &mut q_loads)
            .expect("sizes match");
        // τ = ID(q, v, a) − Q.
        let mut tau = [0.0; NV];
        reference
            .inverse_dynamics(&q, &v, &a, None, &mut tau)
            .expect("sizes match");
        let expected: Vec<f64> = tau.iter().zip(&q_loads).map(|(t, l)| t - l).collect();
        let got = (m.inverse_dynamics)(&q, &v, &a, &loads);
        assert_close(&what("inverse dynamics"), &got, &expected, 1e-12);
        // q̈ = FD(q, v, τ + Q), to 1e-12 times cond(M).
        let forces: [f64; NV] = std::array::from_fn(|_| rng.uniform(-5.0, 5.0));
        let tau_and_q: Vec<f64> = forces.iter().zip(&q_loads).map(|(t, l)| t + l).collect();
        let mut qdd = vec![0.0; NV];
        reference
            .forward_dynamics(&q, &v, &tau_and_q, None, &mut qdd)
            .expect("sizes match");
        let mut mass = DMatrix::zeros(NV, NV);
        reference.mass_matrix(&q, &mut mass).expect("sizes match");
        let got = (m.forward_dynamics)(&q, &v, &forces, &loads);
        assert_close(
            &what("forward dynamics"),
            &got,
            &qdd,
            1e-12 * condition_number(&mass),
        );
        // The joint reactions, the loads turned by hand into body wrenches [F; M_P].
        let poses = reference.body_poses(&q).expect("sizes match").to_vec();
        let mut wrenches = vec![Wrench::zero(); model.bodies().len()];
        for load in model.loads() {
            let b = load.body.expect("a moving body");
            let in_world = poses[b].rotation_in_world;
            let declared_in_world = in_world * load.placement_in_body.rotation;
            let (force, couple) = force_and_couple_in_world(
                load.kind,
                load.frame,
                &loads,
                load.input_offset,
                &declared_in_world,
            );
            let (force, couple) = (in_world.transpose() * force, in_world.transpose() * couple);
            wrenches[b].force += force;
            wrenches[b].moment += load.placement_in_body.translation.cross(&force) + couple;
        }
        let mut reactions = vec![Wrench::zero(); model.bodies().len()];
        reference
            .joint_reactions(&q, &v, &a, Some(&wrenches), &mut reactions)
            .expect("sizes match");
        let expected: Vec<f64> = reactions
            .iter()
            .flat_map(|w| w.to_vector6().iter().copied().collect::<Vec<_>>())
            .collect();
        let got = (m.joint_reactions)(&q, &v, &a, &loads);
        assert_close(
            &what("joint reactions"),
            got.as_flattened(),
            &expected,
            1e-12,
        );
    }
}

#[test]
fn the_runtime_model_has_the_declared_loads_and_their_axes() {
    let axes = |model: Model| -> Vec<(String, LoadFrame)> {
        model
            .loads()
            .iter()
            .map(|l| (l.name.clone(), l.frame))
            .collect()
    };
    let named = |pairs: &[(&str, LoadFrame)]| -> Vec<(String, LoadFrame)> {
        pairs.iter().map(|(n, f)| (n.to_string(), *f)).collect()
    };
    use LoadFrame::{Body, World};
    assert_eq!(
        axes(WorldPushArm::model()),
        named(&[("grip", Body), ("push", World)])
    );
    assert_eq!(
        axes(BodyPushArm::model()),
        named(&[("grip", Body), ("push", Body)])
    );
    assert_eq!(
        axes(FreeTreeLoads::model()),
        named(&[
            ("spin", World),
            ("kick", World),
            ("grip", Body),
            ("shove", World)
        ])
    );
}

#[test]
fn generated_loads_match_the_reference_on_a_spatial_arm() {
    check_against_reference(&world_push_arm(), 0x10ad);
    check_against_reference(&body_push_arm(), 0x10ae);
}

#[test]
fn generated_loads_match_the_reference_on_a_free_tree() {
    check_against_reference(&free_tree(), 0x10af);
}

/// Load by load: τ(q, v, a, 0) − τ(q, v, a, L) = J_Pᵀ F + J_ωᵀ M, with J_P and J_ω the
/// generated Jacobian of a frame at the load's point, checked against central differences
/// of the generated frame placements first.
fn check_virtual_work<
    const NQ: usize,
    const NV: usize,
    const NL: usize,
    const NB: usize,
    const NF: usize,
>(
    m: &Loaded<NQ, NV, NL, NB, NF>,
    seed: u64,
) {
    let model = (m.model)();
    let mut rng = SplitMix(seed);
    let h = 1e-6;
    for state in 0..STATES {
        let (q, v, a, loads) = random_inputs::<NQ, NV, NL>(&model, &mut rng);
        let placements = (m.frame_placements)(&q);
        let jacobians = (m.frame_jacobians)(&q);
        // J against the placements' central differences along q ⊕ t e_k.
        for k in 0..NV {
            let mut unit = [0.0; NV];
            unit[k] = 1.0;
            let moved =
                |t: f64| -> [f64; NQ] { integrate(&model, &q, &unit, t).try_into().expect("nq") };
            let (plus, minus) = (
                (m.frame_placements)(&moved(h)),
                (m.frame_placements)(&moved(-h)),
            );
            for &f in m.frame_at_load {
                let rate = |r: usize, c: usize| (plus[f].0[r][c] - minus[f].0[r][c]) / (2.0 * h);
                // Ṙ Rᵀ = ω̂.
                let spin = |r: usize, c: usize| {
                    (0..3)
                        .map(|s| rate(r, s) * placements[f].0[c][s])
                        .sum::<f64>()
                };
                let omega = [spin(2, 1), spin(0, 2), spin(1, 0)];
                for r in 0..3 {
                    let velocity = (plus[f].1[r] - minus[f].1[r]) / (2.0 * h);
                    let (linear, angular) = (jacobians[f][r][k], jacobians[f][3 + r][k]);
                    assert!(
                        (linear - velocity).abs() <= 1e-7 && (angular - omega[r]).abs() <= 1e-7,
                        "{} state {state} frame {f} column {k} row {r}: J {linear}, {angular}; \
                         differences {velocity}, {}",
                        m.name,
                        omega[r]
                    );
                }
            }
        }
        let unloaded = (m.inverse_dynamics)(&q, &v, &a, &[0.0; NL]);
        for (load, &f) in model.loads().iter().zip(m.frame_at_load) {
            // This load's inputs alone.
            let n = load.kind.input_count();
            let range = load.input_offset..load.input_offset + n;
            let mut alone = [0.0; NL];
            alone[range.clone()].copy_from_slice(&loads[range]);
            let (force, couple) = force_and_couple_in_world(
                load.kind,
                load.frame,
                &alone,
                load.input_offset,
                &rotation(&placements[f].0),
            );
            let expected: Vec<f64> = (0..NV)
                .map(|k| {
                    (0..3)
                        .map(|r| jacobians[f][r][k] * force[r] + jacobians[f][3 + r][k] * couple[r])
                        .sum()
                })
                .collect();
            let loaded = (m.inverse_dynamics)(&q, &v, &a, &alone);
            let got: Vec<f64> = unloaded.iter().zip(&loaded).map(|(u, l)| u - l).collect();
            assert_close(
                &format!("{} state {state}: the work of load `{}`", m.name, load.name),
                &got,
                &expected,
                1e-12,
            );
        }
    }
}

#[test]
fn each_load_does_the_virtual_work_of_its_point_on_a_spatial_arm() {
    check_virtual_work(&world_push_arm(), 0x3a1);
    check_virtual_work(&body_push_arm(), 0x3a2);
}

#[test]
fn each_load_does_the_virtual_work_of_its_point_on_a_free_tree() {
    check_virtual_work(&free_tree(), 0x3a3);
}

/// The wrench `push` given in world axes to `WorldPushArm`, and the same wrench turned by
/// hand into the forearm's axes (read from `frame_placements`) to `BodyPushArm`: the same
/// τ, q̈ and joint reactions.
#[test]
fn a_load_in_world_axes_is_the_load_in_body_axes_turned_by_hand() {
    let model = WorldPushArm::model();
    let mut rng = SplitMix(0x7a1);
    for state in 0..STATES {
        let (q, v, a, in_world) = random_inputs::<4, 4, 9>(&model, &mut rng);
        let fore = rotation(&BodyPushArm::frame_placements(&q)[BodyPushArm::FRAME_PUSH_POINT].0);
        let mut in_body = in_world;
        for offset in [3, 6] {
            let turned = fore.transpose() * three(&in_world, offset);
            in_body[offset..offset + 3].copy_from_slice(turned.as_slice());
        }
        let what = |item: &str| format!("state {state}: {item}");
        assert_close(
            &what("inverse dynamics"),
            &WorldPushArm::inverse_dynamics(&q, &v, &a, &in_world),
            &BodyPushArm::inverse_dynamics(&q, &v, &a, &in_body),
            1e-12,
        );
        assert_close(
            &what("forward dynamics"),
            &WorldPushArm::forward_dynamics(&q, &v, &a, &in_world),
            &BodyPushArm::forward_dynamics(&q, &v, &a, &in_body),
            1e-10,
        );
        assert_close(
            &what("joint reactions"),
            WorldPushArm::joint_reactions(&q, &v, &a, &in_world).as_flattened(),
            BodyPushArm::joint_reactions(&q, &v, &a, &in_body).as_flattened(),
            1e-12,
        );
        // And the turn matters: the world components fed to the body-frame declaration
        // give another τ (unless the forearm happens to be aligned with the world).
        let unturned = BodyPushArm::inverse_dynamics(&q, &v, &a, &in_world);
        let world = WorldPushArm::inverse_dynamics(&q, &v, &a, &in_world);
        let difference = unturned
            .iter()
            .zip(&world)
            .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(difference > 1e-3, "state {state}: {difference}");
    }
}
