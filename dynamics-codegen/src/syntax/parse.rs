//! Parsing `mechanism!` tokens into the syntax tree (syn).
//!
//! Items are `pub struct Name;`, settings `key: value;`, `body`, `joint` and `load`
//! declarations, each optionally preceded by doc comments. Errors point at the offending
//! token and say what was expected.

use super::ast::*;
use super::closest;
use proc_macro2::{Delimiter, Span};
use syn::ext::IdentExt;
use syn::parse::{Parse, ParseStream};
use syn::punctuated::Punctuated;
use syn::{braced, bracketed, parenthesized, Attribute, Expr, Ident, LitBool, LitStr, Token};

impl Parse for Mechanism {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let mut header: Option<(Vec<String>, syn::Visibility, Ident)> = None;
        let mut mechanism = Mechanism {
            docs: Vec::new(),
            visibility: syn::Visibility::Inherited,
            name: Ident::new("Mechanism", Span::call_site()),
            gravity: None,
            outputs: None,
            parameters: Vec::new(),
            allow: Vec::new(),
            urdf: None,
            bodies: Vec::new(),
            joints: Vec::new(),
            loads: Vec::new(),
            constraints: Vec::new(),
            frames: Vec::new(),
            frame_selection: None,
            analysis: None,
            isa: None,
            lanes: false,
            rotation_tolerance: None,
        };
        // `floating_base:`, `urdf_damping:` and `urdf_mimic:`, each with the span of its
        // keyword: they apply to the `urdf:` file, so they are errors without one.
        let mut floating_base: Option<(bool, Span)> = None;
        let mut urdf_damping: Option<(bool, Span)> = None;
        let mut urdf_mimic: Option<(bool, Span)> = None;
        // Each setting once: the name and the span of its first occurrence.
        let mut given: Vec<(String, Span)> = Vec::new();
        while !input.is_empty() {
            let docs = parse_docs(input)?;
            let item_start = input.cursor();
            if input.peek(Token![pub]) || input.peek(Token![struct]) {
                let visibility: syn::Visibility = input.parse()?;
                input.parse::<Token![struct]>()?;
                let name: Ident = input.parse()?;
                semicolon(input, item_start)?;
                if let Some((_, _, first)) = &header {
                    let mut error =
                        syn::Error::new(name.span(), "the mechanism's type is declared twice");
                    error.combine(syn::Error::new(
                        first.span(),
                        format!("the mechanism's type `{first}` is first declared here"),
                    ));
                    return Err(error);
                }
                header = Some((docs, visibility, name));
                continue;
            }
            let keyword: Ident = input.parse().map_err(|e| {
                syn::Error::new(
                    e.span(),
                    "expected `pub struct Name;`, a setting (`gravity: ...;`), `body`, `joint`, `load`, `constraint` or `frame`",
                )
            })?;
            match keyword.to_string().as_str() {
                "body" if input.peek(Ident) => mechanism.bodies.push(parse_body(input, docs)?),
                "joint" if input.peek(Ident) => mechanism.joints.push(parse_joint(input, docs)?),
                "load" if input.peek(Ident) => mechanism.loads.push(parse_load(input, docs)?),
                "constraint" if input.peek(Ident) => {
                    mechanism.constraints.push(parse_constraint(input, docs)?)
                }
                "frame" if input.peek(Ident) => mechanism.frames.push(parse_frame(input, docs)?),
                setting => {
                    if !input.peek(Token![:]) {
                        return Err(unknown_item(&keyword));
                    }
                    input.parse::<Token![:]>()?;
                    if let Some((_, first)) = given.iter().find(|(name, _)| name == setting) {
                        let mut error = syn::Error::new(
                            keyword.span(),
                            format!("`{setting}` is given twice; a setting is given once"),
                        );
                        error.combine(syn::Error::new(
                            *first,
                            format!("the first `{setting}` is here"),
                        ));
                        return Err(error);
                    }
                    given.push((setting.to_string(), keyword.span()));
                    match setting {
                        "gravity" => mechanism.gravity = Some(parse_gravity(input)?),
                        "outputs" => mechanism.outputs = Some(parse_name_list(input)?),
                        "frames" => mechanism.frame_selection = Some(parse_name_list(input)?),
                        "allow" => mechanism.allow = parse_name_list(input)?,
                        "parameters" => mechanism.parameters = parse_parameters(input)?,
                        "urdf" => {
                            let path: LitStr = input.parse()?;
                            mechanism.urdf = Some(UrdfSource {
                                path,
                                floating_base: false,
                                damping: true,
                                mimic: true,
                            });
                        }
                        "floating_base" => {
                            floating_base = Some((parse_flag(input, setting)?, keyword.span()))
                        }
                        "urdf_damping" => {
                            urdf_damping = Some((parse_flag(input, setting)?, keyword.span()))
                        }
                        "urdf_mimic" => {
                            urdf_mimic = Some((parse_flag(input, setting)?, keyword.span()))
                        }
                        "force_analysis" => {
                            let plane: Ident = input.parse()?;
                            let kind = match plane.to_string().as_str() {
                                "planar" => AnalysisPlane::Planar,
                                "spatial" => AnalysisPlane::Spatial,
                                other => {
                                    return Err(syn::Error::new(
                                        plane.span(),
                                        format!("unknown force analysis `{other}`; expected planar or spatial"),
                                    ))
                                }
                            };
                            mechanism.analysis = Some((kind, plane.span()));
                        }
                        "rotation_tolerance" => {
                            mechanism.rotation_tolerance = Some(parse_number(input)?)
                        }
                        "lanes" => mechanism.lanes = parse_flag(input, setting)?,
                        "isa" => {
                            let isa: Ident = input.parse()?;
                            mechanism.isa = Some(match isa.to_string().as_str() {
                                "dispatch" => Isa::Dispatch,
                                "baseline" => Isa::Baseline,
                                other => {
                                    return Err(syn::Error::new(
                                        isa.span(),
                                        format!("unknown isa `{other}`; expected dispatch (two copies, chosen at run time) or baseline (the crate's target only)"),
                                    ))
                                }
                            });
                        }
                        _ => {
                            let hint = match closest(setting, &SETTINGS) {
                                Some(near) => format!("did you mean `{near}`? The settings are"),
                                None => "expected one of".to_owned(),
                            };
                            return Err(syn::Error::new(
                                keyword.span(),
                                format!(
                                    "unknown setting `{setting}`; {hint} {} (or `body`, `joint`, \
                                     `load`, `constraint`, `frame`)",
                                    SETTINGS.join(", ")
                                ),
                            ));
                        }
                    }
                    semicolon(input, item_start)?;
                }
            }
        }
        let Some((docs, visibility, name)) = header else {
            return Err(syn::Error::new(
                Span::call_site(),
                "a mechanism starts with its type: `pub struct Name;`",
            ));
        };
        mechanism.docs = docs;
        mechanism.visibility = visibility;
        mechanism.name = name;
        match &mut mechanism.urdf {
            Some(urdf) => {
                if let Some((flag, _)) = floating_base {
                    urdf.floating_base = flag;
                }
                if let Some((flag, _)) = urdf_damping {
                    urdf.damping = flag;
                }
                if let Some((flag, _)) = urdf_mimic {
                    urdf.mimic = flag;
                }
            }
            None => {
                let misplaced = [
                    ("floating_base", floating_base),
                    ("urdf_damping", urdf_damping),
                    ("urdf_mimic", urdf_mimic),
                ];
                if let Some((setting, span)) = misplaced
                    .into_iter()
                    .find_map(|(setting, given)| given.map(|(_, span)| (setting, span)))
                {
                    return Err(syn::Error::new(
                        span,
                        format!(
                            "`{setting}` applies to a URDF file, and this mechanism imports none; \
                             add `urdf: \"path/to/robot.urdf\";` or remove `{setting}`"
                        ),
                    ));
                }
            }
        }
        Ok(mechanism)
    }
}

