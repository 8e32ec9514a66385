//! A generated function over slices of states, four (`f64`) or eight (`f32`) states per call.
//!
//! # Contract
//!
//! `mapN(x₁, …, x_N, out, f)` sets `out[i]` to `f` of the i-th elements of `x₁ … x_N`, for
//! every `i`, with `f` called on SIMD lanes: [`F64x4`] for `f64` data, [`F32x8`] for `f32`.
//! The states are packed [`Lanes::LANES`] at a time, `f` runs once per pack, and the pack's
//! result is unpacked into `out`. When the length is not a multiple of the lane count, the
//! last pack is filled up with copies of its last state (real numbers, so no spurious NaN
//! or division by zero in lanes whose results are then dropped); there is no scalar tail,
//! so every state goes through the same code. For a generated function the lanes are
//! independent, so `out[i]` is bit for bit what `f` gives for state `i` in any lane of any
//! pack: the contract of [`F64x4`] and [`F32x8`] (for `F64x4` in a build without AVX, the
//! `f64` call on the state in the copy `f64` runs; see [`lanes`](crate::lanes)).
//!
//! Every input slice must be as long as `out`; otherwise the call returns
//! [`LengthMismatch`] and leaves `out` untouched. No allocation, no panic (unless `f`
//! panics). Inputs and outputs are any [`Shape`]: a number, an array of shapes (`[f64; 6]`,
//! `[[f64; 6]; 6]`), or a pair or triple of shapes, as the generated functions take and
//! return them.
//!
//! With the `rayon` feature (off by default) `par_mapN` does the same on all of rayon's
//! threads, in blocks of 16 packs: the same results, bit for bit.
//!
//! The loop (packing, the calls, unpacking) runs in the copy the kernels run in: compiled
//! for AVX2 and FMA where `f64`'s kernels are ([`isa`](crate::isa)), so that packing and
//! unpacking move whole AVX registers. It only moves numbers, and each call still runs the
//! copy its kernel chooses, so the results are those of that copy either way.
//!
//! A full pack of [`F64x4`] is unpacked four entries of four results at a time (a 4 × 4
//! transpose, AVX registers in the AVX2 copy). For functions that write their result into
//! their last argument, as the generated `_into` functions do, `map1_into`..`map5_into`
//! keep one packed result for the whole call instead of returning one per pack by value.
//!
//! Speed (the [`lanes`](crate::lanes) module, "Speed"; BENCHMARKS.md, "Many states per
//! call", at 49ca3da): in a default build an [`F64x4`] runs in the AVX2 + FMA copy where
//! `f64` does; through these helpers, packing included, 1.9 to 2.4× the throughput of
//! `f64` calls for inverse and forward dynamics on 64 states, 1.4 to 1.9× for mass
//! matrices (`map1_into`: the quadruped's 18 × 18 result, 2.6 kB a state, 1.55× the `f64`
//! call that returns it, 1.08× its `_into` call); on states already in lanes 2.4 to 3.0×
//! and 1.9 to 2.2×.
//!
//! # Example
//!
//! One line per generated function: the generic generated function itself is the `f`
//! (it takes the packs, `&[F64x4; N]` arrays, as they are). A closure passes what is the
//! same for every state, such as parameters or loads, splatted:
//! `|q, v, a| Robot::inverse_dynamics(q, v, a, &loads)` with `loads = [F64x4::splat(0.0); 12]`.
//!
//! ```
//! use dynamics_runtime::{batch, mechanism};
//!
//! mechanism! {
//!     /// A rod pivoted at one end, the pivot on a slider.
//!     pub struct Cart;
//!     gravity: [0.0, -9.81, 0.0];
//!     outputs: [inverse_dynamics, mass_matrix, kinetic_energy];
//!     body slider { mass: 1.0, shape: point }
//!     body rod { mass: 2.0, com: [0.0, -0.3, 0.0], shape: rod(length: 0.6, axis: y) }
//!     joint x: prismatic(ground -> slider) { axis: x }
//!     joint pivot: revolute(slider -> rod) { axis: z }
//! }
//!
//! // f64 and the lanes on the same copy of the kernels in any build (`lanes`' contract).
//! dynamics_runtime::isa::choose(false);
//! let q = vec![[0.1, 0.2], [0.0, 1.0], [0.3, -0.4], [0.0, 0.5], [0.2, 2.0]]; // 5 states
//! let v = vec![[0.0, 1.0]; 5];
//! let a = vec![[1.0, 0.0]; 5];
//! let (mut tau, mut m, mut t) = (vec![[0.0; 2]; 5], vec![[[0.0; 2]; 2]; 5], vec![0.0; 5]);
//!
//! batch::map3(&q, &v, &a, &mut tau, Cart::inverse_dynamics)?;
//! batch::map1(&q, &mut m, Cart::mass_matrix)?;
//! batch::map2(&q, &v, &mut t, Cart::kinetic_energy)?;
//!
//! for i in 0..5 {
//!     assert_eq!(tau[i], Cart::inverse_dynamics(&q[i], &v[i], &a[i]));
//!     assert_eq!(m[i], Cart::mass_matrix(&q[i]));
//! }
//! // A slice of the wrong length is an error, not a panic.
//! let err = batch::map3(&q, &v[..4], &a, &mut tau, Cart::inverse_dynamics);
//! assert_eq!(err, Err(batch::LengthMismatch { input: 1, len: 4, expected: 5 }));
//! # Ok::<(), batch::LengthMismatch>(())
//! ```

