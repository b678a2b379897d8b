//! A page opened in headless Chromium (Debian's `chromium`, installed by `scripts/setup`):
//! the console lines and errors it raises and the images it fails to show.
//!
//! The page is copied beside itself with a probe script first in its `<head>`: the probe
//! records `console.error` calls and every error event (a script error, or a resource that
//! does not load), and once the page has loaded it counts the `<img>` elements, lists
//! those that show no picture, and counts the `<svg>` elements. Chromium prints the
//! document after the load (`--dump-dom`), and the probe's findings are read back from an
//! attribute of `<body>`; whatever the page wrote to the console comes from Chromium's log.

use std::path::Path;
use std::process::Command;

/// What a page did in the browser.
#[derive(Debug)]
pub struct PageCheck {
    /// `<img>` elements on the page.
    pub images: usize,
    /// `<svg>` elements on the page.
    pub svgs: usize,
    /// The `src` of every image not shown (not loaded, or no pixels).
    pub broken: Vec<String>,
    /// Error events and `console.error` calls, in order.
    pub errors: Vec<String>,
    /// Every line the page wrote to the console (Chromium's log), the probe's own included.
    pub console: Vec<String>,
}

impl PageCheck {
    /// Nothing went wrong: no console line, no error, every image shown.
    pub fn clean(&self) -> bool {
        self.broken.is_empty() && self.errors.is_empty() && self.console.is_empty()
    }
}

const PROBE: &str = r#"<script>
var probeErrors = [];
var probeConsoleError = console.error;
console.error = function () {
  probeErrors.push(Array.prototype.join.call(arguments, " "));
  probeConsoleError.apply(console, arguments);
};
window.addEventListener("error", function (e) {
  var t = e.target;
  probeErrors.push(t && t !== window ? "failed to load " + (t.src || t.href) : e.message);
}, true);
window.addEventListener("load", function () {
  var images = Array.prototype.slice.call(document.images);
  var broken = images
    .filter(function (i) { return !i.complete || i.naturalWidth === 0; })
    .map(function (i) { return i.getAttribute("src"); });
  document.body.setAttribute("data-probe", JSON.stringify({
    images: images.length,
    svgs: document.querySelectorAll("svg").length,
    broken: broken,
    errors: probeErrors
  }));
});
</script>"#;

/// Opens `page` in headless Chromium (a fresh profile, no network) and reports what it did.
pub fn open(page: &Path) -> PageCheck {
    let html = std::fs::read_to_string(page).expect("the page reads");
    let at = match html.find("<head>") {
        Some(i) => i + "<head>".len(),
        None => html
            .find("<body>")
            .expect("the page has a <head> or a <body>"),
    };
    let probed = format!("{}{PROBE}{}", &html[..at], &html[at..]);
    let copy = page.with_file_name(".probe.html");
    let profile = page.with_file_name(".chromium-profile");
    std::fs::write(&copy, probed).unwrap();
    let out = Command::new("chromium")
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--allow-file-access-from-files",
            "--virtual-time-budget=10000",
            "--enable-logging=stderr",
            "--v=0",
            "--dump-dom",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(format!("file://{}", copy.canonicalize().unwrap().display()))
        .output()
        .expect("Debian's `chromium` runs (bash scripts/setup installs it)");
    std::fs::remove_file(&copy).ok();
    std::fs::remove_dir_all(&profile).ok();
    let dom = String::from_utf8_lossy(&out.stdout);
    let attr = dom
        .split("data-probe=\"")
        .nth(1)
        .and_then(|rest| rest.split('"').next())
        .unwrap_or_else(|| {
            panic!(
                "the probe did not report; chromium said:\n{}",
                String::from_utf8_lossy(&out.stderr)
            )
        });
    let json = attr
        .replace("&quot;", "\"")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&");
    let v: serde_json::Value = serde_json::from_str(&json).expect("the probe writes JSON");
    let strings = |k: &str| -> Vec<String> {
        v[k].as_array()
            .unwrap()
            .iter()
            .map(|s| s.as_str().unwrap_or("").to_string())
            .collect()
    };
    PageCheck {
        images: v["images"].as_u64().unwrap() as usize,
        svgs: v["svgs"].as_u64().unwrap() as usize,
        broken: strings("broken"),
        errors: strings("errors"),
        console: String::from_utf8_lossy(&out.stderr)
            .lines()
            .filter(|l| l.contains(":CONSOLE"))
            .map(str::to_string)
            .collect(),
    }
}