/// The mechanism settings, `name: value;`, each given at most once.
const SETTINGS: [&str; 13] = [
    "gravity",
    "outputs",
    "frames",
    "parameters",
    "allow",
    "urdf",
    "floating_base",
    "urdf_damping",
    "urdf_mimic",
    "force_analysis",
    "isa",
    "lanes",
    "rotation_tolerance",
];

/// The value of a yes-or-no setting: `true` or `false`.
fn parse_flag(input: ParseStream, setting: &str) -> syn::Result<bool> {
    let flag: LitBool = input.parse().map_err(|e| {
        syn::Error::new(
            e.span(),
            format!("expected `true` or `false` after `{setting}:`"),
        )
    })?;
    Ok(flag.value)
}

/// The item keywords, each followed by a name.
const ITEMS: [&str; 5] = ["body", "joint", "load", "constraint", "frame"];

/// A word at item level that is neither an item keyword followed by a name nor a setting
/// followed by `:`: names itself and, for a typo, the keyword meant.
fn unknown_item(keyword: &Ident) -> syn::Error {
    let word = keyword.to_string();
    let message = if ITEMS.contains(&word.as_str()) {
        format!("expected a name after `{word}`")
    } else if let Some(near) = closest(&word, &ITEMS) {
        format!("unknown item `{word}`; did you mean `{near}`?")
    } else if let Some(near) = closest(&word, &SETTINGS) {
        format!("unknown item `{word}`; did you mean the setting `{near}: ...;`?")
    } else {
        format!(
            "unknown item `{word}`; expected `body`, `joint`, `load`, `constraint`, `frame` or a setting \
             `name: value;` ({})",
            SETTINGS.join(", ")
        )
    };
    syn::Error::new(keyword.span(), message)
}

/// The value of `gravity:`: `[x, y, z]` or `none` (zero gravity).
fn parse_gravity(input: ParseStream) -> syn::Result<Gravity> {
    if input.peek(Ident) {
        let word: Ident = input.parse()?;
        if word == "none" {
            return Ok(Gravity::None(SpanRange::from(word.span())));
        }
        return Err(syn::Error::new(
            word.span(),
            format!("expected `[x, y, z]` or `none` (zero gravity), found `{word}`"),
        ));
    }
    Ok(Gravity::Vector(parse_vector(input)?))
}

/// Doc comments (`///` lines) before an item.
fn parse_docs(input: ParseStream) -> syn::Result<Vec<String>> {
    let attrs = input.call(Attribute::parse_outer)?;
    let mut docs = Vec::new();
    for attr in attrs {
        match &attr.meta {
            syn::Meta::NameValue(nv) if nv.path.is_ident("doc") => {
                if let Expr::Lit(syn::ExprLit {
                    lit: syn::Lit::Str(s),
                    ..
                }) = &nv.value
                {
                    docs.push(s.value());
                }
            }
            _ => {
                return Err(syn::Error::new_spanned(
                    &attr,
                    "only doc comments are allowed here",
                ))
            }
        }
    }
    Ok(docs)
}

fn parse_name(input: ParseStream) -> syn::Result<Name> {
    let ident: Ident = input.parse()?;
    Ok(Name {
        text: ident.to_string(),
        span: ident.span(),
    })
}

/// `[a, b, c]` of identifiers.
fn parse_name_list(input: ParseStream) -> syn::Result<Vec<Name>> {
    let content;
    bracketed!(content in input);
    let idents = Punctuated::<Ident, Token![,]>::parse_terminated(&content)?;
    Ok(idents
        .into_iter()
        .map(|i| Name {
            text: i.to_string(),
            span: i.span(),
        })
        .collect())
}

/// `[name = nominal, ...]`.
fn parse_parameters(input: ParseStream) -> syn::Result<Vec<Parameter>> {
    let content;
    bracketed!(content in input);
    let mut parameters = Vec::new();
    while !content.is_empty() {
        let name = parse_name(&content)?;
        content.parse::<Token![=]>()?;
        let nominal = parse_number(&content)?;
        parameters.push(Parameter { name, nominal });
        if content.is_empty() {
            break;
        }
        content.parse::<Token![,]>()?;
    }
    Ok(parameters)
}

/// How deeply parentheses may nest in a number: far beyond any hand-written expression,
/// far below what would exhaust the stack.
const MAX_NESTING: usize = 64;

/// A number: a constant expression, or a parameter scaled by a constant.
///
/// Parsed by hand rather than as a `syn::Expr`, whose parser and tree recurse per level
/// and per term: sums and products are loops, a run of unary minus signs is counted, and
/// parentheses may nest [`MAX_NESTING`] deep (deeper is an error at the parenthesis).
pub(crate) fn parse_number(input: ParseStream) -> syn::Result<Number> {
    let (value, span) = parse_sum(input, 0)?;
    Ok(Number { value, span })
}

/// A binary operator of a number.
#[derive(Clone, Copy)]
enum Operator {
    Add,
    Sub,
    Mul,
    Div,
}

/// `term (+|- term)*`, left to right, in a loop.
fn parse_sum(input: ParseStream, depth: usize) -> syn::Result<(NumberValue, SpanRange)> {
    let (mut value, mut span) = parse_product(input, depth)?;
    loop {
        let op = if input.peek(Token![+]) && !input.peek(Token![+=]) {
            input.parse::<Token![+]>()?;
            Operator::Add
        } else if input.peek(Token![-]) && !input.peek(Token![-=]) && !input.peek(Token![->]) {
            input.parse::<Token![-]>()?;
            Operator::Sub
        } else {
            return Ok((value, span));
        };
        let (right, right_span) = parse_product(input, depth)?;
        span = SpanRange::new(span.first, right_span.last);
        value = combine(op, value, right, span)?;
    }
}

/// `factor (*|/ factor)*`, left to right, in a loop.
fn parse_product(input: ParseStream, depth: usize) -> syn::Result<(NumberValue, SpanRange)> {
    let (mut value, mut span) = parse_factor(input, depth)?;
    loop {
        let op = if input.peek(Token![*]) && !input.peek(Token![*=]) {
            input.parse::<Token![*]>()?;
            Operator::Mul
        } else if input.peek(Token![/]) && !input.peek(Token![/=]) {
            input.parse::<Token![/]>()?;
            Operator::Div
        } else {
            return Ok((value, span));
        };
        let (right, right_span) = parse_factor(input, depth)?;
        span = SpanRange::new(span.first, right_span.last);
        value = combine(op, value, right, span)?;
    }
}

/// `-`* then a literal, `pi`, a parameter or a parenthesized number; the minus signs are
/// counted in a loop.
fn parse_factor(input: ParseStream, depth: usize) -> syn::Result<(NumberValue, SpanRange)> {
    let mut negations = 0_usize;
    let mut first = None;
    while input.peek(Token![-]) {
        let minus = input.parse::<Token![-]>()?;
        first.get_or_insert(minus.span);
        negations += 1;
    }
    let (value, span) = parse_atom(input, depth)?;
    let value = if negations % 2 == 1 {
        match value {
            NumberValue::Constant(c) => NumberValue::Constant(-c),
            NumberValue::Parameter { name, coefficient } => NumberValue::Parameter {
                name,
                coefficient: -coefficient,
            },
        }
    } else {
        value
    };
    Ok((
        value,
        SpanRange::new(first.unwrap_or(span.first), span.last),
    ))
}

