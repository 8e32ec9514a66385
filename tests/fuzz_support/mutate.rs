//! The mutations of `fuzz.rs`: a `mechanism!` declaration changed token by token, a URDF
//! file changed as text. Each mutation is a [`Mutation`], four numbers that pick what to
//! change, where, and what to put there, so that proptest can draw and shrink them; applying
//! the same list to the same input always gives the same text.

use proc_macro2::{Delimiter, Spacing, TokenStream, TokenTree};
use std::str::FromStr;

/// One mutation: its kind and three choices, each taken modulo the number of candidates
/// when applied (so any values are valid).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mutation {
    /// Which mutation (modulo the number of kinds).
    pub kind: u8,
    /// Where (a token, an item, an element, a number ... of the input).
    pub at: u32,
    /// A second place, for swaps and moves.
    pub other: u32,
    /// What to put there (an entry of a replacement list).
    pub pick: u32,
}

// ---------------------------------------------------------------------------------------
// Declarations, token by token.

/// A token of a declaration: a leaf (an identifier, a literal, or a run of joint
/// punctuation such as `->`, as written) or a delimited group.
#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Leaf(String),
    Group(Delimiter, Vec<Tok>),
}

impl Tok {
    fn is_number(&self) -> bool {
        matches!(self, Tok::Leaf(s) if s.starts_with(|c: char| c.is_ascii_digit()))
    }

    fn is_ident(&self) -> bool {
        matches!(self, Tok::Leaf(s) if s.starts_with(|c: char| c.is_alphabetic() || c == '_'))
    }

    fn is_string(&self) -> bool {
        matches!(self, Tok::Leaf(s) if s.starts_with('"'))
    }

    fn is_leaf(&self, text: &str) -> bool {
        matches!(self, Tok::Leaf(s) if s == text)
    }
}

/// The tokens of `text`, or `None` if it does not lex (unbalanced delimiters).
fn lex(text: &str) -> Option<Vec<Tok>> {
    TokenStream::from_str(text).ok().map(tokens)
}

fn tokens(stream: TokenStream) -> Vec<Tok> {
    let mut out = Vec::new();
    let mut joint = String::new();
    for tree in stream {
        match tree {
            TokenTree::Punct(p) => {
                joint.push(p.as_char());
                if p.spacing() == Spacing::Alone {
                    out.push(Tok::Leaf(std::mem::take(&mut joint)));
                }
            }
            // A lifetime: `'` joint with the identifier after it.
            TokenTree::Ident(i) if joint == "'" => {
                out.push(Tok::Leaf(format!("'{i}")));
                joint.clear();
            }
            other => {
                if !joint.is_empty() {
                    out.push(Tok::Leaf(std::mem::take(&mut joint)));
                }
                out.push(match other {
                    TokenTree::Group(g) => Tok::Group(g.delimiter(), tokens(g.stream())),
                    TokenTree::Ident(i) => Tok::Leaf(i.to_string()),
                    TokenTree::Literal(l) => Tok::Leaf(l.to_string()),
                    TokenTree::Punct(_) => unreachable!("handled above"),
                });
            }
        }
    }
    if !joint.is_empty() {
        out.push(Tok::Leaf(joint));
    }
    out
}

fn render(tokens: &[Tok]) -> String {
    let mut s = String::new();
    render_into(tokens, &mut s);
    s
}

fn render_into(tokens: &[Tok], s: &mut String) {
    for t in tokens {
        if !s.is_empty() && !s.ends_with(['\n', ' ']) {
            s.push(' ');
        }
        match t {
            Tok::Leaf(text) => {
                s.push_str(text);
                // A top-level item per line, for readable failure reports.
                if text == ";" {
                    s.push('\n');
                }
            }
            Tok::Group(delimiter, inner) => {
                let (open, close) = match delimiter {
                    Delimiter::Parenthesis => ("(", ")"),
                    Delimiter::Bracket => ("[", "]"),
                    Delimiter::Brace => ("{", "}"),
                    Delimiter::None => ("", ""),
                };
                s.push_str(open);
                render_into(inner, s);
                s.push(' ');
                s.push_str(close);
            }
        }
    }
}

/// The position of every token, groups and their contents, depth first: the indices from
/// the top-level list down.
fn paths(tokens: &[Tok]) -> Vec<Vec<usize>> {
    paths_where(tokens, |_| true)
}

