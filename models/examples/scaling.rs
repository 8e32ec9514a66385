//! How the cost grows with the number of joints: the planar chains of `models::chains`
//! (1 to 30 links), inverse dynamics, mass matrix and forward dynamics, the generated code
//! against the runtime reference (`dynamics_runtime::Reference`).
//!
//! For each chain and function: the operation counts the macro recorded
//! (`Mechanism::FUNCTIONS`) and the time per call, generated and reference (the median of
//! 7 × 20 000 calls, the 20 seeded states taken in turn, by `support::median_ns`; the least
//! of three such medians, so that a run slowed by other jobs on the machine does not set
//! the figure). Before timing, the generated outputs are checked against the reference on
//! every state. The bytes of machine code of each generated function (all its pieces) are
//! read from this executable's symbols with `nm -S` where `nm` is installed (`inlined`: the
//! compiler inlined the function into the timing loop). Prints the table, the growth
//! between 10 and 30 joints, the PUMA 560
//! inverse-dynamics count beside the published ones, and draws `docs/scaling.svg` (ns per
//! call and operations against joints, log–log).
//!
//! Run with `cargo run --release -p models --example scaling`.

use dynamics_runtime::{FunctionCost, Mechanism, Reference};
use models::chains::{Chain1, Chain10, Chain15, Chain2, Chain20, Chain25, Chain3, Chain30, Chain5};
use models::puma560::Puma560;
use nalgebra::DMatrix;
use plotters::prelude::*;
use std::collections::HashMap;
use std::f64::consts::PI;
use std::hint::black_box;
use support::{median_ns, relative_difference, uniform};

mod support;

/// Seeded states per chain.
const STATES: usize = 20;
/// Medians per figure; the least is kept.
const MEDIANS: usize = 3;

/// The least of `MEDIANS` medians of `median_ns`.
fn least_median(mut f: impl FnMut()) -> f64 {
    (0..MEDIANS)
        .map(|_| median_ns(&mut f))
        .fold(f64::INFINITY, f64::min)
}

/// The three functions, by the names of their generated functions, and as labelled.
const FUNCTIONS: [(&str, &str); 3] = [
    ("inverse_dynamics", "inverse dynamics"),
    ("mass_matrix", "mass matrix"),
    ("forward_dynamics", "forward dynamics"),
];

/// One chain, one function.
struct Row {
    /// The chain's type name.
    chain: &'static str,
    /// The generated function's name.
    name: &'static str,
    joints: usize,
    function: &'static str,
    cost: FunctionCost,
    generated_ns: f64,
    reference_ns: f64,
    /// Largest difference from the reference over the states, relative to 1 + max |reference|.
    error: f64,
}

impl Row {
    /// Every arithmetic operation the generated function performs.
    fn ops(&self) -> usize {
        self.cost.mul + self.cost.add + self.cost.div + self.cost.sqrt + self.cost.trig
    }
}

fn cost<M: Mechanism>(function: &str) -> FunctionCost {
    *M::FUNCTIONS
        .iter()
        .find(|f| f.name == function)
        .unwrap_or_else(|| panic!("{} has no {function}", M::NAME))
}

