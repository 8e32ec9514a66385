//! The batch helpers: every length (whole packs and every tail), each arity, nested and
//! tuple shapes, `f64` and `f32`; the padding of the last pack; the length errors; and,
//! with the `rayon` feature, the parallel helpers against the sequential ones.

// std's prelude, for the build without the `std` feature (lib.rs).
use super::{map1, map1_into, map2, map2_into, map3, map4, map5, LengthMismatch};
use crate::{F32x8, F64x4, Scalar};
#[allow(unused_imports)]
use std::prelude::rust_2021::*;

/// A function of the generated code's kind, generic over the scalar: batched sines and
/// cosines, products, a division and a square root; a nested output.
fn arm<T: Scalar>(q: &[T; 3], v: &[T; 3]) -> [[T; 3]; 2] {
    let (s, c) = T::sin_cos_array([q[0], q[1], q[2]]);
    let two = T::from_f64(2.0);
    [
        [
            s[0] * v[0] + c[1],
            v[1] / (c[2] + two),
            Scalar::sqrt(v[2] * v[2] + two),
        ],
        [
            -(s[1] * c[0]),
            Scalar::mul_add(v[0], v[1], s[2]),
            q[0] - v[2],
        ],
    ]
}

/// A state of three angles and three rates, different for every `i`.
fn state(i: usize) -> ([f64; 3], [f64; 3]) {
    let x = i as f64;
    (
        [0.3 * x - 1.0, 1.7 - 0.11 * x, 0.05 * x * x],
        [0.5 + 0.1 * x, -0.2 * x, 1.0 - 0.03 * x],
    )
}

fn bits<const N: usize, const M: usize>(x: &[[f64; N]; M]) -> [[u64; N]; M] {
    x.map(|row| row.map(f64::to_bits))
}

/// Every length from 0 to 13: each state's result is the f64 call on it, bit for bit
/// (the lanes run the baseline arithmetic and the runtime's sine and cosine, which is what
/// `f64`'s `sin_cos_array` computes).
#[test]
fn map2_is_the_scalar_call_on_each_state_for_every_length() {
    for n in 0..=13 {
        let (q, v): (Vec<_>, Vec<_>) = (0..n).map(state).unzip();
        let mut out = vec![[[f64::NAN; 3]; 2]; n];
        assert_eq!(map2(&q, &v, &mut out, arm), Ok(()));
        for i in 0..n {
            assert_eq!(bits(&out[i]), bits(&arm(&q[i], &v[i])), "state {i} of {n}");
        }
    }
}

/// The same state gives the same bits in every lane and every pack position.
#[test]
fn a_state_gives_the_same_bits_in_any_lane() {
    let (q, v) = state(5);
    let (q4, v4) = (q.map(F64x4::splat), v.map(F64x4::splat));
    let lanes = arm(&q4, &v4);
    let n = 7;
    let mut out = vec![[[0.0; 3]; 2]; n];
    assert_eq!(map2(&vec![q; n], &vec![v; n], &mut out, arm), Ok(()));
    for lane in 0..4 {
        let unpacked = lanes.map(|row| row.map(|x| x.to_array()[lane]));
        assert_eq!(bits(&unpacked), bits(&arm(&q, &v)));
    }
    assert!(out.iter().all(|o| bits(o) == bits(&arm(&q, &v))));
}

