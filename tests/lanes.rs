//! Generated functions on SIMD lanes (`dynamics_runtime::{F64x4, F32x8}`) against the
//! scalar calls, lane by lane, for the UR5 and the 18-dof quadruped of `models`:
//!
//! - `F64x4`, four different states per call: every lane bit for bit the `f64` call on its
//!   state, with `f64` pinned to its baseline copy (`isa::choose(false)`), for every output
//!   of both robots that has one body; the outputs expanded with packed values (the
//!   quadruped's legs side by side in M, C and forward dynamics, the UR5's columns four to a
//!   value in M and C), whose lanes run the unpacked twin (`Scalar::run_packed`: a packed
//!   value of four lanes of four states would be four registers), within 1e-14 ·
//!   (1 + max |output|) (measured worst 1.3e-15, the quadruped's forward dynamics, which
//!   `f64` computes by the articulated-body algorithm and the lanes by CRBA + LDLᵀ).
//! - The same lanes against `f64`'s AVX2 + FMA copy (where the CPU has it): built without
//!   AVX, `F64x4` runs the copy `f64` runs, so again bit for bit; built with AVX (`wide`
//!   backing, baseline arithmetic) within 1e-14 · (1 + max |output|) (measured worst
//!   2.1e-15, UR5 potential energy).
//! - `F32x8`, eight states per call, against `f32`: the arithmetic is the same, the sines
//!   and cosines differ by up to 1 ulp (`lanes` module): within 2e-6 · (1 + max |output|)
//!   (measured worst 2.1e-7, under two ulps of f32, UR5 forward dynamics; 78 to 100 % of
//!   the outputs bit for bit); and within the same bound against `f32`'s AVX2 + FMA copy,
//!   whose fused arithmetic the lanes do not share (measured worst 4.5e-7).
//!
//! `cargo test -p dynamics-tests --test lanes -- --nocapture` prints each function's
//! worst error and share of bit-for-bit outputs.
//! - `batch::map*` on the generated functions (and `batch::map1_into` on their `_into`
//!   twins), lengths not a multiple of the lanes: every state's result is the scalar call,
//!   bit for bit.
//!
//! The choice of kernel copy is global to the process: each test holds `ISA` while it runs.

use dynamics_runtime::{batch, isa, F32x8, F64x4, Lanes, Mechanism};
use dynamics_tests::random::SplitMix;
use models::anchors::Ur5;
use models::quadruped::Quadruped;
use std::f64::consts::PI;
use std::sync::{Mutex, MutexGuard};

static ISA: Mutex<()> = Mutex::new(());

/// Holds the kernel choice for one test: the baseline copy (`false`) or the AVX2 + FMA copy
/// (`true`; `None` when the CPU lacks it).
fn pin(wide: bool) -> Option<MutexGuard<'static, ()>> {
    let guard = ISA.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    (isa::choose(wide) == wide).then_some(guard)
}

const UR5_NQ: usize = <Ur5 as Mechanism>::NQ;
const QUAD_NQ: usize = <Quadruped as Mechanism>::NQ;
const QUAD_NV: usize = <Quadruped as Mechanism>::NV;
const QUAD_NL: usize = <Quadruped as Mechanism>::NUM_LOAD_INPUTS;

/// One state: configuration, velocity, acceleration, torque, loads.
#[derive(Clone, Copy)]
struct State<E, const NQ: usize, const NV: usize, const NL: usize> {
    q: [E; NQ],
    v: [E; NV],
    a: [E; NV],
    tau: [E; NV],
    l: [E; NL],
}

impl<const NQ: usize, const NV: usize, const NL: usize> State<f64, NQ, NV, NL> {
    /// Random joint angles in ±π, rates in ±2, accelerations and torques in ±5, loads in
    /// [−20, 40]; for a free base (NQ = NV + 1) a unit quaternion in q[3..7].
    fn random(rng: &mut SplitMix) -> Self {
        let mut q: [f64; NQ] = std::array::from_fn(|_| rng.uniform(-PI, PI));
        if NQ == NV + 1 {
            let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
            q[3..7].iter_mut().for_each(|x| *x /= norm);
        }
        Self {
            q,
            v: std::array::from_fn(|_| rng.uniform(-2.0, 2.0)),
            a: std::array::from_fn(|_| rng.uniform(-5.0, 5.0)),
            tau: std::array::from_fn(|_| rng.uniform(-5.0, 5.0)),
            l: std::array::from_fn(|_| rng.uniform(-20.0, 40.0)),
        }
    }