use crate::lanes::{F32x8, F64x4, Lanes};
use crate::Scalar;
use core::fmt;

/// A number type whose states the batch helpers pack into lanes: `f64` into [`F64x4`],
/// `f32` into [`F32x8`].
pub trait Element: Scalar {
    /// The lanes that hold several values of `Self`.
    type Lanes: Lanes<Element = Self>;
}

impl Element for f64 {
    type Lanes = F64x4;
}

impl Element for f32 {
    type Lanes = F32x8;
}

/// One state's input or output, of a fixed shape: an [`Element`] (`f64`, `f32`), an
/// array of shapes, or a pair or triple of shapes of the same element. `Packed` is the
/// same shape with lanes in place of numbers: `[f64; 6]` packs into `[F64x4; 6]`.
pub trait Shape {
    /// The number type.
    type Element: Element;
    /// The same shape, each number replaced by lanes of it.
    type Packed;
    /// The packed value whose lane `i` holds `*lane(i)`, for each lane `i`.
    fn pack<'a, F: Fn(usize) -> &'a Self>(lane: &F) -> Self::Packed
    where
        Self: 'a;
    /// Writes lane `lane` of `packed` into `out` (nothing when `lane` is not a lane).
    fn unpack(packed: &Self::Packed, lane: usize, out: &mut Self);
    /// The packed value with every number 0: the buffer the `map*_into` helpers start from.
    fn zero_packed() -> Self::Packed;
    /// Writes lanes 0 to 3 of `packed` into `out[0]` to `out[3]`: a pack's unpacking, four
    /// results at once. The default goes lane by lane through [`Shape::unpack`]; arrays
    /// hand their entries to [`Shape::unpack4_array`].
    #[inline(always)]
    fn unpack4(packed: &Self::Packed, out: [&mut Self; 4]) {
        for (lane, o) in out.into_iter().enumerate() {
            Self::unpack(packed, lane, o);
        }
    }
    /// Writes lanes 0 to 3 of each `packed[k]` into `out[0][k]` to `out[3][k]`: the
    /// unpacking of an array of `K` packed values. The default takes entry by entry through
    /// [`Shape::unpack4`]; a number ([`Element`]) overrides it to move four entries of four
    /// results at a time, so that it reads and writes whole SIMD registers (a 4 × 4
    /// transpose) instead of one number per instruction.
    #[inline(always)]
    fn unpack4_array<const K: usize>(packed: &[Self::Packed; K], out: [&mut [Self; K]; 4])
    where
        Self: Sized,
    {
        let [a, b, c, d] = out;
        for k in 0..K {
            Self::unpack4(&packed[k], [&mut a[k], &mut b[k], &mut c[k], &mut d[k]]);
        }
    }
}

