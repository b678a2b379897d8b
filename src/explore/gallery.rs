//! The run's gallery page (`--gallery runs/chair/index.html`): one static, offline HTML
//! page with, per prompt, sampled rounds (each view's guidance beside its render), the
//! final variation's views, and the presets of the output rendered.
//!
//! [`page`] writes the HTML only; the pictures it shows are files of the run folder (the
//! round images [`super::run`] keeps, and the final views [`final_views`] renders), linked
//! by paths relative to the page. Invariant: every image the page lists exists when the
//! page is written.

use super::run::{PromptState, RunFolder, State};
use crate::back::plot::escape;
use std::path::{Component, Path, PathBuf};

/// Rounds shown per prompt, at most (evenly spaced, the last always among them).
pub const SAMPLED_ROUNDS: usize = 6;

/// The rounds shown of a prompt that did `done` rounds (from 1).
pub fn sampled_rounds(done: usize) -> Vec<usize> {
    if done <= SAMPLED_ROUNDS {
        return (1..=done).collect();
    }
    let mut r: Vec<usize> = (0..SAMPLED_ROUNDS)
        .map(|i| 1 + i * (done - 1) / (SAMPLED_ROUNDS - 1))
        .collect();
    r.dedup();
    r
}

/// The presets picture of the page at `page`: beside it, `<stem>_presets.png`.
pub fn presets_path(page: &Path) -> PathBuf {
    let stem = page
        .file_stem()
        .map_or("gallery".into(), |s| s.to_string_lossy().into_owned());
    page.with_file_name(format!("{stem}_presets.png"))
}

/// The final view `view` (from 0) of prompt `name`.
pub fn final_view_path(folder: &RunFolder, name: &str, view: usize) -> PathBuf {
    folder
        .rounds_dir(name)
        .join(format!("final_view{}.png", view + 1))
}

/// `to` as a link from a page in folder `from` (both made absolute first).
pub fn link(from: &Path, to: &Path) -> String {
    let abs = |p: &Path| -> Vec<String> {
        std::path::absolute(p)
            .unwrap_or_else(|_| p.to_path_buf())
            .components()
            .filter(|c| !matches!(c, Component::CurDir))
            .map(|c| c.as_os_str().to_string_lossy().into_owned())
            .collect()
    };
    let (a, b) = (abs(from), abs(to));
    let common = a.iter().zip(&b).take_while(|(x, y)| x == y).count();
    let mut parts: Vec<String> = vec!["..".to_string(); a.len() - common];
    parts.extend(b[common..].iter().cloned());
    parts
        .iter()
        .map(|p| {
            p.replace('%', "%25")
                .replace(' ', "%20")
                .replace('#', "%23")
        })
        .collect::<Vec<_>>()
        .join("/")
}

/// An `<img>` of `file` seen from the page's folder `from`, with a caption.
fn figure(from: &Path, file: &Path, caption: &str) -> String {
    format!(
        "<figure><img src=\"{}\" alt=\"{}\"><figcaption>{}</figcaption></figure>",
        escape(&link(from, file)),
        escape(caption),
        escape(caption)
    )
}

/// One prompt's section.
fn section(
    from: &Path,
    folder: &RunFolder,
    p: &PromptState,
    views: usize,
    final_views: usize,
) -> String {
    let mut html = format!(
        "<section><h2>{}</h2><p>{} rounds; image loss {}</p>\n",
        escape(&p.prompt),
        p.round,
        p.loss.last().map_or("–".to_string(), |l| format!("{l:.5}"))
    );
    for r in sampled_rounds(p.round) {
        html += &format!("<div class=\"round\"><h3>round {r}</h3>");
        for v in 0..views {
            let g = folder.image_path(&p.name, r, v, "guide");
            let d = folder.image_path(&p.name, r, v, "render");
            html += &figure(from, &g, &format!("view {} guidance", v + 1));
            html += &figure(from, &d, &format!("view {} render", v + 1));
        }
        html += "</div>\n";
    }
    html += "<div class=\"final\"><h3>final variation</h3>";
    for v in 0..final_views {
        let f = final_view_path(folder, &p.name, v);
        html += &figure(from, &f, &format!("{} view {}", p.name, v + 1));
    }
    html + "</div></section>\n"
}

/// The page, to be written at `at`: the run's prompts (with `views` views a round and
/// `final_views` final views each) and, when drawn, the presets picture `presets`.
pub fn page(
    at: &Path,
    folder: &RunFolder,
    state: &State,
    views: usize,
    final_views: usize,
    presets: Option<&Path>,
) -> String {
    let from = at
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let mut body = String::new();
    for p in &state.prompts {
        body += &section(from, folder, p, views, final_views);
    }
    if let Some(png) = presets {
        body += "<section><h2>the output's presets</h2>";
        body += &figure(from, png, "defaults, each preset, and their even blend");
        body += "</section>\n";
    }
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <title>{title}</title><style>{STYLE}</style></head>\n<body><h1>{title}</h1>\n{body}</body></html>\n",
        title = escape(&format!("explore: kinds of {}", state.object)),
    )
}

const STYLE: &str = "body{font-family:sans-serif;margin:2em;background:#fafafa}\
    figure{display:inline-block;margin:4px;text-align:center}\
    img{width:128px;height:128px;image-rendering:pixelated;border:1px solid #ccc}\
    section>figure img{width:auto;height:auto;max-width:100%}\
    figcaption{font-size:11px;color:#555}h3{margin:.6em 0 .2em}";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounds_are_sampled_evenly_with_the_last() {
        assert_eq!(sampled_rounds(3), [1, 2, 3]);
        assert_eq!(sampled_rounds(400), [1, 80, 160, 240, 320, 400]);
    }

    #[test]
    fn links_are_relative_to_the_page() {
        let base = std::env::temp_dir();
        assert_eq!(
            link(&base.join("run"), &base.join("run/a b/x.png")),
            "a%20b/x.png"
        );
        assert_eq!(
            link(&base.join("pages"), &base.join("run/x.png")),
            "../run/x.png"
        );
    }
}
