//! The lanes' contract, lane by lane against the scalar types: arithmetic bit for bit,
//! `F64x4` sines and cosines bit for bit the runtime's `fast_trig::sin_cos` and within 1
//! ulp of std, `F32x8`'s within 1 ulp of `f32`'s; and the constructors.

// std's prelude, for the build without the `std` feature (lib.rs).
use super::{F32x8, F64x4, Lanes};
use crate::fast_trig;
use crate::Scalar;
use num_traits::{One, Zero};
use std::f64::consts::PI;
#[allow(unused_imports)]
use std::prelude::rust_2021::*;

/// A reproducible stream of uniform numbers in [0, 1) (xorshift64*).
fn uniform(mut state: u64) -> impl Iterator<Item = f64> {
    std::iter::from_fn(move || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        Some((state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64)
    })
}

/// Distance in units in the last place (0 when equal, +0 and −0 one point).
fn ulps_f64(a: f64, b: f64) -> u64 {
    let ordered = |x: f64| {
        let bits = x.to_bits();
        if bits >> 63 == 1 {
            -i128::from(bits & !(1 << 63))
        } else {
            i128::from(bits)
        }
    };
    (ordered(a) - ordered(b)).unsigned_abs() as u64
}

/// [`ulps_f64`] for f32.
fn ulps_f32(a: f32, b: f32) -> u64 {
    let ordered = |x: f32| {
        let bits = x.to_bits();
        if bits >> 31 == 1 {
            -i64::from(bits & !(1 << 31))
        } else {
            i64::from(bits)
        }
    };
    (ordered(a) - ordered(b)).unsigned_abs()
}