/// The list holding the token at `path`, and the token's index in it.
fn siblings<'a>(tokens: &'a mut Vec<Tok>, path: &[usize]) -> (&'a mut Vec<Tok>, usize) {
    let (last, parents) = path.split_last().expect("a path is not empty");
    let mut list = tokens;
    for &k in parents {
        list = match &mut list[k] {
            Tok::Group(_, inner) => inner,
            Tok::Leaf(_) => unreachable!("a path goes through groups"),
        };
    }
    (list, *last)
}

fn token_at<'a>(tokens: &'a mut Vec<Tok>, path: &[usize]) -> &'a mut Tok {
    let (list, k) = siblings(tokens, path);
    &mut list[k]
}

/// What a number is replaced with: edge values of f64, expressions that overflow or give
/// NaN, integers too large for any integer type, suffixes, deep nesting.
fn number_replacements() -> Vec<String> {
    let mut v: Vec<String> = [
        "0",
        "0.0",
        "-0.0",
        "1",
        "-1.0",
        "-1",
        "1e308",
        "-1e308",
        "1e-308",
        "5e-324",
        "1e400",
        "(0.0 / 0.0)",
        "(1.0 / 0.0)",
        "(-1.0 / 0.0)",
        "(1e308 * 10.0)",
        "(1e200 * 1e200 - 1e200 * 1e200)",
        "(0.0 * (1.0 / 0.0))",
        "18446744073709551616",
        "340282366920938463463374607431768211456",
        "0x7f",
        "0b101",
        "1_0.5",
        "2.5f32",
        "3u8",
        "1e15",
        "1e-15",
        "pi",
        "(-pi)",
        "(pi / 0.0)",
        "999999999999999999999999999999.9",
        "1.0000000000000002",
        "0.9999999999999999",
        "(2.0 * (3.0 - 1.0))",
        "1e-9",
        "-1e-9",
        "1e9",
    ]
    .iter()
    .map(|s| (*s).to_owned())
    .collect();
    v.push(format!("{}1.0{}", "(".repeat(200), ")".repeat(200)));
    v.push(format!("{}1.0", "- ".repeat(5000)));
    v.push(vec!["0.001"; 3000].join(" + "));
    v.push(vec!["1.0001"; 3000].join(" * "));
    v
}

/// What an identifier is replaced with (besides the declaration's own identifiers): the
/// language's words, Rust keywords and names the generated code uses.
#[rustfmt::skip]
const IDENT_REPLACEMENTS: &[&str] = &[
    "ground", "body", "joint", "load", "frame", "constraint", "fixed", "free", "revolute",
    "continuous", "prismatic", "x", "y", "z", "point", "rod", "box", "sphere", "cylinder",
    "mass", "com", "inertia", "shape", "axis", "at", "rotation", "rpy", "axis_angle",
    "diag", "principal", "pi", "world", "in", "on", "force", "couple", "wrench", "pin",
    "ball", "roller", "slider", "weld", "normal", "gravity", "none", "outputs",
    "parameters", "allow", "urdf", "floating_base", "urdf_damping", "force_analysis",
    "planar", "spatial", "isa", "baseline", "dispatch", "frames", "armature", "damping",
    "friction", "limits", "lower", "upper", "velocity", "effort", "driven", "true", "false",
    "radius", "length", "size", "triangle_inequality", "inverse_dynamics", "mass_matrix",
    "forward_dynamics", "forward_dynamics_aba", "forward_dynamics_ldlt", "coriolis",
    "energy", "reactions", "joint_placements", "frame_jacobians", "centroidal_bias",
    "inverse_dynamics_derivatives", "mass_matrix_inverse", "constraint_residual",
    "force_analysis", "T", "Self", "self", "crate", "fn", "struct", "pub", "q", "v", "a",
    "tau", "p", "loads", "f64", "Model", "_", "r#type", "NaN", "inf", "PI", "é",
];

