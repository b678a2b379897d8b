//! The token stream: tokens as the grammar reads them, and no failure on any text.

use crate::front::parse::{TokenKind, tokens};

/// `(kind, text)` of every token, numbers as `N`.
fn lex(text: &str) -> Vec<(char, &str)> {
    tokens(text)
        .iter()
        .map(|t| {
            let kind = match t.kind {
                TokenKind::Number(_) => 'N',
                TokenKind::Word => 'W',
                TokenKind::Str => 'S',
                TokenKind::Path => 'P',
                TokenKind::Punct => '.',
            };
            (kind, t.text(text))
        })
        .collect()
}

#[test]
fn numbers_names_and_operators_are_read_as_the_grammar_reads_them() {
    assert_eq!(
        lex("x=1.5e-3+.5*2d<=1e5x&&a!=1."),
        vec![
            ('W', "x"),
            ('.', "="),
            ('N', "1.5e-3"),
            ('.', "+"),
            ('N', ".5"),
            ('.', "*"),
            ('W', "2d"),
            ('.', "<="),
            ('W', "1e5x"),
            ('.', "&&"),
            ('W', "a"),
            ('.', "!="),
            ('N', "1."),
        ]
    );
    let values: Vec<f64> = tokens("1e3 -2 .25")
        .iter()
        .filter_map(|t| match t.kind {
            TokenKind::Number(v) => Some(v),
            _ => None,
        })
        .collect();
    assert_eq!(values, vec![1000.0, 2.0, 0.25]);
}

#[test]
fn comments_and_blanks_are_not_tokens_and_paths_are_one() {
    assert_eq!(
        lex("include <lib//x.scad>\u{a0}// note\n/* a */ s = \"a\\\"b\"; é"),
        vec![
            ('W', "include"),
            ('P', "<lib//x.scad>"),
            ('W', "s"),
            ('.', "="),
            ('S', "\"a\\\"b\""),
            ('.', ";"),
            ('.', "é"),
        ]
    );
    // Not after a statement's end, `include` is a name and `<` an operator.
    assert_eq!(
        lex("a = include < b;")[2..4],
        [('W', "include"), ('.', "<")]
    );
}

#[test]
fn what_the_parser_rejects_runs_to_the_end() {
    assert_eq!(lex("a \"open"), vec![('W', "a"), ('S', "\"open")]);
    assert_eq!(lex("a /* open"), vec![('W', "a")]);
    assert_eq!(
        lex("include <open\nb"),
        vec![('W', "include"), ('.', "<"), ('W', "open"), ('W', "b")]
    );
    let deep = "[".repeat(2000);
    assert_eq!(tokens(&deep).len(), 2000);
}
