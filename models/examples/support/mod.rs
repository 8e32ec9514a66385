//! What the examples share: timing, a small deterministic generator, and how generated
//! outputs are compared with the reference's.

use std::time::Instant;

/// Median over 7 runs of the time per call of `f`, each run 20 000 calls, in ns.
pub fn median_ns(mut f: impl FnMut()) -> f64 {
    let mut runs: Vec<f64> = (0..7)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..20_000 {
                f();
            }
            start.elapsed().as_nanos() as f64 / 20_000.0
        })
        .collect();
    runs.sort_by(f64::total_cmp);
    runs[3]
}

/// A uniform number in [lo, hi) from a 64-bit linear congruential generator.
pub fn uniform(seed: &mut u64, lo: f64, hi: f64) -> f64 {
    *seed = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    lo + (hi - lo) * ((*seed >> 11) as f64 / (1u64 << 53) as f64)
}

/// max |generated − reference| / (1 + max |reference|): the difference the examples report.
#[allow(dead_code)] // each example compiles this module; charts.rs compares with double-double
pub fn relative_difference(generated: &[f64], reference: &[f64]) -> f64 {
    let scale = 1.0 + reference.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    generated
        .iter()
        .zip(reference)
        .fold(0.0_f64, |m, (g, r)| m.max((g - r).abs()))
        / scale
}
