//! The speed–accuracy charts, measured and drawn in one run:
//!
//! - `docs/speed_accuracy.svg`: inverse dynamics, mass matrix and forward dynamics of the
//!   UR5, every method × precision (generated and reference, f64 and f32; forward dynamics
//!   by the articulated-body algorithm and by LDLᵀ of M) as ns/call against the relative
//!   error versus the reference evaluated in double-double (~32 digits), over the same
//!   states;
//! - `docs/simulation_accuracy.svg`: the integrators on the double pendulum (explicit and
//!   semi-implicit Euler, RK4, implicit midpoint, the symplectic variational midpoint), each
//!   step size a point of cost per simulated second against the energy drift and the
//!   trajectory error after 5 s (against RK4 at a 10 µs step).
//!
//! Run with `cargo run --release -p models --example charts`.

use dynamics_runtime::integrators::{self, Inputs, State};
use dynamics_runtime::{mechanism, DoubleDouble as Dd, Energy, Mechanism, Reference};
use models::anchors::{DoublePendulum, Ur5};
use nalgebra::DMatrix;
use plotters::prelude::*;
use std::hint::black_box;
use std::time::Instant;
use support::{median_ns, uniform};

mod support;

mechanism! {
    /// The UR5 (from its URDF twin) with both forward-dynamics methods, by name.
    pub struct Ur5Methods;
    urdf: "urdf/ur5.urdf";
    gravity: [0.0, 0.0, -9.81];
    outputs: [forward_dynamics_aba, forward_dynamics_ldlt];
}

const STATES: usize = 20;

fn relative(got: &[f64], exact: &[Dd]) -> f64 {
    let scale = 1.0 + exact.iter().fold(0.0_f64, |m, x| m.max(x.to_f64().abs()));
    let error = got.iter().zip(exact).fold(0.0_f64, |m, (g, e)| {
        m.max((Dd::new(*g) - *e).abs().to_f64())
    });
    (error / scale).max(1e-17)
}

/// One point of the first chart.
struct Point {
    function: &'static str,
    method: &'static str,
    ns: f64,
    error: f64,
}