/// The results of one pack, written into `out` (at most [`Lanes::LANES`] of them): four at
/// once through [`Shape::unpack4`] when there are four (a full pack of [`F64x4`]), else
/// lane by lane.
#[inline(always)]
fn unpack_pack<O: Shape>(packed: &O::Packed, out: &mut [O]) {
    if let [a, b, c, d] = out {
        O::unpack4(packed, [a, b, c, d]);
    } else {
        for (lane, o) in out.iter_mut().enumerate() {
            O::unpack(packed, lane, o);
        }
    }
}

macro_rules! element_shape {
    ($($t:ty: $transpose:path),*) => {$(
        impl Shape for $t {
            type Element = $t;
            type Packed = <$t as Element>::Lanes;
            #[inline(always)]
            fn pack<'a, F: Fn(usize) -> &'a Self>(lane: &F) -> Self::Packed {
                Lanes::from_fn(|i| *lane(i))
            }
            #[inline(always)]
            fn unpack(packed: &Self::Packed, lane: usize, out: &mut Self) {
                if let Some(x) = Lanes::get(*packed, lane) {
                    *out = x;
                }
            }
            #[inline(always)]
            fn zero_packed() -> Self::Packed {
                Lanes::splat(0.0)
            }
            /// Four entries of four results at a time: lane `l` of `packed[k..k + 4]` is
            /// written to `out[l][k..k + 4]` as one array, which the compiler turns into a
            /// 4 × 4 transpose in registers and one store per result; the last `K mod 4`
            /// entries by one more transpose, each result's part one store.
            #[inline(always)]
            fn unpack4_array<const K: usize>(
                packed: &[Self::Packed; K],
                out: [&mut [Self; K]; 4],
            ) {
                let [a, b, c, d] = out;
                let whole = K - K % 4;
                for k in (0..whole).step_by(4) {
                    let lanes = $transpose(core::array::from_fn(|j| Lanes::first4(packed[k + j])));
                    a[k..k + 4].copy_from_slice(&lanes[0]);
                    b[k..k + 4].copy_from_slice(&lanes[1]);
                    c[k..k + 4].copy_from_slice(&lanes[2]);
                    d[k..k + 4].copy_from_slice(&lanes[3]);
                }
                // The last K mod 4 entries: one more transpose, its missing rows copies of
                // the last entry, each result's part of it one store. Apart from the loop
                // above: folded into it (the end of each block `min(k + 4, K)`), the
                // quadruped's mass matrix through `map1` and `map1_into` took about three
                // times as long (lanes benchmark, 2026-12-04).
                if whole < K {
                    let lanes = $transpose(core::array::from_fn(|j| {
                        Lanes::first4(packed[(whole + j).min(K - 1)])
                    }));
                    let rest = K - whole;
                    a[whole..].copy_from_slice(&lanes[0][..rest]);
                    b[whole..].copy_from_slice(&lanes[1][..rest]);
                    c[whole..].copy_from_slice(&lanes[2][..rest]);
                    d[whole..].copy_from_slice(&lanes[3][..rest]);
                }
            }
        }
    )*};
}

element_shape!(f64: transpose::transpose4, f32: transpose::transpose4_portable);

impl<S: Shape, const K: usize> Shape for [S; K] {
    type Element = S::Element;
    type Packed = [S::Packed; K];
    #[inline(always)]
    fn pack<'a, F: Fn(usize) -> &'a Self>(lane: &F) -> Self::Packed
    where
        Self: 'a,
    {
        core::array::from_fn(|k| S::pack(&|i| &lane(i)[k]))
    }
    #[inline(always)]
    fn unpack(packed: &Self::Packed, lane: usize, out: &mut Self) {
        for (p, o) in packed.iter().zip(out.iter_mut()) {
            S::unpack(p, lane, o);
        }
    }
    #[inline(always)]
    fn zero_packed() -> Self::Packed {
        core::array::from_fn(|_| S::zero_packed())
    }
    #[inline(always)]
    fn unpack4(packed: &Self::Packed, out: [&mut Self; 4]) {
        S::unpack4_array(packed, out);
    }
}