/// The three rows of one chain: checks, then times, generated and reference.
macro_rules! measure {
    ($m:ty) => {{
        const N: usize = <$m as Mechanism>::NV;
        let model = <$m>::model();
        let mut reference = Reference::<f64>::new(&model);
        let mut seed = 1000 + N as u64;
        // (q, v, a or τ): angles anywhere on the circle, speeds and accelerations O(1).
        let states: Vec<[[f64; N]; 3]> = (0..STATES)
            .map(|_| {
                [
                    std::array::from_fn(|_| uniform(&mut seed, -PI, PI)),
                    std::array::from_fn(|_| uniform(&mut seed, -2.0, 2.0)),
                    std::array::from_fn(|_| uniform(&mut seed, -5.0, 5.0)),
                ]
            })
            .collect();
        let mut vector = vec![0.0; N];
        let mut matrix = DMatrix::<f64>::zeros(N, N);
        let mut errors = [0.0_f64; 3];
        for [q, v, a] in &states {
            reference
                .inverse_dynamics(q, v, a, None, &mut vector)
                .expect("sizes");
            errors[0] = errors[0].max(relative_difference(
                &<$m>::inverse_dynamics(q, v, a),
                &vector,
            ));
            reference.mass_matrix(q, &mut matrix).expect("sizes");
            let by_rows: Vec<f64> = matrix.transpose().as_slice().to_vec();
            errors[1] = errors[1].max(relative_difference(
                <$m>::mass_matrix(q).as_flattened(),
                &by_rows,
            ));
            reference
                .forward_dynamics(q, v, a, None, &mut vector)
                .expect("sizes");
            errors[2] = errors[2].max(relative_difference(
                &<$m>::forward_dynamics(q, v, a),
                &vector,
            ));
        }
        for (e, (_, label)) in errors.iter().zip(FUNCTIONS) {
            assert!(
                *e < 1e-9,
                "{} {label}: generated and reference differ by {e:e}",
                <$m as Mechanism>::NAME
            );
        }
        // Cycles through the states; the result is kept by reference, not copied.
        let mut k = 0;
        let mut next = || {
            k = (k + 1) % STATES;
            black_box(&states[k])
        };
        let times = [
            (
                least_median(|| {
                    let [q, v, a] = next();
                    black_box(&<$m>::inverse_dynamics(q, v, a));
                }),
                least_median(|| {
                    let [q, v, a] = next();
                    let _ = black_box(reference.inverse_dynamics(q, v, a, None, &mut vector));
                    black_box(&vector);
                }),
            ),
            (
                least_median(|| {
                    let [q, _, _] = next();
                    black_box(&<$m>::mass_matrix(q));
                }),
                least_median(|| {
                    let [q, _, _] = next();
                    let _ = black_box(reference.mass_matrix(q, &mut matrix));
                    black_box(&matrix);
                }),
            ),
            (
                least_median(|| {
                    let [q, v, tau] = next();
                    black_box(&<$m>::forward_dynamics(q, v, tau));
                }),
                least_median(|| {
                    let [q, v, tau] = next();
                    let _ = black_box(reference.forward_dynamics(q, v, tau, None, &mut vector));
                    black_box(&vector);
                }),
            ),
        ];
        FUNCTIONS
            .iter()
            .zip(times)
            .zip(errors)
            .map(
                |((&(name, label), (generated_ns, reference_ns)), error)| Row {
                    chain: <$m as Mechanism>::NAME,
                    name,
                    joints: N,
                    function: label,
                    cost: cost::<$m>(name),
                    generated_ns,
                    reference_ns,
                    error,
                },
            )
            .collect::<Vec<Row>>()
    }};
}

fn color(index: usize) -> RGBColor {
    [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
    ][index % 3]
}

/// Log-scaled joints against a log-scaled quantity.
type LogLog = Cartesian2d<LogCoord<f64>, LogCoord<f64>>;

/// One panel of the chart: joints (1 to 30) against `y_desc` (1 to 10⁵), both on log scales,
/// with its caption and a light grid.
fn log_log_panel<'a, 'b>(
    area: &'a DrawingArea<SVGBackend<'b>, plotters::coord::Shift>,
    caption: &str,
    y_desc: &str,
) -> Result<ChartContext<'a, SVGBackend<'b>, LogLog>, Box<dyn std::error::Error>> {
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d((0.9f64..35f64).log_scale(), (1f64..1e5f64).log_scale())?;
    chart
        .configure_mesh()
        .light_line_style(WHITE)
        .bold_line_style(RGBColor(220, 220, 220))
        .x_desc("joints")
        .y_desc(y_desc)
        .x_label_formatter(&|x| format!("{x:.0}"))
        .y_label_formatter(&|y| format!("{y:.0}"))
        .draw()?;
    Ok(chart)
}

