//! Two versions of one model's generated code timed in one process (see
//! `../generated_ab.sh`), by `models/examples/support/paired.rs`: for each function each
//! side's median ns and the median of the per-round ratios B/A. The two versions' results
//! must agree to 1e-12 first.

#![allow(dead_code)] // the generated files hold functions the harness does not time

mod paired;

/// One line: A's and B's median ns and the median ratio B/A.
fn line<S, RA, RB>(name: &str, states: &[S], fa: impl Fn(&S) -> RA, fb: impl Fn(&S) -> RB) {
    let [a, b, ratio] = paired::paired(
        |_| {},
        |side, c| {
            let s = &states[c % states.len()];
            if side == 0 {
                std::hint::black_box(fa(s));
            } else {
                std::hint::black_box(fb(s));
            }
        },
    );
    println!("{name:<20} A {a:>9.1} ns  B {b:>9.1} ns  B/A {ratio:>6.3}");
}

fn close(a: &[f64], b: &[f64]) -> bool {
    a.iter()
        .zip(b)
        .all(|(x, y)| (x - y).abs() <= 1e-12 * (1.0 + x.abs()))
}

/// A call with zero loads (`loads`) or without them (`none`).
macro_rules! call {
    (loads, $t:ty, $f:ident, $s:ident) => {
        <$t>::$f(&$s.0, &$s.1, &$s.2, &Default::default())
    };
    (none, $t:ty, $f:ident, $s:ident) => {
        <$t>::$f(&$s.0, &$s.1, &$s.2)
    };
}

/// The lines besides the six: none (`plain`), or the `_into` twins of the mass and Coriolis
/// matrices, M⁻¹ and ∂τ too (`public`, the public robots; ∂τ checked first).
macro_rules! extra {
    (plain, $a:ty, $b:ty, $states:expr) => {};
    (public, $a:ty, $b:ty, $states:expr) => {
        // The `_into` twins write into one buffer, the same for both sides and kept across
        // calls: where an output lies moves its time by up to 1.4× (g1's mass matrix,
        // BENCHMARKS.md), so a buffer a side would time the placements as much as the code.
        // First both sides' twins must give A's returned values.
        let s0 = &$states[0];
        let (ma, mb) = (std::cell::RefCell::new(<$a>::mass_matrix(&s0.0)), std::cell::RefCell::new(<$b>::mass_matrix(&s0.0)));
        for s in $states {
            let (m, n) = (&mut *ma.borrow_mut(), &mut *mb.borrow_mut());
            <$a>::mass_matrix_into(&s.0, m);
            <$b>::mass_matrix_into(&s.0, n);
            assert!(close(m.as_flattened(), <$a>::mass_matrix(&s.0).as_flattened()) && close(n.as_flattened(), m.as_flattened()), "mass_matrix_into disagrees");
            <$a>::coriolis_matrix_into(&s.0, &s.1, m);
            <$b>::coriolis_matrix_into(&s.0, &s.1, n);
            assert!(close(m.as_flattened(), <$a>::coriolis_matrix(&s.0, &s.1).as_flattened()) && close(n.as_flattened(), m.as_flattened()), "coriolis_matrix_into disagrees");
        }
        line("mass_matrix_into", $states, |s| { let m = &mut *ma.borrow_mut(); <$a>::mass_matrix_into(&s.0, m); std::hint::black_box(m); }, |s| { let m = &mut *ma.borrow_mut(); <$b>::mass_matrix_into(&s.0, m); std::hint::black_box(m); });
        line("coriolis_matrix_into", $states, |s| { let m = &mut *ma.borrow_mut(); <$a>::coriolis_matrix_into(&s.0, &s.1, m); std::hint::black_box(m); }, |s| { let m = &mut *ma.borrow_mut(); <$b>::coriolis_matrix_into(&s.0, &s.1, m); std::hint::black_box(m); });
        line("mass_matrix_inverse", $states, |s| <$a>::mass_matrix_inverse(&s.0), |s| <$b>::mass_matrix_inverse(&s.0));
        for s in $states {
            let (da, db) = (<$a>::inverse_dynamics_derivatives(&s.0, &s.1, &s.2), <$b>::inverse_dynamics_derivatives(&s.0, &s.1, &s.2));
            for (x, y) in [(da.0, db.0), (da.1, db.1)] {
                assert!(close(x.as_flattened(), y.as_flattened()), "A and B disagree on ∂τ");
            }
        }
        line("inverse_dynamics_der", $states, |s| <$a>::inverse_dynamics_derivatives(&s.0, &s.1, &s.2), |s| <$b>::inverse_dynamics_derivatives(&s.0, &s.1, &s.2));
    };
}

macro_rules! compare {
    ($a:ty, $b:ty, $states:expr, $loads:ident) => {
        compare!($a, $b, $states, $loads, plain)
    };
    ($a:ty, $b:ty, $states:expr, $loads:ident, $extra:ident) => {{
        let states = $states;
        for s in &states {
            let (ca, cb) = (<$a>::coriolis_matrix(&s.0, &s.1), <$b>::coriolis_matrix(&s.0, &s.1));
            assert!(close(ca.as_flattened(), cb.as_flattened()), "A and B disagree");
        }
        line("coriolis_matrix", &states, |s| <$a>::coriolis_matrix(&s.0, &s.1), |s| <$b>::coriolis_matrix(&s.0, &s.1));
        line("forward_dynamics", &states, |s| call!($loads, $a, forward_dynamics, s), |s| call!($loads, $b, forward_dynamics, s));
        line("mass_matrix", &states, |s| <$a>::mass_matrix(&s.0), |s| <$b>::mass_matrix(&s.0));
        line("inverse_dynamics", &states, |s| call!($loads, $a, inverse_dynamics, s), |s| call!($loads, $b, inverse_dynamics, s));
        line("bias", &states, |s| <$a>::bias(&s.0, &s.1), |s| <$b>::bias(&s.0, &s.1));
        line("gravity", &states, |s| <$a>::gravity(&s.0), |s| <$b>::gravity(&s.0));
        extra!($extra, $a, $b, &states);
    }};
}

// The model's call, written by generated_ab.sh: `compare!(a::Robot, b::Robot, states, …)`.
mod a;
mod b;
mod run;

fn main() {
    run::run();
}