/// A literal, `pi`, a parameter, or a number in parentheses (or in the invisible group a
/// `macro_rules!` fragment arrives in).
fn parse_atom(input: ParseStream, depth: usize) -> syn::Result<(NumberValue, SpanRange)> {
    let not_a_number = |span: Span| {
        syn::Error::new(
            span,
            "expected a number: a literal, `pi`, a parameter, or + - * / of these",
        )
    };
    let nested = |span: Span| -> syn::Result<usize> {
        if depth >= MAX_NESTING {
            return Err(syn::Error::new(
                span,
                format!(
                    "parentheses nest more than {MAX_NESTING} deep in this number; simplify it"
                ),
            ));
        }
        Ok(depth + 1)
    };
    if input.peek(syn::token::Paren) {
        let content;
        let paren = parenthesized!(content in input);
        let inner = nested(paren.span.open())?;
        let (value, _) = parse_sum(&content, inner)?;
        if !content.is_empty() {
            return Err(not_a_number(content.span()));
        }
        return Ok((value, SpanRange::from(paren.span.join())));
    }
    if let Some((group, span)) = input.step(|cursor| match cursor.group(Delimiter::None) {
        Some((inside, span, rest)) => Ok((Some((inside.token_stream(), span.join())), rest)),
        None => Ok((None, *cursor)),
    })? {
        let inner = nested(span)?;
        let value = syn::parse::Parser::parse2(
            |content: ParseStream| {
                let (value, _) = parse_sum(content, inner)?;
                if content.is_empty() {
                    Ok(value)
                } else {
                    Err(not_a_number(content.span()))
                }
            },
            group,
        )?;
        return Ok((value, SpanRange::from(span)));
    }
    if input.peek(syn::Lit) {
        let lit: syn::Lit = input.parse()?;
        let span = SpanRange::from(lit.span());
        let (value, suffix, digits) = match &lit {
            syn::Lit::Float(f) => (f.base10_parse::<f64>()?, f.suffix(), f.base10_digits()),
            syn::Lit::Int(i) => (i.base10_parse::<f64>()?, i.suffix(), i.base10_digits()),
            _ => return Err(not_a_number(lit.span())),
        };
        if !suffix.is_empty() {
            return Err(suffixed_number(&lit, suffix, digits));
        }
        return Ok((NumberValue::Constant(value), span));
    }
    if input.peek(Ident) {
        let ident: Ident = input.parse()?;
        let span = SpanRange::from(ident.span());
        let value = match ident.to_string().as_str() {
            "pi" | "PI" => NumberValue::Constant(std::f64::consts::PI),
            name => NumberValue::Parameter {
                name: name.to_owned(),
                coefficient: 1.0,
            },
        };
        return Ok((value, span));
    }
    Err(not_a_number(input.span()))
}

/// The error for a literal with a type suffix (`300u8`, `1.1f32`, `2.0f64`). The suffix
/// was ignored before (`300u8` read as 300, `1.1f32` as the f64 1.1, not as the f32 it
/// names); it is refused rather than honoured because a mechanism's numbers have no Rust
/// type: the generated code is generic over its scalar (f32, f64, double-double, SIMD
/// lanes) and converts every constant to it. `f64` is refused too, although its value would
/// be the one read: it would promise an f64 constant in the f32 instantiation, and one rule
/// without exceptions is the simpler one to state.
fn suffixed_number(lit: &syn::Lit, suffix: &str, digits: &str) -> syn::Error {
    use quote::ToTokens;
    let plain = if matches!(lit, syn::Lit::Int(_)) {
        format!("{digits}.0")
    } else {
        let written = lit.to_token_stream().to_string();
        written[..written.len() - suffix.len()]
            .trim_end_matches('_')
            .to_owned()
    };
    syn::Error::new(
        lit.span(),
        format!(
            "a number in a mechanism takes no type suffix (`{suffix}`): the generated code \
             converts every number to its own scalar type (f32, f64, …); write `{plain}`"
        ),
    )
}

/// `left op right`: constants combine; a parameter may only be scaled by a constant.
fn combine(
    op: Operator,
    left: NumberValue,
    right: NumberValue,
    span: SpanRange,
) -> syn::Result<NumberValue> {
    use NumberValue::{Constant, Parameter};
    match (op, left, right) {
        (Operator::Add, Constant(x), Constant(y)) => Ok(Constant(x + y)),
        (Operator::Sub, Constant(x), Constant(y)) => Ok(Constant(x - y)),
        (Operator::Mul, Constant(x), Constant(y)) => Ok(Constant(x * y)),
        (Operator::Div, Constant(x), Constant(y)) => Ok(Constant(x / y)),
        (Operator::Mul, Constant(c), Parameter { name, coefficient })
        | (Operator::Mul, Parameter { name, coefficient }, Constant(c)) => Ok(Parameter {
            name,
            coefficient: coefficient * c,
        }),
        (Operator::Div, Parameter { name, coefficient }, Constant(c)) => Ok(Parameter {
            name,
            coefficient: coefficient / c,
        }),
        _ => Err(span.error("a parameter can only be multiplied or divided by a constant here")),
    }
}

/// Numbers separated by commas, up to the end of `content`.
fn parse_number_list(content: ParseStream) -> syn::Result<Vec<Number>> {
    let mut numbers = Vec::new();
    while !content.is_empty() {
        numbers.push(parse_number(content)?);
        if content.is_empty() {
            break;
        }
        content.parse::<Token![,]>()?;
    }
    Ok(numbers)
}

/// `[x, y, z]`.
pub(crate) fn parse_vector(input: ParseStream) -> syn::Result<Vector> {
    let content;
    let bracket = bracketed!(content in input);
    let span = SpanRange::from(bracket.span.join());
    let numbers = parse_number_list(&content)?;
    let components: [Number; 3] = numbers.try_into().map_err(|v: Vec<Number>| {
        span.error(format!("expected 3 numbers `[x, y, z]`, found {}", v.len()))
    })?;
    Ok(Vector { components, span })
}

/// `[[a, b, c], [d, e, f], [g, h, i]]`.
fn parse_matrix(input: ParseStream) -> syn::Result<Matrix> {
    let content;
    let bracket = bracketed!(content in input);
    let span = SpanRange::from(bracket.span.join());
    let mut rows = Vec::new();
    while !content.is_empty() {
        rows.push(parse_vector(&content)?.components);
        if content.is_empty() {
            break;
        }
        content.parse::<Token![,]>()?;
    }
    let rows: [[Number; 3]; 3] = rows.try_into().map_err(|v: Vec<[Number; 3]>| {
        span.error(format!(
            "expected a 3×3 matrix given by 3 rows, found {} rows",
            v.len()
        ))
    })?;
    Ok(Matrix { rows, span })
}