    fn to_f32(self) -> State<f32, NQ, NV, NL> {
        let f = |x: f64| x as f32;
        State {
            q: self.q.map(f),
            v: self.v.map(f),
            a: self.a.map(f),
            tau: self.tau.map(f),
            l: self.l.map(f),
        }
    }
}

fn states<const NQ: usize, const NV: usize, const NL: usize>(
    seed: u64,
    n: usize,
) -> Vec<State<f64, NQ, NV, NL>> {
    let mut rng = SplitMix(seed);
    (0..n).map(|_| State::random(&mut rng)).collect()
}

/// An output of scalars, flattened in order.
trait Flat<E> {
    fn flat(&self, out: &mut Vec<E>);
}

impl Flat<f64> for f64 {
    fn flat(&self, out: &mut Vec<f64>) {
        out.push(*self);
    }
}

impl Flat<f32> for f32 {
    fn flat(&self, out: &mut Vec<f32>) {
        out.push(*self);
    }
}

impl<E, S: Flat<E>, const N: usize> Flat<E> for [S; N] {
    fn flat(&self, out: &mut Vec<E>) {
        self.iter().for_each(|s| s.flat(out));
    }
}

/// Lane k of an output of lanes, flattened in order.
trait LaneOf<E> {
    fn lane(&self, k: usize, out: &mut Vec<E>);
}

impl LaneOf<f64> for F64x4 {
    fn lane(&self, k: usize, out: &mut Vec<f64>) {
        out.extend(self.get(k));
    }
}

impl LaneOf<f32> for F32x8 {
    fn lane(&self, k: usize, out: &mut Vec<f32>) {
        out.extend(self.get(k));
    }
}

impl<E, S: LaneOf<E>, const N: usize> LaneOf<E> for [S; N] {
    fn lane(&self, k: usize, out: &mut Vec<E>) {
        self.iter().for_each(|s| s.lane(k, out));
    }
}

/// Lanes of an array from one array per lane (written here, independently of `batch`).
trait Gather: Lanes {
    /// Lane k of entry j is `state(k)[j]`.
    fn gather<const N: usize>(state: impl Fn(usize) -> [Self::Element; N]) -> [Self; N] {
        std::array::from_fn(|j| Self::from_fn(|k| state(k)[j]))
    }
}

impl<L: Lanes> Gather for L {}

/// How close each lane must be to the scalar call.
#[derive(Clone, Copy, Debug)]
enum Agreement {
    /// Bit for bit.
    Exact,
    /// `max |lane − scalar| ≤ tol · (1 + max |scalar|)` over each output.
    Relative(f64),
}

/// Compares lane by lane; returns the worst `max |lane − scalar| / (1 + max |scalar|)` and
/// the share of outputs that are bit for bit equal.
struct Tally {
    worst: f64,
    equal: usize,
    total: usize,
}

impl Tally {
    fn new() -> Self {
        Self {
            worst: 0.0,
            equal: 0,
            total: 0,
        }
    }

    #[track_caller]
    fn check(&mut self, what: &str, lane: &[f64], scalar: &[f64], agreement: Agreement) {
        assert_eq!(lane.len(), scalar.len(), "{what}: lengths");
        let scale = 1.0 + scalar.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        let error = lane
            .iter()
            .zip(scalar)
            .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
            / scale;
        let bits_equal = lane
            .iter()
            .zip(scalar)
            .all(|(x, y)| x.to_bits() == y.to_bits());
        self.worst = self.worst.max(error);
        self.equal += usize::from(bits_equal);
        self.total += 1;
        match agreement {
            Agreement::Exact => assert!(
                bits_equal,
                "{what}: not bit for bit (relative error {error:e})\n  lane   {lane:?}\n  scalar {scalar:?}"
            ),
            Agreement::Relative(tol) => assert!(
                error <= tol,
                "{what}: relative error {error:e} > {tol:e}\n  lane   {lane:?}\n  scalar {scalar:?}"
            ),
        }
    }
}

