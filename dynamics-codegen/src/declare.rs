//! Emits what a mechanism declares independently of its dynamics: the type, its doc
//! comments, its `Mechanism` implementation (sizes, names, nominal parameters) and the
//! runtime `Model` rebuilt from the same numbers (bodies, joints, frames and loads).
//!
//! The runtime `Model` is built from the declaration as written (fixed joints included,
//! numbers affine in the parameters), so the runtime merges and validates it on its own:
//! that is what lets the reference catch a mistake of the compiler.

use crate::model::{
    DeclaredBody, DeclaredFrame, DeclaredJoint, Load, LoadFrame, LoadKind, Mat3, Model, Value, Vec3,
};
use crate::syntax::JointKind;
use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// A literal that round-trips the f64 exactly.
pub fn float_literal(x: f64) -> TokenStream {
    if x.is_finite() {
        let lit = Literal::f64_suffixed(x.abs());
        if x.is_sign_negative() && x != 0.0 {
            quote!(-#lit)
        } else {
            quote!(#lit)
        }
    } else {
        quote!(::core::f64::NAN)
    }
}

/// A literal of a limit: as [`float_literal`], infinities as `f64::INFINITY`.
fn limit_literal(x: f64) -> TokenStream {
    if x == f64::INFINITY {
        quote!(::core::f64::INFINITY)
    } else if x == f64::NEG_INFINITY {
        quote!(::core::f64::NEG_INFINITY)
    } else {
        float_literal(x)
    }
}

/// A limit for the docs: `∞` and `−∞` for the unbounded ones.
fn limit_text(x: f64) -> String {
    if x == f64::INFINITY {
        "∞".to_owned()
    } else if x == f64::NEG_INFINITY {
        "-∞".to_owned()
    } else {
        format!("{x}")
    }
}

/// Each velocity coordinate's limits and Coulomb friction, in the order of v (a free
/// joint's six unbounded and frictionless).
fn coordinate_limits(model: &Model) -> Vec<(crate::model::JointLimits, f64)> {
    model
        .bodies
        .iter()
        .flat_map(|b| {
            let j = &b.joint;
            std::iter::repeat_n((j.limits, j.friction), j.kind.dofs())
        })
        .collect()
}

/// `constant + Σ coefficient · parameters[k]` as an f64 expression.
fn value_tokens(v: &Value) -> TokenStream {
    let mut expr = float_literal(v.constant);
    for &(k, c) in &v.terms {
        let c = float_literal(c);
        expr = quote!(#expr + #c * parameters[#k]);
    }
    expr
}

fn vec_tokens(v: &Vec3) -> TokenStream {
    let [x, y, z] = [&v[0], &v[1], &v[2]].map(value_tokens);
    quote!([#x, #y, #z])
}

fn mat_tokens(m: &Mat3) -> TokenStream {
    let [a, b, c] = [&m[0], &m[1], &m[2]].map(vec_tokens);
    quote!([#a, #b, #c])
}

fn rows_tokens(m: &[[f64; 3]; 3]) -> TokenStream {
    let rows = m.iter().map(|r| {
        let [x, y, z] = r.map(float_literal);
        quote!([#x, #y, #z])
    });
    quote!([#(#rows),*])
}

fn body_tokens(rt: &TokenStream, b: &DeclaredBody) -> TokenStream {
    let name = &b.name;
    let (mass, com, inertia) = (
        value_tokens(&b.mass),
        vec_tokens(&b.com),
        mat_tokens(&b.inertia),
    );
    quote!(.body(#rt::BodySpec::new(#name, #rt::Inertia::new(#mass, #com, #inertia))))
}

fn joint_tokens(rt: &TokenStream, j: &DeclaredJoint) -> TokenStream {
    let (name, parent, child) = (&j.name, &j.parent, &j.child);
    let axis = j.axis.map(float_literal);
    let constructor = match j.kind {
        JointKind::Revolute => quote!(revolute(#name, #parent, #child, [#(#axis),*])),
        JointKind::Prismatic => quote!(prismatic(#name, #parent, #child, [#(#axis),*])),
        JointKind::Fixed => quote!(fixed(#name, #parent, #child)),
        JointKind::Free => quote!(free_flyer(#name, #child)),
    };
    let translation = vec_tokens(&j.translation);
    let rotation = rows_tokens(&j.rotation);
    let (armature, damping) = (value_tokens(&j.armature), value_tokens(&j.damping));
    // A standard DH row's child frame, Tx(a) Rx(α), when it is not the identity.
    let child_frame = j.child_frame.as_ref().map(|(translation, rotation)| {
        let (translation, rotation) = (vec_tokens(translation), rows_tokens(rotation));
        quote!(.with_child_frame(#translation, #rotation))
    });
    quote! {
        .joint(#rt::JointSpec::#constructor
            .placed(#translation, #rotation)
            #child_frame
            .with_armature(#armature)
            .with_damping(#damping))
    }
}

fn frame_tokens(rt: &TokenStream, f: &DeclaredFrame) -> TokenStream {
    let (name, body) = (&f.name, &f.body);
    let translation = f.translation.map(float_literal);
    let rotation = rows_tokens(&f.rotation);
    quote! {
        .frame(#rt::FrameSpec::new(#name, #body).placed([#(#translation),*], #rotation))
    }
}

fn load_tokens(rt: &TokenStream, l: &Load) -> TokenStream {
    let (name, body) = (&l.name, &l.declared_body);
    let constructor = match l.kind {
        LoadKind::Force => quote!(force),
        LoadKind::Couple => quote!(couple),
        LoadKind::Wrench => quote!(wrench),
    };
    let point = vec_tokens(&l.declared_point);
    let in_world = (l.frame == LoadFrame::World).then(|| quote!(.in_world()));
    quote! {
        .load(#rt::LoadSpec::#constructor(#name, #body).at(#point) #in_world)
    }
}

/// The type's documentation: the user's doc comments, then the coordinates (which entries of
/// q and v each joint owns) and the bodies, each with its own doc comments.
fn documentation(model: &Model) -> Vec<String> {
    use crate::model::JointKind;
    let mut lines = model.docs.clone();
    if !lines.is_empty() {
        lines.push(String::new());
    }
    lines.push(" # Joints and coordinates".into());
    lines.push(String::new());
    lines.push(" | joint | moves | kind | q | v |".into());
    lines.push(" | --- | --- | --- | --- | --- |".into());
    for body in &model.bodies {
        let j = &body.joint;
        let (kind, q, v) = match &axis_as_declared(j) {
            JointKind::Revolute { axis_in_body: a } => (
                format!("revolute about [{}, {}, {}]", a[0], a[1], a[2]),
                format!("q[{}]", j.idx_q),
                format!("v[{}]", j.idx_v),
            ),
            JointKind::Prismatic { axis_in_body: a } => (
                format!("prismatic along [{}, {}, {}]", a[0], a[1], a[2]),
                format!("q[{}]", j.idx_q),
                format!("v[{}]", j.idx_v),
            ),
            JointKind::Free => (
                "free (position, quaternion x y z w; v = [v; ω] in the body frame)".into(),
                format!("q[{}..{}]", j.idx_q, j.idx_q + 7),
                format!("v[{}..{}]", j.idx_v, j.idx_v + 6),
            ),
        };
        let carries: Vec<&str> = body.parts.iter().skip(1).map(|p| p.name.as_str()).collect();
        let moves = if carries.is_empty() {
            format!("`{}`", body.name)
        } else {
            format!("`{}` (with `{}`)", body.name, carries.join("`, `"))
        };
        lines.push(format!(" | `{}` | {moves} | {kind} | {q} | {v} |", j.name));
    }
    if !model.loads.is_empty() {
        lines.push(String::new());
        lines.push(" # Loads".into());
        lines.push(String::new());
        lines.push(
            " Each load's components are consecutive entries of the `loads` argument, in the \
             axes its `in` column names: `body`, the axes of the body it was declared on (the \
             default), or `world`, the world's fixed axes (declared `in world`). A force acts \
             at the load's point, given in the body's frame and fixed on the body; a couple is \
             free."
                .into(),
        );
        lines.push(String::new());
        lines.push(" | load | acts on | at | in | `loads` entries |".into());
        lines.push(" | --- | --- | --- | --- | --- |".into());
        for load in &model.loads {
            let (o, n) = (load.input_offset, load.kind.input_count());
            let entries = match load.kind {
                crate::model::LoadKind::Force => format!("[{o}..{}] = F", o + n),
                crate::model::LoadKind::Couple => format!("[{o}..{}] = M", o + n),
                crate::model::LoadKind::Wrench => {
                    format!("[{o}..{}] = F, [{}..{}] = M", o + 3, o + 3, o + 6)
                }
            };
            let at: Vec<String> = load
                .declared_point
                .iter()
                .map(|v| {
                    if v.terms.is_empty() {
                        format!("{}", v.constant)
                    } else {
                        "(parameter)".to_owned()
                    }
                })
                .collect();
            let axes = match load.frame {
                crate::model::LoadFrame::Body => "body",
                crate::model::LoadFrame::World => "world",
            };
            lines.push(format!(
                " | `{}` | `{}` | [{}] | {axes} | {entries} |",
                load.name,
                load.declared_body,
                at.join(", ")
            ));
        }
        for load in model.loads.iter().filter(|l| !l.docs.is_empty()) {
            lines.push(String::new());
            lines.push(format!(" `{}`:{}", load.name, load.docs.join(" ")));
        }
    }
    if let Some(r) = model.rotation_residues() {
        lines.push(String::new());
        lines.push(" # Rotations".into());
        lines.push(String::new());
        lines.push(format!(" {}", r.advice()));
    }
    if !model.frames.is_empty() {
        lines.push(String::new());
        lines.push(" # Frames".into());
        lines.push(String::new());
        lines.push(
            " The operational frames of the `frame_*` functions, in their order (`FRAME_NAMES`, \
             `Self::FRAME_<NAME>`)."
                .into(),
        );
        lines.push(String::new());
        lines.push(" | index | frame | moves with |".into());
        lines.push(" | --- | --- | --- |".into());
        for (index, frame) in model.frames.iter().enumerate() {
            let body = frame
                .body
                .map_or("the ground", |b| model.bodies[b].name.as_str());
            lines.push(format!(" | {index} | `{}` | `{body}` |", frame.name));
        }
        for frame in model.frames.iter().filter(|f| !f.docs.is_empty()) {
            lines.push(String::new());
            lines.push(format!(" `{}`:{}", frame.name, frame.docs.join(" ")));
        }
    }
    let limited: Vec<&crate::model::Joint> = model
        .bodies
        .iter()
        .map(|b| &b.joint)
        .filter(|j| j.limits.is_bounded() || j.friction != 0.0)
        .collect();
    if !limited.is_empty() {
        lines.push(String::new());
        lines.push(" # Limits and friction".into());
        lines.push(String::new());
        lines.push(
            " Each coordinate's limits (`JOINT_LIMITS`) and Coulomb friction (`JOINT_FRICTION`), \
             as declared; the coordinates not listed have none. No generated function enforces \
             the limits or includes the friction."
                .into(),
        );
        lines.push(String::new());
        lines.push(" | joint | v | position | velocity | effort | friction |".into());
        lines.push(" | --- | --- | --- | --- | --- | --- |".into());
        for j in limited {
            let l = &j.limits;
            lines.push(format!(
                " | `{}` | v[{}] | [{}, {}] | {} | {} | {} |",
                j.name,
                j.idx_v,
                limit_text(l.lower),
                limit_text(l.upper),
                limit_text(l.velocity),
                limit_text(l.effort),
                j.friction
            ));
        }
    }
    // Each moving joint and body, then the fixed joints and bodies welded into it; the
    // bodies welded to the ground first.
    let nominal: Vec<f64> = model.parameters.iter().map(|p| p.nominal).collect();
    let welded = |parts: &[crate::model::Part]| -> Vec<(String, Vec<String>)> {
        parts
            .iter()
            .flat_map(|part| {
                part.weld
                    .clone()
                    .into_iter()
                    .chain([(part.name.clone(), part.docs.clone())])
            })
            .collect()
    };
    let mut documented: Vec<(String, Vec<String>)> = welded(&model.ground_parts);
    for b in &model.bodies {
        documented.push((b.joint.name.clone(), b.joint.docs.clone()));
        documented.push((
            b.name.clone(),
            b.documented(&nominal, model.skip_triangle_inequality),
        ));
        documented.extend(welded(b.parts.get(1..).unwrap_or_default()));
    }
    documented.retain(|(_, docs)| !docs.is_empty());
    if !documented.is_empty() {
        lines.push(String::new());
        lines.push(" # Bodies and joints".into());
        for (name, docs) in documented {
            lines.push(String::new());
            lines.push(format!(" `{name}`:{}", docs.join(" ")));
        }
    }
    lines
}

/// The joint with its axis as declared, in the joint frame. The tree's is in the body's
/// frame, which `joint_frame_in_body` turns (`model::frame_turns`): about the axis, which
/// keeps it, then by a half turn for a coordinate axis declared the negative way.
fn axis_as_declared(j: &crate::model::Joint) -> crate::model::JointKind {
    use crate::model::JointKind;
    let (JointKind::Revolute { axis_in_body: a } | JointKind::Prismatic { axis_in_body: a }) =
        j.kind
    else {
        return j.kind.clone();
    };
    match &j.joint_frame_in_body {
        Some(turn) if a.iter().filter(|x| **x != 0.0).count() == 1 => {
            j.kind.with_axis(std::array::from_fn(|i| {
                (0..3).map(|k| turn[k][i] * a[k]).sum::<f64>().round()
            }))
        }
        _ => j.kind.clone(),
    }
}

/// The type's `# Functions` section: the functions generated, with their operation counts,
/// and the outputs not requested, with the line that adds them (the loop-closure functions
/// only where the mechanism closes loops).
fn functions_section(model: &Model, costs: &[Cost]) -> Vec<String> {
    let closes_loops = model
        .statics
        .as_ref()
        .is_some_and(|s| s.closure_count() > 0);
    let mut lines = vec![String::new(), " # Functions".into(), String::new()];
    for cost in costs {
        let mut into = String::new();
        if model.outputs.wants_into(&cost.name) {
            into += &format!(" With [`Self::{}_into`], writing into `out`.", cost.name);
        }
        if model.outputs.wants_sparse_into(&cost.name) {
            into += &format!(
                " With [`Self::{}_sparse_into`], writing only the entries that can be nonzero.",
                cost.name
            );
        }
        lines.push(format!(" - [`Self::{}`]: {}.{into}", cost.name, cost.ops));
    }
    let missing: Vec<&str> = crate::model::Outputs::NAMES
        .iter()
        .copied()
        .filter(|name| !costs.iter().any(|c| c.name == *name))
        .filter(|name| closes_loops || !name.starts_with("constraint_"))
        .filter(|name| !model.frames.is_empty() || !name.starts_with("frame_"))
        .collect();
    if !missing.is_empty() {
        lines.push(String::new());
        lines.push(format!(
            " Not generated (add a name to the declaration's `outputs: [..];` to get it): {}.",
            missing
                .iter()
                .map(|n| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    lines
}

/// The op counts of one generated function, for `Mechanism::FUNCTIONS`.
pub struct Cost {
    /// The function's name.
    pub name: String,
    /// Its operation counts.
    pub ops: crate::sym::OpCount,
}

/// Inherent constants naming the operational frames: `FRAME_<NAME>` (upper case, other
/// characters than letters and digits as `_`) is the frame's index in the frame outputs;
/// a name that would repeat one already given is left out (use `FRAME_NAMES`).
pub fn frame_constants(model: &Model) -> TokenStream {
    let mut seen: Vec<String> = Vec::new();
    let constants = model
        .frames
        .iter()
        .enumerate()
        .filter_map(|(index, frame)| {
            let upper: String = frame
                .name
                .chars()
                .map(|c| {
                    if c.is_ascii_alphanumeric() {
                        c.to_ascii_uppercase()
                    } else {
                        '_'
                    }
                })
                .collect();
            let constant = format!("FRAME_{upper}");
            if seen.contains(&constant) {
                return None;
            }
            seen.push(constant.clone());
            let ident = syn::Ident::new(&constant, proc_macro2::Span::call_site());
            let doc = format!(
                " Index of frame `{}` in the frame outputs (`FRAME_NAMES[{index}]`).",
                frame.name
            );
            Some(quote! {
                #[doc = #doc]
                pub const #ident: usize = #index;
            })
        });
    quote!(#(#constants)*)
}

/// Inherent constants of a mechanism with a force analysis: the names of the unknowns x
/// (in the order `force_analysis` returns them) and the number of loop-closure equations.
pub fn statics_constants(model: &Model) -> TokenStream {
    let Some(statics) = &model.statics else {
        return TokenStream::new();
    };
    let names = statics.unknowns.iter().map(|u| &u.name);
    let count = statics.unknowns.len();
    let closure = statics.closure_count();
    quote! {
        /// The unknowns of `force_analysis`, in order: reaction components along the axes
        /// of each connection's first body, then driven joints' efforts.
        pub const FORCE_UNKNOWNS: [&'static str; #count] = [#(#names),*];
        /// The number of loop-closure equations φ(q) = 0 of the declared constraints.
        pub const NUM_CLOSURE_EQUATIONS: usize = #closure;
    }
}

/// The mechanism's type and its `Mechanism` implementation.
pub fn declare(model: &Model, costs: &[Cost], rt: &TokenStream) -> TokenStream {
    let name = &model.name;
    let vis = &model.visibility;
    let name_str = name.to_string();
    let mut docs = documentation(model);
    docs.extend(functions_section(model, costs));
    let (nq, nv) = (model.nq, model.nv);
    let body_names = model.bodies.iter().map(|b| &b.name);
    let joint_names = model.bodies.iter().map(|b| &b.joint.name);
    let parameter_names = model.parameters.iter().map(|p| &p.name);
    let nominal = model.parameters.iter().map(|p| float_literal(p.nominal));
    let load_names = model.loads.iter().map(|l| &l.name);
    let frame_names = (!model.frames.is_empty()).then(|| {
        let names = model.frames.iter().map(|f| &f.name);
        quote!(const FRAME_NAMES: &'static [&'static str] = &[#(#names),*];)
    });
    let (limits, friction): (Vec<TokenStream>, Vec<TokenStream>) = coordinate_limits(model)
        .into_iter()
        .map(|(l, f)| {
            let [lower, upper, velocity, effort] =
                [l.lower, l.upper, l.velocity, l.effort].map(limit_literal);
            (
                quote!(#rt::JointLimits { lower: #lower, upper: #upper, velocity: #velocity, effort: #effort }),
                float_literal(f),
            )
        })
        .unzip();
    let num_load_inputs = model.load_inputs;
    let num_parameters = model.parameters.len();
    let gravity = model.gravity_in_world.map(float_literal);
    let bodies = model.declared_bodies.iter().map(|b| body_tokens(rt, b));
    let joints = model.declared_joints.iter().map(|j| joint_tokens(rt, j));
    let frames = model.declared_frames.iter().map(|f| frame_tokens(rt, f));
    let loads = model.loads.iter().map(|l| load_tokens(rt, l));
    let skip = model
        .skip_triangle_inequality
        .then(|| quote!(.skip_triangle_inequality()));
    // Without an output that needs M(q) regular, the compiler does not check that every
    // coordinate moves some inertia (a kinematics-only URDF may have no `<inertial>`): the
    // runtime must not either, or `model()` would panic.
    let allow_without_inertia =
        (!model.outputs.any_dynamics()).then(|| quote!(.allow_coordinates_without_inertia()));
    let sources = model.source_files.iter().map(|path| {
        quote!(
            const _: &[u8] = include_bytes!(#path);
        )
    });
    let unused = (num_parameters == 0).then(|| quote!(let _ = parameters;));
    let functions = costs.iter().map(|c| {
        let (name, o) = (&c.name, &c.ops);
        let (mul, add, div, sqrt, trig) = (o.mul, o.add, o.div, o.sqrt, o.trig);
        quote!(#rt::FunctionCost { name: #name, mul: #mul, add: #add, div: #div, sqrt: #sqrt, trig: #trig })
    });
    quote! {
        #(#[doc = #docs])*
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
        #vis struct #name;

        #(#sources)*

        impl #rt::Mechanism for #name {
            const NAME: &'static str = #name_str;
            const NQ: usize = #nq;
            const NV: usize = #nv;
            const BODY_NAMES: &'static [&'static str] = &[#(#body_names),*];
            const JOINT_NAMES: &'static [&'static str] = &[#(#joint_names),*];
            const PARAMETER_NAMES: &'static [&'static str] = &[#(#parameter_names),*];
            const NOMINAL_PARAMETERS: &'static [f64] = &[#(#nominal),*];
            const LOAD_NAMES: &'static [&'static str] = &[#(#load_names),*];
            #frame_names
            // The limits as written: a URDF's 6.28 is no attempt at τ.
            #[allow(clippy::approx_constant, clippy::excessive_precision, clippy::unreadable_literal)]
            const JOINT_LIMITS: &'static [#rt::JointLimits] = &[#(#limits),*];
            #[allow(clippy::approx_constant, clippy::excessive_precision, clippy::unreadable_literal)]
            const JOINT_FRICTION: &'static [f64] = &[#(#friction),*];
            const NUM_LOAD_INPUTS: usize = #num_load_inputs;
            const FUNCTIONS: &'static [#rt::FunctionCost] = &[#(#functions),*];

            // The runtime `Model` needs the runtime's `std` feature: these two follow it.
            #rt::__if_std! {
            fn model() -> #rt::Model {
                match <Self as #rt::Mechanism>::model_with_parameters(Self::NOMINAL_PARAMETERS) {
                    ::core::result::Result::Ok(model) => model,
                    ::core::result::Result::Err(errors) => ::core::panic!(
                        "mechanism `{}` passed the compile-time checks but the runtime rejects it \
                         (a bug in dynamics-codegen): {}", #name_str, errors
                    ),
                }
            }

            // The declared numbers as written: a rotation's entries may be near 1/√2, π, ...
            #[allow(clippy::approx_constant, clippy::excessive_precision, clippy::unreadable_literal)]
            fn model_with_parameters(
                parameters: &[f64],
            ) -> ::core::result::Result<#rt::Model, #rt::ModelErrors> {
                if parameters.len() != #num_parameters {
                    return ::core::result::Result::Err(#rt::ModelErrors(#rt::__private::vec![
                        #rt::ModelError::ParameterCount { expected: #num_parameters, got: parameters.len() }
                    ]));
                }
                #unused
                #rt::ModelBuilder::new()
                    .gravity([#(#gravity),*])
                    #skip
                    #allow_without_inertia
                    #(#bodies)*
                    #(#joints)*
                    #(#frames)*
                    #(#loads)*
                    .build()
            }
            }
        }
    }
}

/// `impl<T: Scalar> Dynamics<T>` (when forward dynamics is generated) and `Energy<T>`
/// (when the energies are too), delegating to the generated functions, so integrators and
/// controllers can be generic over mechanisms.
pub fn dynamics_traits(model: &Model, rt: &TokenStream) -> TokenStream {
    if !model.outputs.forward_dynamics || model.nv == 0 {
        return TokenStream::new();
    }
    let name = &model.name;
    let (nq, nv, np, nl) = (
        model.nq,
        model.nv,
        model.parameters.len(),
        model.load_inputs,
    );
    let p_arg = (np > 0).then(|| quote!(parameters,));
    let loads_arg = (nl > 0).then(|| quote!(loads,));
    let nominal = model.parameters.iter().map(|p| float_literal(p.nominal));
    let free_bodies = || {
        model
            .bodies
            .iter()
            .filter(|b| matches!(b.joint.kind, crate::model::JointKind::Free))
    };
    let free_joints = free_bodies().map(|b| {
        let (iq, iv) = (b.joint.idx_q, b.joint.idx_v);
        quote!((#iq, #iv))
    });
    let neutral_quaternions = free_bodies().map(|b| {
        let w = b.joint.idx_q + 6;
        quote!(q[#w] = T::one();)
    });
    let unused = quote! {
        let _ = parameters;
        let _ = loads;
    };
    let energy = model.outputs.energy.then(|| {
        quote! {
            impl<T: #rt::Scalar> #rt::Energy<T> for #name {
                #[inline]
                fn total_energy(q: &[T; #nq], v: &[T; #nv], parameters: &[T; #np]) -> T {
                    let _ = parameters;
                    #name::kinetic_energy(q, v, #p_arg) + #name::potential_energy(q, #p_arg)
                }
            }
        }
    });
    let lagrangian = lagrangian_trait(model, rt);
    let acceleration_derivatives = model.outputs.forward_dynamics_derivatives.then(|| {
        // With loads the generated function also gives ∂q̈/∂loads, third.
        let call = if nl > 0 {
            quote! {
                let (by_q, by_v, _) =
                    #name::forward_dynamics_derivatives(q, v, tau, #p_arg #loads_arg);
                Some((by_q, by_v))
            }
        } else {
            quote!(Some(#name::forward_dynamics_derivatives(q, v, tau, #p_arg #loads_arg)))
        };
        quote! {
            #[inline]
            fn acceleration_derivatives(
                q: &[T; #nq],
                v: &[T; #nv],
                tau: &[T; #nv],
                parameters: &[T; #np],
                loads: &[T; #nl],
            ) -> Option<([[T; #nv]; #nv], [[T; #nv]; #nv])> {
                #unused
                #call
            }
        }
    });
    quote! {
        impl<T: #rt::Scalar> #rt::Dynamics<T> for #name {
            type Configuration = [T; #nq];
            type Velocity = [T; #nv];
            type Parameters = [T; #np];
            type Loads = [T; #nl];
            type Matrix = [[T; #nv]; #nv];

            #[inline]
            fn zero_velocity() -> [T; #nv] {
                [T::zero(); #nv]
            }
            #[inline]
            fn zero_loads() -> [T; #nl] {
                [T::zero(); #nl]
            }
            #[inline]
            fn zero_matrix() -> [[T; #nv]; #nv] {
                [[T::zero(); #nv]; #nv]
            }
            #[inline]
            fn nominal_parameters() -> [T; #np] {
                [#(T::from_f64(#nominal)),*]
            }
            #[inline]
            fn neutral_configuration() -> [T; #nq] {
                #[allow(unused_mut)]
                let mut q = [T::zero(); #nq];
                #(#neutral_quaternions)*
                q
            }
            #[inline]
            fn acceleration(
                q: &[T; #nq],
                v: &[T; #nv],
                tau: &[T; #nv],
                parameters: &[T; #np],
                loads: &[T; #nl],
            ) -> [T; #nv] {
                #unused
                #name::forward_dynamics(q, v, tau, #p_arg #loads_arg)
            }
            #acceleration_derivatives
            #[inline]
            fn integrate(q: &[T; #nq], v: &[T; #nv], dt: T) -> [T; #nq] {
                let mut out = *q;
                #rt::integrate_configuration(q, v, dt, &[#(#free_joints),*], &mut out);
                out
            }
        }
        #energy
        #lagrangian
    }
}

/// `impl<T: Scalar> Lagrangian<T>` (M, C and g behind a trait, for variational integrators)
/// when the mechanism generates all three beside forward dynamics, delegating to the
/// generated `mass_matrix`, `coriolis_matrix` and `gravity`, and to `momentum_derivatives`
/// when it generates that too (the variational integrator's exact Newton Jacobian).
fn lagrangian_trait(model: &Model, rt: &TokenStream) -> TokenStream {
    let o = &model.outputs;
    if !(o.forward_dynamics && o.mass_matrix && o.coriolis && o.gravity) || model.nv == 0 {
        return TokenStream::new();
    }
    let name = &model.name;
    let (nq, nv, np, nl) = (
        model.nq,
        model.nv,
        model.parameters.len(),
        model.load_inputs,
    );
    let p_arg = (np > 0).then(|| quote!(parameters));
    let momentum_derivatives = o.momentum_derivatives.then(|| {
        let args = (np > 0)
            .then(|| quote!(parameters,))
            .into_iter()
            .chain((nl > 0).then(|| quote!(loads,)));
        // With loads the generated function also gives ∂ṗ/∂loads, fourth.
        let call = if nl > 0 {
            quote! {
                let (dp_dq, dpdot_dq, dpdot_dv, _) = #name::momentum_derivatives(q, v, #(#args)*);
                Some((dp_dq, dpdot_dq, dpdot_dv))
            }
        } else {
            quote!(Some(#name::momentum_derivatives(q, v, #(#args)*)))
        };
        quote! {
            #[inline]
            fn momentum_derivatives(
                q: &[T; #nq],
                v: &[T; #nv],
                parameters: &[T; #np],
                loads: &[T; #nl],
            ) -> Option<([[T; #nv]; #nv], [[T; #nv]; #nv], [[T; #nv]; #nv])> {
                let _ = parameters;
                let _ = loads;
                #call
            }
        }
    });
    quote! {
        impl<T: #rt::Scalar> #rt::Lagrangian<T> for #name {
            #[inline]
            fn mass_matrix(q: &[T; #nq], parameters: &[T; #np]) -> [[T; #nv]; #nv] {
                let _ = parameters;
                #name::mass_matrix(q, #p_arg)
            }
            #[inline]
            fn coriolis_matrix(
                q: &[T; #nq],
                v: &[T; #nv],
                parameters: &[T; #np],
            ) -> [[T; #nv]; #nv] {
                let _ = parameters;
                #name::coriolis_matrix(q, v, #p_arg)
            }
            #[inline]
            fn gravity(q: &[T; #nq], parameters: &[T; #np]) -> [T; #nv] {
                let _ = parameters;
                #name::gravity(q, #p_arg)
            }
            #momentum_derivatives
        }
    }
}