/// Left: ns per call against joints, generated (filled, solid) and reference (open,
/// dashed). Right: operations of the generated code against joints, with n and n² guides.
fn draw(rows: &[Row], path: &str) -> Result<(), Box<dyn std::error::Error>> {
    let root = SVGBackend::new(path, (1200, 540)).into_drawing_area();
    root.fill(&WHITE)?;
    let panels = root.split_evenly((1, 2));
    let series = |function: &str, y: &dyn Fn(&Row) -> f64| -> Vec<(f64, f64)> {
        rows.iter()
            .filter(|r| r.function == function)
            .map(|r| (r.joints as f64, y(r)))
            .collect()
    };

    let mut chart = log_log_panel(
        &panels[0],
        "planar chains: time per call",
        "ns per call (median)",
    )?;
    for (i, (_, function)) in FUNCTIONS.iter().enumerate() {
        let c = color(i);
        let generated = series(function, &|r| r.generated_ns);
        chart
            .draw_series(LineSeries::new(generated.clone(), c.stroke_width(2)))?
            .label(format!("{function}, generated"))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], c.stroke_width(2)));
        chart.draw_series(generated.into_iter().map(|p| Circle::new(p, 4, c.filled())))?;
        let reference = series(function, &|r| r.reference_ns);
        chart
            .draw_series(DashedLineSeries::new(
                reference.clone(),
                6,
                4,
                c.stroke_width(2),
            ))?
            .label(format!("{function}, reference"))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], c.stroke_width(1)));
        chart.draw_series(
            reference
                .into_iter()
                .map(|p| Circle::new(p, 4, c.stroke_width(1))),
        )?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperLeft)
        .draw()?;

    let mut chart = log_log_panel(
        &panels[1],
        "planar chains: operations of the generated code",
        "mul + add + div + trig",
    )?;
    let grey = RGBColor(160, 160, 160);
    // Guides of slope 1 and 2: 20 n and 2 n².
    for (label, scale, power) in [("∝ n", 20.0, 1), ("∝ n²", 2.0, 2)] {
        let line: Vec<(f64, f64)> = [1.0_f64, 30.0]
            .iter()
            .map(|&n| (n, scale * n.powi(power)))
            .collect();
        chart
            .draw_series(DashedLineSeries::new(line, 3, 3, grey.stroke_width(1)))?
            .label(label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], grey));
    }
    for (i, (_, function)) in FUNCTIONS.iter().enumerate() {
        let c = color(i);
        // The one-link mass matrix is a constant: no operation, no point on a log axis.
        let ops: Vec<(f64, f64)> = series(function, &|r| r.ops() as f64)
            .into_iter()
            .filter(|&(_, y)| y > 0.0)
            .collect();
        chart
            .draw_series(LineSeries::new(ops.clone(), c.stroke_width(2)))?
            .label(*function)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], c.stroke_width(2)));
        chart.draw_series(ops.into_iter().map(|p| Circle::new(p, 4, c.filled())))?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperLeft)
        .draw()?;
    root.present()?;
    Ok(())
}

/// Bytes of machine code of the chains' functions in this executable, by `Chain<n>::<function>`
/// (the pieces `<function>::part_<k>` of a long function added up); empty without `nm`.
fn code_sizes() -> HashMap<String, usize> {
    let mut sizes = HashMap::new();
    let Ok(exe) = std::env::current_exe() else {
        return sizes;
    };
    let Ok(out) = std::process::Command::new("nm")
        .args(["-S", "-C"])
        .arg(exe)
        .output()
    else {
        return sizes;
    };
    for line in String::from_utf8_lossy(&out.stdout).lines() {
        // `address size type name`
        let mut fields = line.splitn(4, ' ');
        let (Some(_), Some(size), Some(_), Some(name)) =
            (fields.next(), fields.next(), fields.next(), fields.next())
        else {
            continue;
        };
        let Some(path) = name.strip_prefix("models::chains::") else {
            continue;
        };
        let mut parts = path.split("::");
        let (Some(chain), Some(function)) = (parts.next(), parts.next()) else {
            continue;
        };
        if FUNCTIONS.iter().any(|(f, _)| *f == function) {
            let bytes = usize::from_str_radix(size, 16).unwrap_or(0);
            *sizes.entry(format!("{chain}::{function}")).or_insert(0) += bytes;
        }
    }
    sizes
}

