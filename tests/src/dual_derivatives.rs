//! Derivatives of the dynamics against the runtime reference at dual numbers: the ε parts
//! of its Newton–Euler τ and articulated-body q̈ along q ⊕ t e_j (a free root moved on its
//! manifold by `integrate_configuration`, so that its columns are in the tangent space, as
//! the generated ones are) and along v + t e_j.

use dynamics_runtime::{integrate_configuration, Dual, Model, Reference};

type D = Dual<f64>;

/// A generated function of (q, v, a) or (q, v, τ) with `NQ` and `NV` coordinates, giving
/// `R`.
pub type StateFunction<const NQ: usize, const NV: usize, R> =
    fn(&[f64; NQ], &[f64; NV], &[f64; NV]) -> R;

/// Two NV × NV matrices: derivatives with respect to q and to v.
pub type MatrixPair<const NV: usize> = ([[f64; NV]; NV], [[f64; NV]; NV]);

/// The ε parts of the runtime reference's τ (`inverse`, at the accelerations `a`) or q̈
/// (at the forces `tau`) at dual-number inputs: one column of its derivatives.
pub fn dual_reference_column<const N: usize>(
    reference: &mut Reference<D>,
    (q, v): (&[D], &[D]),
    (a, tau): (&[D], &[D]),
    inverse: bool,
) -> [f64; N] {
    let mut out = [D::constant(0.0); N];
    if inverse {
        reference.inverse_dynamics(q, v, a, None, &mut out)
    } else {
        reference.forward_dynamics(q, v, tau, None, &mut out)
    }
    .expect("sizes");
    out.map(|x| x.derivative)
}

/// The generated functions of a mechanism with a free root (its first joint) and no loads:
/// inverse dynamics, its derivatives (∂τ/∂q, ∂τ/∂v) and the forward dynamics' (∂q̈/∂q,
/// ∂q̈/∂v).
pub struct GeneratedDerivatives<const NQ: usize, const NV: usize> {
    /// τ(q, v, a).
    pub inverse_dynamics: StateFunction<NQ, NV, [f64; NV]>,
    /// (∂τ/∂q, ∂τ/∂v) at (q, v, a).
    pub inverse_dynamics_derivatives: StateFunction<NQ, NV, MatrixPair<NV>>,
    /// (∂q̈/∂q, ∂q̈/∂v) at (q, v, τ).
    pub forward_dynamics_derivatives: StateFunction<NQ, NV, MatrixPair<NV>>,
}

/// Asserts that `generated`'s ∂τ (within 1e-12 · (1 + |entry|)) and ∂q̈ (1e-11) are the
/// reference's at dual numbers, at four states with velocities and accelerations, the
/// forward dynamics' at τ = the inverse dynamics of that state.
pub fn assert_derivatives_are_the_reference_dual_numbers<const NQ: usize, const NV: usize>(
    model: &Model,
    generated: &GeneratedDerivatives<NQ, NV>,
) {
    let mut reference = Reference::<D>::new(model);
    let constant = |x: &[f64]| -> Vec<D> { x.iter().map(|&x| D::constant(x)).collect() };
    for k in 0..4 {
        let wave = |n: usize, f: f64, s: f64| -> Vec<f64> {
            (0..n)
                .map(|i| s * (f * (i + 3 * k) as f64 + 0.4).sin())
                .collect()
        };
        let mut q: [f64; NQ] = wave(NQ, 0.7, 1.2).try_into().expect("NQ");
        let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
        q[3..7].iter_mut().for_each(|x| *x /= norm);
        let v: [f64; NV] = wave(NV, 1.3, 2.0).try_into().expect("NV");
        let a: [f64; NV] = wave(NV, 0.9, 3.0).try_into().expect("NV");
        let tau = (generated.inverse_dynamics)(&q, &v, &a);
        let (dtau_dq, dtau_dv) = (generated.inverse_dynamics_derivatives)(&q, &v, &a);
        let (ddq_dq, ddq_dv) = (generated.forward_dynamics_derivatives)(&q, &v, &tau);
        let (q_d, v_d) = (constant(&q), constant(&v));
        let (a_d, tau_d) = (constant(&a), constant(&tau));
        for col in 0..NV {
            let mut unit = [0.0; NV];
            unit[col] = 1.0;
            let mut q_moved = [D::constant(0.0); NQ];
            integrate_configuration(
                &q_d,
                &constant(&unit),
                D::variable(0.0),
                &[(0, 0)],
                &mut q_moved,
            );
            let mut v_moved = v_d.clone();
            v_moved[col] = D::variable(v[col]);
            let mut column = |q_in: &[D], v_in: &[D], inverse: bool| {
                dual_reference_column::<NV>(&mut reference, (q_in, v_in), (&a_d, &tau_d), inverse)
            };
            let expected = [
                ("∂τ/∂q", column(&q_moved, &v_d, true), &dtau_dq, 1e-12),
                ("∂τ/∂v", column(&q_d, &v_moved, true), &dtau_dv, 1e-12),
                ("∂q̈/∂q", column(&q_moved, &v_d, false), &ddq_dq, 1e-11),
                ("∂q̈/∂v", column(&q_d, &v_moved, false), &ddq_dv, 1e-11),
            ];
            for (what, want, got, tolerance) in expected {
                for row in 0..NV {
                    let (x, y) = (got[row][col], want[row]);
                    assert!(
                        (x - y).abs() <= tolerance * (1.0 + y.abs()),
                        "state {k}, {what}[{row}][{col}]: generated {x}, reference {y}"
                    );
                }
            }
        }
    }
}