/// `x`, `-y`, `z` or `[a, b, c]`.
fn parse_axis(input: ParseStream) -> syn::Result<Axis> {
    if input.peek(syn::token::Bracket) {
        let direction = parse_vector(input)?;
        return Ok(Axis {
            span: direction.span,
            direction,
        });
    }
    let minus: Option<Token![-]> = input.parse()?;
    let ident: Ident = input.parse()?;
    let span = match &minus {
        Some(m) => SpanRange::new(m.span, ident.span()),
        None => SpanRange::from(ident.span()),
    };
    let sign = if minus.is_some() { -1.0 } else { 1.0 };
    let unit = match ident.to_string().as_str() {
        "x" => [sign, 0.0, 0.0],
        "y" => [0.0, sign, 0.0],
        "z" => [0.0, 0.0, sign],
        other => {
            return Err(syn::Error::new(
                ident.span(),
                format!("unknown axis `{other}`; expected x, y, z, -x, -y, -z or [a, b, c]"),
            ))
        }
    };
    let components = unit.map(|c| Number::constant(c, span));
    Ok(Axis {
        direction: Vector { components, span },
        span,
    })
}

/// `rpy(r, p, y)`, `axis_angle([x, y, z], angle)` or a 3×3 matrix.
fn parse_rotation(input: ParseStream) -> syn::Result<Rotation> {
    if input.peek(syn::token::Bracket) {
        return Ok(Rotation::Matrix(parse_matrix(input)?));
    }
    let form: Ident = input.parse()?;
    let content;
    let paren = parenthesized!(content in input);
    let span = SpanRange::new(form.span(), paren.span.join());
    match form.to_string().as_str() {
        "rpy" => {
            let numbers = parse_number_list(&content)?;
            let angles: [Number; 3] = numbers.try_into().map_err(|_| {
                span.error("expected `rpy(roll, pitch, yaw)` with three angles in radians")
            })?;
            Ok(Rotation::Rpy(angles, span))
        }
        "axis_angle" => {
            let axis = parse_vector(&content)?;
            content.parse::<Token![,]>()?;
            let angle = parse_number(&content)?;
            Ok(Rotation::AxisAngle(axis, angle, span))
        }
        other => Err(syn::Error::new(
            form.span(),
            format!("unknown rotation `{other}`; expected rpy(r, p, y), axis_angle([x, y, z], angle) or a 3×3 matrix"),
        )),
    }
}

/// Named arguments `name: value, ...` inside a shape or a `principal(...)` form.
fn expect_arg(content: ParseStream, expected: &str) -> syn::Result<Span> {
    let name: Ident = content.parse()?;
    if name != expected {
        return Err(syn::Error::new(
            name.span(),
            format!("expected `{expected}:` here"),
        ));
    }
    content.parse::<Token![:]>()?;
    Ok(name.span())
}

fn comma_unless_end(content: ParseStream) -> syn::Result<()> {
    if !content.is_empty() {
        content.parse::<Token![,]>()?;
    }
    Ok(())
}

/// `rod(length: l, axis: y)`, `box(size: [x, y, z])`, `cylinder(radius: r, length: l, axis: z)`,
/// `sphere(radius: r)`, `point`.
fn parse_shape(input: ParseStream) -> syn::Result<Shape> {
    let form = Ident::parse_any(input)?;
    let name = form.to_string();
    if name == "point" {
        return Ok(Shape {
            kind: ShapeKind::Point,
            span: SpanRange::from(form.span()),
        });
    }
    let content;
    let paren = parenthesized!(content in input);
    let span = SpanRange::new(form.span(), paren.span.join());
    let kind = match name.as_str() {
        "rod" => {
            expect_arg(&content, "length")?;
            let length = parse_number(&content)?;
            content.parse::<Token![,]>()?;
            expect_arg(&content, "axis")?;
            let axis = parse_axis(&content)?;
            ShapeKind::Rod { length, axis }
        }
        "box" => {
            expect_arg(&content, "size")?;
            ShapeKind::Box {
                size: parse_vector(&content)?,
            }
        }
        "cylinder" => {
            expect_arg(&content, "radius")?;
            let radius = parse_number(&content)?;
            content.parse::<Token![,]>()?;
            expect_arg(&content, "length")?;
            let length = parse_number(&content)?;
            content.parse::<Token![,]>()?;
            expect_arg(&content, "axis")?;
            let axis = parse_axis(&content)?;
            ShapeKind::Cylinder {
                radius,
                length,
                axis,
            }
        }
        "sphere" => {
            expect_arg(&content, "radius")?;
            ShapeKind::Sphere {
                radius: parse_number(&content)?,
            }
        }
        other => {
            return Err(syn::Error::new(
                form.span(),
                format!("unknown shape `{other}`; expected rod, box, cylinder, sphere or point"),
            ))
        }
    };
    comma_unless_end(&content)?;
    if !content.is_empty() {
        return Err(content.error("unexpected argument"));
    }
    Ok(Shape { kind, span })
}

/// `[[..]..]`, `diag([..])` or `principal([..], rotation: ...)`.
fn parse_inertia(input: ParseStream) -> syn::Result<InertiaForm> {
    if input.peek(syn::token::Bracket) {
        return Ok(InertiaForm::Matrix(parse_matrix(input)?));
    }
    let form: Ident = input.parse()?;
    let content;
    let paren = parenthesized!(content in input);
    let span = SpanRange::new(form.span(), paren.span.join());
    match form.to_string().as_str() {
        "diag" => Ok(InertiaForm::Principal {
            moments: parse_vector(&content)?,
            rotation: None,
            span,
        }),
        "principal" => {
            let moments = parse_vector(&content)?;
            let mut rotation = None;
            if content.parse::<Option<Token![,]>>()?.is_some() && !content.is_empty() {
                expect_arg(&content, "rotation")?;
                rotation = Some(parse_rotation(&content)?);
                comma_unless_end(&content)?;
            }
            Ok(InertiaForm::Principal {
                moments,
                rotation,
                span,
            })
        }
        other => Err(syn::Error::new(
            form.span(),
            format!(
                "unknown inertia form `{other}`; expected a 3×3 matrix, diag([i1, i2, i3]) or \
                 principal([i1, i2, i3], rotation: rpy(r, p, y))"
            ),
        )),
    }
}

/// Parses `{ field: value, ... }`, calling `field` for each field name.
fn parse_fields(
    input: ParseStream,
    mut field: impl FnMut(&Ident, ParseStream) -> syn::Result<bool>,
) -> syn::Result<SpanRange> {
    let content;
    let brace = braced!(content in input);
    let mut seen: Vec<Ident> = Vec::new();
    while !content.is_empty() {
        let name: Ident = content.parse()?;
        content.parse::<Token![:]>()?;
        let text = name.to_string();
        if let Some(first) = seen.iter().find(|s| **s == text) {
            let mut error = syn::Error::new(name.span(), format!("`{text}` is given twice"));
            error.combine(syn::Error::new(
                first.span(),
                format!("`{text}` is first given here"),
            ));
            return Err(error);
        }
        if !field(&name, &content)? {
            return Err(syn::Error::new(
                name.span(),
                format!("unknown field `{text}`"),
            ));
        }
        seen.push(name);
        comma_unless_end(&content)?;
    }
    Ok(SpanRange::from(brace.span.join()))
}

/// `body name { mass: .., com: .., inertia: .. | shape: .. }`.
fn parse_body(input: ParseStream, docs: Vec<String>) -> syn::Result<Body> {
    let name = parse_name(input)?;
    let (mut mass, mut com, mut inertia) = (None, None, None);
    let span = parse_fields(input, |field, content| {
        match field.to_string().as_str() {
            "mass" => mass = Some(parse_number(content)?),
            "com" => com = Some(parse_vector(content)?),
            "inertia" | "shape" if inertia.is_some() => {
                return Err(syn::Error::new(
                    field.span(),
                    "give either `inertia` or `shape`, not both",
                ))
            }
            "inertia" => inertia = Some(parse_inertia(content)?),
            "shape" => inertia = Some(InertiaForm::Shape(parse_shape(content)?)),
            _ => return Ok(false),
        }
        Ok(true)
    })
    .map_err(|e| with_hint(e, "body fields are mass, com, inertia (or shape)"))?;
    Ok(Body {
        docs,
        name,
        mass,
        com,
        inertia,
        span,
    })
}