fn dynamics_points() -> Vec<Point> {
    let model = Ur5::model();
    let mut exact = Reference::<Dd>::new(&model);
    let (mut r64, mut r32) = (Reference::<f64>::new(&model), Reference::<f32>::new(&model));
    let mut seed = 7;
    let states: Vec<[[f64; 6]; 3]> = (0..STATES)
        .map(|_| std::array::from_fn(|_| std::array::from_fn(|_| uniform(&mut seed, -2.0, 2.0))))
        .collect();
    let dd = |x: &[f64; 6]| x.map(Dd::new);
    let narrow = |x: &[f64; 6]| x.map(|y| y as f32);
    let widen32 = |x: &[f32]| x.iter().map(|&y| f64::from(y)).collect::<Vec<f64>>();
    let mut points = Vec::new();
    let mut error = std::collections::HashMap::<(&str, &str), f64>::new();
    let mut note = |f: &'static str, m: &'static str, e: f64| {
        let slot = error.entry((f, m)).or_insert(0.0);
        *slot = slot.max(e);
    };
    let (mut out, mut out32) = (vec![Dd::new(0.0); 6], vec![0.0_f32; 6]);
    let mut out64 = vec![0.0; 6];
    let (mut m_dd, mut m64, mut m32) = (
        DMatrix::from_element(6, 6, Dd::new(0.0)),
        DMatrix::zeros(6, 6),
        DMatrix::from_element(6, 6, 0.0_f32),
    );
    for [q, v, a] in &states {
        exact
            .inverse_dynamics(&dd(q), &dd(v), &dd(a), None, &mut out)
            .expect("sizes");
        note(
            "inverse dynamics",
            "generated f64",
            relative(&Ur5::inverse_dynamics(q, v, a), &out),
        );
        note(
            "inverse dynamics",
            "generated f32",
            relative(
                &widen32(&Ur5::inverse_dynamics(&narrow(q), &narrow(v), &narrow(a))),
                &out,
            ),
        );
        r64.inverse_dynamics(q, v, a, None, &mut out64)
            .expect("sizes");
        note("inverse dynamics", "reference f64", relative(&out64, &out));
        r32.inverse_dynamics(&narrow(q), &narrow(v), &narrow(a), None, &mut out32)
            .expect("sizes");
        note(
            "inverse dynamics",
            "reference f32",
            relative(&widen32(&out32), &out),
        );

        exact.mass_matrix(&dd(q), &mut m_dd).expect("sizes");
        let flat_dd: Vec<Dd> = (0..36).map(|k| m_dd[(k / 6, k % 6)]).collect();
        note(
            "mass matrix",
            "generated f64",
            relative(Ur5::mass_matrix(q).as_flattened(), &flat_dd),
        );
        let g32 = Ur5::mass_matrix(&narrow(q));
        note(
            "mass matrix",
            "generated f32",
            relative(&widen32(g32.as_flattened()), &flat_dd),
        );
        r64.mass_matrix(q, &mut m64).expect("sizes");
        note(
            "mass matrix",
            "reference f64",
            relative(
                &(0..36).map(|k| m64[(k / 6, k % 6)]).collect::<Vec<_>>(),
                &flat_dd,
            ),
        );
        r32.mass_matrix(&narrow(q), &mut m32).expect("sizes");
        note(
            "mass matrix",
            "reference f32",
            relative(
                &(0..36)
                    .map(|k| f64::from(m32[(k / 6, k % 6)]))
                    .collect::<Vec<_>>(),
                &flat_dd,
            ),
        );

        let tau = a; // torques of the same scale
        exact
            .forward_dynamics(&dd(q), &dd(v), &dd(tau), None, &mut out)
            .expect("sizes");
        note(
            "forward dynamics",
            "generated ABA f64",
            relative(&Ur5Methods::forward_dynamics_aba(q, v, tau), &out),
        );
        note(
            "forward dynamics",
            "generated LDLT f64",
            relative(&Ur5Methods::forward_dynamics_ldlt(q, v, tau), &out),
        );
        note(
            "forward dynamics",
            "generated ABA f32",
            relative(
                &widen32(&Ur5Methods::forward_dynamics_aba(
                    &narrow(q),
                    &narrow(v),
                    &narrow(tau),
                )),
                &out,
            ),
        );
        note(
            "forward dynamics",
            "generated LDLT f32",
            relative(
                &widen32(&Ur5Methods::forward_dynamics_ldlt(
                    &narrow(q),
                    &narrow(v),
                    &narrow(tau),
                )),
                &out,
            ),
        );
        r64.forward_dynamics(q, v, tau, None, &mut out64)
            .expect("sizes");
        note(
            "forward dynamics",
            "reference ABA f64",
            relative(&out64, &out),
        );
        r32.forward_dynamics(&narrow(q), &narrow(v), &narrow(tau), None, &mut out32)
            .expect("sizes");
        note(
            "forward dynamics",
            "reference ABA f32",
            relative(&widen32(&out32), &out),
        );
    }
    let [q, v, a] = states[0];
    let (q32, v32, a32) = (narrow(&q), narrow(&v), narrow(&a));
    let timings: Vec<(&str, &str, f64)> = vec![
        (
            "inverse dynamics",
            "generated f64",
            median_ns(|| {
                let _ = black_box(Ur5::inverse_dynamics(black_box(&q), &v, &a));
            }),
        ),
        (
            "inverse dynamics",
            "generated f32",
            median_ns(|| {
                let _ = black_box(Ur5::inverse_dynamics(black_box(&q32), &v32, &a32));
            }),
        ),
        (
            "inverse dynamics",
            "reference f64",
            median_ns(|| {
                let _ = black_box(r64.inverse_dynamics(black_box(&q), &v, &a, None, &mut out64));
            }),
        ),
        (
            "inverse dynamics",
            "reference f32",
            median_ns(|| {
                let _ =
                    black_box(r32.inverse_dynamics(black_box(&q32), &v32, &a32, None, &mut out32));
            }),
        ),
        (
            "mass matrix",
            "generated f64",
            median_ns(|| {
                let _ = black_box(Ur5::mass_matrix(black_box(&q)));
            }),
        ),
        (
            "mass matrix",
            "generated f32",
            median_ns(|| {
                let _ = black_box(Ur5::mass_matrix(black_box(&q32)));
            }),
        ),
        (
            "mass matrix",
            "reference f64",
            median_ns(|| {
                let _ = black_box(r64.mass_matrix(black_box(&q), &mut m64));
            }),
        ),
        (
            "mass matrix",
            "reference f32",
            median_ns(|| {
                let _ = black_box(r32.mass_matrix(black_box(&q32), &mut m32));
            }),
        ),
        (
            "forward dynamics",
            "generated ABA f64",
            median_ns(|| {
                let _ = black_box(Ur5Methods::forward_dynamics_aba(black_box(&q), &v, &a));
            }),
        ),
        (
            "forward dynamics",
            "generated LDLT f64",
            median_ns(|| {
                let _ = black_box(Ur5Methods::forward_dynamics_ldlt(black_box(&q), &v, &a));
            }),
        ),
        (
            "forward dynamics",
            "generated ABA f32",
            median_ns(|| {
                let _ = black_box(Ur5Methods::forward_dynamics_aba(
                    black_box(&q32),
                    &v32,
                    &a32,
                ));
            }),
        ),
        (
            "forward dynamics",
            "generated LDLT f32",
            median_ns(|| {
                let _ = black_box(Ur5Methods::forward_dynamics_ldlt(
                    black_box(&q32),
                    &v32,
                    &a32,
                ));
            }),
        ),
        (
            "forward dynamics",
            "reference ABA f64",
            median_ns(|| {
                let _ = black_box(r64.forward_dynamics(black_box(&q), &v, &a, None, &mut out64));
            }),
        ),
        (
            "forward dynamics",
            "reference ABA f32",
            median_ns(|| {
                let _ =
                    black_box(r32.forward_dynamics(black_box(&q32), &v32, &a32, None, &mut out32));
            }),
        ),
    ];
    for (function, method, ns) in timings {
        let e = error.get(&(function, method)).copied().unwrap_or(f64::NAN);
        points.push(Point {
            function,
            method,
            ns,
            error: e,
        });
    }
    points
}

