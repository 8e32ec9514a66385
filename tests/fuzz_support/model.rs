//! The runtime model a compiled declaration's generated code builds, without compiling it:
//! a small interpreter of the generated `Mechanism::model_with_parameters` (the
//! `ModelBuilder` chain `declare.rs` prints: `ModelBuilder::new().gravity(..).body(..)
//! .joint(..).frame(..).load(..).build()`, its numbers `constant + coefficient *
//! parameters[k]`) and of `NOMINAL_PARAMETERS`.
//!
//! This is the model the macro's user gets from `Mechanism::model()`, so building it checks
//! that whatever the compiler accepts the runtime accepts too (else `model()` panics), and
//! it is the reference's model for the fuzzed declarations, as for `generated_*.rs`.

use dynamics_runtime::{
    BodySpec, FrameSpec, Inertia, JointSpec, LoadSpec, Model, ModelBuilder, ModelErrors,
};
use syn::{Expr, ImplItem, Item, Lit};

/// A value of the builder chain.
enum Value {
    Number(f64),
    Text(String),
    List(Vec<Value>),
    Builder(ModelBuilder),
    Body(BodySpec),
    Inertia(Inertia),
    Joint(JointSpec),
    Frame(FrameSpec),
    Load(LoadSpec),
    Built(Result<Model, ModelErrors>),
}

fn number(v: Value) -> Result<f64, String> {
    match v {
        Value::Number(x) => Ok(x),
        _ => Err("expected a number".into()),
    }
}

fn text(v: Value) -> Result<String, String> {
    match v {
        Value::Text(s) => Ok(s),
        _ => Err("expected a string".into()),
    }
}

fn vector(v: Value) -> Result<[f64; 3], String> {
    match v {
        Value::List(items) if items.len() == 3 => {
            let mut out = [0.0; 3];
            for (o, item) in out.iter_mut().zip(items) {
                *o = number(item)?;
            }
            Ok(out)
        }
        _ => Err("expected [x, y, z]".into()),
    }
}

fn matrix(v: Value) -> Result<[[f64; 3]; 3], String> {
    match v {
        Value::List(rows) if rows.len() == 3 => {
            let mut out = [[0.0; 3]; 3];
            for (o, row) in out.iter_mut().zip(rows) {
                *o = vector(row)?;
            }
            Ok(out)
        }
        _ => Err("expected a 3 × 3 matrix".into()),
    }
}

/// The arguments of a call, evaluated.
fn arguments<'a>(
    args: impl IntoIterator<Item = &'a Expr>,
    parameters: &[f64],
) -> Result<Vec<Value>, String> {
    args.into_iter().map(|a| eval(a, parameters)).collect()
}

