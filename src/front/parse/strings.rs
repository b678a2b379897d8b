//! String literals: OpenSCAD's escapes, decoded.

/// The value of a string literal (quotes included in `raw`), with OpenSCAD's escapes:
/// `\n \t \r \\ \"`, `\xHH` (ASCII; `\x00` reads as a space), `\uHHHH`, `\UHHHHHH` and
/// also `\u{H...}` (an invalid or zero code point reads as a space). A backslash before
/// any other character is dropped, and raw line breaks are dropped, as OpenSCAD does.
pub(super) fn decode_string(raw: &str) -> String {
    let inner = raw
        .strip_prefix('"')
        .and_then(|s| s.strip_suffix('"'))
        .unwrap_or(raw);
    let mut out = String::with_capacity(inner.len());
    let mut rest = inner;
    while let Some(c) = rest.chars().next() {
        rest = &rest[c.len_utf8()..];
        match c {
            '\\' => rest = escape(rest, &mut out),
            '\n' | '\r' => {}
            _ => out.push(c),
        }
    }
    out
}

/// Decodes the escape after a backslash; returns the text after it.
fn escape<'s>(rest: &'s str, out: &mut String) -> &'s str {
    let Some(c) = rest.chars().next() else {
        return rest;
    };
    let after = &rest[c.len_utf8()..];
    let simple = match c {
        'n' => Some('\n'),
        't' => Some('\t'),
        'r' => Some('\r'),
        _ => None,
    };
    if let Some(s) = simple {
        out.push(s);
        return after;
    }
    let coded = match c {
        'x' => hex_escape(after, 2).filter(|&(v, _)| v <= 0x7f),
        'u' if after.starts_with('{') => braced_escape(after),
        'u' => hex_escape(after, 4),
        'U' => hex_escape(after, 6),
        _ => None,
    };
    match coded {
        Some((value, used)) => {
            out.push(
                char::from_u32(value)
                    .filter(|&ch| ch != '\0')
                    .unwrap_or(' '),
            );
            &after[used..]
        }
        // `\\`, `\"` and unknown escapes: the backslash goes, the character stays.
        None => {
            out.push(c);
            after
        }
    }
}

/// `digits` hex digits at the start of `s`: their value and length.
fn hex_escape(s: &str, digits: usize) -> Option<(u32, usize)> {
    let hex = s.get(..digits)?;
    if !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    u32::from_str_radix(hex, 16).ok().map(|v| (v, digits))
}

/// `{H...}` (1 to 6 hex digits) at the start of `s`: its value and length.
fn braced_escape(s: &str) -> Option<(u32, usize)> {
    let close = s.bytes().take(8).position(|b| b == b'}')?;
    let hex = &s[1..close];
    if hex.is_empty() || !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    u32::from_str_radix(hex, 16).ok().map(|v| (v, close + 1))
}