/// One to five inputs, on f32 and eight lanes: each state's result is the lanes' call on
/// that state (lane 0 of a splat), for every length from 0 to 20.
#[test]
fn every_arity_on_f32_for_every_length() {
    fn sum<T: Scalar>(x: &[T]) -> T {
        x.iter().fold(T::zero(), |s, &x| s * T::from_f64(0.5) + x)
    }
    let lane0 = |x: F32x8| x.to_array()[0];
    let splat = |x: &[f32; 2]| x.map(F32x8::splat);
    for n in 0..=20 {
        let input = |k: usize| -> Vec<[f32; 2]> {
            (0..n)
                .map(|i| [(i * k) as f32 * 0.37 - 1.0, (i + k) as f32 * 0.21])
                .collect()
        };
        let (x, y, z, w, u) = (input(1), input(2), input(3), input(4), input(5));
        let mut out = vec![f32::NAN; n];
        let check = |out: &[f32], f: &dyn Fn(usize) -> F32x8| {
            for (i, o) in out.iter().enumerate() {
                assert_eq!(o.to_bits(), lane0(f(i)).to_bits(), "state {i} of {n}");
            }
        };
        let f1 = |x: &[F32x8; 2]| Scalar::sin(sum(x));
        assert_eq!(map1(&x, &mut out, f1), Ok(()));
        check(&out, &|i| f1(&splat(&x[i])));
        let f2 = |x: &[F32x8; 2], y: &[F32x8; 2]| sum(x) / sum(y);
        assert_eq!(map2(&x, &y, &mut out, f2), Ok(()));
        check(&out, &|i| f2(&splat(&x[i]), &splat(&y[i])));
        let f3 = |x: &[F32x8; 2], y: &[F32x8; 2], z: &[F32x8; 2]| sum(x) * sum(y) - sum(z);
        assert_eq!(map3(&x, &y, &z, &mut out, f3), Ok(()));
        check(&out, &|i| f3(&splat(&x[i]), &splat(&y[i]), &splat(&z[i])));
        let f4 = |x: &[F32x8; 2], y: &[F32x8; 2], z: &[F32x8; 2], w: &[F32x8; 2]| {
            Scalar::cos(sum(x) + sum(y)) * sum(z) + sum(w)
        };
        assert_eq!(map4(&x, &y, &z, &w, &mut out, f4), Ok(()));
        check(&out, &|i| {
            f4(&splat(&x[i]), &splat(&y[i]), &splat(&z[i]), &splat(&w[i]))
        });
        let f5 =
            |x: &[F32x8; 2], y: &[F32x8; 2], z: &[F32x8; 2], w: &[F32x8; 2], u: &[F32x8; 2]| {
                sum(x) - sum(y) * sum(z) + Scalar::sqrt(sum(w) * sum(w) + sum(u) * sum(u))
            };
        assert_eq!(map5(&x, &y, &z, &w, &u, &mut out, f5), Ok(()));
        check(&out, &|i| {
            f5(
                &splat(&x[i]),
                &splat(&y[i]),
                &splat(&z[i]),
                &splat(&w[i]),
                &splat(&u[i]),
            )
        });
    }
}

/// A wider result, written in place as the generated `_into` functions write theirs: five
/// rows of six (so the unpacking takes one block of four entries and two single entries
/// per row) and a vector of seven.
fn wide_into<T: Scalar>(q: &[T; 3], v: &[T; 3], out: &mut ([[T; 6]; 5], [T; 7])) {
    let (s, c) = T::sin_cos_array(*q);
    for (r, row) in out.0.iter_mut().enumerate() {
        for (k, x) in row.iter_mut().enumerate() {
            *x = s[k % 3] * T::from_f64(r as f64 + 1.0) + c[(r + k) % 3] * v[k % 3];
        }
    }
    for (k, x) in out.1.iter_mut().enumerate() {
        *x = v[k % 3] / (c[k % 3] + T::from_f64(2.0)) - q[(k + 1) % 3];
    }
}

/// `wide_into` returning its result, for `map2`.
fn wide<T: Scalar>(q: &[T; 3], v: &[T; 3]) -> ([[T; 6]; 5], [T; 7]) {
    let mut out = ([[T::zero(); 6]; 5], [T::zero(); 7]);
    wide_into(q, v, &mut out);
    out
}

type Wide = ([[f64; 6]; 5], [f64; 7]);

fn wide_bits(x: &Wide) -> Vec<u64> {
    x.0.iter()
        .flatten()
        .chain(&x.1)
        .map(|x| x.to_bits())
        .collect()
}

/// `map2_into` and `map2` (both unpacking four results at a time, through the 4 × 4
/// transpose) give each state the scalar call's bits, for every length from 0 to 13.
#[test]
fn into_and_returned_results_are_the_scalar_call_for_every_length() {
    for n in 0..=13 {
        let (q, v): (Vec<_>, Vec<_>) = (0..n).map(state).unzip();
        let nan = ([[f64::NAN; 6]; 5], [f64::NAN; 7]);
        let (mut into, mut returned) = (vec![nan; n], vec![nan; n]);
        assert_eq!(map2_into(&q, &v, &mut into, wide_into), Ok(()));
        assert_eq!(map2(&q, &v, &mut returned, wide), Ok(()));
        for i in 0..n {
            let expected = wide_bits(&wide(&q[i], &v[i]));
            assert_eq!(wide_bits(&into[i]), expected, "into, state {i} of {n}");
            assert_eq!(
                wide_bits(&returned[i]),
                expected,
                "returned, state {i} of {n}"
            );
        }
    }
}

