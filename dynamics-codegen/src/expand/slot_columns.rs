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
//! column `columns[k]` (a packed slot's columns, lane by lane, or single columns packed four
//! to a value where they meet), so one operation moves up to four columns' wrenches.

use super::geometry::{self, JointTransform};
use super::slots::padded;
use super::spatial::Six;
use crate::sym::{Graph, Node, Vec3};

/// The wrenches of up to four columns of a matrix on their way up the tree, in the frame of
/// the slot they have reached: lane k of each is column `columns[k]`.
pub(crate) struct CarriedColumns {
    /// The wrenches [F; M_P] the columns are built from, the same number for every column.
    pub wrenches: Vec<Six>,
    /// The column of each lane (one to four).
    pub columns: Vec<usize>,
}

impl CarriedColumns {
    /// Whether this is one column with scalar values.
    fn is_scalar(&self, g: &Graph) -> bool {
        self.columns.len() == 1
            && !self
                .wrenches
                .iter()
                .flat_map(|(f, m)| f.0.iter().chain(&m.0))
                .any(|&n| g.is_packed(n))
    }

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

/// The fewest single columns at a body that travel on packed: two or more share every
/// step above it at the cost of one.
const PACK_COLUMNS_FROM: usize = 2;

/// Single columns' wrenches packed four at a time, in column order (so that a row's entries
/// of one pack are adjacent in the matrix); the others as they are.
pub(crate) fn pack_single_columns(g: &Graph, carried: Vec<CarriedColumns>) -> Vec<CarriedColumns> {
    let (mut singles, mut out): (Vec<_>, Vec<_>) =
        carried.into_iter().partition(|c| c.is_scalar(g));
    if singles.len() < PACK_COLUMNS_FROM {
        out.extend(singles);
        return out;
    }
    singles.sort_by_key(|c| c.columns[0]);
    for chunk in singles.chunks(4) {
        let lanes = |value: &dyn Fn(&CarriedColumns) -> Node| {
            g.pack(std::array::from_fn(|k| value(padded(chunk, k))))
        };
        let wrenches = (0..chunk[0].wrenches.len())
            .map(|w| {
                let part = |linear: bool, i: usize| {
                    lanes(&|c: &CarriedColumns| {
                        let (f, m) = c.wrenches[w];
                        if linear {
                            f.0[i]
                        } else {
                            m.0[i]
                        }
                    })
                };
                (
                    Vec3(std::array::from_fn(|i| part(true, i))),
                    Vec3(std::array::from_fn(|i| part(false, i))),
                )
            })
            .collect();
        out.push(CarriedColumns {
            wrenches,
            columns: chunk.iter().map(|c| c.columns[0]).collect(),
        });
    }
    out
}
