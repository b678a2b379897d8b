//! Parser tests: every construct, precedence, spans, comments, every error kind, and
//! robustness (garbage, truncations, deep nesting on a 2 MiB thread).

use super::*;
use crate::front::ast::{
    Arg, Binding, Expr, ExprKind, Instance, InstanceKind, Param, Stmt, StmtKind, UnaryOp,
    VecElem,
};
use crate::front::diag::Diagnostic;
use crate::front::source::SourceMap;

// ---------------------------------------------------------------- helpers

fn parse(src: &str) -> Program {
    match parse_program(0, src) {
        Ok(program) => program,
        Err(err) => panic!("{src:?} should parse: {}", render(src, &err)),
    }
}

fn parse_err(src: &str) -> Box<Diagnostic> {
    match parse_program(0, src) {
        Ok(program) => panic!("{src:?} should not parse: {:?}", program.stmts),
        Err(err) => err,
    }
}

fn render(src: &str, err: &Diagnostic) -> String {
    let mut sources = SourceMap::new();
    sources.add("test.scad", src.to_string());
    err.render_plain(&sources)
}

/// The value assigned by `x = <src>;`.
fn expr(src: &str) -> Expr {
    let text = format!("x = {src};");
    match parse(&text).stmts.into_iter().next().map(|s| s.kind) {
        Some(StmtKind::Assign { value, .. }) => value,
        other => panic!("not an assignment: {other:?}"),
    }
}

/// The value of `x = <src>;` as an S-expression.
fn sx(src: &str) -> String {
    sexp(&expr(src))
}

fn sexp(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Number { text, .. } => text.clone(),
        ExprKind::Bool(b) => b.to_string(),
        ExprKind::Str(s) => format!("{s:?}"),
        ExprKind::Undef => "undef".into(),
        ExprKind::Ident(name) => name.clone(),
        ExprKind::Vector(elems) => format!("[{}]", list(elems.iter().map(elem_sexp))),
        ExprKind::Range { start, step, end } => match step {
            Some(step) => format!("[{} : {} : {}]", sexp(start), sexp(step), sexp(end)),
            None => format!("[{} : {}]", sexp(start), sexp(end)),
        },
        ExprKind::Unary(op, x) => format!("({op:?} {})", sexp(x)),
        ExprKind::Binary(op, a, b) => format!("({op:?} {} {})", sexp(a), sexp(b)),
        ExprKind::Ternary(c, a, b) => format!("(? {} {} {})", sexp(c), sexp(a), sexp(b)),
        ExprKind::Index(a, i) => format!("(index {} {})", sexp(a), sexp(i)),
        ExprKind::Member(a, m) => format!("(. {} {})", sexp(a), m.name),
        ExprKind::Call { callee, args } => format!("(call {} {})", sexp(callee), args_sexp(args)),
        ExprKind::Let { bindings, body } => {
            format!("(let {} {})", bindings_sexp(bindings), sexp(body))
        }
        ExprKind::Assert { args, body } => format!("(assert {}{})", args_sexp(args), opt(body)),
        ExprKind::Echo { args, body } => format!("(echo {}{})", args_sexp(args), opt(body)),
        ExprKind::FunctionLiteral { params, body } => {
            format!("(fn {} {})", params_sexp(params), sexp(body))
        }
    }
}

fn elem_sexp(e: &VecElem) -> String {
    match e {
        VecElem::Expr(e) => sexp(e),
        VecElem::For { bindings, body, .. } => {
            format!("(for {} {})", bindings_sexp(bindings), elem_sexp(body))
        }
        VecElem::ForC {
            init,
            cond,
            update,
            body,
            ..
        } => format!(
            "(forc {} {} {} {})",
            bindings_sexp(init),
            sexp(cond),
            bindings_sexp(update),
            elem_sexp(body)
        ),
        VecElem::If {
            cond,
            then,
            otherwise,
            ..
        } => match otherwise {
            Some(o) => format!("(if {} {} {})", sexp(cond), elem_sexp(then), elem_sexp(o)),
            None => format!("(if {} {})", sexp(cond), elem_sexp(then)),
        },
        VecElem::Let { bindings, body, .. } => {
            format!("(lclet {} {})", bindings_sexp(bindings), elem_sexp(body))
        }
        VecElem::Each(body, _) => format!("(each {})", elem_sexp(body)),
    }
}

