//! What parses, and into what: literals, expressions, statements, spans, comments.

use super::*;

// ---------------------------------------------------------------- literals and names

#[test]
fn numbers_keep_their_text_and_value() {
    for (text, value) in [
        ("1", 1.0),
        ("1.5", 1.5),
        (".5", 0.5),
        ("1e3", 1000.0),
        ("1.5E-2", 0.015),
        ("3.", 3.0),
        ("0.125e+2", 12.5),
        ("1.e2", 100.0),
        ("007", 7.0),
    ] {
        match expr(text).kind {
            ExprKind::Number { value: v, text: t } => {
                assert_eq!((t.as_str(), v), (text, value));
            }
            other => panic!("{text}: {other:?}"),
        }
    }
}

#[test]
fn identifiers_follow_openscad_lexing() {
    assert_eq!(
        sx("$fn + $fa + $fs + $t + $children"),
        "(Add (Add (Add (Add $fn $fa) $fs) $t) $children)"
    );
    // A word longer than any number reading of it is a name.
    assert_eq!(
        sx("2d + 1e5x + _a1 + intersection_for"),
        "(Add (Add (Add 2d 1e5x) _a1) intersection_for)"
    );
    assert_eq!(sx("1e5"), "1e5");
    assert_eq!(sx("[use, include]"), "[use include]");
    assert_eq!(sx("true_ + undefined"), "(Add true_ undefined)");
}

#[test]
fn constants() {
    assert_eq!(sx("[true, false, undef]"), "[true false undef]");
}