fn with_hint(error: syn::Error, hint: &str) -> syn::Error {
    if error.to_string().starts_with("unknown field") {
        syn::Error::new(error.span(), format!("{error}; {hint}"))
    } else {
        error
    }
}

/// `joint name: kind(parent -> child) { ... }` or `... ;`.
fn parse_joint(input: ParseStream, docs: Vec<String>) -> syn::Result<Joint> {
    let start = input.cursor();
    let name = parse_name(input)?;
    input.parse::<Token![:]>()?;
    let kind_ident: Ident = input.parse()?;
    let kind = match kind_ident.to_string().as_str() {
        "revolute" | "continuous" => JointKind::Revolute,
        "prismatic" => JointKind::Prismatic,
        "fixed" => JointKind::Fixed,
        "free" => JointKind::Free,
        other => {
            return Err(syn::Error::new(
                kind_ident.span(),
                format!(
                    "unknown joint kind `{other}`; expected revolute, prismatic, fixed or free"
                ),
            ))
        }
    };
    let content;
    parenthesized!(content in input);
    let parent = parse_name(&content)?;
    content.parse::<Token![->]>()?;
    let child = parse_name(&content)?;
    let mut joint = Joint {
        docs,
        name,
        kind,
        kind_span: kind_ident.span(),
        parent,
        child,
        axis: None,
        at: None,
        rotation: None,
        placement: None,
        armature: None,
        damping: None,
        friction: None,
        limits: None,
        driven: None,
    };
    if !input.peek(syn::token::Brace) {
        semicolon(input, start)?;
        return Ok(joint);
    }
    parse_fields(input, |field, content| {
        match field.to_string().as_str() {
            "axis" => joint.axis = Some(parse_axis(content)?),
            "at" => joint.at = Some(parse_vector(content)?),
            "rotation" => joint.rotation = Some(parse_rotation(content)?),
            "placement" => joint.placement = Some(parse_dh_placement(content)?),
            "armature" => joint.armature = Some(parse_number(content)?),
            "damping" => joint.damping = Some(parse_number(content)?),
            "friction" => joint.friction = Some(parse_number(content)?),
            "limits" => joint.limits = Some(parse_limits(content)?),
            "driven" => {
                let flag: LitBool = content.parse()?;
                joint.driven = Some((flag.value, flag.span()));
            }
            _ => return Ok(false),
        }
        Ok(true)
    })
    .map_err(|e| {
        with_hint(
            e,
            "joint fields are axis, at, rotation, placement, armature, damping, friction, limits, \
             driven",
        )
    })?;
    Ok(joint)
}

/// The forms of a joint's `placement:`.
const DH_FORMS: [&str; 2] = ["dh", "mdh"];

/// The entries of a DH row, in the order of [`DhPlacement`]'s fields.
const DH_ENTRIES: [&str; 4] = ["a", "alpha", "d", "theta"];

/// `dh(a: .., alpha: .., d: .., theta: ..)` or `mdh(..)`: each entry at most once, in any
/// order, 0 when absent.
fn parse_dh_placement(input: ParseStream) -> syn::Result<DhPlacement> {
    let expected = "expected `dh(a: .., alpha: .., d: .., theta: ..)` (standard \
                    Denavit–Hartenberg) or `mdh(..)` (modified, Craig's)";
    let form = input
        .call(Ident::parse_any)
        .map_err(|e| syn::Error::new(e.span(), expected))?;
    let convention = match form.to_string().as_str() {
        "dh" => DhConvention::Standard,
        "mdh" => DhConvention::Modified,
        other => {
            let hint = match closest(other, &DH_FORMS) {
                Some(near) => format!("did you mean `{near}`? "),
                None => String::new(),
            };
            return Err(syn::Error::new(
                form.span(),
                format!("unknown placement `{other}`; {hint}{expected}"),
            ));
        }
    };
    if !input.peek(syn::token::Paren) {
        return Err(syn::Error::new(
            form.span(),
            format!("expected `{form}(a: .., alpha: .., d: .., theta: ..)`"),
        ));
    }
    let content;
    let paren = parenthesized!(content in input);
    let span = SpanRange::new(form.span(), paren.span.join());
    let mut entries: [Option<(Number, Span)>; 4] = Default::default();
    while !content.is_empty() {
        let key = content.call(Ident::parse_any)?;
        let text = key.to_string();
        let Some(index) = DH_ENTRIES.iter().position(|e| *e == text) else {
            let hint = match closest(&text, &DH_ENTRIES) {
                Some(near) => format!("did you mean `{near}`? The entries are"),
                None => "the entries are".to_owned(),
            };
            return Err(syn::Error::new(
                key.span(),
                format!(
                    "unknown DH entry `{text}`; {hint} a, alpha, d, theta (lengths in m, angles \
                     in rad; each 0 when absent)"
                ),
            ));
        };
        if let Some((_, first)) = &entries[index] {
            let mut error = syn::Error::new(key.span(), format!("`{text}` is given twice"));
            error.combine(syn::Error::new(
                *first,
                format!("`{text}` is first given here"),
            ));
            return Err(error);
        }
        content.parse::<Token![:]>()?;
        entries[index] = Some((parse_number(&content)?, key.span()));
        comma_unless_end(&content)?;
    }
    let [a, alpha, d, theta] = entries.map(|e| e.map(|(number, _)| number));
    Ok(DhPlacement {
        convention,
        a,
        alpha,
        d,
        theta,
        span,
    })
}

/// `{ lower: .., upper: .., velocity: .., effort: .. }`, each entry optional.
fn parse_limits(input: ParseStream) -> syn::Result<Limits> {
    let (mut lower, mut upper, mut velocity, mut effort) = (None, None, None, None);
    let span = parse_fields(input, |field, content| {
        let slot = match field.to_string().as_str() {
            "lower" => &mut lower,
            "upper" => &mut upper,
            "velocity" => &mut velocity,
            "effort" => &mut effort,
            _ => return Ok(false),
        };
        *slot = Some(parse_number(content)?);
        Ok(true)
    })
    .map_err(|e| {
        // Named a limit, not a field, so that the joint's hint is not added after it.
        match e.to_string().strip_prefix("unknown field") {
            Some(rest) => syn::Error::new(
                e.span(),
                format!("unknown limit{rest}; the limits are lower, upper, velocity, effort"),
            ),
            None => e,
        }
    })?;
    Ok(Limits {
        lower,
        upper,
        velocity,
        effort,
        span,
    })
}