macro_rules! tuple_shape {
    ($first:ident $(, $rest:ident)*; $($index:tt),*) => {
        impl<$first: Shape $(, $rest: Shape<Element = $first::Element>)*> Shape for ($first, $($rest),*) {
            type Element = $first::Element;
            type Packed = ($first::Packed, $($rest::Packed),*);
            #[inline(always)]
            fn pack<'a, F: Fn(usize) -> &'a Self>(lane: &F) -> Self::Packed
            where
                Self: 'a,
            {
                ($(Shape::pack(&|i| &lane(i).$index)),*)
            }
            #[inline(always)]
            fn unpack(packed: &Self::Packed, lane: usize, out: &mut Self) {
                $(Shape::unpack(&packed.$index, lane, &mut out.$index);)*
            }
            #[inline(always)]
            fn zero_packed() -> Self::Packed {
                ($first::zero_packed(), $($rest::zero_packed()),*)
            }
            #[inline(always)]
            fn unpack4(packed: &Self::Packed, out: [&mut Self; 4]) {
                let [a, b, c, d] = out;
                $(Shape::unpack4(
                    &packed.$index,
                    [&mut a.$index, &mut b.$index, &mut c.$index, &mut d.$index],
                );)*
            }
        }
    };
}

tuple_shape!(A, B; 0, 1);
tuple_shape!(A, B, C; 0, 1, 2);

/// An input slice whose length is not that of `out`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LengthMismatch {
    /// Which input, counted from 0 in the order of the arguments.
    pub input: usize,
    /// Its length.
    pub len: usize,
    /// The length of `out`.
    pub expected: usize,
}

impl fmt::Display for LengthMismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "input {} of the batch holds {} states, the output {}",
            self.input, self.len, self.expected
        )
    }
}

impl core::error::Error for LengthMismatch {}

/// The first input whose length is not `expected`.
fn check(expected: usize, lengths: &[usize]) -> Result<(), LengthMismatch> {
    match lengths.iter().position(|&len| len != expected) {
        Some(input) => Err(LengthMismatch {
            input,
            len: lengths.get(input).copied().unwrap_or(expected),
            expected,
        }),
        None => Ok(()),
    }
}

/// The lanes of `E` (at least 1, so that `chunks` never sees 0).
#[inline(always)]
fn lanes_of<E: Element>() -> usize {
    <E::Lanes as Lanes>::LANES.max(1)
}

/// A chunk of at most `LANES` states, packed, the missing lanes copies of its last state;
/// `None` for an empty chunk (which `chunks` never yields).
#[inline(always)]
fn pack<S: Shape>(chunk: &[S]) -> Option<S::Packed> {
    let last = chunk.last()?;
    Some(S::pack(&|i| chunk.get(i).unwrap_or(last)))
}

/// Rayon's work unit: this many packs.
#[cfg(feature = "rayon")]
const PACKS_PER_TASK: usize = 16;

