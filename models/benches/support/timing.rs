//! The throughput benchmarks' records (`lanes.rs`, `batch.rs`): each benchmark timed under
//! criterion with `iter_custom`, the seconds per iteration of every timed sample kept for
//! the tables printed after criterion's report.

use criterion::measurement::WallTime;
use criterion::BenchmarkGroup;
use std::cell::RefCell;
use std::time::Instant;

thread_local! {
    /// (id, seconds per iteration of each timed sample), in order.
    static TIMES: RefCell<Vec<(String, Vec<f64>)>> = const { RefCell::new(Vec::new()) };
}

/// Times `f` (one call: one iteration) under criterion as `<group>/<id>`, recording each
/// sample's seconds per iteration.
pub fn bench(g: &mut BenchmarkGroup<'_, WallTime>, group: &str, id: &str, mut f: impl FnMut()) {
    let mut times = Vec::new();
    g.bench_function(id, |b| {
        b.iter_custom(|iters| {
            let start = Instant::now();
            for _ in 0..iters {
                f();
            }
            let elapsed = start.elapsed();
            times.push(elapsed.as_secs_f64() / iters as f64);
            elapsed
        })
    });
    if !times.is_empty() {
        TIMES.with(|t| t.borrow_mut().push((format!("{group}/{id}"), times)));
    }
}

/// The ids recorded, in order.
pub fn ids() -> Vec<String> {
    TIMES.with(|t| t.borrow().iter().map(|(id, _)| id.clone()).collect())
}

/// The median of the last `count` samples of `id` (criterion's samples; the calls before
/// them are its warm-up), seconds per iteration; `None` if `id` was not timed.
pub fn median_of_last(id: &str, count: usize) -> Option<f64> {
    TIMES.with(|t| {
        t.borrow()
            .iter()
            .find(|(name, _)| name == id)
            .and_then(|(_, times)| {
                let mut last = times[times.len().saturating_sub(count)..].to_vec();
                last.sort_by(f64::total_cmp);
                last.get(last.len() / 2).copied()
            })
    })
}
