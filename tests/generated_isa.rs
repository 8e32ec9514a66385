//! The generated code's copies (`dynamics_runtime::isa`): a mechanism declared with
//! `isa: baseline;` emits the baseline copy alone, bit for bit the baseline copy of the same
//! mechanism declared without it; and the AVX2 + FMA copy, where the CPU has it, agrees
//! with the baseline one to rounding. One test function, because the choice of copy is
//! global to the process.

use dynamics_runtime::{isa, mechanism};

/// A three-link spatial arm, declared twice: once per `isa` setting.
macro_rules! arm {
    ($($head:tt)*) => {
        mechanism! {
            $($head)*
            gravity: [0.0, 0.0, -9.81];
            body upper { mass: 2.0, com: [0.2, 0.0, 0.01], inertia: [[0.02, 0.0, 0.0], [0.0, 0.03, 0.0], [0.0, 0.0, 0.04]] }
            body fore { mass: 1.2, com: [0.15, 0.02, 0.0], inertia: [[0.01, 0.0, 0.0], [0.0, 0.02, 0.0], [0.0, 0.0, 0.02]] }
            body hand { mass: 0.5, com: [0.05, 0.0, 0.03], inertia: [[0.002, 0.0, 0.0], [0.0, 0.003, 0.0], [0.0, 0.0, 0.003]] }
            joint base: revolute(ground -> upper) { axis: z }
            joint elbow: revolute(upper -> fore) { at: [0.4, 0.0, 0.0], axis: y }
            joint wrist: revolute(fore -> hand) { at: [0.3, 0.0, 0.0], axis: x }
        }
    };
}

arm!(
    pub struct TwoCopies;
);
arm!(pub struct OneCopy; isa: baseline;);

fn bits<const N: usize>(x: [f64; N]) -> [u64; N] {
    x.map(f64::to_bits)
}

#[test]
fn one_copy_is_the_baseline_copy_and_the_wide_copy_agrees() {
    let states = [
        ([0.3, -1.2, 2.0], [0.5, -0.7, 1.1], [1.0, 0.2, -0.4]),
        ([-2.5, 0.4, -0.9], [-1.5, 2.2, 0.3], [-0.3, 0.8, 2.0]),
    ];
    assert!(!isa::choose(false));
    for (q, v, a) in &states {
        assert_eq!(
            bits(OneCopy::inverse_dynamics(q, v, a)),
            bits(TwoCopies::inverse_dynamics(q, v, a))
        );
        assert_eq!(
            bits(OneCopy::forward_dynamics(q, v, a)),
            bits(TwoCopies::forward_dynamics(q, v, a))
        );
        assert_eq!(
            OneCopy::mass_matrix(q).map(bits),
            TwoCopies::mass_matrix(q).map(bits)
        );
    }
    if !isa::choose(true) {
        return; // no AVX2 + FMA here: the baseline copies are all there is
    }
    for (q, v, a) in &states {
        let baseline = OneCopy::inverse_dynamics(q, v, a);
        let wide = TwoCopies::inverse_dynamics(q, v, a);
        let scale = 1.0 + baseline.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        for k in 0..3 {
            assert!(
                (wide[k] - baseline[k]).abs() <= 1e-14 * scale,
                "{k}: {} vs {}",
                wide[k],
                baseline[k]
            );
        }
    }
}
