//! The main demo: mechanisms declared with `mechanism!`, their generated dynamics on the
//! textbook's worked examples, and, for every bundled model, what the generated code costs
//! (operation counts, time per call) and how far it is from the independent reference.
//!
//! Run with `cargo run --release -p models --example demo`.

use dynamics_runtime::Wrench;
use dynamics_runtime::{DoubleDouble as Dd, Mechanism, Model, Reference};
use models::anchors::{DoublePendulum, Panda, Pendulum, Planar3, Ur5};
use models::puma560::Puma560;
use models::scenes::{PlanarArm, PlanarArmIn3d};
use models::seed::{EccentricRotor, FallingRod, GyroscopicBody};
use nalgebra::DMatrix;
use std::hint::black_box;
use support::{median_ns, relative_difference, uniform};

mod support;

/// Reports one bundled model, with closures over its generated functions.
macro_rules! report {
    ($m:ident) => {
        report::<$m>(
            |q, v, a, out| out.copy_from_slice(&$m::inverse_dynamics(&arr(q), &arr(v), &arr(a))),
            |q, out| out.copy_from_slice($m::mass_matrix(&arr(q)).as_flattened()),
            |q, v, t, out| out.copy_from_slice(&$m::forward_dynamics(&arr(q), &arr(v), &arr(t))),
            |q, v, a, out| out.copy_from_slice(&$m::inverse_dynamics(&arr(q), &arr(v), &arr(a))),
        )
    };
}

fn main() {
    textbook_examples();
    println!();
    println!("Bundled models: generated code vs the runtime reference (40 random states, f64)");
    println!(
        "{:<16} {:>3}  {:<18} {:>6} {:>6} {:>4} {:>5}  {:>9} {:>9}  {:>9} {:>9} {:>7}",
        "model",
        "dof",
        "function",
        "mul",
        "add",
        "div",
        "trig",
        "vs ref",
        "vs 32 dig",
        "gen ns",
        "ref ns",
        "speedup"
    );
    report!(Pendulum);
    report!(DoublePendulum);
    report!(Planar3);
    report!(Ur5);
    report!(Puma560);
    report!(Panda);
    report!(PlanarArm);
    report!(PlanarArmIn3d);
    println!();
    println!("vs ref: max |generated − reference| / (1 + max |reference|) in f64; vs 32 dig: the generated f64");
    println!("inverse dynamics against the same code in double-double (~32 digits); times: median of 7 × 20 000 calls.");
    println!("PlanarArm and PlanarArmIn3d are one arm: declared planar, and with every body frame turned (3-D).");
    println!("The speed-accuracy chart: docs/speed_accuracy.svg (cargo run --release -p models --example charts).");
    println!("See the generated code of any model with: cargo run -p dynamics-codegen -- models/src/anchors.rs --only Ur5");
}

fn arr<T: Copy, const N: usize>(x: &[T]) -> [T; N] {
    std::array::from_fn(|i| x[i])
}

/// The textbook's worked numbers, computed by generated code.
fn textbook_examples() {
    println!("The textbook's worked examples (Satici, ch. 10), computed by generated code");
    let theta = 30f64.to_radians();
    let qdd = FallingRod::forward_dynamics(&[theta], &[0.0], &[0.0])[0];
    println!(
        "  falling rod, released at 30°:   θ̈ = {qdd:.4} rad/s²            (textbook: −12.2625)"
    );
    let hold = FallingRod::gravity(&[theta])[0];
    println!(
        "  holding torque at 30°:          τ = {hold:.4} N·m               (textbook: +2.943)"
    );
    let w = FallingRod::joint_reactions(&[theta], &[0.0], &[qdd])[0];
    let (s, c) = theta.sin_cos();
    let (rx, ry) = (c * w[0] - s * w[1], s * w[0] + c * w[1]);
    println!("  pin reaction on the rod:        R = ({rx:.3}, {ry:.3}) N         (textbook: (−6.372, 15.941))");
    let tau = GyroscopicBody::inverse_dynamics(
        &[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0],
        &[0.0, 0.0, 0.0, 1.0, 2.0, 3.0],
        &[0.0; 6],
    );
    println!(
        "  gyroscopic torque ω × I_G ω:    M = ({:.1}, {:.1}, {:.1}) N·m        (textbook: (0.6, −0.6, 0.2))",
        tau[3], tau[4], tau[5]
    );
    for omega in [100.0_f64, 200.0] {
        let w = EccentricRotor::joint_reactions(&[0.0], &[omega], &[0.0])[0];
        let f = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
        println!(
            "  eccentric rotor at {omega:>3} rad/s: bearing force m e ω² = {f:.1} N   (textbook: {})",
            if omega < 150.0 { "20 N" } else { "80 N" }
        );
    }
    // Energy check: Ė = τ θ̇ along a driven motion, by central differences.
    let (th, thd, torque) = (0.4_f64, 1.1_f64, 0.7_f64);
    let thdd = FallingRod::forward_dynamics(&[th], &[thd], &[torque])[0];
    let energy = |t: f64| {
        let (q, v) = (th + thd * t + 0.5 * thdd * t * t, thd + thdd * t);
        FallingRod::kinetic_energy(&[q], &[v]) + FallingRod::potential_energy(&[q])
    };
    let h = 1e-5;
    let rate = (energy(h) - energy(-h)) / (2.0 * h);
    println!(
        "  energy check:                   dE/dt = {rate:.6} W, τ θ̇ = {:.6} W",
        torque * thd
    );
}

