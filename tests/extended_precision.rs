//! The generated code and the reference in double-double (~32 digits), and the f64 and f32
//! errors of the generated code measured against its own double-double evaluation (the same
//! folded constants, so the difference is the arithmetic's rounding alone).
//!
//! The generator folds derived constants (I_P = I_G − m ĉ², composite inertias, merged
//! parts, rotations) in f64 at compile time, while the reference derives them in the scalar
//! it runs in: in double-double the two therefore differ by the f64 rounding of those
//! constants (~1e-16 relative), which bounds how exactly an f64 model is known anyway.

use dynamics_runtime::{DoubleDouble, Reference};
use dynamics_tests::random::SplitMix;
use dynamics_tests::{max_abs_dd, max_abs_diff_dd};
use models::anchors::{Panda, Ur5};
use nalgebra::DMatrix;

type Dd = DoubleDouble;

/// Error of an f64 result against a double-double one, relative to `1 + max |exact|`.
fn relative(got: &[f64], exact: &[Dd]) -> f64 {
    max_abs_diff_dd(got, exact) / (1.0 + max_abs_dd(exact))
}

macro_rules! extended_precision {
    ($($test:ident: $m:ty, $nv:expr;)*) => {$(
        #[test]
        fn $test() {
            use dynamics_runtime::Mechanism;
            let model = <$m>::model();
            let mut reference = Reference::<Dd>::new(&model);
            let mut rng = SplitMix(99);
            let (mut worst_f64, mut worst_f32, mut gen_vs_ref) = (0.0_f64, 0.0_f64, 0.0_f64);
            for _ in 0..10 {
                let draw = |rng: &mut SplitMix, s: f64| -> [f64; $nv] { std::array::from_fn(|_| rng.uniform(-s, s)) };
                let (q, v, a) = (draw(&mut rng, 3.0), draw(&mut rng, 2.0), draw(&mut rng, 3.0));
                let (qd, vd, ad) = (q.map(Dd::new), v.map(Dd::new), a.map(Dd::new));
                // Inverse dynamics: generated in double-double against reference in double-double.
                let exact = <$m>::inverse_dynamics(&qd, &vd, &ad);
                let mut tau_ref = vec![Dd::new(0.0); $nv];
                reference.inverse_dynamics(&qd, &vd, &ad, None, &mut tau_ref).expect("sizes");
                let spread = exact.iter().zip(&tau_ref).fold(0.0_f64, |m, (x, y)| m.max((*x - *y).abs().to_f64()));
                gen_vs_ref = gen_vs_ref.max(spread / (1.0 + exact.iter().fold(0.0_f64, |m, x| m.max(x.to_f64().abs()))));
                worst_f64 = worst_f64.max(relative(&<$m>::inverse_dynamics(&q, &v, &a), &exact));
                let (q32, v32, a32) = (q.map(|x| x as f32), v.map(|x| x as f32), a.map(|x| x as f32));
                let id32: Vec<f64> = <$m>::inverse_dynamics(&q32, &v32, &a32).iter().map(|&x| f64::from(x)).collect();
                worst_f32 = worst_f32.max(relative(&id32, &exact));
                // Mass matrix, the same way.
                let m_exact = <$m>::mass_matrix(&qd);
                let mut m_ref = DMatrix::from_element($nv, $nv, Dd::new(0.0));
                reference.mass_matrix(&qd, &mut m_ref).expect("sizes");
                for i in 0..$nv {
                    for j in 0..$nv {
                        gen_vs_ref = gen_vs_ref.max((m_exact[i][j] - m_ref[(i, j)]).abs().to_f64());
                    }
                }
                let m64 = <$m>::mass_matrix(&q);
                let flat_exact: Vec<Dd> = m_exact.iter().flatten().copied().collect();
                worst_f64 = worst_f64.max(relative(m64.as_flattened(), &flat_exact));
            }
            println!("{}: generated vs reference, both in double-double: {gen_vs_ref:.1e} (constant rounding); generated f64 error {worst_f64:.1e}, f32 error {worst_f32:.1e} (against generated double-double)", <$m>::NAME);
            // Independent algorithms agree to the rounding of the folded f64 constants.
            assert!(gen_vs_ref < 1e-14, "{gen_vs_ref}");
            // f64 carries ~16 digits through the whole expansion; f32 ~7.
            assert!(worst_f64 < 1e-14, "{worst_f64}");
            assert!(worst_f32 < 1e-5, "{worst_f32}");
        }
    )*};
}

extended_precision! {
    ur5: Ur5, 6;
    panda: Panda, 7;
}
