//! Seeded states for the throughput benchmarks (`lanes.rs`, `batch.rs`): a fixed SplitMix64
//! stream, so every run times the same numbers.

use std::f64::consts::PI;

/// SplitMix64 in [lo, hi).
pub struct Rng(pub u64);

impl Rng {
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        lo + (hi - lo) * ((z >> 11) as f64 / (1u64 << 53) as f64)
    }

    pub fn array<const K: usize>(&mut self, lo: f64, hi: f64) -> [f64; K] {
        std::array::from_fn(|_| self.uniform(lo, hi))
    }
}

/// `count` states of one model, each field a slice: angles in ±π (the unit quaternion of a
/// free joint normalized, when NQ = NV + 1), rates in ±2, accelerations and torques in ±5,
/// loads in [−20, 40].
pub struct States<const NQ: usize, const NV: usize, const NL: usize> {
    pub q: Vec<[f64; NQ]>,
    pub v: Vec<[f64; NV]>,
    pub a: Vec<[f64; NV]>,
    pub tau: Vec<[f64; NV]>,
    pub loads: Vec<[f64; NL]>,
}

impl<const NQ: usize, const NV: usize, const NL: usize> States<NQ, NV, NL> {
    pub fn new(seed: u64, count: usize) -> Self {
        let mut rng = Rng(seed);
        let q = (0..count)
            .map(|_| {
                let mut q: [f64; NQ] = rng.array(-PI, PI);
                if NQ == NV + 1 {
                    let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
                    q[3..7].iter_mut().for_each(|x| *x /= norm);
                }
                q
            })
            .collect();
        Self {
            q,
            v: (0..count).map(|_| rng.array(-2.0, 2.0)).collect(),
            a: (0..count).map(|_| rng.array(-5.0, 5.0)).collect(),
            tau: (0..count).map(|_| rng.array(-5.0, 5.0)).collect(),
            loads: (0..count).map(|_| rng.array(-20.0, 40.0)).collect(),
        }
    }
}