/// Generated inverse dynamics, writing τ into the last slice.
type Id = fn(&[f64], &[f64], &[f64], &mut [f64]);
/// Generated mass matrix, writing M by rows into the last slice.
type Mm = fn(&[f64], &mut [f64]);
/// Generated forward dynamics, writing q̈ into the last slice.
type Fd = fn(&[f64], &[f64], &[f64], &mut [f64]);
/// Generated inverse dynamics in double-double.
type IdDd = fn(&[Dd], &[Dd], &[Dd], &mut [Dd]);

fn report<M: Mechanism>(id: Id, mm: Mm, fd: Fd, id_dd: IdDd) {
    let model: Model = M::model();
    let mut reference = Reference::<f64>::new(&model);
    let nv = model.nv();
    let mut seed = 42;
    let states: Vec<[Vec<f64>; 4]> = (0..40)
        .map(|_| std::array::from_fn(|_| (0..nv).map(|_| uniform(&mut seed, -2.0, 2.0)).collect()))
        .collect();
    let (mut out, mut m) = (vec![0.0; nv], DMatrix::zeros(nv, nv));
    let (mut gen, mut gen_m) = (vec![0.0; nv], vec![0.0; nv * nv]);
    let mut err = [0.0_f64; 3];
    let mut err_dd = 0.0_f64;
    let mut exact = vec![Dd::new(0.0); nv];
    for [q, v, a, t] in &states {
        reference
            .inverse_dynamics(q, v, a, None::<&[Wrench<f64>]>, &mut out)
            .expect("sizes");
        id(q, v, a, &mut gen);
        err[0] = err[0].max(relative_difference(&gen, &out));
        let widen = |x: &[f64]| x.iter().map(|&y| Dd::new(y)).collect::<Vec<_>>();
        id_dd(&widen(q), &widen(v), &widen(a), &mut exact);
        let scale = 1.0 + exact.iter().fold(0.0_f64, |m, x| m.max(x.to_f64().abs()));
        let dd_error = gen.iter().zip(&exact).fold(0.0_f64, |m, (g, e)| {
            m.max((Dd::new(*g) - *e).abs().to_f64())
        });
        err_dd = err_dd.max(dd_error / scale);
        reference.mass_matrix(q, &mut m).expect("sizes");
        let rows: Vec<f64> = (0..nv)
            .flat_map(|i| (0..nv).map(move |j| (i, j)))
            .map(|(i, j)| m[(i, j)])
            .collect();
        mm(q, &mut gen_m);
        err[1] = err[1].max(relative_difference(&gen_m, &rows));
        reference
            .forward_dynamics(q, v, t, None, &mut out)
            .expect("sizes");
        fd(q, v, t, &mut gen);
        err[2] = err[2].max(relative_difference(&gen, &out));
    }
    let [q, v, a, t] = &states[0];
    let timings = [
        (
            median_ns(|| {
                id(
                    black_box(q),
                    black_box(v),
                    black_box(a),
                    black_box(&mut gen),
                )
            }),
            median_ns(|| {
                let _ = black_box(reference.inverse_dynamics(black_box(q), v, a, None, &mut out));
            }),
        ),
        (
            median_ns(|| mm(black_box(q), black_box(&mut gen_m))),
            median_ns(|| {
                let _ = black_box(reference.mass_matrix(black_box(q), &mut m));
            }),
        ),
        (
            median_ns(|| {
                fd(
                    black_box(q),
                    black_box(v),
                    black_box(t),
                    black_box(&mut gen),
                )
            }),
            median_ns(|| {
                let _ = black_box(reference.forward_dynamics(black_box(q), v, t, None, &mut out));
            }),
        ),
    ];
    for (k, name) in ["inverse_dynamics", "mass_matrix", "forward_dynamics"]
        .iter()
        .enumerate()
    {
        let cost = M::FUNCTIONS.iter().find(|f| f.name == *name).copied();
        let (mul, add, div, trig) = cost.map_or((0, 0, 0, 0), |c| (c.mul, c.add, c.div, c.trig));
        let (gen_ns, ref_ns) = timings[k];
        println!(
            "{:<16} {:>3}  {:<18} {:>6} {:>6} {:>4} {:>5}  {:>9.1e} {:>9}  {:>9.1} {:>9.1} {:>6.1}×",
            if k == 0 { M::NAME } else { "" },
            if k == 0 {
                nv.to_string()
            } else {
                String::new()
            },
            name,
            mul,
            add,
            div,
            trig,
            err[k],
            if k == 0 { format!("{err_dd:.1e}") } else { String::new() },
            gen_ns,
            ref_ns,
            ref_ns / gen_ns
        );
    }
}