/// `load name: force|couple|wrench on body [at [x, y, z]] [in world | in body];`, the
/// point and the axes in either order, each at most once.
fn parse_load(input: ParseStream, docs: Vec<String>) -> syn::Result<Load> {
    let start = input.cursor();
    let name = parse_name(input)?;
    input.parse::<Token![:]>()?;
    let kind_ident: Ident = input.parse()?;
    let kind = match kind_ident.to_string().as_str() {
        "force" => LoadKind::Force,
        "couple" => LoadKind::Couple,
        "wrench" => LoadKind::Wrench,
        other => {
            return Err(syn::Error::new(
                kind_ident.span(),
                format!("unknown load `{other}`; expected force, couple or wrench"),
            ))
        }
    };
    let on: Ident = input.parse()?;
    if on != "on" {
        return Err(syn::Error::new(on.span(), "expected `on <body>`"));
    }
    let body = parse_name(input)?;
    let (mut at, mut frame): (Option<Vector>, Option<(LoadFrame, Span)>) = (None, None);
    // The first `in`, for an error at a second one.
    let mut first_in: Option<Span> = None;
    loop {
        if input.peek(Token![in]) {
            let in_token: Token![in] = input.parse()?;
            let parsed = parse_load_frame(input, in_token.span)?;
            if let (Some((first, first_word)), Some(first_in)) = (frame, first_in) {
                let mut error = SpanRange::new(in_token.span, parsed.1).error(format!(
                    "the load's axes are given twice (`in {}`, then `in {}`); write `in world` or \
                     `in body` once",
                    load_frame_word(first),
                    load_frame_word(parsed.0)
                ));
                error.combine(SpanRange::new(first_in, first_word).error("the first is here"));
                return Err(error);
            }
            first_in = Some(in_token.span);
            frame = Some(parsed);
        } else if input.peek(Ident) && !next_is_new_item(input) {
            let at_kw: Ident = input.parse()?;
            if at_kw != "at" {
                return Err(syn::Error::new(
                    at_kw.span(),
                    "expected `at [x, y, z]`, `in world`, `in body` or `;`",
                ));
            }
            if at.is_some() {
                return Err(syn::Error::new(at_kw.span(), "`at` is given twice"));
            }
            at = Some(parse_vector(input)?);
        } else {
            break;
        }
    }
    semicolon(input, start)?;
    Ok(Load {
        docs,
        name,
        kind,
        body,
        at,
        frame,
    })
}

/// The words that may follow a load's `in`.
const LOAD_FRAMES: [&str; 2] = ["world", "body"];

/// The word of a load frame, as written after `in`.
fn load_frame_word(frame: LoadFrame) -> &'static str {
    match frame {
        LoadFrame::World => "world",
        LoadFrame::Body => "body",
    }
}

/// The word after a load's `in`: `world` or `body`, with its span (the `in`'s when the
/// word is missing).
fn parse_load_frame(input: ParseStream, in_span: Span) -> syn::Result<(LoadFrame, Span)> {
    let axes = "`in world` (the world's fixed axes) or `in body` (the loaded body's axes, the \
                default)";
    let Ok(word) = input.call(Ident::parse_any) else {
        let at = if input.is_empty() {
            in_span
        } else {
            input.span()
        };
        return Err(syn::Error::new(
            at,
            format!("expected `world` or `body` after `in`: a load's components are given {axes}"),
        ));
    };
    match word.to_string().as_str() {
        "world" => Ok((LoadFrame::World, word.span())),
        "body" => Ok((LoadFrame::Body, word.span())),
        other => {
            let hint = match closest(other, &LOAD_FRAMES) {
                Some(near) => format!("did you mean `in {near}`? A load's components are given"),
                None => "a load's components are given".to_owned(),
            };
            Err(SpanRange::new(in_span, word.span())
                .error(format!("unknown load axes `in {other}`; {hint} {axes}")))
        }
    }
}

