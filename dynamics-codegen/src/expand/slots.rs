//! Isomorphic limbs side by side: the tree's bodies grouped into slots of one to four
//! bodies whose values a sweep computes together, one per lane of packed values
//! ([`crate::sym`]'s `Graph::pack`).
//!
//! Sibling subtrees of the same shape (the same joint kinds and axes, the same branching,
//! as a humanoid's legs or a quadruped's four legs are) are packed: their roots form one
//! slot, and each of their bodies forms a slot with the bodies at the same place in the
//! others. A slot's joint transform and inertia are the lanes' zipped (`Graph::zip`): a
//! packed operation where the lanes compute the same operation on different numbers or
//! angles. Every other body is a slot of its own, with scalar values. A slot's lanes
//! share one parent slot, lane k's parent in its lane k, or one parent body (scalar) for
//! all lanes.

use super::geometry::{self, BodyInertia, JointTransform};
use super::spatial::{add6, Six};
use crate::model::Model;
use crate::sym::{Graph, Mat3, Node, Vec3};

/// One slot: bodies computed side by side.
pub struct Slot {
    /// The body of each lane (one to four), lane 0 first.
    pub lanes: Vec<usize>,
    /// Where the lanes hang.
    pub parent: SlotParent,
}

/// A slot's parent.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SlotParent {
    /// The ground: the lanes are roots.
    Ground,
    /// The slot holding the lanes' parents, lane k's parent in its lane k.
    Packed(usize),
    /// One body, every lane's parent (a scalar slot).
    Body(usize),
}

/// The slots of a tree.
pub struct Slots {
    /// Parents' slots before their children's (in the order of lane 0's body).
    pub slots: Vec<Slot>,
    /// The slot and lane of each body.
    pub of_body: Vec<(usize, usize)>,
}

impl Slots {
    /// Every body alone, in body order: a sweep over these is the sweep over the bodies.
    pub fn each_body(model: &Model) -> Slots {
        let slots = model
            .bodies
            .iter()
            .enumerate()
            .map(|(b, body)| Slot {
                lanes: vec![b],
                parent: body.parent.map_or(SlotParent::Ground, SlotParent::Body),
            })
            .collect();
        let of_body = (0..model.bodies.len()).map(|b| (b, 0)).collect();
        Slots { slots, of_body }
    }

    /// Isomorphic sibling subtrees packed up to four at a time (the first siblings of each
    /// shape in body order), every other body alone; every body alone for a model that does
    /// not pack ([`Model::packs`]).
    pub fn of(model: &Model) -> Slots {
        if !model.packs {
            return Slots::each_body(model);
        }
        let n = model.bodies.len();
        let mut children = vec![Vec::new(); n];
        for (b, body) in model.bodies.iter().enumerate() {
            if let Some(p) = body.parent {
                children[p].push(b);
            }
        }
        let mut shapes = vec![String::new(); n];
        for b in (0..n).rev() {
            let kids: Vec<&str> = children[b].iter().map(|&c| shapes[c].as_str()).collect();
            shapes[b] = format!("{:?}({})", model.bodies[b].joint.kind, kids.join(","));
        }
        // (lanes, the slot index of the packed parent) in the order they are made.
        let mut made: Vec<(Vec<usize>, Option<usize>)> = Vec::new();
        let mut placed = vec![false; n];
        for b in 0..n {
            if placed[b] {
                continue;
            }
            let parent = model.bodies[b].parent;
            let group: Vec<usize> = (b..n)
                .filter(|&c| {
                    !placed[c] && model.bodies[c].parent == parent && shapes[c] == shapes[b]
                })
                .take(4)
                .collect();
            // The group's subtrees, level by level: lanes of corresponding bodies.
            let mut pending = vec![(group, None)];
            while let Some((lanes, packed_parent)) = pending.pop() {
                let id = made.len();
                for &l in &lanes {
                    placed[l] = true;
                }
                if lanes.len() > 1 {
                    for j in 0..children[lanes[0]].len() {
                        let next = lanes.iter().map(|&l| children[l][j]).collect();
                        pending.push((next, Some(id)));
                    }
                }
                made.push((lanes, packed_parent));
            }
        }
        // Sorted by lane 0's body: a parent's lane 0 comes before its children's.
        let mut order: Vec<usize> = (0..made.len()).collect();
        order.sort_by_key(|&s| made[s].0[0]);
        let mut new_id = vec![0; made.len()];
        for (new, &old) in order.iter().enumerate() {
            new_id[old] = new;
        }
        let slots: Vec<Slot> = order
            .iter()
            .map(|&old| {
                let (lanes, packed_parent) = &made[old];
                let parent = match (packed_parent, model.bodies[lanes[0]].parent) {
                    (Some(p), _) => SlotParent::Packed(new_id[*p]),
                    (None, Some(body)) => SlotParent::Body(body),
                    (None, None) => SlotParent::Ground,
                };
                Slot {
                    lanes: lanes.clone(),
                    parent,
                }
            })
            .collect();
        let mut of_body = vec![(0, 0); n];
        for (s, slot) in slots.iter().enumerate() {
            for (k, &b) in slot.lanes.iter().enumerate() {
                of_body[b] = (s, k);
            }
        }
        Slots { slots, of_body }
    }

