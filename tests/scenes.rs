//! Scenes that model no more than they need (models/src/scenes.rs): the planar arm and its
//! general 3-D twin are the same physics, the planar one costs a fraction; a gravity-only
//! scene generates gravity only, at the full scene's cost for it.

use dynamics_runtime::{FunctionCost, Mechanism};
use dynamics_tests::random::SplitMix;
use dynamics_tests::{max_abs_diff, tolerance_scale};
use models::scenes::{PlanarArm, PlanarArmGravityOnly, PlanarArmIn3d};

fn cost(functions: &[FunctionCost], name: &str) -> FunctionCost {
    *functions
        .iter()
        .find(|f| f.name == name)
        .expect("generated")
}

#[test]
fn planar_and_general_declarations_are_the_same_physics() {
    let mut rng = SplitMix(17);
    for _ in 0..20 {
        let draw = |rng: &mut SplitMix, s: f64| -> [f64; 4] {
            std::array::from_fn(|_| rng.uniform(-s, s))
        };
        let (q, v, a) = (
            draw(&mut rng, 3.0),
            draw(&mut rng, 2.0),
            draw(&mut rng, 3.0),
        );
        let planar = PlanarArm::inverse_dynamics(&q, &v, &a);
        let general = PlanarArmIn3d::inverse_dynamics(&q, &v, &a);
        assert!(
            max_abs_diff(&planar, &general) <= 1e-12 * tolerance_scale(&planar),
            "{planar:?} vs {general:?}"
        );
        let (m_p, m_g) = (PlanarArm::mass_matrix(&q), PlanarArmIn3d::mass_matrix(&q));
        assert!(
            max_abs_diff(m_p.as_flattened(), m_g.as_flattened())
                <= 1e-12 * tolerance_scale(m_p.as_flattened())
        );
        let g = PlanarArmGravityOnly::gravity(&q);
        assert_eq!(g, PlanarArm::gravity(&q));
    }
}

#[test]
fn planar_code_costs_a_fraction_of_the_general_code() {
    for name in [
        "inverse_dynamics",
        "mass_matrix",
        "forward_dynamics",
        "gravity",
    ] {
        let (planar, general) = (
            cost(PlanarArm::FUNCTIONS, name),
            cost(PlanarArmIn3d::FUNCTIONS, name),
        );
        println!(
            "{name}: planar {} mul {} add, general 3-D {} mul {} add",
            planar.mul, planar.add, general.mul, general.add
        );
        assert!(
            5 * (planar.mul + planar.add) <= general.mul + general.add,
            "{name}: {planar:?} vs {general:?}"
        );
    }
}

#[test]
fn gravity_only_scene_generates_gravity_only() {
    assert_eq!(PlanarArmGravityOnly::FUNCTIONS.len(), 1);
    let only = cost(PlanarArmGravityOnly::FUNCTIONS, "gravity");
    assert_eq!(only, cost(PlanarArm::FUNCTIONS, "gravity"));
    let full: usize = PlanarArm::FUNCTIONS
        .iter()
        .map(|f| f.mul + f.add + f.div + f.trig)
        .sum();
    println!(
        "gravity-only scene: {} ops; the full set of outputs: {full} ops",
        only.mul + only.add + only.trig
    );
    assert!(10 * (only.mul + only.add + only.trig) < full);
}
