//! Base inertial parameters for the functions of the Lagrangian alone.
//!
//! M(q), C(q, q̇) (Christoffel's, made of M's derivatives), g(q) and q̈ = FD(q, q̇, τ) depend
//! on the bodies' inertias only through the Lagrangian L = T − V. A share of a body that its joint's motion leaves unchanged
//! ([`geometry::movable_shares`]: about a revolute axis s the mass, the first moment along s
//! and an inertia Y (1 − s sᵀ); along a prismatic axis the rotational inertia) moves as if
//! fixed to the parent: handed to the parent (or dropped at the fixed ground, which changes V
//! by a constant) it leaves L, and so M, C, g and q̈, unchanged, while the body's inertia loses
//! entries and the expansion operations (Khalil and Kleinfinger's regrouping, done at compile
//! time on numbers). The joint wrenches, the energies and the force analysis are not functions
//! of L alone and keep the declared inertias.
//!
//! [`regroup`] chooses, body by body from the leaves to the root, the share (or none) that
//! makes a given function cost the fewest operations, then additions.

use super::geometry::{self, BodyInertia, JointTransform};
use crate::model::Model;
use crate::sym::{Graph, Node, Op};

/// The inertias, regrouped so that `build` (which expands one function of the Lagrangian
/// over the inertias it is given) costs the fewest operations; `inertias` unchanged when no
/// share helps. Every candidate is expanded in `g`; only the chosen one's nodes end up live.
pub fn regroup(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    build: impl Fn(&[BodyInertia]) -> Vec<Node>,
) -> Vec<BodyInertia> {
    let start = build(inertias);
    if arithmetic_cost(g, &start).0 * model.bodies.len() > SEARCH_BUDGET {
        return super::rnea::base_parameters(g, model, transforms, inertias);
    }
    greedy(
        g,
        model,
        inertias,
        start,
        |outputs| arithmetic_cost(g, outputs),
        |_, candidate, _| build(candidate),
    )
    .1
}

/// The most operations (the declared function's, times the number of bodies) for which
/// [`regroup`] expands every candidate; above it, it takes inverse dynamics' choice, computed
/// incrementally ([`super::rnea::base_parameters`]). The search finds fewer operations (with
/// the Coriolis matrix's first, dense-B form: UR5 874 against 1154; quadruped 3684 against
/// 4143; the quadruped's present form, 3309 operations, is under the budget) but expands the
/// function once per candidate. Measured with the command-line compiler at opt-level 0 (as the proc
/// macro runs inside `cargo build`), whole files with every output: searching everything,
/// the quadruped took 1.9 s and a 30-link chain 9.7 s; with this budget 0.64 s and 0.95 s
/// (0.3 s and 0.5 s before base parameters reached beyond inverse dynamics).
pub const SEARCH_BUDGET: usize = 50_000;

/// The greedy walk of every regrouping: bodies from the leaves to the root, so that what a
/// body receives moves on with it; for each, every movable share
/// ([`geometry::movable_shares`]) is tried and the one that makes the cost lowest (below the
/// current one) is kept. The caller's state `S` is what the cost is read from (the expanded
/// function, or an incrementally updated sweep): `change(state, candidate, changed)` gives
/// the state for the candidate inertias, of which the bodies `changed` differ from the
/// current ones. Returns the final state and inertias.
pub fn greedy<S>(
    g: &Graph,
    model: &Model,
    inertias: &[BodyInertia],
    start: S,
    cost: impl Fn(&S) -> (usize, usize),
    change: impl Fn(&S, &[BodyInertia], &[usize]) -> S,
) -> (S, Vec<BodyInertia>) {
    let mut current = inertias.to_vec();
    let mut state = start;
    let mut best_cost = cost(&state);
    for i in (0..model.bodies.len()).rev() {
        let body = &model.bodies[i];
        let mut best = None;
        for share in geometry::movable_shares(g, &body.joint, &current[i]) {
            let parent = body.parent.map(|p| &current[p]);
            let Some((kept, gained)) =
                geometry::move_share(g, &body.joint, &current[i], parent, &share)
            else {
                continue;
            };
            let mut candidate = current.clone();
            candidate[i] = kept;
            let mut changed = vec![i];
            if let (Some(p), Some(gained)) = (body.parent, gained) {
                candidate[p] = gained;
                changed.push(p);
            }
            let next = change(&state, &candidate, &changed);
            let c = cost(&next);
            if c < best_cost {
                best_cost = c;
                best = Some((next, candidate));
            }
        }
        if let Some((next, candidate)) = best {
            state = next;
            current = candidate;
        }
    }
    (state, current)
}

/// (operations, additions) that computing `outputs` costs: the products, sums and
/// differences among the nodes they need. The same as [`Graph::op_count`] gives, by a
/// search from the outputs that visits only those nodes (the graph holds every candidate
/// that a regrouping tried).
pub fn arithmetic_cost(g: &Graph, outputs: &[Node]) -> (usize, usize) {
    let mut seen = vec![false; g.len()];
    let mut stack: Vec<Node> = Vec::new();
    for &node in outputs {
        if !std::mem::replace(&mut seen[node.index()], true) {
            stack.push(node);
        }
    }
    let (mut ops, mut adds) = (0, 0);
    while let Some(node) = stack.pop() {
        let op = g.op(node);
        match op {
            Op::Add(..) | Op::Sub(..) => {
                ops += 1;
                adds += 1;
            }
            Op::Mul(..) => ops += 1,
            _ => {}
        }
        for child in op.children() {
            if !std::mem::replace(&mut seen[child.index()], true) {
                stack.push(child);
            }
        }
    }
    (ops, adds)
}
