//! The base-parameter pass: the bodies' inertias regrouped into base inertial parameters
//! for the functions of the Lagrangian alone, chosen per function.
//!
//! M(q), C(q, q̇) (Christoffel's, made of M's derivatives), g(q) and q̈ = FD(q, q̇, τ) depend
//! on the bodies' inertias only through the Lagrangian L = T − V. A share of a body that its joint's motion leaves unchanged
//! ([`movable_shares`]: about a revolute axis s the mass, the first moment along s
//! and an inertia Y (1 − s sᵀ); along a prismatic axis the rotational inertia) moves as if
//! fixed to the parent: handed to the parent (or dropped at the fixed ground, which changes V
//! by a constant) it leaves L, and so M, C, g and q̈, unchanged, while the body's inertia loses
//! entries and the expansion operations (Khalil and Kleinfinger's regrouping, done at compile
//! time on numbers). The joint wrenches, the energies and the force analysis are not functions
//! of L alone and keep the declared inertias.
//!
//! [`regroup`] chooses, body by body from the leaves to the root, the share (or none) that
//! makes a given function cost the fewest operations, then additions, expanding the function
//! once per candidate; [`regroup_sweep`] makes the same choice for the joint forces τ of a
//! Newton–Euler sweep, redoing only the changed bodies' paths to the root. The expansion
//! itself ([`crate::expand`]) always takes the inertias it is given.

use crate::expand::geometry::{
    self, inertia_from, is_constant_inertia, vector, BodyInertia, JointTransform,
};
use crate::expand::rnea::{self, Backward, SweepInputs};
use crate::model::{self, JointKind, Model};
use crate::sym::{Array, Graph, Mat3, Node, Op, Vec3};
use std::collections::HashSet;