macro_rules! map_fn {
    (
        $(#[$doc:meta])*
        $name:ident, $par:ident, $run:ident;
        $name_into:ident, $par_into:ident, $run_into:ident;
        $first:ident: $First:ident $(, $arg:ident: $Arg:ident)*
    ) => {
        $(#[$doc])*
        pub fn $name<$First, $($Arg,)* O, F>(
            $first: &[$First],
            $($arg: &[$Arg],)*
            out: &mut [O],
            f: F,
        ) -> Result<(), LengthMismatch>
        where
            $First: Shape,
            $($Arg: Shape<Element = $First::Element>,)*
            O: Shape<Element = $First::Element>,
            F: FnMut(&$First::Packed, $(&$Arg::Packed),*) -> O::Packed,
        {
            check(out.len(), &[$first.len(), $($arg.len()),*])?;
            $run($first, $($arg,)* out, f);
            Ok(())
        }

        /// The loop of the sequential and parallel helpers, on slices of equal lengths.
        #[inline(always)]
        fn $run<$First, $($Arg,)* O, F>(
            $first: &[$First],
            $($arg: &[$Arg],)*
            out: &mut [O],
            mut f: F,
        ) where
            $First: Shape,
            $($Arg: Shape<Element = $First::Element>,)*
            O: Shape<Element = $First::Element>,
            F: FnMut(&$First::Packed, $(&$Arg::Packed),*) -> O::Packed,
        {
            let lanes = lanes_of::<$First::Element>();
            let mut $first = $first.chunks(lanes);
            $(let mut $arg = $arg.chunks(lanes);)*
            crate::isa::run_loop(
                #[inline(always)]
                || {
                    for out in out.chunks_mut(lanes) {
                        let (Some($first), $(Some($arg),)*) =
                            ($first.next().and_then(pack), $($arg.next().and_then(pack),)*)
                        else {
                            break;
                        };
                        let packed = f(&$first, $(&$arg),*);
                        unpack_pack::<O>(&packed, out);
                    }
                },
            );
        }

        #[doc = concat!("[`", stringify!($name), "`] for a function that writes its result into")]
        /// its last argument, as the generated `_into` functions do: e.g.
        /// `batch::map1_into(&q, &mut m, Robot::mass_matrix_into)`. One packed result lives
        /// for the whole call, nothing is returned by value, and it is unpacked four results
        /// at a time. `f` must set every entry of that result (the generated `_into`
        /// functions set all of them, zeros included) or leave zero those it does not set
        /// (the `_sparse_into` functions: below M's diagonal, or between branches): the
        /// buffer starts at zero and is not cleared between packs.
        ///
        /// # Errors
        /// [`LengthMismatch`] for the first input not as long as `out` (nothing written).
        pub fn $name_into<$First, $($Arg,)* O, F>(
            $first: &[$First],
            $($arg: &[$Arg],)*
            out: &mut [O],
            f: F,
        ) -> Result<(), LengthMismatch>
        where
            $First: Shape,
            $($Arg: Shape<Element = $First::Element>,)*
            O: Shape<Element = $First::Element>,
            F: FnMut(&$First::Packed, $(&$Arg::Packed,)* &mut O::Packed),
        {
            check(out.len(), &[$first.len(), $($arg.len()),*])?;
            $run_into($first, $($arg,)* out, f);
            Ok(())
        }

        /// The loop of the sequential and parallel `_into` helpers, on slices of equal lengths.
        /// (The returning helpers keep a loop of their own: moving each returned result into
        /// this loop's buffer took the quadruped's mass matrix 164.8 ns a state instead of
        /// 132.0, lanes benchmark.)
        #[inline(always)]
        fn $run_into<$First, $($Arg,)* O, F>(
            $first: &[$First],
            $($arg: &[$Arg],)*
            out: &mut [O],
            mut f: F,
        ) where
            $First: Shape,
            $($Arg: Shape<Element = $First::Element>,)*
            O: Shape<Element = $First::Element>,
            F: FnMut(&$First::Packed, $(&$Arg::Packed,)* &mut O::Packed),
        {
            let lanes = lanes_of::<$First::Element>();
            let mut $first = $first.chunks(lanes);
            $(let mut $arg = $arg.chunks(lanes);)*
            let mut packed = O::zero_packed();
            crate::isa::run_loop(
                #[inline(always)]
                || {
                    for out in out.chunks_mut(lanes) {
                        let (Some($first), $(Some($arg),)*) =
                            ($first.next().and_then(pack), $($arg.next().and_then(pack),)*)
                        else {
                            break;
                        };
                        f(&$first, $(&$arg,)* &mut packed);
                        unpack_pack::<O>(&packed, out);
                    }
                },
            );
        }

        #[doc = concat!("[`", stringify!($name), "`] on rayon's threads (feature `rayon`): ")]
        /// the states in blocks of 16 packs, each block one task; the same results, bit for
        /// bit, and the same errors.
        #[cfg(feature = "rayon")]
        pub fn $par<$First, $($Arg,)* O, F>(
            $first: &[$First],
            $($arg: &[$Arg],)*
            out: &mut [O],
            f: F,
        ) -> Result<(), LengthMismatch>
        where
            $First: Shape + Sync,
            $($Arg: Shape<Element = $First::Element> + Sync,)*
            O: Shape<Element = $First::Element> + Send,
            F: Fn(&$First::Packed, $(&$Arg::Packed),*) -> O::Packed + Sync,
        {
            use rayon::prelude::*;
            check(out.len(), &[$first.len(), $($arg.len()),*])?;
            let block = lanes_of::<$First::Element>() * PACKS_PER_TASK;
            out.par_chunks_mut(block)
                .zip($first.par_chunks(block))
                $(.zip($arg.par_chunks(block)))*
                .for_each(|map_fn!(@pattern (out, $first) $($arg)*)| {
                    $run($first, $($arg,)* out, &f)
                });
            Ok(())
        }

        #[doc = concat!("[`", stringify!($name_into), "`] on rayon's threads (feature `rayon`): ")]
        /// the states in blocks of 16 packs, each block one task with its own packed
        /// result; the same results, bit for bit, and the same errors.
        #[cfg(feature = "rayon")]
        pub fn $par_into<$First, $($Arg,)* O, F>(
            $first: &[$First],
            $($arg: &[$Arg],)*
            out: &mut [O],
            f: F,
        ) -> Result<(), LengthMismatch>
        where
            $First: Shape + Sync,
            $($Arg: Shape<Element = $First::Element> + Sync,)*
            O: Shape<Element = $First::Element> + Send,
            F: Fn(&$First::Packed, $(&$Arg::Packed,)* &mut O::Packed) + Sync,
        {
            use rayon::prelude::*;
            check(out.len(), &[$first.len(), $($arg.len()),*])?;
            let block = lanes_of::<$First::Element>() * PACKS_PER_TASK;
            out.par_chunks_mut(block)
                .zip($first.par_chunks(block))
                $(.zip($arg.par_chunks(block)))*
                .for_each(|map_fn!(@pattern (out, $first) $($arg)*)| {
                    $run_into($first, $($arg,)* out, &f)
                });
            Ok(())
        }
    };
    // The nested pairs of rayon's zips: (((out, a), b), c).
    (@pattern $acc:tt) => { $acc };
    (@pattern $acc:tt $next:ident $($rest:ident)*) => {
        map_fn!(@pattern ($acc, $next) $($rest)*)
    };
}

map_fn!(
    /// `out[i] = f(x[i])` on lanes (see the [module documentation](self)): e.g.
    /// `batch::map1(&q, &mut m, Robot::mass_matrix)`.
    ///
    /// # Errors
    /// [`LengthMismatch`] when `x` is not as long as `out` (nothing written).
    map1, par_map1, run1;
    map1_into, par_map1_into, run1_into;
    x: X
);
map_fn!(
    /// `out[i] = f(x[i], y[i])` on lanes (see the [module documentation](self)): e.g.
    /// `batch::map2(&q, &v, &mut h, Robot::bias)`.
    ///
    /// # Errors
    /// [`LengthMismatch`] for the first input not as long as `out` (nothing written).
    map2, par_map2, run2;
    map2_into, par_map2_into, run2_into;
    x: X, y: Y
);
map_fn!(
    /// `out[i] = f(x[i], y[i], z[i])` on lanes (see the [module documentation](self)):
    /// e.g. `batch::map3(&q, &v, &a, &mut tau, Robot::inverse_dynamics)`.
    ///
    /// # Errors
    /// [`LengthMismatch`] for the first input not as long as `out` (nothing written).
    map3, par_map3, run3;
    map3_into, par_map3_into, run3_into;
    x: X, y: Y, z: Z
);
map_fn!(
    /// `out[i] = f(x[i], y[i], z[i], w[i])` on lanes (see the [module documentation](self)):
    /// e.g. inverse dynamics with loads, `batch::map4(&q, &v, &a, &loads, &mut tau,
    /// Robot::inverse_dynamics)`.
    ///
    /// # Errors
    /// [`LengthMismatch`] for the first input not as long as `out` (nothing written).
    map4, par_map4, run4;
    map4_into, par_map4_into, run4_into;
    x: X, y: Y, z: Z, w: W
);
map_fn!(
    /// `out[i] = f(x[i], y[i], z[i], w[i], u[i])` on lanes (see the
    /// [module documentation](self)): e.g. inverse dynamics with parameters and loads.
    ///
    /// # Errors
    /// [`LengthMismatch`] for the first input not as long as `out` (nothing written).
    map5, par_map5, run5;
    map5_into, par_map5_into, run5_into;
    x: X, y: Y, z: Z, w: W, u: U
);

#[cfg(test)]
mod tests;
mod transpose;
