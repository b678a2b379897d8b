//! No input panics or overflows the stack; nesting has a limit.

use super::*;

#[test]
fn deep_but_allowed_nesting_parses_on_a_small_stack() {
    on_small_stack(|| {
        let n = MAX_DEPTH - 10;
        for (open, close) in [("(", ")"), ("[", "]"), ("f(", ")"), ("v[", "]")] {
            let src = format!("x = {}1{};", open.repeat(n), close.repeat(n));
            parse(&src);
        }
        // A comprehension level is two: the `for` and the expression in it.
        let src = format!(
            "x = {}1{};",
            "[for (i = a) ".repeat(n / 2),
            "]".repeat(n / 2)
        );
        parse(&src);
        parse(&format!("x = {}1;", "a ? b : ".repeat(n)));
        parse(&format!("{}cube();", "translate(v) ".repeat(n)));
        parse(&format!("{}cube();", "if (a) cube(); else ".repeat(n)));
        parse(&format!("{}{}", "{".repeat(n), "}".repeat(n)));
    });
}

#[test]
fn huge_nesting_fails_cleanly_on_a_small_stack() {
    on_small_stack(|| {
        for open in ["(", "[", "f(", "{"] {
            let src = format!("x = {}", open.repeat(100_000));
            assert_eq!(parse_err(&src).message, "nesting too deep", "{open:?}");
        }
        for chain in ["a ? b : ", "-", "let (a = 1) ", "[each "] {
            let src = format!("x = {}1;", chain.repeat(100_000));
            assert_eq!(parse_err(&src).message, "nesting too deep", "{chain:?}");
        }
        let statements = format!("{}cube();", "translate(v) ".repeat(100_000));
        assert_eq!(parse_err(&statements).message, "nesting too deep");
        let long_sum = format!("x = 1{};", " + 1".repeat(100_000));
        assert_eq!(parse_err(&long_sum).message, "nesting too deep");
    });
}

/// A small deterministic generator (xorshift), so failures reproduce.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// Parses `src`; on failure, checks the diagnostic points inside the text and renders.
fn parse_any(src: &str) {
    if let Err(err) = parse_program(0, src) {
        assert_eq!(err.code, SYNTAX_ERROR);
        let (span, _) = primary(&err);
        assert!(
            span.end as usize <= src.len() && span.start <= span.end,
            "{src:?}"
        );
        assert!(src.is_char_boundary(span.start as usize), "{src:?}");
        assert!(src.is_char_boundary(span.end as usize), "{src:?}");
        render(src, &err);
    }
}

#[test]
fn mismatched_brackets_are_syntax_errors() {
    let src = "x = (]".repeat(1000);
    let err = parse_err(&src);
    assert_eq!(err.message, "expected an expression");
    assert_eq!(primary(&err).0, Span::new(0, 5, 6));
}

#[test]
fn random_bytes_never_panic() {
    on_small_stack(|| {
        let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
        for _ in 0..300 {
            let len = rng.below(200);
            let bytes: Vec<u8> = (0..len).map(|_| rng.next() as u8).collect();
            parse_any(&String::from_utf8_lossy(&bytes));
        }
    });
}

#[test]
fn random_token_soup_never_panics() {
    const TOKENS: [&str; 48] = [
        "(",
        ")",
        "[",
        "]",
        "{",
        "}",
        ";",
        ",",
        ":",
        "?",
        "=",
        "==",
        "!",
        "!=",
        "<",
        ">",
        "<=",
        "+",
        "-",
        "*",
        "/",
        "%",
        "^",
        "&&",
        "||",
        "#",
        ".",
        "x",
        "$fn",
        "1",
        "1.5e3",
        "\"s\"",
        "for",
        "if",
        "else",
        "let",
        "each",
        "function",
        "module",
        "assert",
        "echo",
        "include <a>",
        "use",
        "true",
        "undef",
        "/* c */",
        "// c\n",
        " ",
    ];
    on_small_stack(|| {
        let mut rng = Rng(12345);
        for _ in 0..2000 {
            let len = rng.below(40);
            let src: String = (0..len)
                .map(|_| TOKENS[rng.below(TOKENS.len())])
                .collect::<Vec<_>>()
                .join(" ");
            parse_any(&src);
        }
    });
}

#[test]
fn every_truncation_of_a_model_is_handled() {
    let model = "// model\ninclude <lib.scad>\n$fn = 32;\nmodule leg(h = 10, r = [1, 2,]) {\n  \
                 translate([0, 0, -h]) #cylinder(h = h, r = r[0] ^ 2);\n}\n\
                 function f(x) = x < 0 ? -x : let (y = x * 2) [for (i = [0 : 2 : y]) if (i % 2 == 0) i else each [i]];\n\
                 for (i = [0 : 3]) if (i > 1) leg(i); else { %sphere(\"s\\n\"); }\n/* end */";
    parse(model);
    on_small_stack(move || {
        for end in (0..=model.len()).filter(|&e| model.is_char_boundary(e)) {
            parse_any(&model[..end]);
            parse_any(&model[end..]);
        }
    });
}
