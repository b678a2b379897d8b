//! Target folders for fit tests: five views of a model drawn by `reparamc render -o dir/`
//! (the CPU backend, antialiased PNGs and a `cameras.json`).

use reparamc::command::fit::{Fitted, Options as FitOpts, Settings, prepare};
use reparamc::command::render::{
    BackendChoice, Cameras, Layout, Options as RenderOpts, Pictures, render,
};
use reparamc::front::source::SourceMap;
use std::path::{Path, PathBuf};

/// A fresh scratch folder for one test case.
pub fn scratch(test: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("reparamc-{test}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Renders five views of `model`, `size` pixels square, into `dir`.
pub fn render_views(model: &Path, dir: &Path, size: u32) {
    let opts = RenderOpts {
        model: model.to_path_buf(),
        call: None,
        size: (size, size),
        cameras: Cameras::Around(5),
        backend: BackendChoice {
            gpu: false,
            cpu: true,
        },
        layout: Layout::Views,
    };
    let out = render(&opts, &mut SourceMap::new()).unwrap_or_else(|e| panic!("render: {e:?}"));
    let Pictures::Views {
        files,
        cameras_json,
    } = out.pictures
    else {
        panic!("no views");
    };
    std::fs::create_dir_all(dir).unwrap();
    for (name, png) in files {
        std::fs::write(dir.join(name), png).unwrap();
    }
    std::fs::write(dir.join("cameras.json"), cameras_json).unwrap();
}

/// Fits `model` to the target folder `target` with `settings`, on the CPU, as
/// `reparamc fit` does.
pub fn fit_cpu(model: &Path, target: &Path, settings: Settings) -> Fitted {
    let opts = FitOpts {
        model: model.to_path_buf(),
        target: target.to_path_buf(),
        subspace: false,
        max_size: None,
        gallery: false,
        backend: BackendChoice {
            gpu: false,
            cpu: true,
        },
        settings,
    };
    let job = prepare(&opts, &mut SourceMap::new())
        .unwrap_or_else(|_| panic!("prepare {}", model.display()));
    job.run(&mut |_| {})
        .unwrap_or_else(|_| panic!("fit {}", model.display()))
}
