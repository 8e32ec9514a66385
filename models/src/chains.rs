//! Planar chains of 1 to 30 links, for the scaling benchmarks (issue #5): how the generated
//! code's cost grows with the number of joints.
//!
//! Every link is the same uniform rod, 1 kg and 0.3 m long along its body x axis (mass
//! centre at its middle, m l²/12 about y and z); every joint turns about z and sits at the
//! tip of the previous link; gravity is −y, in the plane of motion. Only inverse dynamics,
//! the mass matrix and forward dynamics are generated.
//!
//! `planar_chain!` writes the `mechanism!` declaration from the list of link names: body
//! `linkK` and the joint `linkK` that moves it (bodies and joints have separate namespaces).
//! `Chain3` expands to
//!
//! ```text
//! mechanism! {
//!     pub struct Chain3;
//!     gravity: [0.0, -9.81, 0.0];
//!     outputs: [inverse_dynamics, mass_matrix, forward_dynamics];
//!     body link1 { mass: 1.0, com: [0.15, 0.0, 0.0], shape: rod(length: 0.3, axis: x) }
//!     body link2 { mass: 1.0, com: [0.15, 0.0, 0.0], shape: rod(length: 0.3, axis: x) }
//!     body link3 { mass: 1.0, com: [0.15, 0.0, 0.0], shape: rod(length: 0.3, axis: x) }
//!     joint link1: revolute(ground -> link1) { axis: z }
//!     joint link2: revolute(link1 -> link2) { axis: z, at: [0.3, 0.0, 0.0] }
//!     joint link3: revolute(link2 -> link3) { axis: z, at: [0.3, 0.0, 0.0] }
//! }
//! ```
//!
//! `models/tools/compile_cost.sh` writes the same chains out in full (with every output) to
//! time their compilation.

use dynamics_runtime::mechanism;

