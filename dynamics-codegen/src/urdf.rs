//! URDF import: a URDF file's links and joints land in the same syntax tree as a hand-written
//! declaration, with spans pointing at the path literal, so every rule of the model stage
//! applies to them and reports at the path, naming the element.
//!
//! Links become bodies (mass, c = the inertial origin, I_G rotated from the inertial frame
//! into the link frame: I_G = R I Rᵀ); `revolute` and `continuous` joints become revolute
//! joints, `prismatic` prismatic, `fixed` fixed (merged later into composite bodies); the
//! joint origin gives the placement (translation and roll-pitch-yaw) and `<dynamics
//! damping>` the viscous friction. The root link is welded to the ground, or given a free
//! joint with `floating_base: true`. Mimic, planar, floating and spherical joints are
//! refused: the tree expansion has no closed form for them.

use crate::syntax::{
    self, Axis, Body, InertiaForm, Joint, JointKind, Matrix, Name, Number, Rotation, SpanRange,
    Vector,
};
use std::path::{Path, PathBuf};

/// Reads the mechanism's URDF file (if it names one) and appends its bodies and joints.
/// Returns the absolute path read, so that the caller can make Cargo rebuild on change.
pub fn import(
    mechanism: &mut syntax::Mechanism,
    manifest_dir: &Path,
) -> syn::Result<Option<PathBuf>> {
    let Some(source) = mechanism.urdf.clone() else {
        return Ok(None);
    };
    let span = source.path.span();
    let written = source.path.value();
    let path = manifest_dir.join(&written);
    let text = std::fs::read_to_string(&path).map_err(|e| {
        syn::Error::new(
            span,
            format!(
                "cannot read URDF file `{written}` (looked for {}): {e}",
                path.display()
            ),
        )
    })?;
    let robot = urdf_rs::read_from_string(&text)
        .map_err(|e| syn::Error::new(span, malformed(&written, &text, &e)))?;
    let mut errors: Option<syn::Error> = None;
    let mut refuse = |message: String| {
        let e = syn::Error::new(span, format!("URDF file `{written}`: {message}"));
        match &mut errors {
            Some(all) => all.combine(e),
            None => errors = Some(e),
        }
    };
    let number = |x: f64| Number::constant(x, span);
    let range = SpanRange::from(span);
    let vector = |v: [f64; 3]| Vector {
        components: v.map(number),
        span: range,
    };
    let name = |text: &str| Name {
        text: text.to_owned(),
        span,
    };
    for link in &robot.links {
        let i = &link.inertial.inertia;
        let inertia_in_inertial = nalgebra::Matrix3::new(
            i.ixx, i.ixy, i.ixz, i.ixy, i.iyy, i.iyz, i.ixz, i.iyz, i.izz,
        );
        let rpy = link.inertial.origin.rpy.0;
        let r = *nalgebra::Rotation3::from_euler_angles(rpy[0], rpy[1], rpy[2]).matrix();
        let inertia = r * inertia_in_inertial * r.transpose();
        mechanism.bodies.push(Body {
            docs: vec![format!(" Link `{}` of `{written}`.", link.name)],
            name: name(&link.name),
            mass: Some(number(link.inertial.mass.value)),
            com: Some(vector(link.inertial.origin.xyz.0)),
            inertia: Some(InertiaForm::Matrix(Matrix {
                rows: std::array::from_fn(|a| std::array::from_fn(|b| number(inertia[(a, b)]))),
                span: range,
            })),
            span: range,
        });
    }
    for joint in &robot.joints {
        let kind = match joint.joint_type {
            urdf_rs::JointType::Revolute | urdf_rs::JointType::Continuous => JointKind::Revolute,
            urdf_rs::JointType::Prismatic => JointKind::Prismatic,
            urdf_rs::JointType::Fixed => JointKind::Fixed,
            urdf_rs::JointType::Floating
            | urdf_rs::JointType::Planar
            | urdf_rs::JointType::Spherical => {
                let written_type = match joint.joint_type {
                    urdf_rs::JointType::Floating => "floating",
                    urdf_rs::JointType::Planar => "planar",
                    _ => "spherical",
                };
                refuse(format!(
                    "joint `{}` is a `{written_type}` joint, which is not supported (use \
                     revolute, continuous, prismatic or fixed joints)",
                    joint.name
                ));
                continue;
            }
        };
        if let Some(mimic) = &joint.mimic {
            refuse(format!(
                "joint `{}` mimics joint `{}`; mimic joints are not supported (declare it as an \
                 independent joint or make it fixed)",
                joint.name, mimic.joint
            ));
            continue;
        }
        let moving = matches!(kind, JointKind::Revolute | JointKind::Prismatic);
        mechanism.joints.push(Joint {
            docs: vec![format!(" Joint `{}` of `{written}`.", joint.name)],
            name: name(&joint.name),
            kind,
            kind_span: span,
            parent: name(&joint.parent.link),
            child: name(&joint.child.link),
            axis: moving.then(|| Axis {
                direction: vector(joint.axis.xyz.0),
                span: range,
            }),
            at: Some(vector(joint.origin.xyz.0)),
            rotation: Some(Rotation::Rpy(joint.origin.rpy.0.map(number), range)),
            armature: None,
            damping: joint
                .dynamics
                .as_ref()
                .filter(|d| d.damping != 0.0)
                .map(|d| number(d.damping)),
        });
    }
    let roots: Vec<&str> = robot
        .links
        .iter()
        .map(|l| l.name.as_str())
        .filter(|l| !robot.joints.iter().any(|j| j.child.link == *l))
        .collect();
    match roots.as_slice() {
        [root] => mechanism.joints.push(Joint {
            docs: vec![format!(" Attaches the root link `{root}` to the ground.")],
            name: name(if source.floating_base {
                "root_joint"
            } else {
                "ground_weld"
            }),
            kind: if source.floating_base {
                JointKind::Free
            } else {
                JointKind::Fixed
            },
            kind_span: span,
            parent: name("ground"),
            child: name(root),
            axis: None,
            at: None,
            rotation: None,
            armature: None,
            damping: None,
        }),
        _ => refuse(format!(
            "expected exactly one root link (a link that is no joint's child), found {}: {}",
            roots.len(),
            roots.join(", ")
        )),
    }
    match errors {
        Some(e) => Err(e),
        None => Ok(Some(path)),
    }
}