fn list(items: impl Iterator<Item = String>) -> String {
    items.collect::<Vec<_>>().join(" ")
}

fn opt(body: &Option<Box<Expr>>) -> String {
    body.as_ref().map_or(String::new(), |b| format!(" {}", sexp(b)))
}

fn args_sexp(args: &[Arg]) -> String {
    let items = args.iter().map(|a| match &a.name {
        Some(name) => format!("{}={}", name.name, sexp(&a.value)),
        None => sexp(&a.value),
    });
    format!("({})", list(items))
}

fn bindings_sexp(bindings: &[Binding]) -> String {
    let items = bindings.iter().map(|b| format!("{}={}", b.name.name, sexp(&b.value)));
    format!("({})", list(items))
}

fn params_sexp(params: &[Param]) -> String {
    let items = params.iter().map(|p| match &p.default {
        Some(d) => format!("{}={}", p.name.name, sexp(d)),
        None => p.name.name.clone(),
    });
    format!("({})", list(items))
}

/// A statement tree in one line: `call name (args) {children}` and so on.
fn stmt_sexp(s: &Stmt) -> String {
    match &s.kind {
        StmtKind::Empty => ";".into(),
        StmtKind::Block(stmts) => format!("{{{}}}", stmts_sexp(stmts)),
        StmtKind::Assign { name, value } => format!("{} = {}", name.name, sexp(value)),
        StmtKind::ModuleDef { name, params, body } => {
            format!("module {} {} {{{}}}", name.name, params_sexp(params), stmts_sexp(body))
        }
        StmtKind::FunctionDef { name, params, body } => {
            format!("function {} {} {}", name.name, params_sexp(params), sexp(body))
        }
        StmtKind::Include { path, use_, .. } => {
            format!("{} <{path}>", if *use_ { "use" } else { "include" })
        }
        StmtKind::Instance(Instance { modifiers, kind }) => {
            let mut out = String::new();
            for (on, c) in [
                (modifiers.root, '!'),
                (modifiers.highlight, '#'),
                (modifiers.background, '%'),
                (modifiers.disable, '*'),
            ] {
                if on {
                    out.push(c);
                }
            }
            out + &instance_sexp(kind)
        }
    }
}

fn instance_sexp(kind: &InstanceKind) -> String {
    match kind {
        InstanceKind::Call {
            name,
            args,
            children,
        } => format!("{}{} {{{}}}", name.name, args_sexp(args), stmts_sexp(children)),
        InstanceKind::If {
            cond,
            then,
            otherwise,
        } => match otherwise {
            Some(o) => format!(
                "if {} {{{}}} else {{{}}}",
                sexp(cond),
                stmts_sexp(then),
                stmts_sexp(o)
            ),
            None => format!("if {} {{{}}}", sexp(cond), stmts_sexp(then)),
        },
        InstanceKind::For { bindings, body } => {
            format!("for {} {{{}}}", bindings_sexp(bindings), stmts_sexp(body))
        }
        InstanceKind::IntersectionFor { bindings, body } => {
            format!("intersection_for {} {{{}}}", bindings_sexp(bindings), stmts_sexp(body))
        }
        InstanceKind::Let { bindings, body } => {
            format!("let {} {{{}}}", bindings_sexp(bindings), stmts_sexp(body))
        }
    }
}

fn stmts_sexp(stmts: &[Stmt]) -> String {
    list(stmts.iter().map(stmt_sexp))
}

fn program_sexp(src: &str) -> String {
    stmts_sexp(&parse(src).stmts)
}

fn snippet<'s>(src: &'s str, span: Span) -> &'s str {
    &src[span.range()]
}