/// Declares a planar chain from its link names, base first (see the module docs).
macro_rules! planar_chain {
    ($(#[$($doc:tt)*])* $name:ident: [$first:ident $(, $link:ident)* $(,)?]) => {
        planar_chain!(@joints
            [$(#[$($doc)*])* $name]
            [$first $($link)*]
            [joint $first: revolute(ground -> $first) { axis: z }]
            $first $($link)*
        );
    };
    // One joint per consecutive pair of links, accumulated in the third group.
    (@joints $head:tt $links:tt [$($joints:tt)*] $parent:ident $child:ident $($rest:ident)*) => {
        planar_chain!(@joints
            $head
            $links
            [$($joints)* joint $child: revolute($parent -> $child) { axis: z, at: [0.3, 0.0, 0.0] }]
            $child $($rest)*
        );
    };
    (@joints [$(#[$($doc:tt)*])* $name:ident] [$($link:ident)*] [$($joints:tt)*] $last:ident) => {
        mechanism! {
            $(#[$($doc)*])*
            pub struct $name;
            gravity: [0.0, -9.81, 0.0];
            outputs: [inverse_dynamics, mass_matrix, forward_dynamics];
            $(body $link { mass: 1.0, com: [0.15, 0.0, 0.0], shape: rod(length: 0.3, axis: x) })*
            $($joints)*
        }
    };
}

planar_chain! {
    /// A planar chain of 1 link (a pendulum).
    Chain1: [link1]
}

planar_chain! {
    /// A planar chain of 2 links.
    Chain2: [link1, link2]
}

planar_chain! {
    /// A planar chain of 3 links.
    Chain3: [link1, link2, link3]
}

planar_chain! {
    /// A planar chain of 5 links.
    Chain5: [link1, link2, link3, link4, link5]
}

planar_chain! {
    /// A planar chain of 10 links.
    Chain10: [link1, link2, link3, link4, link5, link6, link7, link8, link9, link10]
}

planar_chain! {
    /// A planar chain of 15 links.
    Chain15: [
        link1, link2, link3, link4, link5, link6, link7, link8, link9, link10,
        link11, link12, link13, link14, link15,
    ]
}

planar_chain! {
    /// A planar chain of 20 links.
    Chain20: [
        link1, link2, link3, link4, link5, link6, link7, link8, link9, link10,
        link11, link12, link13, link14, link15, link16, link17, link18, link19, link20,
    ]
}

planar_chain! {
    /// A planar chain of 25 links.
    Chain25: [
        link1, link2, link3, link4, link5, link6, link7, link8, link9, link10,
        link11, link12, link13, link14, link15, link16, link17, link18, link19, link20,
        link21, link22, link23, link24, link25,
    ]
}

planar_chain! {
    /// A planar chain of 30 links.
    Chain30: [
        link1, link2, link3, link4, link5, link6, link7, link8, link9, link10,
        link11, link12, link13, link14, link15, link16, link17, link18, link19, link20,
        link21, link22, link23, link24, link25, link26, link27, link28, link29, link30,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use dynamics_runtime::{Mechanism, Reference};
    use nalgebra::DMatrix;

    /// max |generated − reference| / (1 + max |reference|).
    fn difference(generated: &[f64], reference: &[f64]) -> f64 {
        let scale = 1.0 + reference.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        generated
            .iter()
            .zip(reference)
            .fold(0.0_f64, |m, (g, r)| m.max((g - r).abs()))
            / scale
    }

    /// The declared chain, its three outputs against the reference on the runtime model
    /// rebuilt from the same declaration, at a few states.
    macro_rules! agrees_with_reference {
        ($test:ident, $m:ty, $n:literal) => {
            #[test]
            fn $test() {
                assert_eq!(<$m as Mechanism>::NV, $n);
                assert_eq!(<$m as Mechanism>::BODY_NAMES.len(), $n);
                let model = <$m>::model();
                let mut reference = Reference::<f64>::new(&model);
                let (mut vector, mut matrix) = (vec![0.0; $n], DMatrix::zeros($n, $n));
                for s in 0..4 {
                    let x = |k: usize, scale: f64| scale * ((7 * k + 3 * s + 1) as f64).sin();
                    let q: [f64; $n] = std::array::from_fn(|k| x(k, 3.0));
                    let v: [f64; $n] = std::array::from_fn(|k| x(k + 50, 2.0));
                    let a: [f64; $n] = std::array::from_fn(|k| x(k + 100, 5.0));
                    reference
                        .inverse_dynamics(&q, &v, &a, None, &mut vector)
                        .expect("sizes");
                    let e = difference(&<$m>::inverse_dynamics(&q, &v, &a), &vector);
                    assert!(e < 1e-12, "inverse dynamics: {e:e}");
                    reference.mass_matrix(&q, &mut matrix).expect("sizes");
                    let by_rows = matrix.transpose();
                    let e = difference(<$m>::mass_matrix(&q).as_flattened(), by_rows.as_slice());
                    assert!(e < 1e-12, "mass matrix: {e:e}");
                    reference
                        .forward_dynamics(&q, &v, &a, None, &mut vector)
                        .expect("sizes");
                    let e = difference(&<$m>::forward_dynamics(&q, &v, &a), &vector);
                    assert!(e < 1e-10, "forward dynamics: {e:e}");
                }
            }
        };
    }

    agrees_with_reference!(chain1_agrees_with_the_reference, Chain1, 1);
    agrees_with_reference!(chain2_agrees_with_the_reference, Chain2, 2);
    agrees_with_reference!(chain10_agrees_with_the_reference, Chain10, 10);
    agrees_with_reference!(chain30_agrees_with_the_reference, Chain30, 30);

    #[test]
    fn only_the_three_outputs_are_generated() {
        let names: Vec<&str> = Chain30::FUNCTIONS.iter().map(|f| f.name).collect();
        assert_eq!(
            names,
            ["inverse_dynamics", "mass_matrix", "forward_dynamics"]
        );
    }
}
