//! The report as one HTML page (`--report r.html`) a person reads in a browser, offline.
//!
//! [`report_page`] lays out what the [`Report`] records: the model's views, the sliders
//! (name, description, range, the numbers each drives), the relations kept in words with
//! their evidence, the ones left out and why, the distortion plot, the presets gallery and
//! the optional parts with the variations that drop them. Invariant: the page is whole in
//! itself: styles inline, pictures as `data:` URLs or inline SVG, no script, no link out;
//! every text from the model is escaped.

use super::emit::EmitPlan;
use super::gallery::{Tile, cameras, render_tile};
use super::plot::escape;
use super::report::Report;
use crate::analysis::noise::NoiseModel;
use crate::analysis::reparam::Solution;
use crate::ir::Model;
use std::fmt::Write;

/// How many views of the model the page shows.
const VIEWS: usize = 4;

/// What the page shows besides the report.
pub struct PageInputs<'a> {
    pub report: &'a Report,
    pub model: &'a Model,
    pub solution: &'a Solution,
    pub plan: &'a EmitPlan,
    /// The distortion plot as SVG text (inline, with its tooltips).
    pub plot_svg: Option<&'a str>,
    /// The presets gallery (PNG).
    pub gallery_png: Option<&'a [u8]>,
}

const STYLE: &str = "body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}\
h1{font-size:1.6em}h2{margin-top:1.6em;border-bottom:1px solid #ccc}\
table{border-collapse:collapse;width:100%}td,th{border:1px solid #ddd;padding:4px 8px;text-align:left;vertical-align:top}\
th{background:#f4f4f4}.views img,.gallery img{max-width:100%;border:1px solid #ddd}\
.views{display:flex;flex-wrap:wrap;gap:8px}.views img{width:240px}.views figure{margin:0}figcaption{text-align:center;color:#555}\
code{background:#f4f4f4;padding:0 3px}.left{color:#844}.small{color:#666;font-size:.9em}";

/// The page as HTML text; an error when a picture cannot be drawn.
pub fn report_page(p: &PageInputs) -> Result<String, String> {
    let r = p.report;
    let mut h = String::new();
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <title>reparamc report: {m}</title><style>{STYLE}</style></head><body>\n\
         <h1>reparamc report: <code>{m}</code></h1>\n<p>{s}</p>\n",
        m = escape(&r.model),
        s = escape(&r.summary_line(&r.model)),
    );
    views(&mut h, p)?;
    sliders(&mut h, p);
    relations(&mut h, r);
    h += "<h2>Distortion</h2>\n";
    match p.plot_svg {
        Some(svg) => {
            h += "<p class=\"small\">Hover a step for its relation.</p>\n";
            h += svg.trim_start_matches(|c| c != '<');
            h += "\n";
        }
        None => h += "<p>No curve: there are no variations to measure it on.</p>\n",
    }
    if let Some(png) = p.gallery_png {
        let _ = write!(
            h,
            "<h2>Presets</h2>\n<div class=\"gallery\"><img alt=\"the defaults, each preset and an even blend\" src=\"data:image/png;base64,{}\"></div>\n",
            base64(png)
        );
    }
    optional(&mut h, r);
    h += "</body></html>\n";
    Ok(h)
}

/// The model at its defaults from a few views around it.
fn views(h: &mut String, p: &PageInputs) -> Result<(), String> {
    let tile = Tile {
        name: String::new(),
        values: p.model.slot_values(),
        skip: Vec::new(),
    };
    let cams = cameras(p.model, std::slice::from_ref(&tile), VIEWS)?;
    *h += "<h2>The model</h2>\n<div class=\"views\">\n";
    for c in &cams {
        let png = render_tile(p.model, &tile, c)?.encode_png();
        let _ = writeln!(
            h,
            "<figure><img alt=\"{n} view\" src=\"data:image/png;base64,{}\"><figcaption>{n}</figcaption></figure>",
            base64(&png),
            n = escape(&c.name)
        );
    }
    *h += "</div>\n";
    Ok(())
}

/// One row per slider: what it is, its range and the numbers of the model it drives.
fn sliders(h: &mut String, p: &PageInputs) {
    *h += "<h2>Sliders</h2>\n";
    if p.plan.sliders.is_empty() {
        *h += "<p>No sliders: every number is fixed by the relations kept.</p>\n";
        return;
    }
    *h += "<table><tr><th>slider</th><th>description</th><th>range</th><th>default</th><th>numbers it drives</th></tr>\n";
    for (i, s) in p.plan.sliders.iter().enumerate() {
        let driven: Vec<String> = p
            .solution
            .exprs
            .iter()
            .enumerate()
            .filter(|(_, e)| e.terms.iter().any(|&(k, _)| k == i))
            .map(|(slot, _)| {
                let sl = &p.model.slots[slot];
                format!("<code>{}</code> ({})", escape(&sl.name), escape(&sl.text))
            })
            .collect();
        let _ = writeln!(
            h,
            "<tr><td><code>{}</code></td><td>{}</td><td>{} to {}</td><td>{}</td><td>{} {}: {}</td></tr>",
            escape(&s.name),
            escape(&s.description),
            s.range.min,
            s.range.max,
            s.value,
            driven.len(),
            if driven.len() == 1 {
                "number"
            } else {
                "numbers"
            },
            driven.join(", ")
        );
    }
    *h += "</table>\n";
}