#[test]
fn strings_decode_escapes() {
    let cases = [
        (r#""plain""#, "plain"),
        (r#""a\nb\tc\rd""#, "a\nb\tc\rd"),
        (r#""q\"uote\\slash""#, "q\"uote\\slash"),
        (r#""\x41\x7f""#, "A\x7f"),
        (r#""\x00""#, " "),
        (r#""\u00e9\U01F600""#, "é😀"),
        (r#""\u{41}\u{1F600}""#, "A😀"),
        (r#""\u{D800}""#, " "),
        (r#""\q\x8""#, "qx8"),
        ("\"two\nlines\"", "twolines"),
        (r#""// not /* a comment""#, "// not /* a comment"),
        (r#""ünïcödé""#, "ünïcödé"),
    ];
    for (src, value) in cases {
        assert_eq!(expr(src).kind, ExprKind::Str(value.into()), "{src}");
    }
}

// ---------------------------------------------------------------- expressions

#[test]
fn vectors_and_ranges() {
    assert_eq!(sx("[]"), "[]");
    assert_eq!(sx("[,]"), "[]");
    assert_eq!(sx("[1, 2, 3]"), "[1 2 3]");
    assert_eq!(sx("[1, 2,]"), "[1 2]");
    assert_eq!(sx("[1,, 2]"), "[1 2]");
    assert_eq!(sx("[[1], [2, [3]]]"), "[[1] [2 [3]]]");
    assert_eq!(sx("[0 : 5]"), "[0 : 5]");
    assert_eq!(sx("[0 : 0.5 : 5]"), "[0 : 0.5 : 5]");
    assert_eq!(sx("[a + 1 : -b]"), "[(Add a 1) : (Neg b)]");
}

#[test]
fn list_comprehensions() {
    assert_eq!(
        sx("[for (i = [0 : 3]) i * 2]"),
        "[(for (i=[0 : 3]) (Mul i 2))]"
    );
    assert_eq!(sx("[for (i = a, j = b) [i, j]]"), "[(for (i=a j=b) [i j])]");
    assert_eq!(
        sx("[for (i = 0; i < n; i = i + 1) i]"),
        "[(forc (i=0) (Lt i n) (i=(Add i 1)) i)]"
    );
    assert_eq!(
        sx("[for (i = a) if (i > 0) i]"),
        "[(for (i=a) (if (Gt i 0) i))]"
    );
    assert_eq!(
        sx("[for (i = a) if (i) 1 else 2]"),
        "[(for (i=a) (if i 1 2))]"
    );
    assert_eq!(
        sx("[for (i = a) let (s = i * i) s]"),
        "[(for (i=a) (let (s=(Mul i i)) s))]"
    );
    assert_eq!(sx("[each a, 6]"), "[(each a) 6]");
    assert_eq!(
        sx("[for (a = x) for (b = y) a + b]"),
        "[(for (a=x) (for (b=y) (Add a b)))]"
    );
    assert_eq!(
        sx("[let (a = 1) for (i = a) i]"),
        "[(lclet (a=1) (for (i=a) i))]"
    );
    assert_eq!(sx("[let (a = 1) a]"), "[(let (a=1) a)]");
    assert_eq!(sx("[each for (i = a) i]"), "[(each (for (i=a) i))]");
    assert_eq!(
        sx("[1, (for (i = a) i), ((if (c) 2))]"),
        "[1 (for (i=a) i) (if c 2)]"
    );
    assert_eq!(sx("[if (a) if (b) 1 else 2]"), "[(if a (if b 1 2))]");
    assert_eq!(sx("[for (i = a) (i)]"), "[(for (i=a) i)]");
}

#[test]
fn postfix_calls_and_literals() {
    assert_eq!(sx("v[0]"), "(index v 0)");
    assert_eq!(sx("p.x + p.y * p.z"), "(Add (. p x) (Mul (. p y) (. p z)))");
    assert_eq!(sx("f(1, b = 2)"), "(call f (1 b=2))");
    assert_eq!(sx("f(a == b)"), "(call f ((Eq a b)))");
    assert_eq!(sx("f()(2)[3].y"), "(. (index (call (call f ()) (2)) 3) y)");
    assert_eq!(sx("[1, 2][0]"), "(index [1 2] 0)");
    assert_eq!(sx("function (x) x * 2"), "(fn (x) (Mul x 2))");
    assert_eq!(sx("function (a, b = 1,) a"), "(fn (a b=1) a)");
    assert_eq!(
        sx("(function (y) y / 2)(8)"),
        "(call (fn (y) (Div y 2)) (8))"
    );
    assert_eq!(sx("let (a = 1, b = a) a + b"), "(let (a=1 b=a) (Add a b))");
    assert_eq!(
        sx("assert(x > 0, \"msg\") x"),
        "(assert ((Gt x 0) \"msg\") x)"
    );
    assert_eq!(sx("echo(\"h\", v = 1) 5"), "(echo (\"h\" v=1) 5)");
    assert_eq!(sx("[assert(a), echo(b)]"), "[(assert (a)) (echo (b))]");
}

#[test]
fn precedence_and_associativity() {
    let cases = [
        ("1 + 2 * 3", "(Add 1 (Mul 2 3))"),
        ("(1 + 2) * 3", "(Mul (Add 1 2) 3)"),
        ("1 - 2 - 3", "(Sub (Sub 1 2) 3)"),
        ("8 / 4 % 3 * 2", "(Mul (Mod (Div 8 4) 3) 2)"),
        ("-2 ^ 2", "(Neg (Pow 2 2))"),
        ("2 ^ 3 ^ 2", "(Pow 2 (Pow 3 2))"),
        ("2 ^ -1", "(Pow 2 (Neg 1))"),
        ("2 ^ -1 ^ 2", "(Pow 2 (Neg (Pow 1 2)))"),
        ("a * -b", "(Mul a (Neg b))"),
        ("2 * 3 ^ 2", "(Mul 2 (Pow 3 2))"),
        ("-a[0]", "(Neg (index a 0))"),
        ("- - +x", "(Neg (Neg (Plus x)))"),
        ("!a && b", "(And (Not a) b)"),
        ("a || b && c", "(Or a (And b c))"),
        ("a == b < c", "(Eq a (Lt b c))"),
        ("a < b <= c > d >= e", "(Ge (Gt (Le (Lt a b) c) d) e)"),
        ("a != b == c", "(Eq (Ne a b) c)"),
        ("a + b < c * d", "(Lt (Add a b) (Mul c d))"),
        ("a ? b : c ? d : e", "(? a b (? c d e))"),
        ("a ? b ? c : d : e", "(? a (? b c d) e)"),
        ("a || b ? c + 1 : d", "(? (Or a b) (Add c 1) d)"),
        (
            "a ? let (x = 1) x : function (y) y",
            "(? a (let (x=1) x) (fn (y) y))",
        ),
        ("let (a = 1) a ? b : c", "(let (a=1) (? a b c))"),
        ("echo(1) a + b", "(echo (1) (Add a b))"),
    ];
    for (src, want) in cases {
        assert_eq!(sx(src), want, "{src}");
    }
    assert!(matches!(expr("-x").kind, ExprKind::Unary(UnaryOp::Neg, _)));
}

// ---------------------------------------------------------------- statements

#[test]
fn statements() {
    let cases = [
        (";", ";"),
        ("{ a = 1; { } }", "{a = 1 {}}"),
        ("$fn = 32;", "$fn = 32"),
        (
            "module m(a, b = 2,) { cube(a); }",
            "module m (a b=2) {cube(a) {}}",
        ),
        ("module m() cube();", "module m () {cube() {}}"),
        ("module m();", "module m () {}"),
        (
            "module outer() { module inner() ; function f() = 1; }",
            "module outer () {module inner () {} function f () 1}",
        ),
        (
            "function f(x, y = 1) = x + y;",
            "function f (x y=1) (Add x y)",
        ),
        ("cube(10);", "cube(10) {}"),
        (
            "translate([1, 2, 3]) cube();",
            "translate([1 2 3]) {cube() {}}",
        ),
        (
            "union() { cube(); sphere(r = 2); }",
            "union() {cube() {} sphere(r=2) {}}",
        ),
        (
            "union() { x = 1; { cube(x); } ; }",
            "union() {x = 1 {cube(x) {}} ;}",
        ),
        ("a() b() c();", "a() {b() {c() {}}}"),
        ("echo(\"s\", v = 1);", "echo(\"s\" v=1) {}"),
        ("assert(true);", "assert(true) {}"),
        ("each(1);", "each(1) {}"),
        (
            "for (i = [0 : 2], j = a) cube(i);",
            "for (i=[0 : 2] j=a) {cube(i) {}}",
        ),
        (
            "intersection_for (i = a) sphere(i);",
            "intersection_for (i=a) {sphere(i) {}}",
        ),
        (
            "let (a = 1, b = 2) cube(a + b);",
            "let (a=1 b=2) {cube((Add a b)) {}}",
        ),
        ("if (a) cube();", "if a {cube() {}}"),
        (
            "if (a) cube(); else sphere();",
            "if a {cube() {}} else {sphere() {}}",
        ),
        ("if (a) { } else { x = 1; }", "if a {} else {x = 1}"),
        (
            "if (a) if (b) x(); else y();",
            "if a {if b {x() {}} else {y() {}}}",
        ),
        (
            "if (a) x(); else if (b) y(); else z();",
            "if a {x() {}} else {if b {y() {}} else {z() {}}}",
        ),
        ("!#%*cube();", "!#%*cube() {}"),
        ("* * cube();", "*cube() {}"),
        ("%if (a) cube();", "%if a {cube() {}}"),
        ("# for (i = a) cube();", "#for (i=a) {cube() {}}"),
        ("translate(v) !cube();", "translate(v) {!cube() {}}"),
        ("use = 1; include = use;", "use = 1 include = use"),
        ("f(,a,,b = 1,);", "f(a b=1) {}"),
    ];
    for (src, want) in cases {
        assert_eq!(program_sexp(src), want, "{src}");
    }
}

#[test]
fn includes_keep_their_path() {
    let src = "include <lib/shapes.scad>\nuse<a//b /*c*/.scad> x = 1;";
    let program = parse(src);
    assert_eq!(
        program_sexp(src),
        "include <lib/shapes.scad> use <a//b /*c*/.scad> x = 1"
    );
    let StmtKind::Include { path_span, .. } = &program.stmts[1].kind else {
        panic!("not an include");
    };
    assert_eq!(snippet(src, *path_span), "a//b /*c*/.scad");
    assert_eq!(
        snippet(src, program.stmts[0].span),
        "include <lib/shapes.scad>"
    );
    assert!(program.comments.is_empty(), "{:?}", program.comments);
    // Wherever a statement may be; elsewhere `include` and `use` are names.
    let src = "module m() include <x//y.scad>\nx = use < 3; // c\nif (a) { use <z> }";
    assert_eq!(
        program_sexp(src),
        "module m () {include <x//y.scad>} x = (Lt use 3) if a {use <z>}"
    );
    assert_eq!(parse(src).comments.len(), 1);
}

// ---------------------------------------------------------------- spans

#[test]
fn number_spans_are_exactly_the_literal() {
    let src = "x = -5 + (1.5e3) * [.25, 7.];";
    let program = parse(src);
    let mut numbers = Vec::new();
    collect_numbers(&program.stmts, &mut numbers);
    let texts: Vec<&str> = numbers.iter().map(|s| snippet(src, *s)).collect();
    assert_eq!(texts, ["5", "1.5e3", ".25", "7."]);
    let StmtKind::Assign { value, .. } = &program.stmts[0].kind else {
        panic!()
    };
    let ExprKind::Binary(_, neg, product) = &value.kind else {
        panic!()
    };
    assert_eq!(snippet(src, neg.span), "-5");
    assert_eq!(snippet(src, product.span), "(1.5e3) * [.25, 7.]");
    assert_eq!(snippet(src, value.span), "-5 + (1.5e3) * [.25, 7.]");
}

fn collect_numbers(stmts: &[Stmt], out: &mut Vec<Span>) {
    fn walk(e: &Expr, out: &mut Vec<Span>) {
        match &e.kind {
            ExprKind::Number { .. } => out.push(e.span),
            ExprKind::Unary(_, x) => walk(x, out),
            ExprKind::Binary(_, a, b) => {
                walk(a, out);
                walk(b, out);
            }
            ExprKind::Vector(elems) => {
                for el in elems {
                    if let VecElem::Expr(e) = el {
                        walk(e, out);
                    }
                }
            }
            _ => {}
        }
    }
    for stmt in stmts {
        if let StmtKind::Assign { value, .. } = &stmt.kind {
            walk(value, out);
        }
    }
}

#[test]
fn statement_spans_cover_modifiers_and_children_but_not_trailing_comments() {
    let src = "  !#translate([1, 0, 0]) /* c */ cube(1) ; // tail\nx = a ? b : c /* d */ ;\n";
    let program = parse(src);
    assert_eq!(
        snippet(src, program.stmts[0].span),
        "!#translate([1, 0, 0]) /* c */ cube(1) ;"
    );
    assert_eq!(
        snippet(src, program.stmts[1].span),
        "x = a ? b : c /* d */ ;"
    );
    let StmtKind::Assign { name, value } = &program.stmts[1].kind else {
        panic!()
    };
    assert_eq!(snippet(src, name.span), "x");
    assert_eq!(snippet(src, value.span), "a ? b : c");
    let StmtKind::Instance(Instance {
        kind:
            InstanceKind::Call {
                name,
                args,
                children,
            },
        ..
    }) = &program.stmts[0].kind
    else {
        panic!()
    };
    assert_eq!(snippet(src, name.span), "translate");
    assert_eq!(snippet(src, args[0].span), "[1, 0, 0]");
    assert_eq!(snippet(src, children[0].span), "cube(1) ;");
}

#[test]
fn argument_and_expression_spans() {
    let src = "f(a = 1 + 2 /* c */, b);\ny = f(1)[2].z;\nz = assert(c) /* no body */ ;";
    let program = parse(src);
    let StmtKind::Instance(Instance {
        kind: InstanceKind::Call { args, .. },
        ..
    }) = &program.stmts[0].kind
    else {
        panic!()
    };
    assert_eq!(snippet(src, args[0].span), "a = 1 + 2");
    assert_eq!(snippet(src, args[0].value.span), "1 + 2");
    assert_eq!(snippet(src, args[1].span), "b");
    for (stmt, want) in [(1, "f(1)[2].z"), (2, "assert(c)")] {
        let StmtKind::Assign { value, .. } = &program.stmts[stmt].kind else {
            panic!()
        };
        assert_eq!(snippet(src, value.span), want);
    }
}

#[test]
fn spans_use_the_file_id() {
    let program = parse_program(7, "x = 1;").expect("parses");
    assert_eq!(program.stmts[0].span, Span::new(7, 0, 6));
}

// ---------------------------------------------------------------- comments

#[test]
fn comments_are_collected_in_order() {
    let src = "// first \n/* block\n  two */ x = /* in */ 1; // tail\r\ns = \"// no\"; /**/ //";
    let program = parse(src);
    let got: Vec<(&str, &str, bool)> = program
        .comments
        .iter()
        .map(|c| (c.text.as_str(), snippet(src, c.span), c.block))
        .collect();
    assert_eq!(
        got,
        [
            ("first", "// first", false),
            ("block\n  two", "/* block\n  two */", true),
            ("in", "/* in */", true),
            ("tail", "// tail", false),
            ("", "/**/", true),
            ("", "//", false),
        ]
    );
}

#[test]
fn comments_fit_anywhere_blanks_do() {
    let src = "/*a*/translate/*b*/(/*c*/[1/*d*/,2]/*e*/)/*f*/cube//g\n(/*h*/)/*i*/;/*j*/";
    assert_eq!(program_sexp(src), "translate([1 2]) {cube() {}}");
    assert_eq!(parse(src).comments.len(), 10);
}

#[test]
fn model_files_parse() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut seen = 0;
    for dir in ["examples", "tests/models", "tests/models/lib"] {
        let Ok(entries) = std::fs::read_dir(root.join(dir)) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.extension().is_some_and(|e| e == "scad") {
                let text = std::fs::read_to_string(&path).expect("readable model");
                if let Err(err) = parse_program(0, &text) {
                    panic!("{}: {}", path.display(), render(&text, &err));
                }
                seen += 1;
            }
        }
    }
    assert!(seen > 0, "no model files found");
}
