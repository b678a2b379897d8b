//! Every kind of syntax error, its message, labels and notes.

use super::*;

#[test]
fn missing_semicolon_after_assignment() {
    let src = "x = 1\ny = 2;";
    let err = parse_err(src);
    assert_eq!(err.code, SYNTAX_ERROR);
    assert_eq!(err.message, "expected `;` after assignment");
    let (span, label) = primary(&err);
    assert_eq!((snippet(src, span), label), ("y", "unexpected `y`"));
    assert_eq!(err.secondary.len(), 1);
    assert_eq!(snippet(src, err.secondary[0].0), "1");
    assert_eq!(
        parse_err("function f(x) = x").message,
        "expected `;` after function definition"
    );
}

#[test]
fn error_at_end_of_file_is_empty_and_labels_the_open_brace() {
    let src = "module m() {\n  cube();\n";
    let err = parse_err(src);
    assert!(err.message.starts_with("expected "), "{}", err.message);
    assert!(err.message.contains("`}`"), "{}", err.message);
    let (span, label) = primary(&err);
    assert_eq!(span, Span::new(0, src.len(), src.len()));
    assert_eq!(label, "unexpected end of file");
    assert_eq!(err.secondary[0].0, Span::new(0, 11, 12));
    assert_eq!(err.secondary[0].1, "this `{` is still open");
    render(src, &err);
}

#[test]
fn expected_tokens_are_named() {
    let cases = [
        ("cube(1;", "expected `,` or `)`"),
        ("x = [1, 2;", "expected `,` or `]`"),
        ("x = 1 + ;", "expected an expression"),
        ("x = ;", "expected an expression"),
        ("x = a ? b;", "expected `:`"),
        ("cube(1)", "expected `;`, `{` or a statement"),
        ("if (a)", "expected `;`, `{` or a statement"),
        ("module m( { }", "expected `,`, `)` or a name"),
        ("x = 1; }", "unmatched `}`"),
        ("x = [for (i = a)];", "expected an expression"),
        ("module = 3;", "expected a name"),
        ("x", "expected `=` or `(`"),
        ("@", "expected a statement"),
    ];
    for (src, message) in cases {
        let err = parse_err(src);
        assert_eq!(err.message, message, "{src}");
        assert_eq!(err.code, SYNTAX_ERROR);
        render(src, &err);
    }
}

#[test]
fn notes_for_likely_mistakes() {
    let err = parse_err("if (a = 1) cube();");
    assert_eq!(err.notes, ["to compare two values, use `==`"]);
    let err = parse_err("function for(x) = 1;");
    assert_eq!(
        err.notes,
        ["`for` is a keyword and cannot be used as a name"]
    );
    let src = "translate([1, 2) cube();";
    let err = parse_err(src);
    assert_eq!(snippet(src, err.secondary[0].0), "[");
}

#[test]
fn unterminated_string() {
    let src = "x = \"abc\\\";\ncube();";
    let err = parse_err(src);
    assert_eq!(err.message, "unterminated string");
    assert_eq!(primary(&err).0, Span::new(0, 4, 5));
}

#[test]
fn unterminated_block_comment() {
    let src = "x = 1; /* never /* closed";
    let err = parse_err(src);
    assert_eq!(err.message, "unterminated block comment");
    assert_eq!(snippet(src, primary(&err).0), "/*");
}

#[test]
fn unterminated_include_path() {
    let src = "include <lib/a.scad\ncube();";
    let err = parse_err(src);
    assert_eq!(err.message, "unterminated `include` path");
    assert_eq!(primary(&err).0, Span::new(0, 8, 9));
    assert_eq!(parse_err("use <x").message, "unterminated `use` path");
}

#[test]
fn comprehension_outside_a_vector() {
    let src = "x = (for (i = a) i);";
    let err = parse_err(src);
    assert_eq!(err.message, "list comprehension `for` outside of a vector");
    assert_eq!(snippet(src, primary(&err).0), "for");
    assert_eq!(
        parse_err("x = let (a = 1) each a;").message,
        "list comprehension `each` outside of a vector"
    );
}

#[test]
fn loops_need_named_bindings() {
    let src = "for ([1, 2]) cube();";
    let err = parse_err(src);
    assert_eq!(err.message, "`for` takes `name = value` bindings");
    assert_eq!(snippet(src, primary(&err).0), "[1, 2]");
    assert_eq!(
        parse_err("let (1) cube();").message,
        "`let` takes `name = value` bindings"
    );
}

#[test]
fn nesting_too_deep() {
    let n = MAX_DEPTH + 10;
    let cases = [
        ("x = ", "(", "1", ")", ";"),
        ("x = ", "[", "1", "]", ";"),
        ("x = ", "f(", "1", ")", ";"),
        ("x = ", "a ? b : ", "1", "", ";"),
        ("x = ", "-", "1", "", ";"),
        ("x = ", "1 + ", "1", "", ";"),
        ("x = ", "let (a = 1) ", "1", "", ";"),
        ("x = ", "v", "", "[0]", ";"),
        ("", "{", "", "}", ""),
        ("", "cube() ", ";", "", ""),
        ("", "if (a) cube(); else ", ";", "", ""),
    ];
    for (head, open, middle, close, tail) in cases {
        let src = format!("{head}{}{middle}{}{tail}", open.repeat(n), close.repeat(n));
        let err = parse_err(&src);
        assert_eq!(err.message, "nesting too deep", "{open:?}");
        render(&src, &err);
        // Unclosed, brackets are refused before anything else.
        if !open.ends_with(['(', '[', '{']) {
            continue;
        }
        let unclosed = format!("{head}{}", open.repeat(100_000));
        assert_eq!(parse_err(&unclosed).message, "nesting too deep", "{open:?}");
    }
}
