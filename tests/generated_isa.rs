//! The generated code's copies (`dynamics_runtime::isa`): a mechanism declared with
//! `isa: baseline;` emits the baseline copy alone, bit for bit the baseline copy of the same
//! mechanism declared without it; and the AVX2 + FMA copy, where the CPU has it, agrees
//! with the baseline one to rounding; with the feature `avx512`, on a CPU with AVX-512, the
//! wide copy's AVX-512 build is the AVX2 one bit for bit. One test function, because the
//! choice of copy is global to the process.

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
    avx512_copy_is_the_avx2_copy();
}

/// With the feature `avx512`, on a CPU with AVX-512F/VL: the wide kernels' AVX-512 copy
/// (32 vector registers, the same operations) gives the AVX2 copy's bits, on `f64` and on
/// `F64x4`, for the 18-dof quadruped's longest outputs. Without the feature (or on another
/// CPU) `isa::choose_avx512(true)` grants nothing and there is one wide copy to test.
fn avx512_copy_is_the_avx2_copy() {
    use dynamics_runtime::{F64x4, Lanes, Mechanism};
    use models::quadruped::Quadruped;
    const NQ: usize = <Quadruped as Mechanism>::NQ;
    const NV: usize = <Quadruped as Mechanism>::NV;
    const NL: usize = <Quadruped as Mechanism>::NUM_LOAD_INPUTS;
    if !isa::choose_avx512(true) {
        assert!(!isa::avx512());
        #[cfg(all(feature = "avx512", target_arch = "x86_64"))]
        assert!(
            !(std::arch::is_x86_feature_detected!("avx512f")
                && std::arch::is_x86_feature_detected!("avx512vl")),
            "the feature is on and the CPU has AVX-512F/VL, but the copy was not granted"
        );
        return;
    }
    assert!(isa::avx512() && isa::wide());
    let state = |k: usize| {
        let x = |i: usize| ((i * 7 + k * 13) % 17) as f64 * 0.2 - 1.6;
        let mut q: [f64; NQ] = std::array::from_fn(x);
        let norm = q[3..7].iter().map(|c| c * c).sum::<f64>().sqrt();
        q[3..7].iter_mut().for_each(|c| *c /= norm);
        let v: [f64; NV] = std::array::from_fn(|i| x(i + 3));
        let l: [f64; NL] = std::array::from_fn(|i| x(i + 5) * 10.0);
        (q, v, l)
    };
    let states: Vec<_> = (0..4).map(state).collect();
    // Lane i of each packed input is state i's.
    let lanes = |x: &dyn Fn(usize) -> f64| <F64x4 as Lanes>::from_fn(x);
    let q4: [F64x4; NQ] = std::array::from_fn(|j| lanes(&|i| states[i].0[j]));
    let v4: [F64x4; NV] = std::array::from_fn(|j| lanes(&|i| states[i].1[j]));
    let l4: [F64x4; NL] = std::array::from_fn(|j| lanes(&|i| states[i].2[j]));
    let outputs = || {
        let mut bits = Vec::new();
        for (q, v, l) in &states {
            bits.extend(Quadruped::inverse_dynamics(q, v, v, l).map(f64::to_bits));
            bits.extend(Quadruped::forward_dynamics(q, v, v, l).map(f64::to_bits));
            let c = Quadruped::coriolis_matrix(q, v);
            bits.extend(c.iter().flatten().map(|x| x.to_bits()));
        }
        let mut m4 = [[<F64x4 as Lanes>::splat(0.0); NV]; NV];
        Quadruped::mass_matrix_into(&q4, &mut m4);
        let tau4 = Quadruped::inverse_dynamics(&q4, &v4, &v4, &l4);
        for x in m4.iter().flatten().chain(&tau4) {
            bits.extend(x.to_array().map(f64::to_bits));
        }
        bits
    };
    let avx512 = outputs();
    assert!(!isa::choose_avx512(false));
    assert!(isa::wide() && !isa::avx512());
    let avx2 = outputs();
    assert_eq!(avx512.len(), avx2.len());
    let differ = avx512.iter().zip(&avx2).filter(|(a, b)| a != b).count();
    assert_eq!(differ, 0, "{differ} of {} outputs differ", avx2.len());
}