/// On `f32`'s eight lanes: a last pack of four states goes through the four-at-once
/// unpacking, other lengths lane by lane; every length from 0 to 20 gives the lanes' call.
#[test]
fn into_on_f32_for_every_length() {
    let f = |x: &[F32x8; 5], out: &mut [[F32x8; 5]; 6]| {
        for (r, row) in out.iter_mut().enumerate() {
            for (k, o) in row.iter_mut().enumerate() {
                *o = x[k] * F32x8::splat(r as f32) - x[(k + r) % 5];
            }
        }
    };
    for n in 0..=20 {
        let x: Vec<[f32; 5]> = (0..n)
            .map(|i| core::array::from_fn(|k| (i * 7 + k) as f32 * 0.25 - 3.0))
            .collect();
        let mut out = vec![[[f32::NAN; 5]; 6]; n];
        assert_eq!(super::map1_into(&x, &mut out, f), Ok(()));
        for i in 0..n {
            let mut lanes = [[F32x8::splat(0.0); 5]; 6];
            f(&x[i].map(F32x8::splat), &mut lanes);
            let expected = lanes.map(|row| row.map(|x| x.to_array()[0].to_bits()));
            assert_eq!(
                out[i].map(|row| row.map(f32::to_bits)),
                expected,
                "{i} of {n}"
            );
        }
    }
}

/// An `_into` function's buffer is not cleared between packs: what `f` leaves unwritten
/// keeps the previous pack's value (the documented contract: `f` sets every entry).
#[test]
fn into_buffer_carries_what_f_does_not_write() {
    let x: Vec<f64> = (0..8).map(f64::from).collect();
    let mut out = vec![[0.0; 2]; 8];
    let mut first = true;
    let result = map1_into(&x, &mut out, |x: &F64x4, o: &mut [F64x4; 2]| {
        o[0] = *x;
        if first {
            o[1] = *x * F64x4::splat(10.0);
            first = false;
        }
    });
    assert_eq!(result, Ok(()));
    assert_eq!(out[5], [5.0, 10.0]);
    assert_eq!(out[2], [2.0, 20.0]);
}

/// The last pack of a length that is not a multiple of four is filled with copies of its
/// last state; one call per pack.
#[test]
fn the_last_pack_is_padded_with_its_last_state() {
    for n in 1..=9 {
        let x: Vec<f64> = (0..n).map(|i| 10.0 + i as f64).collect();
        let mut seen = Vec::new();
        let mut out = vec![0.0; n];
        let result = map1(&x, &mut out, |x: &F64x4| {
            seen.push(x.to_array());
            *x * *x
        });
        assert_eq!(result, Ok(()));
        assert_eq!(seen.len(), n.div_ceil(4));
        for (p, pack) in seen.iter().enumerate() {
            for (lane, value) in pack.iter().enumerate() {
                let i = (4 * p + lane).min(n - 1);
                assert_eq!(*value, x[i], "pack {p}, lane {lane} of {n} states");
            }
        }
        assert!(out.iter().zip(&x).all(|(o, x)| *o == x * x));
    }
}

/// Arrays of every length from 1 to 9 (whole blocks of four entries and every remainder,
/// which the unpacking takes by one more transpose), nested too, through `map1` and
/// `map1_into` for every number of states from 0 to 9: each result is its state.
#[test]
fn arrays_of_every_length_unpack_to_their_states() {
    fn value(i: usize, k: usize) -> f64 {
        (100 * i + k) as f64 + 0.5
    }
    macro_rules! lengths {
        ($($k:literal),*) => {$(
            for n in 0..=9 {
                let x: Vec<[f64; $k]> = (0..n).map(|i| core::array::from_fn(|k| value(i, k))).collect();
                let mut out = vec![[f64::NAN; $k]; n];
                assert_eq!(map1(&x, &mut out, |p: &[F64x4; $k]| *p), Ok(()));
                assert_eq!(out, x, "{} entries, {n} states", $k);
                let nested: Vec<[[f64; $k]; 2]> = x.iter().map(|r| [*r, r.map(|v| -v)]).collect();
                let mut out = vec![[[f64::NAN; $k]; 2]; n];
                let copy = |p: &[[F64x4; $k]; 2], o: &mut [[F64x4; $k]; 2]| *o = *p;
                assert_eq!(map1_into(&nested, &mut out, copy), Ok(()));
                assert_eq!(out, nested, "2 × {} entries, {n} states", $k);
            }
        )*};
    }
    lengths!(1, 2, 3, 4, 5, 6, 7, 8, 9);
}