/// Evaluates `$call` on packs of `$L::LANES` states of `$states` (lanes of the fields q, v,
/// a, tau, l) and on each state alone, and checks each lane against its state's call.
macro_rules! compare {
    (
        $L:ty, $what:expr, $states:expr, $agreement:expr,
        |$q:ident, $v:ident, $a:ident, $tau:ident, $l:ident| $call:expr
    ) => {{
        let mut tally = Tally::new();
        for pack in $states.chunks_exact(<$L as Lanes>::LANES) {
            let $q = <$L as Gather>::gather(|k| pack[k].q);
            let $v = <$L as Gather>::gather(|k| pack[k].v);
            let $a = <$L as Gather>::gather(|k| pack[k].a);
            let $tau = <$L as Gather>::gather(|k| pack[k].tau);
            let $l = <$L as Gather>::gather(|k| pack[k].l);
            let got = {
                let ($q, $v, $a, $tau, $l) = (&$q, &$v, &$a, &$tau, &$l);
                $call
            };
            for (k, state) in pack.iter().enumerate() {
                let expected = {
                    let ($q, $v, $a, $tau, $l) =
                        (&state.q, &state.v, &state.a, &state.tau, &state.l);
                    $call
                };
                let (mut lane, mut scalar) = (Vec::new(), Vec::new());
                got.lane(k, &mut lane);
                expected.flat(&mut scalar);
                let widen = |x: &Vec<_>| x.iter().map(|&x| f64::from(x)).collect::<Vec<f64>>();
                tally.check(
                    &format!("{} lane {k}", $what),
                    &widen(&lane),
                    &widen(&scalar),
                    $agreement,
                );
            }
        }
        println!(
            "{:<40} {:>4} outputs, {:>5.1} % bit for bit, worst relative error {:.2e}",
            format!("{} ({})", $what, stringify!($L)),
            tally.total,
            100.0 * tally.equal as f64 / tally.total as f64,
            tally.worst
        );
        tally.worst
    }};
}

/// Every output of the UR5 on `$L` lanes against its element type.
macro_rules! ur5_outputs {
    ($L:ty, $states:expr, $tol:expr) => {{
        let s = $states;
        let tol: [Agreement; 9] = $tol;
        compare!($L, "UR5 inverse_dynamics", s, tol[0], |q, v, a, _t, _l| {
            Ur5::inverse_dynamics(q, v, a)
        });
        compare!($L, "UR5 mass_matrix", s, tol[1], |q, _v, _a, _t, _l| {
            Ur5::mass_matrix(q)
        });
        compare!($L, "UR5 forward_dynamics", s, tol[2], |q, v, _a, t, _l| {
            Ur5::forward_dynamics(q, v, t)
        });
        compare!($L, "UR5 bias", s, tol[3], |q, v, _a, _t, _l| Ur5::bias(
            q, v
        ));
        compare!($L, "UR5 gravity", s, tol[4], |q, _v, _a, _t, _l| {
            Ur5::gravity(q)
        });
        compare!($L, "UR5 coriolis_matrix", s, tol[5], |q, v, _a, _t, _l| {
            Ur5::coriolis_matrix(q, v)
        });
        compare!($L, "UR5 kinetic_energy", s, tol[6], |q, v, _a, _t, _l| {
            Ur5::kinetic_energy(q, v)
        });
        compare!(
            $L,
            "UR5 potential_energy",
            s,
            tol[7],
            |q, _v, _a, _t, _l| Ur5::potential_energy(q)
        );
        compare!($L, "UR5 joint_reactions", s, tol[8], |q, v, a, _t, _l| {
            Ur5::joint_reactions(q, v, a)
        });
    }};
}