/// Tokens inserted before a token.
#[rustfmt::skip]
const INSERTIONS: &[&str] = &[
    ";", ",", ":", "->", "-", "*", "/", "+", "=", "!", "#", ".", "..", "::", "&", "<", ">",
    "ground", "body", "joint", "fixed", "free", "load", "frame", "constraint", "pub",
    "struct", "at", "in", "world", "on", "0.0", "1.0", "pi", "x", "[]", "{}", "()",
    "[0.0, 0.0, 0.0]", "rpy(0.0, 0.0, 0.0)", "\"s\"", "true", "'c'", "b'x'",
    "#[doc = \"x\"]", "#[allow(x)]", "pub(crate)", "body b {}",
    "joint j: fixed(ground -> b);",
];

/// String literals put in place of a string (the URDF path).
const STRING_REPLACEMENTS: &[&str] = &[
    "\"\"",
    "\"/\"",
    "\".\"",
    "\"/dev/null\"",
    "\"../models/urdf/panda.urdf\"",
    "\"../models/urdf/ur5.urdf\"",
    "\"../tests/data/urdf/branched.urdf\"",
    "\"Cargo.toml\"",
    "\"\\u{0}\"",
    "\"ünïcödé.urdf\"",
    "r\"raw.urdf\"",
    "b\"bytes\"",
    "'c'",
];

/// The kinds of declaration mutations, by weight: a kind's number appears once per unit
/// of weight, the mutations that keep the declaration parsing (numbers, identifiers,
/// items) more often than those that break it. The first is what proptest shrinks
/// towards.
#[rustfmt::skip]
const DECLARATION_KINDS: &[u8] = &[
    4, 4, 4, 4, 5, 5, 5, 6, 6, 6, 6, 14, 14, 14, 14, 15, 15, 0, 1, 2, 3, 7, 8, 9, 10, 11, 12, 13,
];

/// The scale factors of [`DECLARATION_KINDS`]' kind 15, an identifier of the declaration
/// (a parameter, in a declaration that has some) scaled by an edge value.
#[rustfmt::skip]
const SCALINGS: &[&str] = &[
    "* 1e308", "/ 0.0", "* (0.0 / 0.0)", "/ 1e-308", "* 0.0", "* -1.0", "/ -0.0",
    "* 5e-324", "+ 1.0", "* pi",
];

/// The declaration `text` after `mutations`, in order (a mutation that finds nothing to
/// change leaves the text as it is).
pub fn mutate_declaration(text: &str, mutations: &[Mutation]) -> String {
    let Some(mut toks) = lex(text) else {
        return text.to_owned();
    };
    let mut idents: Vec<String> = Vec::new();
    let mut numbers: Vec<String> = Vec::new();
    collect_leaves(&toks, &mut idents, &mut numbers);
    let number_replacements = number_replacements();
    for m in mutations {
        apply(&mut toks, m, &idents, &numbers, &number_replacements);
        // Through text and back, so that inserted runs are tokens like the others (the
        // mutations keep the delimiters balanced, so this lexes).
        match lex(&render(&toks)) {
            Some(lexed) => toks = lexed,
            None => break,
        }
    }
    render(&toks)
}

fn collect_leaves(toks: &[Tok], idents: &mut Vec<String>, numbers: &mut Vec<String>) {
    for t in toks {
        match t {
            Tok::Leaf(s) if t.is_ident() && !idents.contains(s) => idents.push(s.clone()),
            Tok::Leaf(s) if t.is_number() && !numbers.contains(s) => numbers.push(s.clone()),
            Tok::Leaf(_) => {}
            Tok::Group(_, inner) => collect_leaves(inner, idents, numbers),
        }
    }
}

fn pick<T: Clone>(from: &[T], choice: u32) -> Option<T> {
    (!from.is_empty()).then(|| from[choice as usize % from.len()].clone())
}

/// The paths of the tokens satisfying `keep`, depth first.
fn paths_where(toks: &[Tok], keep: impl Fn(&Tok) -> bool) -> Vec<Vec<usize>> {
    fn walk(
        tokens: &[Tok],
        keep: &dyn Fn(&Tok) -> bool,
        prefix: &mut Vec<usize>,
        out: &mut Vec<Vec<usize>>,
    ) {
        for (k, t) in tokens.iter().enumerate() {
            prefix.push(k);
            if keep(t) {
                out.push(prefix.clone());
            }
            if let Tok::Group(_, inner) = t {
                walk(inner, keep, prefix, out);
            }
            prefix.pop();
        }
    }
    let mut out = Vec::new();
    walk(toks, &keep, &mut Vec::new(), &mut out);
    out
}