/// One integrator run: cost per simulated second, energy drift and trajectory error at 5 s.
struct Run {
    integrator: &'static str,
    dt: f64,
    ns_per_second: f64,
    energy_drift: f64,
    trajectory_error: f64,
}

type Step = fn(
    &State<f64, DoublePendulum>,
    &Inputs<f64, DoublePendulum>,
    f64,
) -> State<f64, DoublePendulum>;

fn implicit(
    s: &State<f64, DoublePendulum>,
    inputs: &Inputs<f64, DoublePendulum>,
    dt: f64,
) -> State<f64, DoublePendulum> {
    integrators::implicit_midpoint(s, inputs, dt, 1e-12, 30).unwrap_or(State {
        q: [f64::NAN; 2],
        v: [f64::NAN; 2],
    })
}

fn variational(
    s: &State<f64, DoublePendulum>,
    inputs: &Inputs<f64, DoublePendulum>,
    dt: f64,
) -> State<f64, DoublePendulum> {
    integrators::variational_midpoint(s, inputs, dt, 1e-12, 30).unwrap_or(State {
        q: [f64::NAN; 2],
        v: [f64::NAN; 2],
    })
}

fn simulation_runs() -> Vec<Run> {
    let start = State::<f64, DoublePendulum> {
        q: [1.0, 0.5],
        v: [0.0, 0.0],
    };
    let (tau, p, loads) = ([0.0; 2], [0.0; 0], [0.0; 0]);
    let inputs = Inputs::<f64, DoublePendulum> {
        tau: &tau,
        parameters: &p,
        loads: &loads,
    };
    let horizon = 5.0;
    let simulate = |step: Step, dt: f64| {
        let mut s = start;
        for _ in 0..(horizon / dt).round() as usize {
            s = step(&s, &inputs, dt);
        }
        s
    };
    let truth = simulate(integrators::rk4, 1e-5);
    let e0 = DoublePendulum::total_energy(&start.q, &start.v, &p);
    let mut runs = Vec::new();
    let methods: [(&str, Step); 5] = [
        ("explicit Euler", integrators::explicit_euler),
        ("semi-implicit Euler", integrators::semi_implicit_euler),
        ("RK4", integrators::rk4),
        ("implicit midpoint", implicit),
        ("variational midpoint", variational),
    ];
    for (integrator, step) in methods {
        for dt in [1e-2, 4e-3, 1e-3, 2.5e-4] {
            let begin = Instant::now();
            let end = simulate(step, dt);
            let ns_per_second = begin.elapsed().as_nanos() as f64 / horizon;
            let energy_drift = (DoublePendulum::total_energy(&end.q, &end.v, &p) - e0)
                .abs()
                .max(1e-16);
            let trajectory_error = (0..2)
                .map(|k| (end.q[k] - truth.q[k]).abs())
                .fold(0.0, f64::max)
                .max(1e-16);
            runs.push(Run {
                integrator,
                dt,
                ns_per_second,
                energy_drift,
                trajectory_error,
            });
        }
    }
    runs
}

fn color(index: usize) -> RGBColor {
    [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
        RGBColor(214, 39, 40),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(127, 127, 127),
    ][index % 8]
}