/// Runs `f` on a thread with a 2 MiB stack, the default for spawned threads.
fn on_small_stack(f: impl FnOnce() + Send + 'static) {
    let handle = std::thread::Builder::new()
        .stack_size(2 << 20)
        .spawn(f)
        .expect("spawn test thread");
    handle.join().expect("the test thread panicked");
}

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
    assert_eq!(sx("$fn + $fa + $fs + $t + $children"), "(Add (Add (Add (Add $fn $fa) $fs) $t) $children)");
    // A word longer than any number reading of it is a name.
    assert_eq!(sx("2d + 1e5x + _a1 + intersection_for"), "(Add (Add (Add 2d 1e5x) _a1) intersection_for)");
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
    assert_eq!(sx("[for (i = [0 : 3]) i * 2]"), "[(for (i=[0 : 3]) (Mul i 2))]");
    assert_eq!(sx("[for (i = a, j = b) [i, j]]"), "[(for (i=a j=b) [i j])]");
    assert_eq!(sx("[for (i = 0; i < n; i = i + 1) i]"), "[(forc (i=0) (Lt i n) (i=(Add i 1)) i)]");
    assert_eq!(sx("[for (i = a) if (i > 0) i]"), "[(for (i=a) (if (Gt i 0) i))]");
    assert_eq!(sx("[for (i = a) if (i) 1 else 2]"), "[(for (i=a) (if i 1 2))]");
    assert_eq!(sx("[for (i = a) let (s = i * i) s]"), "[(for (i=a) (let (s=(Mul i i)) s))]");
    assert_eq!(sx("[each a, 6]"), "[(each a) 6]");
    assert_eq!(sx("[for (a = x) for (b = y) a + b]"), "[(for (a=x) (for (b=y) (Add a b)))]");
    assert_eq!(sx("[let (a = 1) for (i = a) i]"), "[(lclet (a=1) (for (i=a) i))]");
    assert_eq!(sx("[let (a = 1) a]"), "[(let (a=1) a)]");
    assert_eq!(sx("[each for (i = a) i]"), "[(each (for (i=a) i))]");
    assert_eq!(sx("[1, (for (i = a) i), ((if (c) 2))]"), "[1 (for (i=a) i) (if c 2)]");
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
    assert_eq!(sx("(function (y) y / 2)(8)"), "(call (fn (y) (Div y 2)) (8))");
    assert_eq!(sx("let (a = 1, b = a) a + b"), "(let (a=1 b=a) (Add a b))");
    assert_eq!(sx("assert(x > 0, \"msg\") x"), "(assert ((Gt x 0) \"msg\") x)");
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
        ("a ? let (x = 1) x : function (y) y", "(? a (let (x=1) x) (fn (y) y))"),
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
        ("module m(a, b = 2,) { cube(a); }", "module m (a b=2) {cube(a) {}}"),
        ("module m() cube();", "module m () {cube() {}}"),
        ("module m();", "module m () {}"),
        ("module outer() { module inner() ; function f() = 1; }", "module outer () {module inner () {} function f () 1}"),
        ("function f(x, y = 1) = x + y;", "function f (x y=1) (Add x y)"),
        ("cube(10);", "cube(10) {}"),
        ("translate([1, 2, 3]) cube();", "translate([1 2 3]) {cube() {}}"),
        ("union() { cube(); sphere(r = 2); }", "union() {cube() {} sphere(r=2) {}}"),
        ("union() { x = 1; { cube(x); } ; }", "union() {x = 1 {cube(x) {}} ;}"),
        ("a() b() c();", "a() {b() {c() {}}}"),
        ("echo(\"s\", v = 1);", "echo(\"s\" v=1) {}"),
        ("assert(true);", "assert(true) {}"),
        ("each(1);", "each(1) {}"),
        ("for (i = [0 : 2], j = a) cube(i);", "for (i=[0 : 2] j=a) {cube(i) {}}"),
        ("intersection_for (i = a) sphere(i);", "intersection_for (i=a) {sphere(i) {}}"),
        ("let (a = 1, b = 2) cube(a + b);", "let (a=1 b=2) {cube((Add a b)) {}}"),
        ("if (a) cube();", "if a {cube() {}}"),
        ("if (a) cube(); else sphere();", "if a {cube() {}} else {sphere() {}}"),
        ("if (a) { } else { x = 1; }", "if a {} else {x = 1}"),
        ("if (a) if (b) x(); else y();", "if a {if b {x() {}} else {y() {}}}"),
        ("if (a) x(); else if (b) y(); else z();", "if a {x() {}} else {if b {y() {}} else {z() {}}}"),
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
    assert_eq!(program_sexp(src), "include <lib/shapes.scad> use <a//b /*c*/.scad> x = 1");
    let StmtKind::Include { path_span, .. } = &program.stmts[1].kind else {
        panic!("not an include");
    };
    assert_eq!(snippet(src, *path_span), "a//b /*c*/.scad");
    assert_eq!(snippet(src, program.stmts[0].span), "include <lib/shapes.scad>");
    assert!(program.comments.is_empty(), "{:?}", program.comments);
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
    assert_eq!(snippet(src, program.stmts[0].span), "!#translate([1, 0, 0]) /* c */ cube(1) ;");
    assert_eq!(snippet(src, program.stmts[1].span), "x = a ? b : c /* d */ ;");
    let StmtKind::Assign { name, value } = &program.stmts[1].kind else {
        panic!()
    };
    assert_eq!(snippet(src, name.span), "x");
    assert_eq!(snippet(src, value.span), "a ? b : c");
    let StmtKind::Instance(Instance {
        kind: InstanceKind::Call {
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

// ---------------------------------------------------------------- errors

fn primary(err: &Diagnostic) -> (Span, &str) {
    let (span, label) = err.primary.as_ref().expect("a primary label");
    (*span, label.as_str())
}

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
    assert_eq!(parse_err("function f(x) = x").message, "expected `;` after function definition");
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
    assert_eq!(err.notes, ["`for` is a keyword and cannot be used as a name"]);
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
fn comprehension_outside_a_vector() {
    let src = "x = (for (i = a) i);";
    let err = parse_err(src);
    assert_eq!(err.message, "list comprehension `for` outside of a vector");
    assert_eq!(snippet(src, primary(&err).0), "for");
    assert_eq!(parse_err("x = let (a = 1) each a;").message, "list comprehension `each` outside of a vector");
}

#[test]
fn loops_need_named_bindings() {
    let src = "for ([1, 2]) cube();";
    let err = parse_err(src);
    assert_eq!(err.message, "`for` takes `name = value` bindings");
    assert_eq!(snippet(src, primary(&err).0), "[1, 2]");
    assert_eq!(parse_err("let (1) cube();").message, "`let` takes `name = value` bindings");
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
        // Unclosed, the brackets are refused before anything else.
        if close.is_empty() {
            continue;
        }
        let unclosed = format!("{head}{}", open.repeat(100_000));
        assert_eq!(parse_err(&unclosed).message, "nesting too deep", "{open:?}");
    }
}

#[test]
fn deep_but_allowed_nesting_parses_on_a_small_stack() {
    on_small_stack(|| {
        let n = MAX_DEPTH - 10;
        for (open, close) in [("(", ")"), ("[", "]"), ("f(", ")"), ("v[", "]")] {
            let src = format!("x = {}1{};", open.repeat(n), close.repeat(n));
            parse(&src);
        }
        // A comprehension level is two: the `for` and the expression in it.
        let src = format!("x = {}1{};", "[for (i = a) ".repeat(n / 2), "]".repeat(n / 2));
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

// ---------------------------------------------------------------- robustness

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
        assert!(span.end as usize <= src.len() && span.start <= span.end, "{src:?}");
        assert!(src.is_char_boundary(span.start as usize), "{src:?}");
        assert!(src.is_char_boundary(span.end as usize), "{src:?}");
        render(src, &err);
    }
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
        "(", ")", "[", "]", "{", "}", ";", ",", ":", "?", "=", "==", "!", "!=", "<", ">",
        "<=", "+", "-", "*", "/", "%", "^", "&&", "||", "#", ".", "x", "$fn", "1", "1.5e3",
        "\"s\"", "for", "if", "else", "let", "each", "function", "module", "assert", "echo",
        "include <a>", "use", "true", "undef", "/* c */", "// c\n", " ",
    ];
    on_small_stack(|| {
        let mut rng = Rng(12345);
        for _ in 0..2000 {
            let len = rng.below(40);
            let src: String = (0..len).map(|_| TOKENS[rng.below(TOKENS.len())]).collect::<Vec<_>>().join(" ");
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