/// The exponent k of x ∝ nᵏ between two chains.
fn growth(
    rows: &[Row],
    function: &str,
    value: impl Fn(&Row) -> f64,
    from: usize,
    to: usize,
) -> f64 {
    let at = |n| {
        rows.iter()
            .find(|r| r.function == function && r.joints == n)
            .map(&value)
            .unwrap_or(f64::NAN)
    };
    (at(to) / at(from)).ln() / (to as f64 / from as f64).ln()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let docs = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs");
    std::fs::create_dir_all(&docs)?;
    let rows: Vec<Row> = [
        measure!(Chain1),
        measure!(Chain2),
        measure!(Chain3),
        measure!(Chain5),
        measure!(Chain10),
        measure!(Chain15),
        measure!(Chain20),
        measure!(Chain25),
        measure!(Chain30),
    ]
    .into_iter()
    .flatten()
    .collect();

    let sizes = code_sizes();
    println!("| joints | function | mul | add | div | trig | machine code KiB | generated ns | reference ns | reference / generated | max rel. diff. |");
    println!("| ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    for (_, function) in FUNCTIONS {
        for r in rows.iter().filter(|r| r.function == function) {
            let code = match sizes.get(&format!("{}::{}", r.chain, r.name)) {
                Some(bytes) => format!("{:.1}", *bytes as f64 / 1024.0),
                None if sizes.is_empty() => "–".to_owned(),
                None => "inlined".to_owned(),
            };
            println!(
                "| {} | {} | {} | {} | {} | {} | {code} | {:.1} | {:.1} | {:.1}× | {:.0e} |",
                r.joints,
                r.function,
                r.cost.mul,
                r.cost.add,
                r.cost.div,
                r.cost.trig,
                r.generated_ns,
                r.reference_ns,
                r.reference_ns / r.generated_ns,
                r.error
            );
        }
    }

    println!();
    println!("Growth exponent k (x ∝ nᵏ) from 10 to 30 joints:");
    println!("| function | ops | generated ns | reference ns |");
    println!("| --- | ---: | ---: | ---: |");
    for (_, function) in FUNCTIONS {
        println!(
            "| {function} | {:.2} | {:.2} | {:.2} |",
            growth(&rows, function, |r| r.ops() as f64, 10, 30),
            growth(&rows, function, |r| r.generated_ns, 10, 30),
            growth(&rows, function, |r| r.reference_ns, 10, 30),
        );
    }

    let puma = cost::<Puma560>("inverse_dynamics");
    println!();
    println!("PUMA 560 inverse dynamics, operation counts:");
    println!("| method | mul | add |");
    println!("| --- | ---: | ---: |");
    for (method, mul, add) in [
        ("Lagrangian, closed form (published)", 66_271, 51_548),
        ("recursive Newton–Euler (published)", 852, 738),
        ("Kane's equations (published)", 646, 394),
        ("Murray–Neuman ARM, customized RNE (published)", 224, 174),
        ("generated here (`Puma560::FUNCTIONS`)", puma.mul, puma.add),
    ] {
        println!("| {method} | {mul} | {add} |");
    }
    println!(
        "(the generated code also takes {} sines and cosines and {} divisions)",
        puma.trig, puma.div
    );

    let chart = docs.join("scaling.svg");
    draw(&rows, &chart.to_string_lossy())?;
    println!();
    println!("wrote {}", chart.display());
    Ok(())
}
