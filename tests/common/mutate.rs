//! Edits of model text for the no-panic property tests: the token alphabet, extreme
//! numbers, and byte-level mutations (delete, insert, duplicate, swap, replace a number,
//! replace a byte).

#![allow(dead_code)]

use proptest::prelude::*;

#[rustfmt::skip]
pub const TOKENS: &[&str] = &[
    // keywords and statements
    "module", "function", "if", "else", "for", "let", "each", "intersection_for", "true",
    "false", "undef", "echo", "assert", "children", "$children", "include", "use", "return",
    // built-in modules
    "cube", "cylinder", "sphere", "translate", "rotate", "scale", "mirror", "multmatrix",
    "color", "union", "difference", "intersection", "hull", "minkowski", "linear_extrude",
    "rotate_extrude", "polyhedron", "text", "import", "surface", "square", "circle", "render",
    "group", "offset", "projection", "resize",
    // built-in functions
    "sqrt", "pow", "abs", "min", "max", "floor", "ceil", "round", "sin", "cos", "tan", "asin",
    "acos", "atan", "atan2", "len", "concat", "str", "lookup", "search", "norm", "cross",
    "is_num", "is_undef", "exp", "ln", "log", "sign", "chr", "ord", "rands",
    // argument names and identifiers
    "center", "size", "h", "r", "r1", "r2", "d", "d1", "d2", "v", "a", "m", "c", "x", "y", "i",
    "n", "leg", "seat_w", "width", "PI", "inf", "nan", "$fn", "$fa", "$fs", "$t", "$vpr",
    "$parent_modules", "$preview",
    // numbers
    "0", "1", "2", "10", "-1", "0.5", ".5", "1.", "1e3", "1e308", "1e309", "-1e308", "1e-308",
    "5e-324", "-0", "0.0", "1e", "0x10", "1.2.3", "99999999999999999999", "4294967296",
    "9007199254740993", "0/0", "1/0", "-1/0",
    // brackets and punctuation
    "(", ")", "[", "]", "{", "}", ";", ",", ":", "=", ".", "?",
    // operators
    "+", "-", "*", "/", "%", "^", "<", ">", "<=", ">=", "==", "!=", "&&", "||", "!", "#",
    // strings and comments
    "\"\"", "\"abc\"", "\"a\\\"b\"", "\"\\u00e9\"", "\"\\x41\"", "\"é✓\"", "\"", "//", "/*",
    "*/", "// note\n", "/* block */", "<lib/shapes.scad>", "<missing.scad>", "<>",
    // whitespace
    " ", " ", " ", "\n", "\t", "\r\n",
    // idioms
    "cube(10);", "translate([1,2,3])", "rotate([0,90,0])", "for(i=[0:3])", "for(i=[0:1e9])",
    "scale([2,2,2])", "cylinder(h=5,r=1);", "module m(){children();}", "m()",
    "function f(x)=x;", "f(1)", "[for(i=[0:2])i]", "let(a=1)",
];

/// A number-like replacement for a literal.
#[rustfmt::skip]
pub const NUMBERS: &[&str] = &[
    "1e308", "-1e308", "1e309", "1e-308", "5e-324", "-0", "0", "0.0", "0/0", "1/0", "-1/0",
    "-1", "-1000000", "1e15", "nan", "inf", "-inf", "undef", "\"7\"", "[]", "[1,2]", "true",
    "99999999999999999999999", "1e-320", "0.1",
];

/// One edit of a model's bytes; positions are fractions of the current length.
#[derive(Debug, Clone)]
pub enum Mutation {
    Delete { at: f64, len: usize },
    Insert { at: f64, text: String },
    Duplicate { at: f64, len: usize, to: f64 },
    Swap { a: f64, b: f64, len: usize },
    Number { which: usize, with: &'static str },
    Byte { at: f64, byte: u8 },
}

pub fn mutation() -> impl Strategy<Value = Mutation> {
    let frac = 0.0..1.0f64;
    prop_oneof![
        1 => (frac.clone(), 1usize..40).prop_map(|(at, len)| Mutation::Delete { at, len }),
        1 => (frac.clone(), prop::sample::select(TOKENS)).prop_map(|(at, t)| Mutation::Insert {
            at,
            text: t.to_owned()
        }),
        1 => (frac.clone(), 1usize..200, frac.clone())
            .prop_map(|(at, len, to)| Mutation::Duplicate { at, len, to }),
        1 => (frac.clone(), frac.clone(), 1usize..30)
            .prop_map(|(a, b, len)| Mutation::Swap { a, b, len }),
        6 => (any::<usize>(), prop::sample::select(NUMBERS))
            .prop_map(|(which, with)| Mutation::Number { which, with }),
        1 => (frac, any::<u8>()).prop_map(|(at, byte)| Mutation::Byte { at, byte }),
    ]
}

pub fn index(at: f64, len: usize) -> usize {
    ((at * len as f64) as usize).min(len)
}

/// Byte ranges of the numeric literals in `text` (digits, `.`, exponents).
pub fn numbers(text: &[u8]) -> Vec<std::ops::Range<usize>> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < text.len() {
        let starts = text[i].is_ascii_digit()
            && (i == 0 || !(text[i - 1].is_ascii_alphanumeric() || text[i - 1] == b'_'));
        if !starts {
            i += 1;
            continue;
        }
        let start = i;
        while i < text.len()
            && (text[i].is_ascii_digit()
                || text[i] == b'.'
                || ((text[i] == b'e' || text[i] == b'E') && i > start))
        {
            i += 1;
        }
        out.push(start..i);
    }
    out
}

pub fn apply(text: &mut Vec<u8>, m: &Mutation) {
    let n = text.len();
    match m {
        Mutation::Delete { at, len } => {
            let s = index(*at, n);
            let e = (s + len).min(n);
            text.drain(s..e);
        }
        Mutation::Insert { at, text: t } => {
            let s = index(*at, n);
            text.splice(s..s, t.bytes());
        }
        Mutation::Duplicate { at, len, to } => {
            let s = index(*at, n);
            let e = (s + len).min(n);
            let piece = text[s..e].to_vec();
            let d = index(*to, n);
            text.splice(d..d, piece);
        }
        Mutation::Swap { a, b, len } => {
            let (mut a, mut b) = (index(*a, n), index(*b, n));
            if a > b {
                std::mem::swap(&mut a, &mut b);
            }
            let len = (*len).min(b - a).min(n - b);
            if len > 0 {
                let first = text[a..a + len].to_vec();
                let second = text[b..b + len].to_vec();
                text.splice(b..b + len, first);
                text.splice(a..a + len, second);
            }
        }
        Mutation::Number { which, with } => {
            let nums = numbers(text);
            if !nums.is_empty() {
                let r = nums[which % nums.len()].clone();
                text.splice(r, with.bytes());
            }
        }
        Mutation::Byte { at, byte } => {
            if n > 0 {
                let i = index(*at, n - 1);
                text[i] = *byte;
            }
        }
    }
}