/// A pair and a triple as outputs (and inputs).
#[test]
fn tuples_pack_and_unpack() {
    let x: Vec<([f64; 2], f64)> = (0..6).map(|i| ([i as f64, 1.0], 0.5 * i as f64)).collect();
    let mut out = vec![(0.0, [0.0; 2], 0.0); 6];
    let result = map1(&x, &mut out, |(a, b): &([F64x4; 2], F64x4)| {
        (a[0] + *b, [a[1], -a[0]], a[0] * *b)
    });
    assert_eq!(result, Ok(()));
    for (i, o) in out.iter().enumerate() {
        let (a, b) = x[i];
        assert_eq!(*o, (a[0] + b, [a[1], -a[0]], a[0] * b));
    }
}

/// A slice of the wrong length, in any position: the first such input named, `out` left
/// as it was, `f` never called.
#[test]
fn a_length_mismatch_is_an_error_and_writes_nothing() {
    let (long, short) = (vec![1.0_f64; 5], vec![1.0_f64; 4]);
    let mut out = vec![7.0; 5];
    let never = |_: &F64x4, _: &F64x4, _: &F64x4| -> F64x4 { unreachable!("not called") };
    for position in 0..3 {
        let arg = |k: usize| if k == position { &short } else { &long };
        assert_eq!(
            map3(arg(0), arg(1), arg(2), &mut out, never),
            Err(LengthMismatch {
                input: position,
                len: 4,
                expected: 5
            })
        );
    }
    assert_eq!(
        map1(&long, &mut out[..3], |x: &F64x4| *x),
        Err(LengthMismatch {
            input: 0,
            len: 5,
            expected: 3
        })
    );
    assert_eq!(out, [7.0; 5]);
    assert_eq!(
        map2(&short, &long, &mut out, |x: &F64x4, _: &F64x4| *x),
        Err(LengthMismatch {
            input: 0,
            len: 4,
            expected: 5
        })
    );
    let err = LengthMismatch {
        input: 2,
        len: 4,
        expected: 5,
    };
    assert_eq!(
        err.to_string(),
        "input 2 of the batch holds 4 states, the output 5"
    );
}

/// The parallel helpers give the sequential helpers' bits, for lengths around the task
/// size, and the same errors.
#[cfg(feature = "rayon")]
#[test]
fn the_parallel_helpers_are_the_sequential_ones() {
    use super::{par_map1, par_map2, par_map3};
    for n in [0, 1, 3, 63, 64, 65, 200, 1001] {
        let (q, v): (Vec<_>, Vec<_>) = (0..n).map(state).unzip();
        let (mut seq, mut par) = (vec![[[0.0; 3]; 2]; n], vec![[[1.0; 3]; 2]; n]);
        assert_eq!(map2(&q, &v, &mut seq, arm), Ok(()));
        assert_eq!(par_map2(&q, &v, &mut par, arm), Ok(()));
        assert!(seq.iter().zip(&par).all(|(s, p)| bits(s) == bits(p)), "{n}");
        let mut single = vec![0.0; n];
        assert_eq!(par_map1(&q, &mut single, |q| q[0] * q[1]), Ok(()));
        assert!(single.iter().zip(&q).all(|(s, q)| *s == q[0] * q[1]));
        let zero = ([[0.0; 6]; 5], [0.0; 7]);
        let (mut seq_into, mut par_into) = (vec![zero; n], vec![zero; n]);
        assert_eq!(map2_into(&q, &v, &mut seq_into, wide_into), Ok(()));
        assert_eq!(
            super::par_map2_into(&q, &v, &mut par_into, wide_into),
            Ok(())
        );
        assert!(seq_into
            .iter()
            .zip(&par_into)
            .all(|(s, p)| wide_bits(s) == wide_bits(p)));
    }
    let mut out = vec![0.0; 3];
    assert_eq!(
        par_map3(
            &[1.0; 3],
            &[1.0; 3],
            &[1.0; 2],
            &mut out,
            |a: &F64x4, _, _| *a
        ),
        Err(LengthMismatch {
            input: 2,
            len: 2,
            expected: 3
        })
    );
}