/// Every output of the quadruped (foot forces as loads) on `$L` lanes.
macro_rules! quadruped_outputs {
    ($L:ty, $states:expr, $tol:expr) => {{
        let s = $states;
        let tol: [Agreement; 9] = $tol;
        compare!(
            $L,
            "quadruped inverse_dynamics",
            s,
            tol[0],
            |q, v, a, _t, l| Quadruped::inverse_dynamics(q, v, a, l)
        );
        compare!(
            $L,
            "quadruped mass_matrix",
            s,
            tol[1],
            |q, _v, _a, _t, _l| Quadruped::mass_matrix(q)
        );
        compare!(
            $L,
            "quadruped forward_dynamics",
            s,
            tol[2],
            |q, v, _a, t, l| Quadruped::forward_dynamics(q, v, t, l)
        );
        compare!($L, "quadruped bias", s, tol[3], |q, v, _a, _t, _l| {
            Quadruped::bias(q, v)
        });
        compare!($L, "quadruped gravity", s, tol[4], |q, _v, _a, _t, _l| {
            Quadruped::gravity(q)
        });
        compare!(
            $L,
            "quadruped coriolis_matrix",
            s,
            tol[5],
            |q, v, _a, _t, _l| Quadruped::coriolis_matrix(q, v)
        );
        compare!(
            $L,
            "quadruped kinetic_energy",
            s,
            tol[6],
            |q, v, _a, _t, _l| Quadruped::kinetic_energy(q, v)
        );
        compare!(
            $L,
            "quadruped potential_energy",
            s,
            tol[7],
            |q, _v, _a, _t, _l| Quadruped::potential_energy(q)
        );
        compare!(
            $L,
            "quadruped joint_reactions",
            s,
            tol[8],
            |q, v, a, _t, l| Quadruped::joint_reactions(q, v, a, l)
        );
    }};
}

const EXACT: [Agreement; 9] = [Agreement::Exact; 9];

/// The outputs of a robot whose expansion packs values (isomorphic limbs, or columns of a
/// tree matrix, four to a `P4`), whose lanes run their unpacked twin (`Scalar::run_packed`):
/// the same function by other operations or in another order (the quadruped's forward
/// dynamics by CRBA + LDLᵀ where `f64` runs the articulated-body algorithm), so agreeing
/// to rounding, not bit for bit: `Relative(TWIN)`, eight times the worst measured (1.3e-15,
/// the quadruped's forward dynamics; the matrices 6e-16 at most).
const TWIN: f64 = 1e-14;

/// [`EXACT`] but for the outputs of `twins` (indices into the robot's list of nine), which
/// must agree within [`TWIN`].
const fn exact_but_twins(twins: &[usize]) -> [Agreement; 9] {
    let mut agreement = EXACT;
    let mut k = 0;
    while k < twins.len() {
        agreement[twins[k]] = Agreement::Relative(TWIN);
        k += 1;
    }
    agreement
}

/// The UR5's mass and Coriolis matrices carry their columns four to a value.
const UR5_EXACT: [Agreement; 9] = exact_but_twins(&[1, 5]);
/// The quadruped's legs side by side in its mass and Coriolis matrices and forward dynamics.
const QUADRUPED_EXACT: [Agreement; 9] = exact_but_twins(&[1, 2, 5]);

/// Four different states per call, 16 packs: each lane is the f64 call, bit for bit.
#[test]
fn f64x4_lanes_are_the_f64_baseline_calls_bit_for_bit() {
    let _pinned = pin(false).expect("the baseline copy is always available");
    ur5_outputs!(F64x4, &states::<UR5_NQ, UR5_NQ, 0>(1, 64), UR5_EXACT);
    quadruped_outputs!(
        F64x4,
        &states::<QUAD_NQ, QUAD_NV, QUAD_NL>(2, 64),
        QUADRUPED_EXACT
    );
}

/// With f64 on its AVX2 + FMA copy, which fuses products into sums (and takes its sines
/// and cosines four at a time): built without AVX, `F64x4` runs the same copy, each lane bit
/// for bit the f64 call; built with AVX (`wide`'s backing), it runs the baseline
/// arithmetic and agrees with the FMA copy to 1e-14 relative (measured worst 2.1e-15).
#[test]
fn f64x4_lanes_against_the_fma_copy_of_f64() {
    let Some(_pinned) = pin(true) else {
        println!("no AVX2 + FMA on this CPU: nothing to compare");
        return;
    };
    let (ur5, quadruped) = if cfg!(target_feature = "avx") {
        let near = [Agreement::Relative(1e-14); 9];
        (near, near)
    } else {
        (UR5_EXACT, QUADRUPED_EXACT)
    };
    ur5_outputs!(F64x4, &states::<UR5_NQ, UR5_NQ, 0>(3, 64), ur5);
    quadruped_outputs!(
        F64x4,
        &states::<QUAD_NQ, QUAD_NV, QUAD_NL>(4, 64),
        quadruped
    );
    isa::choose(false);
}