fn draw_dynamics(points: &[Point], path: &str) -> Result<(), Box<dyn std::error::Error>> {
    let root = SVGBackend::new(path, (1500, 520)).into_drawing_area();
    root.fill(&WHITE)?;
    let panels = root.split_evenly((1, 3));
    for (panel, function) in
        panels
            .iter()
            .zip(["inverse dynamics", "mass matrix", "forward dynamics"])
    {
        let mine: Vec<&Point> = points.iter().filter(|p| p.function == function).collect();
        let mut chart = ChartBuilder::on(panel)
            .caption(format!("UR5 {function}"), ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(75)
            .build_cartesian_2d((5f64..5000f64).log_scale(), (1e-17f64..1e-3f64).log_scale())?;
        chart
            .configure_mesh()
            .x_desc("ns per call")
            .y_desc("relative error vs 32 digits")
            .x_label_formatter(&|x| format!("{x:.0}"))
            .y_label_formatter(&|y| format!("{y:.0e}"))
            .draw()?;
        for (i, p) in mine.iter().enumerate() {
            let c = color(i);
            chart
                .draw_series(std::iter::once(Circle::new((p.ns, p.error), 6, c.filled())))?
                .label(p.method)
                .legend(move |(x, y)| Circle::new((x, y), 5, c.filled()));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()?;
    }
    root.present()?;
    Ok(())
}

/// A quantity the simulation chart plots, with its label.
type Measure = (&'static str, fn(&Run) -> f64);

fn draw_simulation(runs: &[Run], path: &str) -> Result<(), Box<dyn std::error::Error>> {
    let root = SVGBackend::new(path, (1100, 520)).into_drawing_area();
    root.fill(&WHITE)?;
    let panels = root.split_evenly((1, 2));
    let measures: [Measure; 2] = [
        ("|energy drift| after 5 s (J)", |r| r.energy_drift),
        ("trajectory error after 5 s (rad)", |r| r.trajectory_error),
    ];
    for (panel, (label, measure)) in panels.iter().zip(measures) {
        let mut chart = ChartBuilder::on(panel)
            .caption(format!("double pendulum: {label}"), ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(75)
            .build_cartesian_2d((1e3f64..1e7f64).log_scale(), (1e-14f64..1e2f64).log_scale())?;
        chart
            .configure_mesh()
            .x_desc("ns per simulated second")
            .y_desc(label)
            .x_label_formatter(&|x| format!("{x:.0e}"))
            .y_label_formatter(&|y| format!("{y:.0e}"))
            .draw()?;
        for (i, name) in [
            "explicit Euler",
            "semi-implicit Euler",
            "RK4",
            "implicit midpoint",
            "variational midpoint",
        ]
        .iter()
        .enumerate()
        {
            let c = color(i);
            let series: Vec<(f64, f64)> = runs
                .iter()
                .filter(|r| r.integrator == *name)
                .map(|r| (r.ns_per_second, measure(r).min(1e2)))
                .filter(|(_, y)| y.is_finite())
                .collect();
            chart
                .draw_series(LineSeries::new(series.clone(), c.stroke_width(2)))?
                .label(*name)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 16, y)], c.stroke_width(2))
                });
            chart.draw_series(series.into_iter().map(|p| Circle::new(p, 4, c.filled())))?;
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()?;
    }
    root.present()?;
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let docs = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs");
    std::fs::create_dir_all(&docs)?;
    let points = dynamics_points();
    println!(
        "{:<18} {:<20} {:>10} {:>12}",
        "function", "method", "ns/call", "rel. error"
    );
    for p in &points {
        println!(
            "{:<18} {:<20} {:>10.1} {:>12.1e}",
            p.function, p.method, p.ns, p.error
        );
    }
    let runs = simulation_runs();
    println!();
    println!(
        "{:<21} {:>8} {:>14} {:>12} {:>12}",
        "integrator", "dt", "ns per sim s", "|ΔE| (J)", "traj. err"
    );
    for r in &runs {
        println!(
            "{:<21} {:>8.1e} {:>14.3e} {:>12.2e} {:>12.2e}",
            r.integrator, r.dt, r.ns_per_second, r.energy_drift, r.trajectory_error
        );
    }
    let speed = docs.join("speed_accuracy.svg");
    let simulation = docs.join("simulation_accuracy.svg");
    draw_dynamics(&points, &speed.to_string_lossy())?;
    draw_simulation(&runs, &simulation.to_string_lossy())?;
    println!();
    println!("wrote {} and {}", speed.display(), simulation.display());
    Ok(())
}