    /// The slot holding slot `s`'s parents, none for roots.
    pub fn parent_slot(&self, s: usize) -> Option<usize> {
        match self.slots[s].parent {
            SlotParent::Ground => None,
            SlotParent::Packed(p) => Some(p),
            SlotParent::Body(b) => Some(self.of_body[b].0),
        }
    }

    /// How slot `s`'s values join its parent slot's sums: `[None]`, all lanes at once, lane
    /// for lane, into a packed parent; `Some(k)` for each lane k in turn into a scalar one;
    /// nothing for roots.
    pub fn lanes_into_parent(&self, s: usize) -> Vec<Option<usize>> {
        match self.slots[s].parent {
            SlotParent::Packed(_) => vec![None],
            SlotParent::Body(_) => (0..self.slots[s].lanes.len()).map(Some).collect(),
            SlotParent::Ground => Vec::new(),
        }
    }

    /// Slot `s`'s lanes' `value`s (of each lane's body) zipped.
    pub fn zip_lanes(&self, g: &Graph, s: usize, value: impl Fn(usize) -> Node) -> Node {
        let lanes = &self.slots[s].lanes;
        g.zip(std::array::from_fn(|k| value(*padded(lanes, k))))
    }

    /// Each slot's joint transform, its lanes' zipped.
    pub fn transforms(&self, g: &Graph, per_body: &[JointTransform]) -> Vec<JointTransform> {
        self.slots
            .iter()
            .map(|slot| {
                let lanes: Vec<&JointTransform> =
                    slot.lanes.iter().map(|&b| &per_body[b]).collect();
                JointTransform {
                    rotation_to_parent: zip_mat3(g, &lanes, |t| t.rotation_to_parent),
                    origin_in_parent: zip_vec3(g, &lanes, |t| t.origin_in_parent),
                }
            })
            .collect()
    }

    /// Each slot's body inertia, its lanes' zipped.
    pub fn inertias(&self, g: &Graph, per_body: &[BodyInertia]) -> Vec<BodyInertia> {
        self.slots
            .iter()
            .map(|slot| {
                let lanes: Vec<&BodyInertia> = slot.lanes.iter().map(|&b| &per_body[b]).collect();
                BodyInertia {
                    mass: zip(g, &lanes, |i| i.mass),
                    first_moment: zip_vec3(g, &lanes, |i| i.first_moment),
                    inertia_about_origin: zip_mat3(g, &lanes, |i| i.inertia_about_origin),
                    mass_centre: None,
                }
            })
            .collect()
    }
}

/// The subtree sums of slot-indexed wrenches, each in its slot's frame, in place: from the
/// leaves, each slot's sum moved into its parent's frame (`transforms`, indexed by slot)
/// and added there, lane for lane into a packed parent, each lane in turn into a scalar
/// one (the Newton–Euler backward sweep's F_i + Σ X F_child, or C's momenta ½ h^C).
pub fn sum_wrenches_up(
    g: &Graph,
    slots: &Slots,
    transforms: &[JointTransform],
    wrenches: &mut [Six],
) {
    for s in (0..slots.slots.len()).rev() {
        if let Some(p) = slots.parent_slot(s) {
            let (f, m) = wrenches[s];
            let moved = geometry::wrench_to_parent(g, &transforms[s], f, m);
            for k in slots.lanes_into_parent(s) {
                let lane = |x: Vec3| k.map_or(x, |k| x.lane(g, k));
                wrenches[p] = add6(g, wrenches[p], (lane(moved.0), lane(moved.1)));
            }
        }
    }
}

/// Lane k of a group of one to four: a group of fewer than four repeats its last in the
/// lanes beyond it.
pub fn padded<T>(group: &[T], k: usize) -> &T {
    &group[k.min(group.len() - 1)]
}

/// The lanes' `value`s zipped.
fn zip<T>(g: &Graph, lanes: &[&T], value: impl Fn(&T) -> Node) -> Node {
    g.zip(std::array::from_fn(|k| value(*padded(lanes, k))))
}

fn zip_vec3<T>(g: &Graph, lanes: &[&T], value: impl Fn(&T) -> Vec3) -> Vec3 {
    Vec3(std::array::from_fn(|i| zip(g, lanes, |t| value(t).0[i])))
}

fn zip_mat3<T>(g: &Graph, lanes: &[&T], value: impl Fn(&T) -> Mat3) -> Mat3 {
    Mat3(std::array::from_fn(|i| {
        std::array::from_fn(|j| zip(g, lanes, |t| value(t).0[i][j]))
    }))
}