/// Eight different states per call, against f32 (both on the baseline copy): the
/// arithmetic is the same, the sines and cosines differ by up to an ulp: 2e-6 relative,
/// ten times the worst error measured (2.1e-7, under two ulps of f32).
#[test]
fn f32x8_lanes_against_f32() {
    let _pinned = pin(false).expect("the baseline copy is always available");
    f32x8_against_f32();
}

/// The same with f32 on its AVX2 + FMA copy, which fuses products into sums while the
/// lanes run the baseline arithmetic: still within 2e-6.
#[test]
fn f32x8_lanes_against_the_fma_copy_of_f32() {
    let Some(_pinned) = pin(true) else {
        println!("no AVX2 + FMA on this CPU: nothing to compare");
        return;
    };
    f32x8_against_f32();
    isa::choose(false);
}

/// Both robots' outputs on F32x8 against f32, 2e-6 relative.
fn f32x8_against_f32() {
    use Agreement::Relative as R;
    let ur5: Vec<_> = states::<UR5_NQ, UR5_NQ, 0>(5, 128)
        .into_iter()
        .map(State::to_f32)
        .collect();
    ur5_outputs!(F32x8, &ur5, [R(2e-6); 9]);
    let quadruped: Vec<_> = states::<QUAD_NQ, QUAD_NV, QUAD_NL>(6, 128)
        .into_iter()
        .map(State::to_f32)
        .collect();
    quadruped_outputs!(F32x8, &quadruped, [R(2e-6); 9]);
}