/// The names declared by `parameters: [name = value, ..]`.
fn parameter_names(toks: &[Tok]) -> Vec<String> {
    let mut names = Vec::new();
    for window in toks.windows(3) {
        if let [Tok::Leaf(setting), Tok::Leaf(colon), Tok::Group(Delimiter::Bracket, list)] = window
        {
            if setting == "parameters" && colon == ":" {
                for pair in list.windows(2) {
                    if let [Tok::Leaf(name), Tok::Leaf(eq)] = pair {
                        if eq == "=" {
                            names.push(name.clone());
                        }
                    }
                }
            }
        }
    }
    names
}

/// The top-level items: ranges of the top-level list, each ending after a `;` or a braced
/// group (a body's or a joint's fields).
fn items(toks: &[Tok]) -> Vec<std::ops::Range<usize>> {
    let mut out = Vec::new();
    let mut start = 0;
    for (k, t) in toks.iter().enumerate() {
        let ends = t.is_leaf(";") || matches!(t, Tok::Group(Delimiter::Brace, _));
        if ends {
            out.push(start..k + 1);
            start = k + 1;
        }
    }
    if start < toks.len() {
        out.push(start..toks.len());
    }
    out
}

fn apply(
    toks: &mut Vec<Tok>,
    m: &Mutation,
    idents: &[String],
    numbers: &[String],
    number_replacements: &[String],
) {
    let all = paths(toks);
    let Some(at) = pick(&all, m.at) else {
        return;
    };
    match DECLARATION_KINDS[usize::from(m.kind) % DECLARATION_KINDS.len()] {
        // Delete a token (a leaf or a whole group).
        0 => {
            let (list, k) = siblings(toks, &at);
            list.remove(k);
        }
        // Duplicate a token.
        1 => {
            let (list, k) = siblings(toks, &at);
            let copy = list[k].clone();
            list.insert(k + 1, copy);
        }
        // Swap a token with a sibling.
        2 => {
            let (list, k) = siblings(toks, &at);
            let other = m.other as usize % list.len();
            list.swap(k, other);
        }
        // Move a token to another place in its list.
        3 => {
            let (list, k) = siblings(toks, &at);
            let t = list.remove(k);
            let to = m.other as usize % (list.len() + 1);
            list.insert(to, t);
        }
        // Replace a number by an edge value or an expression.
        4 => {
            if let Some(p) = pick(&paths_where(toks, Tok::is_number), m.at) {
                let with = pick(number_replacements, m.pick).expect("not empty");
                *token_at(toks, &p) = Tok::Leaf(with);
            }
        }
        // Replace a number by another number of the declaration.
        5 => {
            if let (Some(p), Some(with)) = (
                pick(&paths_where(toks, Tok::is_number), m.at),
                pick(numbers, m.pick),
            ) {
                *token_at(toks, &p) = Tok::Leaf(with);
            }
        }
        // Replace an identifier by another of the declaration or a word of the language.
        6 => {
            if let Some(p) = pick(&paths_where(toks, Tok::is_ident), m.at) {
                let mut choices: Vec<String> = idents.to_vec();
                choices.extend(IDENT_REPLACEMENTS.iter().map(|s| (*s).to_owned()));
                let with = pick(&choices, m.pick).expect("not empty");
                *token_at(toks, &p) = Tok::Leaf(with);
            }
        }
        // Insert a token before a token.
        7 => {
            let (list, k) = siblings(toks, &at);
            let with = pick(INSERTIONS, m.pick).expect("not empty");
            list.insert(k, Tok::Leaf(with.to_owned()));
        }
        // Drop a `;` (or a `,`).
        8 => {
            let separator = if m.pick % 3 == 2 { "," } else { ";" };
            if let Some(p) = pick(&paths_where(toks, |t| t.is_leaf(separator)), m.at) {
                let (list, k) = siblings(toks, &p);
                list.remove(k);
            }
        }
        // Drop a group.
        9 => {
            if let Some(p) = pick(&paths_where(toks, |t| matches!(t, Tok::Group(..))), m.at) {
                let (list, k) = siblings(toks, &p);
                list.remove(k);
            }
        }
        // Unwrap a group: its tokens without the delimiters.
        10 => {
            if let Some(p) = pick(&paths_where(toks, |t| matches!(t, Tok::Group(..))), m.at) {
                let (list, k) = siblings(toks, &p);
                if let Tok::Group(_, inner) = list.remove(k) {
                    for (n, t) in inner.into_iter().enumerate() {
                        list.insert(k + n, t);
                    }
                }
            }
        }
        // Change a group's delimiters.
        11 => {
            if let Some(p) = pick(&paths_where(toks, |t| matches!(t, Tok::Group(..))), m.at) {
                if let Tok::Group(d, _) = token_at(toks, &p) {
                    *d = match (*d, m.pick % 2) {
                        (Delimiter::Parenthesis, 0) | (Delimiter::Brace, 1) => Delimiter::Bracket,
                        (Delimiter::Bracket, 0) | (Delimiter::Parenthesis, 1) => Delimiter::Brace,
                        _ => Delimiter::Parenthesis,
                    };
                }
            }
        }
        // Empty a group.
        12 => {
            if let Some(p) = pick(&paths_where(toks, |t| matches!(t, Tok::Group(..))), m.at) {
                if let Tok::Group(_, inner) = token_at(toks, &p) {
                    inner.clear();
                }
            }
        }
        // Replace a string literal.
        13 => {
            if let Some(p) = pick(&paths_where(toks, Tok::is_string), m.at) {
                let with = pick(STRING_REPLACEMENTS, m.pick).expect("not empty");
                *token_at(toks, &p) = Tok::Leaf(with.to_owned());
            }
        }
        // Replace a number by an identifier of the declaration scaled by an edge value
        // (`m / 0.0` where `m` is a parameter).
        15 => {
            let parameters = parameter_names(toks);
            let names = if parameters.is_empty() {
                idents
            } else {
                &parameters
            };
            if let (Some(p), Some(ident)) = (
                pick(&paths_where(toks, Tok::is_number), m.at),
                pick(names, m.other),
            ) {
                let by = pick(SCALINGS, m.pick).expect("not empty");
                *token_at(toks, &p) = Tok::Leaf(format!("({ident} {by})"));
            }
        }
        // Duplicate, delete, swap or move a top-level item.
        _ => {
            let items = items(toks);
            let (Some(a), Some(b)) = (pick(&items, m.at), pick(&items, m.other)) else {
                return;
            };
            let item: Vec<Tok> = toks[a.clone()].to_vec();
            match m.pick % 4 {
                0 => {
                    toks.splice(a.end..a.end, item);
                }
                1 => {
                    toks.drain(a);
                }
                2 if a.end <= b.start => {
                    let second: Vec<Tok> = toks[b.clone()].to_vec();
                    toks.splice(b, item);
                    toks.splice(a, second);
                }
                _ => {
                    toks.drain(a);
                    toks.extend(item);
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------
// URDF files, as text.

/// What a number of a URDF file is replaced with.
#[rustfmt::skip]
const URDF_NUMBERS: &[&str] = &[
   
    "nan", "NaN", "inf", "-inf", "1e309", "-1e309", "", " ", "abc", "1,5", "0x10", "0", "-0", "-1",
    "1e-320", "1e308", "1 2", "+", "-", ".", "1e", "١", "0.0.0",
];

/// What an attribute's value is replaced with.
const URDF_VALUES: &[&str] = &[
    "",
    " ",
    "0",
    "1 2",
    "1 2 3 4",
    "0 0 0",
    "nan nan nan",
    "a b c",
    "1e999 0 0",
    "0 0 1e-300",
    "ground",
    "world",
    "true",
    "&amp;",
    "&#0;",
    "x\u{301}",
];

/// What a joint's `type` becomes.
const URDF_TYPES: &[&str] = &[
    "revolute",
    "continuous",
    "prismatic",
    "fixed",
    "floating",
    "planar",
    "spherical",
    "",
    "Revolute",
    "bogus",
];

/// Names put in place of a name.
#[rustfmt::skip]
const URDF_NAMES: &[&str] = &[
    "", "ground", "ground_weld", "root_joint", "a b", "1x", "fn", "self", "T", "é", "\u{0}",
    "x-y", "Self",
];

/// Characters inserted or deleted.
#[rustfmt::skip]
const URDF_CHARACTERS: &[&str] = &[
    "<", ">", "\"", "/", "&", "=", "<!--", "-->", "<![CDATA[", "\u{feff}",
];

/// Plausible numbers, put in place of a number of a URDF file.
#[rustfmt::skip]
const URDF_PLAUSIBLE: &[&str] = &[
    "0", "0.0", "1", "-1", "0.5", "2", "-0.3", "1e-9", "1e3", "3.14159", "1e-3",
];

/// The kinds of URDF mutations, by weight (as [`DECLARATION_KINDS`]).
#[rustfmt::skip]
const URDF_KINDS: &[u8] = &[
    12, 12, 12, 3, 3, 4, 4, 5, 1, 1, 2, 2, 9, 9, 0, 7, 6, 8, 10, 11,
];

/// The byte ranges of `name="value"` attribute values (the value only) in `text`, for
/// attributes called `name` (any attribute when `None`).
fn attribute_values(text: &str, name: Option<&str>) -> Vec<std::ops::Range<usize>> {
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    let mut k = 0;
    while let Some(offset) = text[k..].find("=\"") {
        let eq = k + offset;
        let value_start = eq + 2;
        let Some(len) = text[value_start..].find('"') else {
            break;
        };
        let mut name_start = eq;
        while name_start > 0
            && (bytes[name_start - 1].is_ascii_alphanumeric() || bytes[name_start - 1] == b'_')
        {
            name_start -= 1;
        }
        if name.is_none_or(|n| &text[name_start..eq] == n) {
            out.push(value_start..value_start + len);
        }
        k = value_start + len + 1;
    }
    out
}

/// The byte ranges of the numbers of `text` inside attribute values.
fn numbers(text: &str) -> Vec<std::ops::Range<usize>> {
    let mut out = Vec::new();
    for value in attribute_values(text, None) {
        let bytes = text.as_bytes();
        let mut k = value.start;
        while k < value.end {
            let c = bytes[k];
            if c.is_ascii_digit() || c == b'-' || c == b'.' {
                let start = k;
                while k < value.end && (bytes[k].is_ascii_digit() || b"-+.eE".contains(&bytes[k])) {
                    k += 1;
                }
                out.push(start..k);
            } else {
                k += 1;
            }
        }
    }
    out
}

/// The byte ranges of the elements of `text`: from `<name` to the end of its start tag when
/// it closes itself, else to the end of its matching end tag (or of its start tag, when
/// there is none).
fn elements(text: &str) -> Vec<std::ops::Range<usize>> {
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    let mut k = 0;
    while let Some(offset) = text[k..].find('<') {
        let start = k + offset;
        k = start + 1;
        let Some(&next) = bytes.get(start + 1) else {
            break;
        };
        if !next.is_ascii_alphabetic() {
            continue;
        }
        let name_end = text[start + 1..]
            .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
            .map_or(text.len(), |n| start + 1 + n);
        let name = &text[start + 1..name_end];
        let Some(tag_end) = text[start..].find('>').map(|n| start + n + 1) else {
            continue;
        };
        if text[..tag_end].ends_with("/>") {
            out.push(start..tag_end);
            continue;
        }
        // The matching end tag, counting nested elements of the same name.
        let (open, close) = (format!("<{name}"), format!("</{name}>"));
        let mut depth = 1;
        let mut scan = tag_end;
        let mut end = tag_end;
        while let Some(n) = text[scan..].find(['<']) {
            let at = scan + n;
            if text[at..].starts_with(&close) {
                depth -= 1;
                if depth == 0 {
                    end = at + close.len();
                    break;
                }
                scan = at + close.len();
            } else {
                if text[at..].starts_with(&open) {
                    let tag = text[at..].find('>').map_or(text.len(), |m| at + m + 1);
                    if !text[..tag].ends_with("/>") {
                        depth += 1;
                    }
                }
                scan = at + 1;
            }
        }
        out.push(start..end);
    }
    out
}

fn splice(text: &mut String, range: std::ops::Range<usize>, with: &str) {
    text.replace_range(range, with);
}

/// The nearest character boundary at or below `k`.
fn boundary(text: &str, mut k: usize) -> usize {
    k = k.min(text.len());
    while !text.is_char_boundary(k) {
        k -= 1;
    }
    k
}

/// The URDF `text` after `mutations`, in order.
pub fn mutate_urdf(text: &str, mutations: &[Mutation]) -> String {
    let mut text = text.to_owned();
    for m in mutations {
        let links: Vec<String> = attribute_values(&text, Some("name"))
            .into_iter()
            .map(|r| text[r].to_owned())
            .collect();
        match URDF_KINDS[usize::from(m.kind) % URDF_KINDS.len()] {
            // A number becomes another.
            12 => {
                if let Some(r) = pick(&numbers(&text), m.at) {
                    splice(
                        &mut text,
                        r,
                        pick(URDF_PLAUSIBLE, m.pick).expect("not empty"),
                    );
                }
            }
            // A number becomes garbage.
            0 => {
                if let Some(r) = pick(&numbers(&text), m.at) {
                    splice(&mut text, r, pick(URDF_NUMBERS, m.pick).expect("not empty"));
                }
            }
            // Drop an element.
            1 => {
                if let Some(r) = pick(&elements(&text), m.at) {
                    splice(&mut text, r, "");
                }
            }
            // Duplicate an element (a link or joint twice, a second <origin>, ...).
            2 => {
                if let Some(r) = pick(&elements(&text), m.at) {
                    let copy = text[r.clone()].to_owned();
                    text.insert_str(r.end, &copy);
                }
            }
            // A joint's parent or child becomes another link (cycles, two parents, a
            // joint to itself, disconnected links).
            3 => {
                if let (Some(r), Some(name)) = (
                    pick(&attribute_values(&text, Some("link")), m.at),
                    pick(&links, m.pick),
                ) {
                    splice(&mut text, r, &name);
                }
            }
            // A joint's type.
            4 => {
                if let Some(r) = pick(&attribute_values(&text, Some("type")), m.at) {
                    splice(&mut text, r, pick(URDF_TYPES, m.pick).expect("not empty"));
                }
            }
            // A name becomes another name of the file or an odd one.
            5 => {
                if let Some(r) = pick(&attribute_values(&text, Some("name")), m.at) {
                    let mut names = links.clone();
                    names.extend(URDF_NAMES.iter().map(|s| (*s).to_owned()));
                    splice(&mut text, r, &pick(&names, m.pick).expect("not empty"));
                }
            }
            // Drop an attribute.
            6 => {
                if let Some(r) = pick(&attribute_values(&text, None), m.at) {
                    let bytes = text.as_bytes();
                    let mut start = r.start - 2;
                    while start > 0 && !bytes[start - 1].is_ascii_whitespace() {
                        start -= 1;
                    }
                    splice(&mut text, start..r.end + 1, "");
                }
            }
            // An attribute's value becomes garbage.
            7 => {
                if let Some(r) = pick(&attribute_values(&text, None), m.at) {
                    splice(&mut text, r, pick(URDF_VALUES, m.pick).expect("not empty"));
                }
            }
            // Truncate the file.
            8 => {
                let k = boundary(&text, m.at as usize % (text.len() + 1));
                text.truncate(k);
            }
            // A new joint between two links of the file.
            9 => {
                if let Some(end) = text.rfind("</robot>") {
                    let kind = pick(URDF_TYPES, m.pick).expect("not empty");
                    let parent = pick(&links, m.at).unwrap_or_default();
                    let child = pick(&links, m.other).unwrap_or_default();
                    let joint = format!(
                        "<joint name=\"added_{}\" type=\"{kind}\"><parent link=\"{parent}\"/>\
                         <child link=\"{child}\"/><axis xyz=\"0 0 1\"/>\
                         <limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>\n",
                        m.other
                    );
                    text.insert_str(end, &joint);
                }
            }
            // Delete a character.
            10 => {
                if !text.is_empty() {
                    let k = boundary(&text, m.at as usize % text.len());
                    let next = text[k..].chars().next().map_or(0, char::len_utf8);
                    text.replace_range(k..k + next, "");
                }
            }
            // Insert markup characters.
            _ => {
                let k = boundary(&text, m.at as usize % (text.len() + 1));
                text.insert_str(k, pick(URDF_CHARACTERS, m.pick).expect("not empty"));
            }
        }
    }
    text
}