/// Equal bits, or both NaN (the contract leaves NaN payloads aside).
fn same_f64(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

fn same_f32(a: f32, b: f32) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

/// Operands: the special values, then numbers of every magnitude and sign.
fn operands_f64() -> Vec<f64> {
    let mut x = vec![
        0.0,
        -0.0,
        1.0,
        -1.0,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        f64::MIN_POSITIVE,
        5e-324,
        -5e-324,
        f64::MAX,
        f64::MIN,
        0.1,
        3.0,
    ];
    x.extend(uniform(7).take(4000).enumerate().map(|(i, u)| {
        let m = 10f64.powf(-320.0 + u * 628.0);
        if i % 2 == 0 {
            m
        } else {
            -m
        }
    }));
    x.extend(uniform(8).take(4000).map(|u| (2.0 * u - 1.0) * 10.0));
    x
}

/// A lane type's arithmetic against its scalar's, lane by lane and bit for bit, on the
/// operands: lane k of the i-th vector takes x[i + k] and, as the right operand,
/// x[(7 i + 3 k + 1) mod n]; then the compound assignments.
macro_rules! arithmetic_is_scalar_lane_by_lane {
    ($test:ident, $Lane:ident, $t:ty, $width:literal, $same:ident, $operands:expr) => {
        #[test]
        fn $test() {
            let x: Vec<$t> = $operands;
            let n = x.len();
            for i in 0..n {
                let a: [$t; $width] = std::array::from_fn(|k| x[(i + k) % n]);
                let b: [$t; $width] = std::array::from_fn(|k| x[(7 * i + 3 * k + 1) % n]);
                let c: [$t; $width] = std::array::from_fn(|k| x[(5 * i + k + 2) % n]);
                let (va, vb, vc) = ($Lane::new(a), $Lane::new(b), $Lane::new(c));
                let cases: [(&str, [$t; $width], [$t; $width]); 7] = [
                    (
                        "+",
                        (va + vb).to_array(),
                        std::array::from_fn(|k| a[k] + b[k]),
                    ),
                    (
                        "-",
                        (va - vb).to_array(),
                        std::array::from_fn(|k| a[k] - b[k]),
                    ),
                    (
                        "*",
                        (va * vb).to_array(),
                        std::array::from_fn(|k| a[k] * b[k]),
                    ),
                    (
                        "/",
                        (va / vb).to_array(),
                        std::array::from_fn(|k| a[k] / b[k]),
                    ),
                    ("neg", (-va).to_array(), std::array::from_fn(|k| -a[k])),
                    (
                        "sqrt",
                        Scalar::sqrt(va).to_array(),
                        std::array::from_fn(|k| Scalar::sqrt(a[k])),
                    ),
                    (
                        "mul_add",
                        Scalar::mul_add(va, vb, vc).to_array(),
                        std::array::from_fn(|k| Scalar::mul_add(a[k], b[k], c[k])),
                    ),
                ];
                for (op, got, expected) in cases {
                    for k in 0..$width {
                        assert!(
                            $same(got[k], expected[k]),
                            "{op} lane {k}: {:e}, {:e}: {:e} against {} {:e}",
                            a[k],
                            b[k],
                            got[k],
                            stringify!($t),
                            expected[k]
                        );
                    }
                }
                let mut assigned = va;
                assigned += vb;
                assigned *= vc;
                assigned -= va;
                assigned /= vb;
                let expected: [$t; $width] =
                    std::array::from_fn(|k| ((a[k] + b[k]) * c[k] - a[k]) / b[k]);
                for k in 0..$width {
                    assert!($same(assigned.to_array()[k], expected[k]));
                }
            }
        }
    };
}

arithmetic_is_scalar_lane_by_lane!(
    f64x4_arithmetic_is_f64_lane_by_lane,
    F64x4,
    f64,
    4,
    same_f64,
    operands_f64()
);
arithmetic_is_scalar_lane_by_lane!(
    f32x8_arithmetic_is_f32_lane_by_lane,
    F32x8,
    f32,
    8,
    same_f32,
    operands_f64().into_iter().map(|x| x as f32).collect()
);

/// −(+0) is −0 and −(−0) is +0, as for the scalar types (a subtraction from zero would
/// give +0 for both).
#[test]
fn negation_flips_the_sign_of_zero() {
    let x = (-F64x4::new([0.0, -0.0, 1.0, -2.0])).to_array();
    assert_eq!(
        x.map(f64::to_bits),
        [-0.0, 0.0, -1.0, 2.0].map(f64::to_bits)
    );
    let y = (-F32x8::splat(0.0)).to_array();
    assert!(y.iter().all(|y| y.to_bits() == (-0.0_f32).to_bits()));
}

/// Every sweep: lane by lane bit for bit `fast_trig::sin_cos` (what `sin_cos_array`, the
/// generated code's batched trigonometry, gives for f64), and within 1 ulp of std's
/// `f64::sin_cos` (the runtime's stated bound for |x| ≤ 1.6·10⁶).
#[test]
fn f64x4_sin_cos_is_fast_trig_lane_by_lane_and_within_an_ulp_of_std() {
    let near_half_pi = (1..=20_000).flat_map(|k| {
        let nearest = f64::from(k) * (PI / 2.0);
        (-3i64..=3).map(move |m| f64::from_bits((nearest.to_bits() as i64 + m) as u64))
    });
    let sweeps: [(&str, Vec<f64>); 4] = [
        (
            "uniform, |x| <= 2 pi",
            uniform(11)
                .take(1_000_000)
                .map(|u| (2.0 * u - 1.0) * 2.0 * PI)
                .collect(),
        ),
        (
            "uniform, |x| <= 1e5",
            uniform(12)
                .take(200_000)
                .map(|u| (2.0 * u - 1.0) * 1e5)
                .collect(),
        ),
        ("around k pi/2, k <= 20000", near_half_pi.collect()),
        (
            "log-uniform, 1e-300 <= |x| <= 1.6e6",
            uniform(13)
                .take(160_000)
                .enumerate()
                .map(|(i, u)| 10f64.powf(-300.0 + u * 306.2) * if i % 2 == 0 { 1.0 } else { -1.0 })
                .collect(),
        ),
    ];
    for (name, x) in sweeps {
        let mut worst = 0;
        for group in x.chunks_exact(4) {
            let angles: [f64; 4] = std::array::from_fn(|k| group[k]);
            let (s, c) = Scalar::sin_cos(F64x4::new(angles));
            let (s1, c1) = (
                Scalar::sin(F64x4::new(angles)),
                Scalar::cos(F64x4::new(angles)),
            );
            for k in 0..4 {
                let (fs, fc) = fast_trig::sin_cos(angles[k]);
                let lane = (s.to_array()[k], c.to_array()[k]);
                assert_eq!(
                    (lane.0.to_bits(), lane.1.to_bits()),
                    (fs.to_bits(), fc.to_bits()),
                    "{name}: x = {:e}",
                    angles[k]
                );
                assert_eq!(s1.to_array()[k].to_bits(), fs.to_bits());
                assert_eq!(c1.to_array()[k].to_bits(), fc.to_bits());
                let (ss, cs) = angles[k].sin_cos();
                worst = worst.max(ulps_f64(lane.0, ss)).max(ulps_f64(lane.1, cs));
            }
        }
        println!(
            "F64x4 sin_cos, {name}: {} points, worst {worst} ulp from std",
            x.len()
        );
        assert!(worst <= 1, "{name}: {worst} ulp from std");
    }
}

/// Signed zero, the largest angle that is not NaN, and the ones that are.
#[test]
fn f64x4_sin_cos_special_values() {
    let below = f64::from_bits(2.0_f64.powi(50).to_bits() - 1);
    for x in [
        [0.0, -0.0, f64::NAN, f64::INFINITY],
        [f64::NEG_INFINITY, 2.0_f64.powi(50), -1e300, below],
    ] {
        let (s, c) = Scalar::sin_cos(F64x4::new(x));
        for k in 0..4 {
            let (fs, fc) = fast_trig::sin_cos(x[k]);
            assert!(same_f64(s.to_array()[k], fs) && same_f64(c.to_array()[k], fc));
        }
    }
    let (s, c) = Scalar::sin_cos(F64x4::new([-0.0, f64::NAN, 1e16, below]));
    assert_eq!(s.to_array()[0].to_bits(), 0.0_f64.to_bits());
    assert_eq!(c.to_array()[0], 1.0);
    assert!(s.to_array()[1].is_nan() && s.to_array()[2].is_nan() && c.to_array()[2].is_nan());
    assert!(!s.to_array()[3].is_nan());
}

/// F32x8 against std's `f32::sin_cos`: within 1 ulp on 4 million angles (joint ranges,
/// ±10⁴, and a million consecutive f32 from 0.5 and from 1000), and NaN from 2⁵⁰ on.
#[test]
fn f32x8_sin_cos_within_an_ulp_of_f32() {
    let consecutive = |from: f32| {
        let start = from.to_bits();
        (0..1_000_000u32).map(move |i| f32::from_bits(start + i))
    };
    let sweeps: [(&str, Vec<f32>); 4] = [
        (
            "uniform, |x| <= 2 pi",
            uniform(21)
                .take(1_000_000)
                .map(|u| ((2.0 * u - 1.0) * 2.0 * PI) as f32)
                .collect(),
        ),
        (
            "uniform, |x| <= 1e4",
            uniform(22)
                .take(1_000_000)
                .map(|u| ((2.0 * u - 1.0) * 1e4) as f32)
                .collect(),
        ),
        ("1e6 consecutive from 0.5", consecutive(0.5).collect()),
        ("1e6 consecutive from 1000", consecutive(1000.0).collect()),
    ];
    for (name, x) in sweeps {
        let (mut worst, mut differ, mut rounded) = (0, 0usize, [0usize; 2]);
        for group in x.chunks_exact(8) {
            let angles: [f32; 8] = std::array::from_fn(|k| group[k]);
            let (s, c) = Scalar::sin_cos(F32x8::new(angles));
            for k in 0..8 {
                let (ss, cs) = angles[k].sin_cos();
                let (lane_s, lane_c) = (s.to_array()[k], c.to_array()[k]);
                let e = ulps_f32(lane_s, ss).max(ulps_f32(lane_c, cs));
                worst = worst.max(e);
                differ += usize::from(e > 0);
                // Which of the two is the f64 value rounded to f32 (correctly rounded
                // but for the rare double rounding).
                let (s64, c64) = f64::from(angles[k]).sin_cos();
                let near = |a: f32, b: f32| a == s64 as f32 && b == c64 as f32;
                rounded[0] += usize::from(near(lane_s, lane_c));
                rounded[1] += usize::from(near(ss, cs));
            }
        }
        let percent = |k: usize| 100.0 * k as f64 / x.len() as f64;
        println!(
            "F32x8 sin_cos, {name}: {} points, {:.3} % differ from f32, worst {worst} ulp; \
             both rounded from f64: lanes {:.3} %, f32 {:.3} %",
            x.len(),
            percent(differ),
            percent(rounded[0]),
            percent(rounded[1]),
        );
        assert!(worst <= 1, "{name}: {worst} ulp from f32");
    }
    let (s, c) = Scalar::sin_cos(F32x8::new([
        -0.0,
        f32::NAN,
        f32::INFINITY,
        1.2e15,
        1e20,
        1e15,
        0.0,
        1.0,
    ]));
    let (s, c) = (s.to_array(), c.to_array());
    assert_eq!((s[0].to_bits(), c[0]), (0.0_f32.to_bits(), 1.0));
    assert!((1..5).all(|k| s[k].is_nan() && c[k].is_nan()));
    assert!(!s[5].is_nan() && ulps_f32(s[7], 1.0_f32.sin()) <= 1);
}

#[test]
fn constructors_and_lane_access() {
    let x = F64x4::new([1.0, 2.0, 3.0, 4.0]);
    assert_eq!(x.to_array(), [1.0, 2.0, 3.0, 4.0]);
    assert_eq!(<[f64; 4]>::from(x), [1.0, 2.0, 3.0, 4.0]);
    assert_eq!(F64x4::from([1.0, 2.0, 3.0, 4.0]), x);
    assert_eq!((x.get(0), x.get(3), x.get(4)), (Some(1.0), Some(4.0), None));
    assert_eq!(F64x4::from_fn(|i| i as f64 + 1.0), x);
    assert_eq!(F64x4::splat(2.5).to_array(), [2.5; 4]);
    assert_eq!(<F64x4 as Lanes>::LANES, 4);
    assert_eq!(<F64x4 as Lanes>::get(x, 2), Some(3.0));
    assert_eq!(<F64x4 as Lanes>::splat(1.0), F64x4::one());
    assert_eq!(format!("{x:?}"), "F64x4([1.0, 2.0, 3.0, 4.0])");

    let y = F32x8::from_fn(|i| i as f32);
    assert_eq!(y.get(7), Some(7.0));
    assert_eq!(y.get(8), None);
    assert_eq!(F32x8::LANES, 8);
    assert_eq!(<[f32; 8]>::from(y)[5], 5.0);
    assert_eq!(<F32x8 as Scalar>::from_f64(0.1), F32x8::splat(0.1_f32));
    assert_eq!(<F64x4 as Scalar>::from_f64(0.1), F64x4::splat(0.1));
}

/// `==` holds when every lane is equal, IEEE-wise; `is_zero` when every lane is ±0.
#[test]
fn equality_and_zero_are_over_all_lanes() {
    let x = F64x4::new([0.0, -0.0, 0.0, 0.0]);
    assert!(x.is_zero() && F64x4::zero().is_zero());
    assert_eq!(x, F64x4::zero());
    assert!(!F64x4::new([0.0, 0.0, 1e-300, 0.0]).is_zero());
    assert_ne!(
        F64x4::new([1.0, 2.0, 3.0, 4.0]),
        F64x4::new([1.0, 2.0, 3.0, 5.0])
    );
    assert_ne!(F64x4::splat(f64::NAN), F64x4::splat(f64::NAN));
    assert!(F32x8::zero().is_zero() && !F32x8::one().is_zero());
}

/// The lanes work as nalgebra scalars (the reference algorithms' and `_na` wrappers' use).
#[test]
fn lanes_are_nalgebra_scalars() {
    let a = nalgebra::Matrix2::new(
        F64x4::splat(1.0),
        F64x4::splat(2.0),
        F64x4::new([3.0, 4.0, 5.0, 6.0]),
        F64x4::splat(4.0),
    );
    let b = a * a;
    assert_eq!(b[(1, 0)].to_array(), [15.0, 20.0, 25.0, 30.0]);
}

/// A fused product in either copy of a kernel (`Isa::mul_add`, as generated code writes
/// it): each lane of an `F64x4` is bit for bit `f64`'s in the same copy, fused (one
/// rounding) in the wide one. The copy is whichever `run_kernel` chooses here; both sides
/// are computed inside the same closure, so a test switching the choice cannot split them.
#[test]
fn f64x4_fused_products_are_f64s_lane_by_lane_in_the_copy_that_runs() {
    // 1 + 2⁻³⁰ squared minus its rounded square: zero in two roundings, 2⁻⁶⁰ in one.
    let x = 1.0 + f64::EPSILON.sqrt() / 2.0;
    let (a, b) = (
        F64x4::new([x, -x, 0.5, 3.0]),
        F64x4::new([x, x, 0.25, -7.0]),
    );
    let c = F64x4::new([-(x * x), x * x, 1.0, 21.0]);
    fn run<const WIDE: bool>(
        isa: crate::isa::Isa<WIDE>,
        a: F64x4,
        b: F64x4,
        c: F64x4,
    ) -> (bool, [f64; 4], [f64; 4]) {
        let lanes = isa.mul_add(a, b, c).to_array();
        let each = core::array::from_fn(|i| {
            let lane = |v: F64x4| v.to_array()[i];
            isa.mul_add(lane(a), lane(b), lane(c))
        });
        (WIDE, lanes, each)
    }
    let (wide, lanes, each) =
        <F64x4 as Scalar>::run_kernel(|isa| run(isa, a, b, c), |isa| run(isa, a, b, c));
    assert_eq!(lanes.map(f64::to_bits), each.map(f64::to_bits));
    let exact = x.mul_add(x, -(x * x));
    assert_ne!(exact, 0.0);
    // The baseline copy fuses too when the build targets FMA (`Scalar::mul_add`).
    let fused = wide || cfg!(target_feature = "fma");
    assert_eq!(lanes[0], if fused { exact } else { 0.0 });
}
