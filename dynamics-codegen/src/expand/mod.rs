//! The symbolic expansion: the textbook's recursions written over DAG nodes, one graph per
//! generated function. The code mirrors the recursion (never a closed-form Lagrangian), so
//! its size grows linearly with the number of joints for inverse and forward dynamics and
//! quadratically for the mass matrix.
//!
//! | function | computes | from |
//! | --- | --- | --- |
//! | `inverse_dynamics(q, v, a)` | τ = M q̈ + C q̇ + g + b q̇ − Q | [`rnea`] |
//! | `gravity(q)` | g(q) | [`rnea`] with q̇ = q̈ = 0 |
//! | `bias(q, v)` | C q̇ + g + b q̇ | [`rnea`] with q̈ = 0 |
//! | `mass_matrix(q)` | M(q) (armature on the diagonal) | [`crba`] |
//! | `coriolis_matrix(q, v)` | C(q, q̇) with Ṁ − 2C skew-symmetric | [`coriolis`] |
//! | `forward_dynamics(q, v, tau)` | q̈ = M⁻¹(τ + Q − C q̇ − g − b q̇) | [`crba`] + [`ldlt`] |
//! | `kinetic_energy(q, v)`, `potential_energy(q)` | T, V | [`energy`] |
//! | `joint_reactions(q, v, a)` | [F; M_P] each joint transmits to its body | [`rnea`] |
//!
//! Symbolic parameters add a `p` argument, declared loads a `loads` argument (Q).

pub mod coriolis;
pub mod crba;
pub mod energy;
pub mod geometry;
pub mod ldlt;
pub mod rnea;

use crate::emit::{Arg, FunctionSpec, Output};
use crate::model::Model;
use crate::sym::{Array, Graph, Node};

/// One generated function: its graph and how to emit it.
pub struct Function {
    /// The expression DAG.
    pub graph: Graph,
    /// Name, arguments, outputs, docs.
    pub spec: FunctionSpec,
}

/// What every function of one mechanism shares: sizes and the optional inputs.
struct Signature<'m> {
    model: &'m Model,
    scalar_trait: syn::Path,
}

impl Signature<'_> {
    fn arg(&self, array: Array) -> Option<Arg> {
        let len = match array {
            Array::Q => self.model.nq,
            Array::V | Array::A | Array::Tau => self.model.nv,
            Array::P => self.model.parameters.len(),
            Array::Loads => self.model.load_inputs,
        };
        (len > 0 || matches!(array, Array::Q | Array::V | Array::A | Array::Tau))
            .then_some(Arg { array, len })
    }

    /// The arguments, in the fixed order q, v, a, tau, p, loads.
    fn args(&self, arrays: &[Array]) -> Vec<Arg> {
        arrays
            .iter()
            .chain(&[Array::P])
            .filter_map(|&a| self.arg(a))
            .collect()
    }

    fn function(
        &self,
        graph: Graph,
        name: &str,
        doc: String,
        arrays: &[Array],
        output: Output,
    ) -> Function {
        let mut spec =
            FunctionSpec::new(name, self.scalar_trait.clone(), self.args(arrays), output);
        spec.doc = doc;
        Function { graph, spec }
    }
}

fn inputs(g: &Graph, array: Array, n: usize) -> Vec<Node> {
    (0..n).map(|k| g.input(array, k)).collect()
}