/// The batch helpers on the generated functions, 4k + 1 and 8k + 3 states (a padded last
/// pack): every state's result is the scalar call on it, bit for bit against f64, against
/// the lanes' own call on the state alone for the functions with an unpacked twin (and
/// within [`TWIN`] of f64's), and against the lanes' own call for f32 (whose sines differ
/// from f32's by an ulp).
#[test]
fn batch_helpers_on_generated_functions() {
    let _pinned = pin(false).expect("the baseline copy is always available");
    let ur5 = states::<UR5_NQ, UR5_NQ, 0>(7, 21);
    let q: Vec<_> = ur5.iter().map(|s| s.q).collect();
    let v: Vec<_> = ur5.iter().map(|s| s.v).collect();
    let a: Vec<_> = ur5.iter().map(|s| s.a).collect();
    let tau: Vec<_> = ur5.iter().map(|s| s.tau).collect();
    let n = ur5.len();
    let (mut id, mut fd, mut h) = (vec![[0.0; 6]; n], vec![[0.0; 6]; n], vec![[0.0; 6]; n]);
    let mut m = vec![[[0.0; 6]; 6]; n];
    batch::map3(&q, &v, &a, &mut id, Ur5::inverse_dynamics).expect("equal lengths");
    batch::map1(&q, &mut m, Ur5::mass_matrix).expect("equal lengths");
    batch::map3(&q, &v, &tau, &mut fd, Ur5::forward_dynamics).expect("equal lengths");
    batch::map2(&q, &v, &mut h, Ur5::bias).expect("equal lengths");
    let mut m_into = vec![[[f64::NAN; 6]; 6]; n];
    batch::map1_into(&q, &mut m_into, Ur5::mass_matrix_into).expect("equal lengths");
    let bits = |x: &[f64]| x.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    // The functions with an unpacked twin (`UR5_EXACT`, `QUADRUPED_EXACT`) against the
    // lanes' call on the state alone, whose arithmetic the lanes run.
    let alone = |m: [[F64x4; 6]; 6]| m.map(|row| row.map(|x| x.to_array()[0]));
    for i in 0..n {
        let m_alone = alone(Ur5::mass_matrix(&q[i].map(F64x4::splat)));
        assert_eq!(m_into[i].map(|r| bits(&r)), m_alone.map(|r| bits(&r)));
        assert_eq!(
            bits(&id[i]),
            bits(&Ur5::inverse_dynamics(&q[i], &v[i], &a[i]))
        );
        assert_eq!(
            bits(&fd[i]),
            bits(&Ur5::forward_dynamics(&q[i], &v[i], &tau[i]))
        );
        assert_eq!(bits(&h[i]), bits(&Ur5::bias(&q[i], &v[i])));
        assert_eq!(m[i].map(|r| bits(&r)), m_alone.map(|r| bits(&r)));
    }

    // The quadruped: per-state loads (map4), and the same loads for every state, splatted.
    let quad = states::<QUAD_NQ, QUAD_NV, QUAD_NL>(8, 9);
    let q: Vec<_> = quad.iter().map(|s| s.q).collect();
    let v: Vec<_> = quad.iter().map(|s| s.v).collect();
    let a: Vec<_> = quad.iter().map(|s| s.a).collect();
    let l: Vec<_> = quad.iter().map(|s| s.l).collect();
    let mut id = vec![[0.0; QUAD_NV]; quad.len()];
    batch::map4(&q, &v, &a, &l, &mut id, Quadruped::inverse_dynamics).expect("equal lengths");
    let standing = [0.0, 0.0, 8.0].repeat(4);
    let loads: [F64x4; QUAD_NL] = std::array::from_fn(|k| F64x4::splat(standing[k]));
    let mut fd = vec![[0.0; QUAD_NV]; quad.len()];
    batch::map3(&q, &v, &a, &mut fd, |q, v, tau| {
        Quadruped::forward_dynamics(q, v, tau, &loads)
    })
    .expect("equal lengths");
    let standing: [f64; QUAD_NL] = std::array::from_fn(|k| standing[k]);
    // The 18 × 18 mass matrix written in place: four blocks of four and two single entries
    // per row unpacked.
    let mut m = vec![[[f64::NAN; QUAD_NV]; QUAD_NV]; quad.len()];
    batch::map1_into(&q, &mut m, Quadruped::mass_matrix_into).expect("equal lengths");
    let lane_0 = |x: F64x4| x.to_array()[0];
    for i in 0..quad.len() {
        let splat = |x: &[f64]| x.iter().map(|&x| F64x4::splat(x)).collect::<Vec<_>>();
        let q_alone: [F64x4; QUAD_NQ] = std::array::from_fn(|k| splat(&q[i])[k]);
        let m_alone = Quadruped::mass_matrix(&q_alone).map(|row| row.map(lane_0));
        assert_eq!(m[i].map(|r| bits(&r)), m_alone.map(|r| bits(&r)));
        let expected = Quadruped::inverse_dynamics(&q[i], &v[i], &a[i], &l[i]);
        assert_eq!(bits(&id[i]), bits(&expected));
        let (v_alone, a_alone) = (v[i].map(F64x4::splat), a[i].map(F64x4::splat));
        let expected = Quadruped::forward_dynamics(&q_alone, &v_alone, &a_alone, &loads);
        assert_eq!(bits(&fd[i]), bits(&expected.map(lane_0)));
        let near = Quadruped::forward_dynamics(&q[i], &v[i], &a[i], &standing);
        let scale = 1.0 + near.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        for (x, y) in fd[i].iter().zip(&near) {
            assert!((x - y).abs() <= TWIN * scale, "{x} against f64's {y}");
        }
    }

    // f32 on eight lanes, 11 states: each the lanes' call on that state alone.
    let q: Vec<[f32; 6]> = ur5[..11].iter().map(|s| s.to_f32().q).collect();
    let mut m = vec![[[0.0_f32; 6]; 6]; q.len()];
    batch::map1(&q, &mut m, Ur5::mass_matrix).expect("equal lengths");
    for (i, q) in q.iter().enumerate() {
        let alone = Ur5::mass_matrix(&q.map(F32x8::splat));
        assert_eq!(m[i], alone.map(|row| row.map(|x| x.to_array()[0])));
    }

    // Mismatched lengths: an error naming the input, nothing written.
    let before = id.clone();
    let q: Vec<_> = quad.iter().map(|s| s.q).collect();
    let err = batch::map4(&q, &v, &a[..3], &l, &mut id, Quadruped::inverse_dynamics);
    assert_eq!(
        err,
        Err(batch::LengthMismatch {
            input: 2,
            len: 3,
            expected: 9
        })
    );
    assert_eq!(id, before);
}