/// The message for a file urdf-rs cannot read. Its XML errors carry no position, so when
/// the file is not well-formed XML, roxmltree's message, which has one, replaces them
/// (roxmltree only runs on files urdf-rs refused, so it never refuses one urdf-rs reads).
fn malformed(written: &str, text: &str, urdf_error: &urdf_rs::UrdfError) -> String {
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..roxmltree::ParsingOptions::default()
    };
    let e = match roxmltree::Document::parse_with_options(text, options) {
        Ok(_) => return format!("URDF file `{written}` is malformed: {urdf_error}"),
        Err(e) => e,
    };
    // roxmltree writes the position, when it has one, into its message as ` at row:col`.
    let position = e.pos();
    let at = format!(" at {position}");
    let described = e.to_string();
    let message = match &e {
        roxmltree::Error::UnexpectedCloseTag(expected, actual, _) => format!(
            "found `</{actual}>` where `</{expected}>` was expected (is a `<{expected}>` \
             element left open?)"
        ),
        _ => described.replacen(&at, "", 1),
    };
    if described.contains(&at) {
        format!(
            "URDF file `{written}` is malformed at line {}, column {}: {message}",
            position.row, position.col
        )
    } else {
        format!("URDF file `{written}` is malformed: {message}")
    }
}

/// The manifest directory of the crate being compiled (where URDF paths are relative to).
pub fn manifest_dir() -> PathBuf {
    std::env::var_os("CARGO_MANIFEST_DIR")
        .map(PathBuf::from)
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;
    use quote::quote;

    fn import_tokens(tokens: proc_macro2::TokenStream) -> syn::Result<syntax::Mechanism> {
        let mut m: syntax::Mechanism = syn::parse2(tokens)?;
        import(&mut m, &manifest_dir().join("..").join("models"))?;
        Ok(m)
    }

    #[test]
    fn imports_the_ur5_twin() {
        let m = import_tokens(quote! { struct Ur5; urdf: "urdf/ur5.urdf"; }).expect("imports");
        assert_eq!(m.bodies.len(), 7);
        assert_eq!(m.joints.len(), 7);
        let model = crate::model::lower(&m).expect("valid");
        assert_eq!((model.nq, model.nv), (6, 6));
        assert_eq!(model.bodies[0].name, "shoulder_link");
    }

    #[test]
    fn floating_base_adds_a_free_joint() {
        let m = import_tokens(quote! { struct Ur5; urdf: "urdf/ur5.urdf"; floating_base: true; })
            .expect("imports");
        let model = crate::model::lower(&m).expect("valid");
        assert_eq!((model.nq, model.nv), (13, 12));
    }

    /// Imports `text` as a URDF file written into a fresh temporary directory.
    fn import_text(test: &str, text: &str) -> syn::Result<syntax::Mechanism> {
        let dir = std::env::temp_dir().join(format!(
            "dynamics-codegen-urdf-{test}-{}",
            std::process::id()
        ));
        std::fs::create_dir_all(&dir).expect("temporary directory");
        std::fs::write(dir.join("robot.urdf"), text).expect("write URDF");
        let mut m: syntax::Mechanism = syn::parse2(quote! { struct R; urdf: "robot.urdf"; })?;
        let result = import(&mut m, &dir);
        std::fs::remove_dir_all(&dir).expect("remove temporary directory");
        result.map(|_| m)
    }

    #[test]
    fn malformed_file_reports_a_line_and_column() {
        let e = import_text(
            "malformed",
            "<robot name=\"r\">\n  <link name=\"base\"/>\n  <link name=\"arm\">\n</robot>\n",
        )
        .expect_err("malformed");
        assert_eq!(
            e.to_string(),
            "URDF file `robot.urdf` is malformed at line 4, column 1: found `</robot>` where \
             `</link>` was expected (is a `<link>` element left open?)"
        );
    }

    #[test]
    fn unsupported_joints_are_named_as_in_urdf() {
        let e = import_text(
            "planar",
            r#"<robot name="r">
                 <link name="base"/>
                 <link name="arm">
                   <inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
                 </link>
                 <joint name="slide" type="planar">
                   <parent link="base"/><child link="arm"/>
                 </joint>
               </robot>"#,
        )
        .expect_err("planar");
        assert!(
            e.to_string().contains("joint `slide` is a `planar` joint"),
            "{e}"
        );
    }

    #[test]
    fn missing_file_is_an_error_at_the_path() {
        let e = import_tokens(quote! { struct R; urdf: "urdf/nope.urdf"; }).expect_err("missing");
        assert!(
            e.to_string()
                .contains("cannot read URDF file `urdf/nope.urdf`"),
            "{e}"
        );
    }
}
