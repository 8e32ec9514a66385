//! Columns of a tree matrix carried up the tree by [`Slots`]: the wrenches f that column j
//! (joint j's motion axis s_j) makes at body j, moved to each ancestor's frame in turn,
//!
//! ```text
//! F' = E F,   M'_P = E M_P + r × F'
//! ```
//!
//! (E and r the child's rotation and origin in its parent), where each ancestor's entries of
//! the column are inner products with its own axes. The mass matrix carries one wrench per
//! column (I^C_j s_j), the Coriolis matrix three. A carried value is packed: lane k is
//! column `columns[k]` (a packed slot's columns, lane by lane, or columns packed four to a
//! value where partly filled ones meet), so one operation moves up to four columns'
//! wrenches.

use super::geometry::{self, JointTransform};
use super::slots::{padded, Slots};
use super::spatial::Six;
use crate::sym::{Graph, Vec3};

/// The wrenches of up to four columns of a matrix on their way up the tree, in the frame of
/// the slot they have reached: lane k of each is column `columns[k]`.
pub(crate) struct CarriedColumns {
    /// The wrenches [F; M_P] the columns are built from, the same number for every column.
    pub wrenches: Vec<Six>,
    /// The column of each lane (one to four).
    pub columns: Vec<usize>,
}

impl CarriedColumns {
    /// The wrenches moved into the parent's frame across the joint transform `t`.
    pub fn moved_to_parent(self, g: &Graph, t: &JointTransform) -> CarriedColumns {
        CarriedColumns {
            wrenches: self
                .wrenches
                .into_iter()
                .map(|(f, m)| geometry::wrench_to_parent(g, t, f, m))
                .collect(),
            columns: self.columns,
        }
    }
}

/// The columns that travel on partly filled values (single columns, limbs' columns of
/// fewer than four lanes) packed again, four to a value in column order (so that a row's
/// entries of one pack are adjacent in the matrix), where that makes fewer values to carry;
/// full packs as they are. Two single columns so share every step above at the cost of
/// one, and a chain's columns fill their packs as they meet: two, three, then four.
pub(crate) fn pack_columns(g: &Graph, carried: Vec<CarriedColumns>) -> Vec<CarriedColumns> {
    let (partial, mut out): (Vec<_>, Vec<_>) =
        carried.into_iter().partition(|c| c.columns.len() < 4);
    let lanes: usize = partial.iter().map(|c| c.columns.len()).sum();
    if lanes.div_ceil(4) >= partial.len() {
        out.extend(partial);
        return out;
    }
    // One column a lane: its wrenches' lane.
    let mut columns: Vec<(usize, Vec<Six>)> = partial
        .iter()
        .flat_map(|c| {
            c.columns.iter().enumerate().map(|(k, &column)| {
                let wrenches = c
                    .wrenches
                    .iter()
                    .map(|&(f, m)| (f.lane(g, k), m.lane(g, k)));
                (column, wrenches.collect())
            })
        })
        .collect();
    columns.sort_by_key(|&(column, _)| column);
    for chunk in columns.chunks(4) {
        let pack = |value: &dyn Fn(&[Six]) -> Vec3| {
            Vec3(std::array::from_fn(|i| {
                g.pack(std::array::from_fn(|k| value(&padded(chunk, k).1).0[i]))
            }))
        };
        let wrenches = (0..chunk[0].1.len())
            .map(|w| (pack(&|c| c[w].0), pack(&|c| c[w].1)))
            .collect();
        out.push(CarriedColumns {
            wrenches,
            columns: chunk.iter().map(|&(column, _)| column).collect(),
        });
    }
    out
}

/// The sweep that carries a tree matrix's columns from the leaves to the root over `slots`
/// (with their joint transforms): at each slot, `at_slot(s, carried)` is given the columns
/// arriving from below (in slot s's frame), reads its rows' entries from them and pushes
/// the slot's own columns; they then move to the parent slot, those leaving a scalar slot
/// packed again ([`pack_columns`]) when `repack`.
pub(crate) fn carry_columns_up(
    g: &Graph,
    slots: &Slots,
    transforms: &[JointTransform],
    repack: bool,
    mut at_slot: impl FnMut(usize, &mut Vec<CarriedColumns>),
) {
    let mut arriving: Vec<Vec<CarriedColumns>> = slots.slots.iter().map(|_| Vec::new()).collect();
    for s in (0..slots.slots.len()).rev() {
        let mut carried = std::mem::take(&mut arriving[s]);
        at_slot(s, &mut carried);
        if let Some(p) = slots.parent_slot(s) {
            if repack && slots.slots[s].lanes.len() == 1 {
                carried = pack_columns(g, carried);
            }
            for column in carried {
                arriving[p].push(column.moved_to_parent(g, &transforms[s]));
            }
        }
    }
}
