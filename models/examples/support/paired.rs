//! Two sides timed against each other in one process, for comparisons smaller than a
//! shared host's drift between two runs: 41 rounds, each timing 20 000 calls of either side
//! back to back, the order alternating; the figure is the median of the per-round ratios.
//! Used by the `isa_ab` example, `models/benches/pinocchio/public_isa.rs`, and
//! `models/tools/generated_ab.sh` and `call_context.sh` (which copy this file into their
//! throwaway crates).

use std::hint::black_box;
use std::time::Instant;

const ROUNDS: usize = 41;
const CALLS: usize = 20_000;

/// The medians of side 0's and side 1's ns per call and of the per-round ratio side 1 /
/// side 0. Each side's calls are `call(side, k)` for k in 0..20 000, after `start(side)`.
pub fn paired<R>(
    mut start: impl FnMut(usize),
    mut call: impl FnMut(usize, usize) -> R,
) -> [f64; 3] {
    let (mut a, mut b, mut ratio) = (Vec::new(), Vec::new(), Vec::new());
    for round in 0..ROUNDS {
        let mut ns = [0.0; 2];
        for k in 0..2 {
            let side = if round % 2 == 0 { k } else { 1 - k };
            start(side);
            let begin = Instant::now();
            for c in 0..CALLS {
                black_box(call(side, black_box(c)));
            }
            ns[side] = begin.elapsed().as_nanos() as f64 / CALLS as f64;
        }
        a.push(ns[0]);
        b.push(ns[1]);
        ratio.push(ns[1] / ns[0]);
    }
    [median(a), median(b), median(ratio)]
}

/// [`paired`] for the two copies of generated code (`dynamics_runtime::isa`): side 0 runs the
/// baseline copies, side 1 the AVX2 + FMA copies (switched with `isa::choose`), each call
/// `f` of the next of `states`. The medians: baseline ns, wide ns, and wide / baseline.
/// Leaves the wide copies chosen.
#[allow(dead_code)] // not every crate that includes this file compares the two copies
pub fn copies<S, R>(states: &[S], f: impl Fn(&S) -> R) -> [f64; 3] {
    paired(
        |side| {
            dynamics_runtime::isa::choose(side == 1);
        },
        |_, c| f(&states[c % states.len()]),
    )
}

/// The median of `x` (the upper one of an even count); `x` must not be empty.
pub fn median(mut x: Vec<f64>) -> f64 {
    x.sort_by(f64::total_cmp);
    x[x.len() / 2]
}

/// 20 states (q, v, a or τ) of uniform numbers in [−2, 2) from a fixed xorshift stream;
/// the unit quaternion at `quaternion_at` in q normalized, if given.
pub fn states<const NQ: usize, const NV: usize>(
    quaternion_at: Option<usize>,
) -> Vec<([f64; NQ], [f64; NV], [f64; NV])> {
    let mut s = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
    };
    (0..20)
        .map(|_| {
            let mut q: [f64; NQ] = std::array::from_fn(|_| next());
            if let Some(k) = quaternion_at {
                let norm = q[k..k + 4].iter().map(|x| x * x).sum::<f64>().sqrt();
                q[k..k + 4].iter_mut().for_each(|x| *x /= norm);
            }
            let v = std::array::from_fn(|_| next());
            (q, v, std::array::from_fn(|_| next()))
        })
        .collect()
}