/// The inertias, regrouped so that `build` (which expands one function of the Lagrangian
/// over the inertias it is given) costs the fewest operations; `inertias` unchanged when no
/// share helps. Every candidate is expanded in `g`; only the chosen one's nodes end up live.
pub(crate) fn regroup(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    build: impl Fn(&[BodyInertia]) -> Vec<Node>,
) -> Vec<BodyInertia> {
    let start = build(inertias);
    if arithmetic_cost(g, &start).0 * model.bodies.len() > SEARCH_BUDGET {
        return for_inverse_dynamics(g, model, transforms, inertias);
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
/// incrementally ([`for_inverse_dynamics`]). The search finds fewer operations (with
/// the Coriolis matrix's first, dense-B form: UR5 874 against 1154; quadruped 3684 against
/// 4143; the quadruped's present form, 3309 operations, is under the budget) but expands the
/// function once per candidate. Measured with the command-line compiler at opt-level 0 (as the proc
/// macro runs inside `cargo build`), whole files with every output: searching everything,
/// the quadruped took 1.9 s and a 30-link chain 9.7 s; with this budget 0.64 s and 0.95 s
/// (0.3 s and 0.5 s before base parameters reached beyond inverse dynamics).
pub(crate) const SEARCH_BUDGET: usize = 50_000;

/// The greedy walk of every regrouping: bodies from the leaves to the root, so that what a
/// body receives moves on with it; for each, every movable share
/// ([`movable_shares`]) is tried and the one that makes the cost lowest (below the
/// current one) is kept. The caller's state `S` is what the cost is read from (the expanded
/// function, or an incrementally updated sweep): `change(state, candidate, changed)` gives
/// the state for the candidate inertias, of which the bodies `changed` differ from the
/// current ones. Returns the final state and inertias.
fn greedy<S>(
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
        for share in movable_shares(g, &body.joint, &current[i]) {
            let parent = body.parent.map(|p| &current[p]);
            let Some((kept, gained)) = move_share(g, &body.joint, &current[i], parent, &share)
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
pub(crate) fn arithmetic_cost(g: &Graph, outputs: &[Node]) -> (usize, usize) {
    cost_above(g, outputs, |_| false)
}

/// The inertias that make the joint forces τ of `sweep` (a Newton–Euler sweep over
/// `inertias`, with the inputs `inputs`) cost the fewest operations, and the backward sweep
/// over them: the regrouping of inertial parameters of Khalil and Kleinfinger ("Minimum
/// operations and minimum parameters of the dynamic models of tree structure robots",
/// 1987), chosen by [`greedy`]. Each candidate redoes only the changed bodies' paths to the
/// root ([`Backward::with`]). τ is unchanged; the backward sweep's joint wrenches are not
/// the joints' (use `sweep`'s).
pub(crate) fn regroup_sweep(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inputs: &SweepInputs,
    inertias: &[BodyInertia],
    sweep: &rnea::Sweep,
) -> (Backward, Vec<BodyInertia>) {
    if model.bodies.len() > EXACT_SWEEP_BODIES {
        regroup_sweep_windowed(g, model, transforms, inputs, inertias, sweep)
    } else {
        regroup_sweep_whole(g, model, transforms, inputs, inertias, sweep)
    }
}

/// [`regroup_sweep`] judging each candidate by the whole τ.
fn regroup_sweep_whole(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inputs: &SweepInputs,
    inertias: &[BodyInertia],
    sweep: &rnea::Sweep,
) -> (Backward, Vec<BodyInertia>) {
    greedy(
        g,
        model,
        inertias,
        sweep.backward.clone(),
        |backward| arithmetic_cost(g, &backward.tau),
        |backward, candidate, changed| {
            let changes: Vec<(usize, (Vec3, Vec3))> = changed
                .iter()
                .map(|&k| (k, sweep.own(g, k, &candidate[k])))
                .collect();
            backward.with(g, model, transforms, inputs, &changes)
        },
    )
}

/// The most bodies for which [`regroup_sweep`] judges each candidate by the whole τ: each
/// candidate redoes its bodies' paths to the root, in time and memory quadratic in the
/// tree's depth. Above it, [`regroup_sweep_windowed`] judges each candidate on a window of
/// the tree, in time and memory linear in the number of bodies.
pub(crate) const EXACT_SWEEP_BODIES: usize = 64;

/// How many ancestors above a candidate's parent the windowed search recomputes: enough
/// for a change of a body's inertia to show in the wrench its parent carries up (a zero it
/// makes or fills there).
const WINDOW_ANCESTORS: usize = 1;

/// [`regroup_sweep`] for large trees: the same greedy walk from the leaves to the root, but
/// each candidate is judged on a window (the body, its parent and [`WINDOW_ANCESTORS`] more
/// ancestors) rather than on the whole τ: the window's cost is that of its joints' τ and of
/// the wrench its top carries up, counted down to what every candidate shares (the forward
/// sweep, the joint transforms and the wrenches of the bodies already passed). A body's
/// wrench is final once the walk has passed it (its share decided, its children passed), so
/// each is built once; the sweep over the chosen inertias is built at the end.
fn regroup_sweep_windowed(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inputs: &SweepInputs,
    inertias: &[BodyInertia],
    sweep: &rnea::Sweep,
) -> (Backward, Vec<BodyInertia>) {
    let n = model.bodies.len();
    let children = rnea::children_in_decreasing_order(model);
    // The forward sweep (the bodies' motions and loads; the transforms came before them)
    // was built before anything of the backward sweep: its nodes are the ones below
    // `forward_end`. A node that the rules rewrite from one of them (a negated sum, say) is
    // new, and the count stops at its operands.
    let forward_end = sweep
        .motions
        .iter()
        .flat_map(|m| {
            let rows = m.relative_accel.0.iter().chain(&m.omega_products);
            let vectors = m.omega.0.iter().chain(&m.alpha.0).chain(&m.accel.0);
            rows.flatten()
                .chain(vectors)
                .copied()
                .collect::<Vec<Node>>()
        })
        .chain(
            sweep
                .loads
                .iter()
                .flat_map(|(f, m)| f.0.into_iter().chain(m.0)),
        )
        .map(|node| node.index() + 1)
        .max()
        .unwrap_or(0);
    let mut current = inertias.to_vec();
    let mut own: Vec<(Vec3, Vec3)> = sweep.backward.own_wrenches().to_vec();
    // The wrench each passed body carries to its parent (final), or None; and the nodes
    // they need, which every later window shares.
    let mut carried: Vec<Option<(Vec3, Vec3)>> = vec![None; n];
    let mut passed: HashSet<Node> = HashSet::new();
    let mut tau = vec![g.zero(); model.nv];
    let mut window_cost = |own_of: &dyn Fn(usize) -> (Vec3, Vec3),
                           carried: &[Option<(Vec3, Vec3)>],
                           passed: &HashSet<Node>,
                           bottom: usize| {
        let mut outputs = Vec::new();
        let mut below: Option<(Vec3, Vec3)> = None;
        let mut body = Some(bottom);
        for _ in 0..WINDOW_ANCESTORS + 2 {
            let Some(k) = body else { break };
            let passed_children = children[k].iter().filter_map(|&c| carried[c]);
            let total = rnea::joint_wrench(g, own_of(k), passed_children.chain(below));
            let joint = &model.bodies[k].joint;
            rnea::joint_force(g, joint, total, inputs, &mut tau);
            outputs.extend_from_slice(&tau[joint.idx_v..joint.idx_v + joint.kind.dofs()]);
            below = Some(geometry::wrench_to_parent(
                g,
                &transforms[k],
                total.0,
                total.1,
            ));
            body = model.bodies[k].parent;
        }
        if let Some((f, m)) = below {
            outputs.extend(f.0.into_iter().chain(m.0));
        }
        cost_above(g, &outputs, |node| {
            node.index() < forward_end || passed.contains(&node)
        })
    };
    for i in (0..n).rev() {
        let body = &model.bodies[i];
        let mut best_cost = window_cost(&|k| own[k], &carried, &passed, i);
        let mut best = None;
        for share in movable_shares(g, &body.joint, &current[i]) {
            let parent = body.parent.map(|p| &current[p]);
            let Some((kept, gained)) = move_share(g, &body.joint, &current[i], parent, &share)
            else {
                continue;
            };
            let mut changes = vec![(i, sweep.own(g, i, &kept))];
            if let (Some(p), Some(gained)) = (body.parent, &gained) {
                changes.push((p, sweep.own(g, p, gained)));
            }
            let own_of = |k: usize| {
                changes
                    .iter()
                    .find(|(b, _)| *b == k)
                    .map_or(own[k], |(_, wrench)| *wrench)
            };
            let c = window_cost(&own_of, &carried, &passed, i);
            if c < best_cost {
                best_cost = c;
                best = Some((changes, kept, gained));
            }
        }
        if let Some((changes, kept, gained)) = best {
            current[i] = kept;
            if let (Some(p), Some(gained)) = (body.parent, gained) {
                current[p] = gained;
            }
            for (k, wrench) in changes {
                own[k] = wrench;
            }
        }
        let total = rnea::joint_wrench(g, own[i], children[i].iter().filter_map(|&c| carried[c]));
        let up = geometry::wrench_to_parent(g, &transforms[i], total.0, total.1);
        // Everything the carried wrench needs is shared from now on (not only its six
        // nodes: the rules may rewrite a sum with one of them into one with its operands).
        let mut stack: Vec<Node> = up.0 .0.into_iter().chain(up.1 .0).collect();
        while let Some(node) = stack.pop() {
            if node.index() >= forward_end && passed.insert(node) {
                stack.extend(g.op(node).children());
            }
        }
        carried[i] = Some(up);
    }
    (Backward::new(g, model, transforms, inputs, own), current)
}

/// (operations, additions) of the nodes `outputs` need, neither counting nor looking below
/// the nodes for which `shared` holds.
fn cost_above(g: &Graph, outputs: &[Node], shared: impl Fn(Node) -> bool) -> (usize, usize) {
    let mut seen: HashSet<Node> = HashSet::new();
    let mut stack: Vec<Node> = Vec::new();
    for &node in outputs {
        if !shared(node) && seen.insert(node) {
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
            if !shared(child) && seen.insert(child) {
                stack.push(child);
            }
        }
    }
    (ops, adds)
}

/// The base inertial parameters that make inverse dynamics (with gravity, q̇ and q̈ as
/// inputs, no loads) cheapest, as [`regroup_sweep`] chooses them: a choice computed once,
/// incrementally, that serves the other functions of the Lagrangian when expanding each
/// candidate would cost too much ([`SEARCH_BUDGET`]).
pub(crate) fn for_inverse_dynamics(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
) -> Vec<BodyInertia> {
    let velocity: Vec<Node> = (0..model.nv).map(|k| g.input(Array::V, k)).collect();
    let acceleration: Vec<Node> = (0..model.nv).map(|k| g.input(Array::A, k)).collect();
    let inputs = SweepInputs {
        velocity: &velocity,
        acceleration: &acceleration,
        gravity: true,
        loads: false,
    };
    let sweep = rnea::sweep(g, model, transforms, inertias, &inputs);
    regroup_sweep(g, model, transforms, &inputs, inertias, &sweep).1
}

/// A share of a body's inertia that its joint's motion leaves unchanged, so that it moves
/// as if fixed to the parent (Khalil and Kleinfinger's regrouping of inertial parameters):
/// about a revolute axis s, the mass m, a first moment along s and an inertia Y (1 − s sᵀ)
/// (the kinetic energy ½ Y |ω × s|² and the potential energy do not depend on q or q̇);
/// along a prismatic axis, a pure inertia with no mass (its angular motion is the parent's).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Share {
    /// Mass.
    pub mass: Node,
    /// First moment about P, in the body frame.
    pub first_moment: Vec3,
    /// Inertia about P, in the body frame.
    pub inertia: Mat3,
}

/// The shares of a body that its joint lets it hand to its parent without changing any
/// joint force: for a revolute joint, the mass with the first moment along the axis, and
/// inertias Y (1 − s sᵀ) with Y = 0 or, for a coordinate axis, Y one of the two diagonal
/// entries across the axis (which then vanishes from the body); for a prismatic joint, all
/// of I_P. Empty for a free joint or a body whose inertia is not all numbers.
pub(crate) fn movable_shares(g: &Graph, joint: &model::Joint, inertia: &BodyInertia) -> Vec<Share> {
    if !is_constant_inertia(g, inertia) {
        return Vec::new();
    }
    let zero = g.zero();
    match joint.kind {
        JointKind::Revolute { axis_in_body } => {
            let s = Vec3::constant(g, axis_in_body);
            let along = s.scale(g, s.dot(g, inertia.first_moment));
            let across =
                Mat3::identity(g).sub(g, Mat3::from_rows([0, 1, 2].map(|i| s.scale(g, s.get(i)))));
            let mut ys = vec![zero];
            if axis_in_body.iter().filter(|a| **a != 0.0).count() == 1 {
                let k = axis_in_body.iter().position(|a| *a != 0.0).unwrap_or(2);
                for i in [(k + 1) % 3, (k + 2) % 3] {
                    let y = inertia.inertia_about_origin.get(i, i);
                    if y != zero && !ys.contains(&y) {
                        ys.push(y);
                    }
                }
            }
            let mut shares = Vec::new();
            for &y in &ys {
                for with_mass in [false, true] {
                    if y == zero && !with_mass {
                        continue;
                    }
                    let (mass, first_moment) = if with_mass {
                        (inertia.mass, along)
                    } else {
                        (zero, Vec3::zero(g))
                    };
                    shares.push(Share {
                        mass,
                        first_moment,
                        inertia: across.scale(g, y),
                    });
                }
            }
            shares
        }
        JointKind::Prismatic { .. } => vec![Share {
            mass: zero,
            first_moment: Vec3::zero(g),
            inertia: inertia.inertia_about_origin,
        }],
        JointKind::Free => Vec::new(),
    }
}

/// Moves `share` of body `child` to its parent (`None`: the ground, which drops it): the
/// child keeps the rest; the parent gains m, h + m r + R h_s and
/// R I_s Rᵀ − m r̂² − (r̂ ĥ' + ĥ' r̂) (h' = R h_s), the share's inertia carried to the parent
/// frame (R, the joint's placement rotation, stands for E: the share is invariant under the
/// joint's motion) and shifted from P_child to P_parent. Returns `None` when the joint's
/// offset is not a number.
pub(crate) fn move_share(
    g: &Graph,
    joint: &model::Joint,
    child: &BodyInertia,
    parent: Option<&BodyInertia>,
    share: &Share,
) -> Option<(BodyInertia, Option<BodyInertia>)> {
    let kept = inertia_from(
        g,
        g.sub(child.mass, share.mass),
        child.first_moment.sub(g, share.first_moment),
        child.inertia_about_origin.sub(g, share.inertia),
    );
    let Some(parent) = parent else {
        return Some((kept, None));
    };
    if !is_constant_inertia(g, parent) {
        return None;
    }
    let r = vector(g, &joint.translation_in_parent);
    if r.0.iter().any(|n| g.constant_value(*n).is_none()) {
        return None;
    }
    let rotation = Mat3::constant(g, joint.rotation_in_parent);
    let m = share.mass;
    let h = rotation.mul_vec(g, share.first_moment);
    let (r_hat, h_hat) = (r.cross_matrix(g), h.cross_matrix(g));
    let inertia = rotation
        .mul(g, share.inertia)
        .mul(g, rotation.transpose())
        .sub(g, r_hat.mul(g, r_hat).scale(g, m))
        .sub(g, r_hat.mul(g, h_hat).add(g, h_hat.mul(g, r_hat)));
    let gained = inertia_from(
        g,
        g.add(parent.mass, m),
        parent.first_moment.add(g, r.scale(g, m)).add(g, h),
        parent.inertia_about_origin.add(g, inertia),
    );
    Some((kept, Some(gained)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expand::{aba, coriolis, crba};
    use crate::functions::{forward_dynamics_by, ForwardMethod};

    /// The windowed search (for large trees) judges each candidate on a window of the tree
    /// instead of the whole τ: on chains and a branched tree it finds inverse dynamics of
    /// the same cost as the whole search (measured: equal on these), with the same values.
    #[test]
    fn the_windowed_regrouping_matches_the_whole_search() {
        for (tokens, name) in [
            (
                crate::functions::tests::chain(30, true, quote::quote!([inverse_dynamics])),
                "spatial",
            ),
            (
                crate::functions::tests::chain(30, false, quote::quote!([inverse_dynamics])),
                "planar",
            ),
            (crate::functions::tests::quadruped_tokens(), "quadruped"),
        ] {
            let mechanism: crate::syntax::Mechanism = syn::parse2(tokens).expect("parses");
            let model = crate::model::lower(&mechanism).expect("valid");
            let (g, t, i) = crate::expand::fresh_graph(&model);
            let (v, a) = (
                crate::expand::inputs(&g, Array::V, model.nv),
                crate::expand::inputs(&g, Array::A, model.nv),
            );
            let inputs = SweepInputs {
                velocity: &v,
                acceleration: &a,
                gravity: true,
                loads: false,
            };
            let sweep = rnea::sweep(&g, &model, &t, &i, &inputs);
            let whole = regroup_sweep_whole(&g, &model, &t, &inputs, &i, &sweep)
                .0
                .tau;
            let windowed = regroup_sweep_windowed(&g, &model, &t, &inputs, &i, &sweep)
                .0
                .tau;
            let declared = arithmetic_cost(&g, &sweep.backward.tau).0;
            let (w, h) = (
                arithmetic_cost(&g, &windowed).0,
                arithmetic_cost(&g, &whole).0,
            );
            assert!(w < declared, "{name}: windowed {w}, declared {declared}");
            assert_eq!(w, h, "{name}: windowed {w}, whole search {h}");
            let input = |r: crate::sym::InputRef| (f64::from(r.index) * 0.37 + 0.2).sin();
            let (x, y) = (g.eval(input, &windowed), g.eval(input, &sweep.backward.tau));
            for (x, y) in x.iter().zip(&y) {
                assert!(
                    (x - y).abs() <= 1e-11 * (1.0 + y.abs()),
                    "{name}: {x} vs {y}"
                );
            }
        }
    }

    #[test]
    fn base_parameters_give_the_same_mass_coriolis_and_accelerations_for_fewer_operations() {
        let mechanism: crate::syntax::Mechanism =
            syn::parse2(crate::functions::tests::puma_tokens()).expect("parses");
        let model = crate::model::lower(&mechanism).expect("valid");
        let (g, t, i) = crate::expand::fresh_graph(&model);
        let declared = crba::mass_matrix(&g, &model, &t, &i).concat();
        let regrouped = {
            let build = |i: &[BodyInertia]| crba::mass_matrix(&g, &model, &t, i);
            build(&regroup(&g, &model, &t, &i, |i| build(i).concat())).concat()
        };
        let (v, tau) = (
            crate::expand::inputs(&g, Array::V, model.nv),
            crate::expand::inputs(&g, Array::Tau, model.nv),
        );
        let none = vec![(crate::sym::Vec3::zero(&g), crate::sym::Vec3::zero(&g)); i.len()];
        let aba_declared = aba::forward_dynamics(&g, &model, &t, &i, (&v, &tau), &none);
        let (g2, aba_regrouped) = forward_dynamics_by(&model, ForwardMethod::ArticulatedBody);
        let count = |g: &Graph, nodes: &[Node]| {
            let c = g.op_count(nodes);
            c.mul + c.add
        };
        // Measured: M 280 → 226 operations (mul + add), the articulated-body q̈ 1351 → 943.
        assert!(
            count(&g, &regrouped) * 10 <= count(&g, &declared) * 9,
            "mass matrix: {} regrouped, {} declared",
            count(&g, &regrouped),
            count(&g, &declared)
        );
        assert!(count(&g2, &aba_regrouped) < count(&g, &aba_declared));
        let c_declared = coriolis::coriolis_matrix(&g, &model, &t, &i, &v).concat();
        let c_of = |i: &[BodyInertia]| coriolis::coriolis_matrix(&g, &model, &t, i, &v);
        let c_regrouped = c_of(&regroup(&g, &model, &t, &i, |i| c_of(i).concat())).concat();
        // Measured: 1132 → 867.
        assert!(count(&g, &c_regrouped) * 10 <= count(&g, &c_declared) * 8);
        for k in 0..5 {
            let input = |r: crate::sym::InputRef| {
                let x = f64::from(r.index) + 7.0 * f64::from(k);
                (x * 1.7).sin() * 2.0
            };
            let close = |a: &[f64], b: &[f64]| {
                a.iter()
                    .zip(b)
                    .all(|(x, y)| (x - y).abs() <= 1e-12 * (1.0 + x.abs()))
            };
            let (m0, m1) = (g.eval(input, &declared), g.eval(input, &regrouped));
            assert!(close(&m0, &m1), "M: {m0:?} vs {m1:?}");
            let (a0, a1) = (g.eval(input, &aba_declared), g2.eval(input, &aba_regrouped));
            assert!(close(&a0, &a1), "q̈: {a0:?} vs {a1:?}");
            let (c0, c1) = (g.eval(input, &c_declared), g.eval(input, &c_regrouped));
            assert!(close(&c0, &c1), "C: {c0:?} vs {c1:?}");
        }
    }
}
