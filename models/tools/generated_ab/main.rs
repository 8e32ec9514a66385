//! Two versions of one model's generated code timed in one process, paired (see
//! `../generated_ab.sh`): 41 rounds, each timing A and B back to back (20 000 calls over 20
//! fixed random states, the order alternating); prints each side's median ns and the median
//! of the per-round ratios B/A. The results must agree to 1e-12 first.

#![allow(dead_code)] // the generated files hold functions the harness does not time

use std::hint::black_box;
use std::time::Instant;

const ROUNDS: usize = 41;
const CALLS: usize = 20_000;

pub(crate) fn paired<S, RA, RB>(name: &str, states: &[S], fa: impl Fn(&S) -> RA, fb: impl Fn(&S) -> RB) {
    let (mut ta, mut tb, mut ratio) = (Vec::new(), Vec::new(), Vec::new());
    for round in 0..ROUNDS {
        let mut ns = [0.0; 2];
        for k in 0..2 {
            let side = if round % 2 == 0 { k } else { 1 - k };
            let start = Instant::now();
            for c in 0..CALLS {
                let s = black_box(&states[c % states.len()]);
                if side == 0 {
                    black_box(fa(s));
                } else {
                    black_box(fb(s));
                }
            }
            ns[side] = start.elapsed().as_nanos() as f64 / CALLS as f64;
        }
        ta.push(ns[0]);
        tb.push(ns[1]);
        ratio.push(ns[1] / ns[0]);
    }
    println!(
        "{name:<20} A {:>9.1} ns  B {:>9.1} ns  B/A {:>6.3}",
        median(ta),
        median(tb),
        median(ratio)
    );
}

fn median(mut x: Vec<f64>) -> f64 {
    x.sort_by(f64::total_cmp);
    x[x.len() / 2]
}

pub(crate) fn close(a: &[f64], b: &[f64]) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-12 * (1.0 + x.abs()))
}

/// States of uniform numbers in [−2, 2) (a fixed xorshift stream), quaternions normalized,
/// loads zero.
pub(crate) fn states<const NQ: usize, const NV: usize, const NL: usize>(
    quaternion_at: Option<usize>,
) -> Vec<([f64; NQ], [f64; NV], [f64; NV], [f64; NL])> {
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
                let n = q[k..k + 4].iter().map(|x| x * x).sum::<f64>().sqrt();
                q[k..k + 4].iter_mut().for_each(|x| *x /= n);
            }
            let v = std::array::from_fn(|_| next());
            (q, v, std::array::from_fn(|_| next()), [0.0; NL])
        })
        .collect()
}

/// A call with the loads (`loads`) or without them (`none`).
macro_rules! call {
    (loads, $t:ty, $f:ident, $s:ident) => {
        <$t>::$f(&$s.0, &$s.1, &$s.2, &$s.3)
    };
    (none, $t:ty, $f:ident, $s:ident) => {
        <$t>::$f(&$s.0, &$s.1, &$s.2)
    };
}

macro_rules! compare {
    ($a:ty, $b:ty, $states:expr, $loads:ident) => {{
        let states = $states;
        for s in &states {
            let (ca, cb) = (<$a>::coriolis_matrix(&s.0, &s.1), <$b>::coriolis_matrix(&s.0, &s.1));
            assert!(close(ca.as_flattened(), cb.as_flattened()), "A and B disagree");
        }
        paired("coriolis_matrix", &states, |s| <$a>::coriolis_matrix(&s.0, &s.1), |s| <$b>::coriolis_matrix(&s.0, &s.1));
        paired("forward_dynamics", &states, |s| call!($loads, $a, forward_dynamics, s), |s| call!($loads, $b, forward_dynamics, s));
        paired("mass_matrix", &states, |s| <$a>::mass_matrix(&s.0), |s| <$b>::mass_matrix(&s.0));
        paired("inverse_dynamics", &states, |s| call!($loads, $a, inverse_dynamics, s), |s| call!($loads, $b, inverse_dynamics, s));
        paired("bias", &states, |s| <$a>::bias(&s.0, &s.1), |s| <$b>::bias(&s.0, &s.1));
        paired("gravity", &states, |s| <$a>::gravity(&s.0), |s| <$b>::gravity(&s.0));
    }};
}

// The model's call, written by generated_ab.sh: `compare!(a::Robot, b::Robot, states, …)`.
mod a;
mod b;
mod run;

fn main() {
    run::run();
}