/// Builds every function the model asks for.
pub fn expand(model: &Model, scalar_trait: syn::Path) -> Vec<Function> {
    let sig = Signature {
        model,
        scalar_trait,
    };
    let outputs = model.outputs;
    let nv = model.nv;
    let loads = model.load_inputs > 0;
    let with_loads = |mut arrays: Vec<Array>| {
        if loads {
            arrays.push(Array::Loads);
        }
        arrays
    };
    let mut functions = Vec::new();
    let setup = || {
        let g = Graph::new();
        let transforms = geometry::joint_transforms(&g, model);
        let inertias: Vec<_> = model
            .bodies
            .iter()
            .map(|b| geometry::body_inertia(&g, b))
            .collect();
        (g, transforms, inertias)
    };
    if outputs.inverse_dynamics && nv > 0 {
        let (g, t, i) = setup();
        let (v, a) = (inputs(&g, Array::V, nv), inputs(&g, Array::A, nv));
        let s = rnea::sweep(
            &g,
            model,
            &t,
            &i,
            &rnea::SweepInputs {
                velocity: &v,
                acceleration: &a,
                gravity: true,
                loads,
            },
        );
        let doc =
            "Inverse dynamics: τ = M(q) q̈ + C(q, q̇) q̇ + g(q) + b q̇ − Q, the joint forces that \
                   produce the accelerations `a` at state (`q`, `v`) (recursive Newton–Euler, \
                   shifted-inertia form)."
                .to_owned();
        let arrays = with_loads(vec![Array::Q, Array::V, Array::A]);
        functions.push(sig.function(g, "inverse_dynamics", doc, &arrays, Output::Vector(s.tau)));
    }
    if outputs.gravity && nv > 0 {
        let (g, t, i) = setup();
        let zero = vec![g.zero(); nv];
        let s = rnea::sweep(
            &g,
            model,
            &t,
            &i,
            &rnea::SweepInputs {
                velocity: &zero,
                acceleration: &zero,
                gravity: true,
                loads: false,
            },
        );
        let doc = "Gravity torques g(q): the joint forces that hold the mechanism still at `q`."
            .to_owned();
        functions.push(sig.function(g, "gravity", doc, &[Array::Q], Output::Vector(s.tau)));
    }
    if outputs.bias && nv > 0 {
        let (g, t, i) = setup();
        let v = inputs(&g, Array::V, nv);
        let zero = vec![g.zero(); nv];
        let s = rnea::sweep(
            &g,
            model,
            &t,
            &i,
            &rnea::SweepInputs {
                velocity: &v,
                acceleration: &zero,
                gravity: true,
                loads: false,
            },
        );
        let doc =
            "Bias forces C(q, q̇) q̇ + g(q) + b q̇: inverse dynamics at zero acceleration.".to_owned();
        functions.push(sig.function(g, "bias", doc, &[Array::Q, Array::V], Output::Vector(s.tau)));
    }
    if outputs.mass_matrix && nv > 0 {
        let (g, t, i) = setup();
        let m = crba::mass_matrix(&g, model, &t, &i);
        let doc =
            "Mass matrix M(q) (symmetric, armature on the diagonal), by composite rigid bodies."
                .to_owned();
        functions.push(sig.function(g, "mass_matrix", doc, &[Array::Q], Output::Matrix(m)));
    }
    if outputs.coriolis && nv > 0 {
        let (g, t, i) = setup();
        let v = inputs(&g, Array::V, nv);
        let c = coriolis::coriolis_matrix(&g, model, &t, &i, &v);
        let doc =
            "Coriolis matrix C(q, q̇), the Christoffel-consistent one: C q̇ is the Coriolis and \
                   centrifugal force and Ṁ − 2C is skew-symmetric."
                .to_owned();
        functions.push(sig.function(
            g,
            "coriolis_matrix",
            doc,
            &[Array::Q, Array::V],
            Output::Matrix(c),
        ));
    }
    if outputs.forward_dynamics && nv > 0 {
        let (g, t, i) = setup();
        let v = inputs(&g, Array::V, nv);
        let tau = inputs(&g, Array::Tau, nv);
        let zero = vec![g.zero(); nv];
        let bias = rnea::sweep(
            &g,
            model,
            &t,
            &i,
            &rnea::SweepInputs {
                velocity: &v,
                acceleration: &zero,
                gravity: true,
                loads,
            },
        );
        let rhs: Vec<Node> = tau
            .iter()
            .zip(&bias.tau)
            .map(|(&t, &b)| g.sub(t, b))
            .collect();
        let m = crba::mass_matrix(&g, model, &t, &i);
        let qdd = ldlt::solve(&g, model, m, rhs);
        let doc =
            "Forward dynamics: q̈ = M(q)⁻¹ (τ + Q − C(q, q̇) q̇ − g(q) − b q̇), by a tree-sparse \
                   LDLᵀ factorization of M. A singular M gives non-finite values, never a panic."
                .to_owned();
        let arrays = with_loads(vec![Array::Q, Array::V, Array::Tau]);
        functions.push(sig.function(g, "forward_dynamics", doc, &arrays, Output::Vector(qdd)));
    }
    if outputs.energy {
        let (g, t, i) = setup();
        let v = inputs(&g, Array::V, nv);
        let kinetic = energy::kinetic(&g, model, &t, &i, &v);
        let doc = "Kinetic energy T = ½ q̇ᵀ M(q) q̇.".to_owned();
        functions.push(sig.function(
            g,
            "kinetic_energy",
            doc,
            &[Array::Q, Array::V],
            Output::Scalar(kinetic),
        ));
        let (g, t, i) = setup();
        let potential = energy::potential(&g, model, &t, &i);
        let doc = "Potential energy of gravity V(q) = −Σ m_i g·c_i (zero at the world origin)."
            .to_owned();
        functions.push(sig.function(
            g,
            "potential_energy",
            doc,
            &[Array::Q],
            Output::Scalar(potential),
        ));
    }
    if outputs.reactions && nv > 0 {
        let (g, t, i) = setup();
        let (v, a) = (inputs(&g, Array::V, nv), inputs(&g, Array::A, nv));
        let s = rnea::sweep(
            &g,
            model,
            &t,
            &i,
            &rnea::SweepInputs {
                velocity: &v,
                acceleration: &a,
                gravity: true,
                loads,
            },
        );
        let rows = s
            .wrenches
            .iter()
            .map(|(f, m)| vec![f.get(0), f.get(1), f.get(2), m.get(0), m.get(1), m.get(2)])
            .collect();
        let doc =
            "Joint reactions: for each body, the wrench [F; M_P] its joint transmits to it from \
                   the parent (actuator component included), in the body frame about the joint \
                   point P."
                .to_owned();
        let arrays = with_loads(vec![Array::Q, Array::V, Array::A]);
        functions.push(sig.function(g, "joint_reactions", doc, &arrays, Output::Matrix(rows)));
    }
    functions
}