/// What the report says of the variations' noise.
fn noise_line(n: &NoiseModel) -> String {
    if !n.told {
        " No relation the variations move cancels their changes, so nothing tells their noise from a change of design: a relation any variation breaks is left out."
            .to_string()
    } else if n.exact() {
        " The variations are exact (no noise): a relation any variation breaks is left out."
            .to_string()
    } else {
        format!(
            " The variations' noise: {} (pooled over {} relations); a relation is broken beyond {:.1} deviations.",
            n.describe(),
            n.pooled,
            n.critical_z
        )
    }
}

/// The relations kept, and those left out with why.
fn relations(h: &mut String, r: &Report) {
    let keep = r.keep_step().min(r.chosen.len());
    let _ = writeln!(
        h,
        "<h2>Relations kept ({keep})</h2>\n<p class=\"small\">How they were chosen: {}.{}</p>\n<ol>",
        escape(&r.method),
        r.noise.as_ref().map_or(String::new(), noise_line)
    );
    for c in &r.chosen[..keep] {
        let _ = writeln!(
            h,
            "<li>{} <span class=\"small\">({})</span></li>",
            escape(&c.relation),
            c.evidence(r.noise.as_ref())
        );
    }
    *h += "</ol>\n";
    let left = &r.chosen[keep..];
    let implied = r.base_constraint_count.saturating_sub(r.chosen.len());
    if r.cutoff.is_none() {
        if implied > 0 {
            let _ = writeln!(
                h,
                "<h2>Relations left out ({implied})</h2>\n<p>{implied} more relations hold on the input; with no variations to test them, the choice ({}) leaves them out.</p>",
                escape(&r.method)
            );
        }
        return;
    }
    if left.is_empty() && implied == 0 {
        return;
    }
    let _ = writeln!(
        h,
        "<h2>Relations left out ({})</h2>\n<ol start=\"{}\">",
        left.len(),
        keep + 1
    );
    for (k, c) in left.iter().enumerate() {
        let why = match (&r.cutoff, k) {
            (Some(cut), 0) => format!("noise: {}", cut.reason),
            _ if c.intent_probability.is_some_and(|p| p < 0.5) => {
                "noise: the variations break it (more likely broken than intent)".to_string()
            }
            _ => format!(
                "cutoff: the test stops at relation {}, the first the noise does not explain",
                keep + 1
            ),
        };
        let _ = writeln!(
            h,
            "<li class=\"left\">{} <span class=\"small\">({}) — {}</span></li>",
            escape(&c.relation),
            c.evidence(r.noise.as_ref()),
            escape(&why)
        );
    }
    *h += "</ol>\n";
    if implied > 0 {
        let _ = writeln!(
            h,
            "<p class=\"small\">{implied} more relations that hold on the input follow from those taken before them, so they add nothing.</p>"
        );
    }
}

/// The part switches and the variations that do without their parts.
fn optional(h: &mut String, r: &Report) {
    *h += "<h2>Optional parts</h2>\n";
    if r.toggles.is_empty() {
        *h += "<p>None: every variation has every part.</p>\n";
        return;
    }
    *h += "<table><tr><th>parts</th><th>variations that drop them</th></tr>\n";
    for parts in &r.toggles {
        let by: Vec<String> = r
            .variations
            .iter()
            .filter(|v| parts.iter().any(|p| v.optional_parts.contains(p)))
            .map(|v| format!("<code>{}</code>", escape(&v.name)))
            .collect();
        let names: Vec<String> = parts
            .iter()
            .map(|p| format!("<code>{}</code>", escape(p)))
            .collect();
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td>{}</td></tr>",
            names.join(", "),
            by.join(", ")
        );
    }
    *h += "</table>\n";
}

/// Standard base64 (RFC 4648, with padding), for `data:` URLs.
pub fn base64(bytes: &[u8]) -> String {
    const ABC: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ABC[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::base64;

    #[test]
    fn base64_matches_the_rfc_examples() {
        let cases = [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foobar", "Zm9vYmFy"),
        ];
        for (plain, coded) in cases {
            assert_eq!(base64(plain.as_bytes()), coded);
        }
    }
}