/// Whether the next tokens start another item (a doc comment, the type, a setting
/// `name:` or an item keyword followed by a name): what follows an item whose `;` is missing.
fn next_is_new_item(input: ParseStream) -> bool {
    if input.peek(Token![#]) || input.peek(Token![pub]) || input.peek(Token![struct]) {
        return true;
    }
    let fork = input.fork();
    match fork.parse::<Ident>() {
        Ok(word) => {
            fork.peek(Token![:]) || (ITEMS.contains(&word.to_string().as_str()) && fork.peek(Ident))
        }
        Err(_) => false,
    }
}

/// The `;` that ends an item; its absence is reported at the item's last token (the end
/// of the macro's input would otherwise underline the whole invocation).
fn semicolon(input: ParseStream, item_start: syn::buffer::Cursor) -> syn::Result<()> {
    if input.peek(Token![;]) {
        input.parse::<Token![;]>()?;
        return Ok(());
    }
    let (mut cursor, end, mut last) = (item_start, input.cursor(), None);
    while cursor != end {
        let Some((token, next)) = cursor.token_tree() else {
            break;
        };
        last = Some(token.span());
        cursor = next;
    }
    Err(syn::Error::new(
        last.unwrap_or_else(|| input.span()),
        "expected `;` after this",
    ))
}

/// `frame name: on body [at [x, y, z]] [rotation ..];`.
fn parse_frame(input: ParseStream, docs: Vec<String>) -> syn::Result<Frame> {
    let start = input.cursor();
    let name = parse_name(input)?;
    input.parse::<Token![:]>()?;
    let on: Ident = input.parse()?;
    if on != "on" {
        return Err(syn::Error::new(
            on.span(),
            "expected `on <body>`: a frame is attached to a body (or `ground`)",
        ));
    }
    let body = parse_name(input)?;
    let (mut at, mut rotation) = (None, None);
    while input.peek(Ident) && !next_is_new_item(input) {
        let word: Ident = input.parse().map_err(|e| {
            syn::Error::new(e.span(), "expected `at [x, y, z]`, `rotation ...` or `;`")
        })?;
        match word.to_string().as_str() {
            "at" if at.is_none() => at = Some(parse_vector(input)?),
            "rotation" if rotation.is_none() => rotation = Some(parse_rotation(input)?),
            "at" | "rotation" => {
                return Err(syn::Error::new(
                    word.span(),
                    format!("`{word}` is given twice"),
                ))
            }
            _ => {
                return Err(syn::Error::new(
                    word.span(),
                    "expected `at [x, y, z]`, `rotation ...` or `;`",
                ))
            }
        }
    }
    semicolon(input, start)?;
    Ok(Frame {
        docs,
        name,
        body,
        at,
        rotation,
    })
}

/// `constraint name: kind(a at [..], b at [..]) { normal: .. | axis: .. };`.
fn parse_constraint(input: ParseStream, docs: Vec<String>) -> syn::Result<Constraint> {
    let name = parse_name(input)?;
    input.parse::<Token![:]>()?;
    let kind_ident: Ident = input.parse()?;
    let kind = match kind_ident.to_string().as_str() {
        "pin" => ConstraintKind::Pin,
        "ball" => ConstraintKind::Ball,
        "roller" | "slider" => ConstraintKind::Roller,
        "prismatic" => ConstraintKind::Prismatic,
        "weld" => ConstraintKind::Weld,
        other => {
            return Err(syn::Error::new(
                kind_ident.span(),
                format!("unknown constraint `{other}`; expected pin, ball, roller, slider, prismatic or weld"),
            ))
        }
    };
    let content;
    parenthesized!(content in input);
    let end = |content: ParseStream| -> syn::Result<ConstraintEnd> {
        let body = parse_name(content)?;
        let mut at = None;
        if content.peek(Ident) {
            let at_kw: Ident = content.parse()?;
            if at_kw != "at" {
                return Err(syn::Error::new(at_kw.span(), "expected `at [x, y, z]`"));
            }
            at = Some(parse_vector(content)?);
        }
        Ok(ConstraintEnd { body, at })
    };
    let first = end(&content)?;
    content.parse::<Token![,]>()?;
    let second = end(&content)?;
    comma_unless_end(&content)?;
    if !content.is_empty() {
        return Err(
            content.error("a constraint connects exactly two bodies: `(a at [..], b at [..])`")
        );
    }
    let mut direction = None;
    if input.peek(syn::token::Brace) {
        parse_fields(input, |field, content| {
            match field.to_string().as_str() {
                "normal" | "axis" => direction = Some(parse_axis(content)?),
                _ => return Ok(false),
            }
            Ok(true)
        })
        .map_err(|e| {
            with_hint(
                e,
                "constraint fields are normal (roller) and axis (prismatic, spatial pin)",
            )
        })?;
    }
    input.parse::<Option<Token![;]>>()?;
    Ok(Constraint {
        docs,
        name,
        kind,
        kind_span: kind_ident.span(),
        first,
        second,
        direction,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use quote::quote;

    fn parse(tokens: proc_macro2::TokenStream) -> syn::Result<Mechanism> {
        syn::parse2(tokens)
    }

    #[test]
    fn parses_the_falling_rod() {
        let m = parse(quote! {
            /// The textbook's falling rod.
            pub struct FallingRod;
            gravity: [0.0, -9.81, 0.0];
            outputs: [inverse_dynamics, mass_matrix];
            /// A uniform rod.
            body rod { mass: 2.0, com: [0.0, -0.6 / 2.0, 0.0], shape: rod(length: 0.6, axis: y) }
            joint pivot: revolute(ground -> rod) { axis: z, damping: 0.1 }
            load tip: force on rod at [0.0, -0.6, 0.0];
        })
        .expect("parses");
        assert_eq!(m.name, "FallingRod");
        assert_eq!(m.docs, vec![" The textbook's falling rod."]);
        assert_eq!(m.bodies.len(), 1);
        assert_eq!(m.bodies[0].docs, vec![" A uniform rod."]);
        let com = m.bodies[0].com.as_ref().expect("com");
        assert_eq!(com.components[1].value, NumberValue::Constant(-0.3));
        assert_eq!(m.joints[0].kind, JointKind::Revolute);
        assert_eq!(m.joints[0].parent.text, "ground");
        assert_eq!(m.loads[0].kind, LoadKind::Force);
        assert_eq!(m.outputs.as_ref().map(Vec::len), Some(2));
    }

    /// A load's components are in the body's axes unless `in world`; the point and the
    /// axes come in either order, each once; a misspelt frame names the word meant.
    #[test]
    fn loads_take_their_axes_after_in() {
        let frames = |load: proc_macro2::TokenStream| {
            parse(quote! { struct P; #load }).map(|m| {
                let load = &m.loads[0];
                (load.frame(), load.at.is_some())
            })
        };
        let ok = |load| frames(load).expect("parses");
        assert_eq!(ok(quote!(load l: force on b;)), (LoadFrame::Body, false));
        assert_eq!(
            ok(quote!(load l: force on b at [0.0, 0.0, 0.1] in world;)),
            (LoadFrame::World, true)
        );
        assert_eq!(
            ok(quote!(load l: wrench on b in world at [0.0, 0.0, 0.1];)),
            (LoadFrame::World, true)
        );
        assert_eq!(
            ok(quote!(load l: couple on b in body;)),
            (LoadFrame::Body, false)
        );
        let error = |load| frames(load).expect_err("rejected").to_string();
        let e = error(quote!(load l: force on b in wrold;));
        assert!(
            e.contains("unknown load axes `in wrold`; did you mean `in world`?"),
            "{e}"
        );
        let e = error(quote!(load l: force on b in space;));
        assert!(
            e.contains("unknown load axes `in space`;") && !e.contains("did you mean"),
            "{e}"
        );
        let e = error(quote!(load l: force on b in world in world;));
        assert!(e.contains("the load's axes are given twice"), "{e}");
        let e = error(quote!(load l: force on b in;));
        assert!(e.contains("expected `world` or `body` after `in`"), "{e}");
        let e = error(quote!(load l: force on b at [0.0, 0.0, 0.0] at [1.0, 0.0, 0.0];));
        assert!(e.contains("`at` is given twice"), "{e}");
    }

    #[test]
    fn isa_setting_takes_dispatch_or_baseline() {
        let with = |isa: proc_macro2::TokenStream| {
            parse(quote! {
                struct P;
                isa: #isa;
                body b { mass: 1.0, shape: point }
                joint j: prismatic(ground -> b) { axis: x }
            })
        };
        assert_eq!(
            with(quote!(baseline)).expect("parses").isa,
            Some(Isa::Baseline)
        );
        assert_eq!(
            with(quote!(dispatch)).expect("parses").isa,
            Some(Isa::Dispatch)
        );
        let e = with(quote!(avx512)).expect_err("unknown");
        assert!(e.to_string().contains("unknown isa `avx512`"), "{e}");
    }

    #[test]
    fn lanes_setting_is_a_flag_off_by_default() {
        let with = |setting: proc_macro2::TokenStream| {
            parse(quote! {
                struct P;
                #setting
                body b { mass: 1.0, shape: point }
                joint j: prismatic(ground -> b) { axis: x }
            })
        };
        assert!(!with(quote!()).expect("parses").lanes);
        assert!(with(quote!(lanes: true;)).expect("parses").lanes);
        assert!(!with(quote!(lanes: false;)).expect("parses").lanes);
        let e = with(quote!(lanes: yes;)).expect_err("not a flag");
        assert!(
            e.to_string()
                .contains("expected `true` or `false` after `lanes:`"),
            "{e}"
        );
    }

    #[test]
    fn numbers_fold_and_scale_parameters() {
        let m = parse(quote! {
            struct P;
            parameters: [payload = 1.5];
            body b { mass: -2 * payload / 4, com: [pi, -(1 + 2), 1e-3], inertia: diag([1, 1, 1]) }
        })
        .expect("parses");
        let b = &m.bodies[0];
        assert_eq!(
            b.mass.as_ref().expect("mass").value,
            NumberValue::Parameter {
                name: "payload".into(),
                coefficient: -0.5
            }
        );
        let c = &b.com.as_ref().expect("com").components;
        assert_eq!(c[0].value, NumberValue::Constant(std::f64::consts::PI));
        assert_eq!(c[1].value, NumberValue::Constant(-3.0));
        assert_eq!(m.parameters[0].nominal.value, NumberValue::Constant(1.5));
    }

    #[test]
    fn rejects_parameter_sums_and_unknown_fields() {
        let e = parse(quote! { struct P; body b { mass: m + 1.0 } }).expect_err("sum");
        assert!(
            e.to_string().contains("only be multiplied or divided"),
            "{e}"
        );
        let e = parse(quote! { struct P; body b { weight: 1.0 } }).expect_err("field");
        assert!(e.to_string().contains("unknown field `weight`"), "{e}");
        let e = parse(quote! { body b { mass: 1.0 } }).expect_err("no type");
        assert!(e.to_string().contains("pub struct Name"), "{e}");
        let e = parse(quote! { struct P; joint j: hinge(ground -> b); }).expect_err("kind");
        assert!(e.to_string().contains("unknown joint kind `hinge`"), "{e}");
    }

    #[test]
    fn repetitions_point_at_the_first_occurrence_too() {
        let e = parse(quote! { struct P; body b { mass: 1.0, mass: 2.0 } }).expect_err("twice");
        let messages: Vec<String> = e.into_iter().map(|e| e.to_string()).collect();
        assert_eq!(
            messages,
            vec!["`mass` is given twice", "`mass` is first given here"]
        );
        let e = parse(quote! { struct P; struct Q; }).expect_err("two types");
        let messages: Vec<String> = e.into_iter().map(|e| e.to_string()).collect();
        assert_eq!(
            messages,
            vec![
                "the mechanism's type is declared twice",
                "the mechanism's type `P` is first declared here"
            ]
        );
    }

    #[test]
    fn parses_rotations_axes_and_shapes() {
        let m = parse(quote! {
            struct P;
            body a { mass: 1, shape: box(size: [0.1, 0.2, 0.3]) }
            body b { mass: 1, inertia: principal([1, 2, 2.5], rotation: rpy(0, 0, pi / 2)) }
            body c { mass: 1, shape: cylinder(radius: 0.1, length: 0.5, axis: -x) }
            joint j1: prismatic(ground -> a) { axis: [1, 1, 0], rotation: axis_angle([0, 0, 1], 0.3) }
            joint j2: fixed(a -> b) { at: [0, 0, 1], rotation: [[1, 0, 0], [0, 1, 0], [0, 0, 1]] }
            joint j3: free(ground -> c);
        })
        .expect("parses");
        assert!(matches!(
            m.joints[0].rotation,
            Some(Rotation::AxisAngle(..))
        ));
        assert!(matches!(m.joints[1].rotation, Some(Rotation::Matrix(..))));
        assert_eq!(m.joints[2].kind, JointKind::Free);
        match &m.bodies[2].inertia {
            Some(InertiaForm::Shape(Shape {
                kind: ShapeKind::Cylinder { axis, .. },
                ..
            })) => {
                assert_eq!(
                    axis.direction.components[0].value,
                    NumberValue::Constant(-1.0)
                )
            }
            other => panic!("unexpected {other:?}"),
        }
    }

    /// `placement: dh(..)` and `mdh(..)` take a, alpha, d, theta in any order, each at most
    /// once and 0 when absent; a misspelt entry or form names the word meant.
    #[test]
    fn parses_dh_placements() {
        let placement = |form: proc_macro2::TokenStream| {
            parse(quote! {
                struct P;
                joint j: revolute(ground -> b) { placement: #form }
            })
            .map(|m| m.joints[0].placement.clone().expect("a placement"))
        };
        let p = placement(quote!(dh(theta: pi / 2, a: 0.4318, alpha: -pi / 2))).expect("parses");
        assert_eq!(p.convention, DhConvention::Standard);
        assert_eq!(p.a.map(|n| n.value), Some(NumberValue::Constant(0.4318)));
        assert_eq!(
            p.alpha.map(|n| n.value),
            Some(NumberValue::Constant(-std::f64::consts::FRAC_PI_2))
        );
        assert!(p.d.is_none());
        let p = placement(quote!(mdh(d: reach,))).expect("parses");
        assert_eq!(p.convention, DhConvention::Modified);
        assert!(matches!(
            p.d.map(|n| n.value),
            Some(NumberValue::Parameter { .. })
        ));
        let error = |form| placement(form).expect_err("rejected").to_string();
        let e = error(quote!(dh(a: 0.1, alhpa: 0.2)));
        assert!(
            e.starts_with("unknown DH entry `alhpa`; did you mean `alpha`? The entries are a, alpha, d, theta"),
            "{e}"
        );
        let e = error(quote!(dh(offset: 0.1)));
        assert!(
            e.starts_with("unknown DH entry `offset`; the entries are"),
            "{e}"
        );
        let e = error(quote!(dh(d: 0.1, d: 0.2)));
        assert_eq!(e, "`d` is given twice");
        let e = error(quote!(mhd(a: 0.1)));
        assert!(
            e.starts_with("unknown placement `mhd`; did you mean `mdh`?"),
            "{e}"
        );
        let e = error(quote!(dh));
        assert_eq!(e, "expected `dh(a: .., alpha: .., d: .., theta: ..)`");
    }

    /// A misspelt item keyword or setting names itself and the word meant.
    #[test]
    fn unknown_items_and_settings_suggest_the_word_meant() {
        let message = |tokens| match parse(tokens) {
            Ok(_) => String::new(),
            Err(e) => e.to_string(),
        };
        assert_eq!(
            message(quote! { pub struct P; bodi rod { mass: 1.0 } }),
            "unknown item `bodi`; did you mean `body`?"
        );
        assert_eq!(
            message(quote! { pub struct P; jiont pivot: revolute(ground -> rod); }),
            "unknown item `jiont`; did you mean `joint`?"
        );
        assert!(message(quote! { pub struct P; gravty: none; })
            .starts_with("unknown setting `gravty`; did you mean `gravity`?"));
        assert!(message(quote! { pub struct P; wheel w {} })
            .starts_with("unknown item `wheel`; expected"));
    }

    /// Parses `pub struct P; gravity: [<number>, 0.0, 0.0];` from a string on a thread with
    /// a 4 MiB stack (less than a main thread's 8 MiB) (the source is parsed, and dropped, there too).
    fn mass_from_source(number: String) -> Result<f64, String> {
        std::thread::Builder::new()
            .stack_size(4 * 1024 * 1024)
            .spawn(move || {
                let source = format!("pub struct P; gravity: [{number}, 0.0, 0.0];");
                let m = syn::parse_str::<Mechanism>(&source).map_err(|e| e.to_string())?;
                match m.gravity {
                    Some(Gravity::Vector(g)) => match g.components[0].value.clone() {
                        NumberValue::Constant(c) => Ok(c),
                        other => Err(format!("{other:?}")),
                    },
                    _ => Err("no gravity vector".to_owned()),
                }
            })
            .map_err(|e| e.to_string())?
            .join()
            .map_err(|_| "the parser's thread panicked".to_owned())?
    }

    /// Issue 21 (item 13's leftovers): a literal with a type suffix is an error at the
    /// literal that says what to write instead; it was read without its suffix.
    #[test]
    fn number_literals_take_no_type_suffix() {
        for (written, plain) in [
            ("300u8", "300.0"),
            ("1.1f32", "1.1"),
            ("2.0f64", "2.0"),
            ("1e3_f64", "1e3"),
            ("7i32", "7.0"),
        ] {
            let e = mass_from_source(format!("-{written} * 2.0")).expect_err(written);
            assert!(e.contains("takes no type suffix"), "{written}: {e}");
            assert!(e.contains(&format!("write `{plain}`")), "{written}: {e}");
        }
        assert_eq!(mass_from_source("300".to_owned()), Ok(300.0));
        assert_eq!(mass_from_source("1.1".to_owned()), Ok(1.1));
    }

    /// Issue item 10: deep nesting is an error, long flat sums and runs of minus signs parse
    /// without recursion per term; none overflows a small stack.
    #[test]
    fn deep_numbers_do_not_overflow_the_stack() {
        let deep = format!("{}1.0{}", "(".repeat(5000), ")".repeat(5000));
        let e = mass_from_source(deep).expect_err("too deep");
        assert!(e.contains("parentheses nest more than 64 deep"), "{e}");
        let ok = format!("{}1.5{}", "(".repeat(64), ")".repeat(64));
        assert_eq!(mass_from_source(ok), Ok(1.5));
        assert_eq!(
            mass_from_source(format!("{}2.0", "-".repeat(20_000))),
            Ok(2.0)
        );
        assert_eq!(
            mass_from_source(format!("{}2.0", "- ".repeat(20_001))),
            Ok(-2.0)
        );
        let sum = vec!["1.0"; 50_000].join(" + ");
        assert_eq!(mass_from_source(sum), Ok(50_000.0));
        let product = vec!["1.0"; 50_000].join(" * ");
        assert_eq!(mass_from_source(product), Ok(1.0));
        assert_eq!(
            mass_from_source("2.0 * (1.0 - 3.0) / 4.0 - -pi".into()),
            Ok(-1.0 + std::f64::consts::PI)
        );
    }
}