fn eval(expr: &Expr, parameters: &[f64]) -> Result<Value, String> {
    match expr {
        Expr::Lit(lit) => match &lit.lit {
            Lit::Float(f) => f
                .base10_parse()
                .map(Value::Number)
                .map_err(|e| e.to_string()),
            Lit::Int(i) => i
                .base10_parse()
                .map(Value::Number)
                .map_err(|e| e.to_string()),
            Lit::Str(s) => Ok(Value::Text(s.value())),
            _ => Err(format!("unexpected literal `{}`", quote::quote!(#lit))),
        },
        Expr::Paren(p) => eval(&p.expr, parameters),
        Expr::Group(g) => eval(&g.expr, parameters),
        Expr::Unary(u) if matches!(u.op, syn::UnOp::Neg(_)) => {
            Ok(Value::Number(-number(eval(&u.expr, parameters)?)?))
        }
        Expr::Binary(b) => {
            let (x, y) = (
                number(eval(&b.left, parameters)?)?,
                number(eval(&b.right, parameters)?)?,
            );
            Ok(Value::Number(match b.op {
                syn::BinOp::Add(_) => x + y,
                syn::BinOp::Sub(_) => x - y,
                syn::BinOp::Mul(_) => x * y,
                syn::BinOp::Div(_) => x / y,
                _ => return Err(format!("unexpected operator in `{}`", quote::quote!(#b))),
            }))
        }
        Expr::Index(i) => {
            let k = number(eval(&i.index, parameters)?)? as usize;
            parameters
                .get(k)
                .copied()
                .map(Value::Number)
                .ok_or_else(|| format!("parameters[{k}] out of range"))
        }
        Expr::Path(p) => {
            let last = p.path.segments.last().map(|s| s.ident.to_string());
            match last.as_deref() {
                Some("NAN") => Ok(Value::Number(f64::NAN)),
                Some("INFINITY") => Ok(Value::Number(f64::INFINITY)),
                Some("NEG_INFINITY") => Ok(Value::Number(f64::NEG_INFINITY)),
                _ => Err(format!("unexpected path `{}`", quote::quote!(#p))),
            }
        }
        Expr::Array(a) => Ok(Value::List(arguments(&a.elems, parameters)?)),
        Expr::Call(call) => {
            let Expr::Path(path) = &*call.func else {
                return Err("unexpected call".into());
            };
            let segments: Vec<String> = path
                .path
                .segments
                .iter()
                .map(|s| s.ident.to_string())
                .collect();
            let name = segments[segments.len().saturating_sub(2)..].join("::");
            let mut args = arguments(&call.args, parameters)?.into_iter();
            let mut next = || {
                args.next()
                    .ok_or_else(|| format!("too few arguments to {name}"))
            };
            Ok(match name.as_str() {
                "ModelBuilder::new" => Value::Builder(ModelBuilder::new()),
                "BodySpec::new" => {
                    let name = text(next()?)?;
                    match next()? {
                        Value::Inertia(i) => Value::Body(BodySpec::new(name, i)),
                        _ => return Err("BodySpec::new takes an Inertia".into()),
                    }
                }
                "Inertia::new" => {
                    let (m, c, i) = (number(next()?)?, vector(next()?)?, matrix(next()?)?);
                    Value::Inertia(Inertia::new(m, c, i))
                }
                "JointSpec::revolute" | "JointSpec::prismatic" => {
                    let (n, p, c, a) = (
                        text(next()?)?,
                        text(next()?)?,
                        text(next()?)?,
                        vector(next()?)?,
                    );
                    Value::Joint(if name.ends_with("revolute") {
                        JointSpec::revolute(&n, &p, &c, a)
                    } else {
                        JointSpec::prismatic(&n, &p, &c, a)
                    })
                }
                "JointSpec::fixed" => {
                    let (n, p, c) = (text(next()?)?, text(next()?)?, text(next()?)?);
                    Value::Joint(JointSpec::fixed(&n, &p, &c))
                }
                "JointSpec::free_flyer" => {
                    let (n, c) = (text(next()?)?, text(next()?)?);
                    Value::Joint(JointSpec::free_flyer(&n, &c))
                }
                "FrameSpec::new" => {
                    let (n, b) = (text(next()?)?, text(next()?)?);
                    Value::Frame(FrameSpec::new(&n, &b))
                }
                "LoadSpec::force" | "LoadSpec::couple" | "LoadSpec::wrench" => {
                    let (n, b) = (text(next()?)?, text(next()?)?);
                    Value::Load(match segments.last().map(String::as_str) {
                        Some("force") => LoadSpec::force(&n, &b),
                        Some("couple") => LoadSpec::couple(&n, &b),
                        _ => LoadSpec::wrench(&n, &b),
                    })
                }
                _ => return Err(format!("unexpected call of `{name}`")),
            })
        }
        Expr::MethodCall(call) => {
            let receiver = eval(&call.receiver, parameters)?;
            let method = call.method.to_string();
            let mut args = arguments(&call.args, parameters)?.into_iter();
            let mut next = || {
                args.next()
                    .ok_or_else(|| format!("too few arguments to .{method}"))
            };
            Ok(match (receiver, method.as_str()) {
                (Value::Builder(b), "gravity") => Value::Builder(b.gravity(vector(next()?)?)),
                (Value::Builder(b), "skip_triangle_inequality") => {
                    Value::Builder(b.skip_triangle_inequality())
                }
                (Value::Builder(b), "allow_coordinates_without_inertia") => {
                    Value::Builder(b.allow_coordinates_without_inertia())
                }
                (Value::Builder(b), "body") => match next()? {
                    Value::Body(s) => Value::Builder(b.body(s)),
                    _ => return Err(".body takes a BodySpec".into()),
                },
                (Value::Builder(b), "joint") => match next()? {
                    Value::Joint(s) => Value::Builder(b.joint(s)),
                    _ => return Err(".joint takes a JointSpec".into()),
                },
                (Value::Builder(b), "frame") => match next()? {
                    Value::Frame(s) => Value::Builder(b.frame(s)),
                    _ => return Err(".frame takes a FrameSpec".into()),
                },
                (Value::Builder(b), "load") => match next()? {
                    Value::Load(s) => Value::Builder(b.load(s)),
                    _ => return Err(".load takes a LoadSpec".into()),
                },
                (Value::Builder(b), "build") => Value::Built(b.build()),
                (Value::Joint(j), "placed") => {
                    let (t, r) = (vector(next()?)?, matrix(next()?)?);
                    Value::Joint(j.placed(t, r))
                }
                (Value::Joint(j), "with_armature") => {
                    Value::Joint(j.with_armature(number(next()?)?))
                }
                (Value::Joint(j), "with_damping") => Value::Joint(j.with_damping(number(next()?)?)),
                (Value::Joint(j), "with_child_frame") => {
                    let (t, r) = (vector(next()?)?, matrix(next()?)?);
                    Value::Joint(j.with_child_frame(t, r))
                }
                (Value::Frame(f), "placed") => {
                    let (t, r) = (vector(next()?)?, matrix(next()?)?);
                    Value::Frame(f.placed(t, r))
                }
                (Value::Load(l), "at") => Value::Load(l.at(vector(next()?)?)),
                (Value::Load(l), "in_world") => Value::Load(l.in_world()),
                _ => return Err(format!("unexpected method `.{method}`")),
            })
        }
        _ => Err(format!("unexpected expression `{}`", quote::quote!(#expr))),
    }
}

/// The items of the `impl`s of `file`, `__if_std!` expanded.
fn impl_items(file: &syn::File) -> impl Iterator<Item = &ImplItem> {
    file.items
        .iter()
        .filter_map(|item| match item {
            Item::Impl(i) => Some(i.items.iter()),
            _ => None,
        })
        .flatten()
}

/// The generated `NOMINAL_PARAMETERS`.
pub fn nominal_parameters(file: &syn::File) -> Result<Vec<f64>, String> {
    for item in impl_items(file) {
        if let ImplItem::Const(c) = item {
            if c.ident == "NOMINAL_PARAMETERS" {
                let Expr::Reference(r) = &c.expr else {
                    return Err("NOMINAL_PARAMETERS is not `&[..]`".into());
                };
                return match eval(&r.expr, &[])? {
                    Value::List(items) => items.into_iter().map(number).collect(),
                    _ => Err("NOMINAL_PARAMETERS is not `&[..]`".into()),
                };
            }
        }
    }
    Err("no NOMINAL_PARAMETERS".into())
}

/// What the generated `model_with_parameters(parameters)` returns: `Err` if the interpreter
/// cannot read the generated code, else the `ModelBuilder`'s result. `file` is the generated
/// code with `__if_std!` expanded (`dynamics_codegen::expand_if_std`).
pub fn model_with_parameters(
    file: &syn::File,
    parameters: &[f64],
) -> Result<Result<Model, ModelErrors>, String> {
    for item in impl_items(file) {
        if let ImplItem::Fn(f) = item {
            if f.sig.ident == "model_with_parameters" {
                let Some(syn::Stmt::Expr(chain, None)) = f.block.stmts.last() else {
                    return Err("model_with_parameters does not end with the builder".into());
                };
                return match eval(chain, parameters)? {
                    Value::Built(result) => Ok(result),
                    _ => Err("model_with_parameters does not end with .build()".into()),
                };
            }
        }
    }
    Err("no model_with_parameters".into())
}
