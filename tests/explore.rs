//! `reparamc explore` end to end against stand-in servers (no network, no GPU): the loop
//! moves the chair towards a hidden bench, the run folder is written and resumes, a
//! failing server is set aside, and bad answers stop the run cleanly with the rounds done
//! kept.

#[path = "explore_support/chair.rs"]
mod chair;
mod common;
#[path = "explore_support/server.rs"]
mod server;

use chair::{CHAIR, bench, explore_chair, three_kinds};
use reparamc::geom::iou;
use reparamc::ir::Model;
use server::{Mode, Server, model_of, start, start_for};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn folder(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("reparamc_explore_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(d.join("chair.scad"), CHAIR).unwrap();
    d
}

/// Runs `reparamc explore` on the chair in `dir` with small, quick settings and `extra`.
fn explore(dir: &Path, servers: &[&Server], extra: &[&str]) -> Output {
    command(dir, servers, extra).output().unwrap()
}

/// The command [`explore`] runs.
fn command(dir: &Path, servers: &[&Server], extra: &[&str]) -> Command {
    let urls: Vec<&str> = servers.iter().map(|s| s.url.as_str()).collect();
    let mut cmd = explore_chair(dir, &urls);
    cmd.args(["--size", "64", "--diffusion-size", "64", "--batch", "3"])
        .args(["--iterations", "30", "--timeout", "20", "--retries", "1"])
        .args(extra);
    cmd
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn state(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("run/state.json")).unwrap()).unwrap()
}

fn iou_of(a: &Model, b: &Model) -> f64 {
    iou((&a.parts, &a.csg), (&b.parts, &b.csg))
}

#[test]
fn the_loop_moves_the_chair_towards_the_bench_and_resumes() {
    let target = model_of("bench.scad", &bench());
    let srv = start(target.clone(), Mode::Good);
    let dir = folder("loop");
    let out = explore(&dir, &[&srv], &["--prompt", "bench", "--rounds", "3"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let varied = std::fs::read_to_string(dir.join("run/bench.scad")).unwrap();
    let start_iou = iou_of(&model_of("chair.scad", CHAIR), &target);
    let after = iou_of(&model_of("bench.scad", &varied), &target);
    eprintln!("IoU with the bench: {start_iou:.3} -> {after:.3}");
    assert!(
        after > 0.6 && after > start_iou + 0.25,
        "IoU with the bench {start_iou:.3} -> {after:.3}"
    );
    let s = state(&dir);
    assert_eq!(s["prompts"][0]["round"], 3);
    assert!(dir.join("run/bench/round0003_view5_guide.png").is_file());
    assert!(dir.join("run/bench/round0001_view1_render.png").is_file());
    // The main job ran on the variation; its preset is named by the prompt.
    let presets = std::fs::read_to_string(dir.join("chair_param.json")).unwrap();
    assert!(presets.contains("\"bench\""), "{presets}");
    assert!(dir.join("chair_param.scad").is_file());
    // Starting again over the same folder is refused; --resume goes on from round 3.
    let again = explore(&dir, &[&srv], &["--prompt", "bench", "--rounds", "3"]);
    assert_eq!(again.status.code(), Some(1));
    assert!(stderr(&again).contains("--resume"), "{}", stderr(&again));
    let before = srv.requests.load(std::sync::atomic::Ordering::SeqCst);
    let resumed = explore(&dir, &[&srv], &["--resume", "--rounds", "4"]);
    assert!(resumed.status.success(), "{}", stderr(&resumed));
    assert!(
        stderr(&resumed).contains("3 of 4 rounds done"),
        "{}",
        stderr(&resumed)
    );
    assert_eq!(state(&dir)["prompts"][0]["round"], 4);
    let after = srv.requests.load(std::sync::atomic::Ordering::SeqCst);
    assert_eq!(after - before, 5, "one more round of five views");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_language_model_s_kinds_are_printed_and_picked() {
    let target = model_of("bench.scad", &bench());
    let srv = start(target, Mode::Good);
    let dir = folder("llm");
    let llm = format!("{}/v1", srv.url);
    std::fs::create_dir_all(dir.join("pages")).unwrap();
    let page = dir.join("pages/index.html").display().to_string();
    let out = explore(
        &dir,
        &[&srv],
        &[
            "--llm",
            &llm,
            "--pick",
            "3",
            "--prompt",
            "bench",
            "--rounds",
            "1",
            "--views",
            "2",
            "--gallery",
            &page,
        ],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let err = stderr(&out);
    eprintln!("{err}");
    assert!(
        err.contains("1. Bench") && err.contains("3. Bar stool"),
        "{err}"
    );
    let s = state(&dir);
    let names: Vec<&str> = s["prompts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["bar_stool", "bench"]);
    assert!(dir.join("run/bar_stool.scad").is_file());
    // The gallery page, opened in a browser: no console error, every image it lists shown.
    let page = std::fs::read_to_string(dir.join("pages/index.html")).unwrap();
    let images = image_links(&page);
    // Per prompt: one round of two views (guidance, render) and four final views; presets.
    assert_eq!(images.len(), 2 * (2 * 2 + 4) + 1, "{page}");
    assert!(dir.join("pages/index_presets.png").is_file());
    let shown = common::browser::open(&dir.join("pages/index.html"));
    assert_eq!(shown.images, images.len(), "{shown:?}");
    assert!(shown.clean(), "{shown:?}");
    // The probe sees a missing picture.
    std::fs::remove_file(dir.join("pages").join(&images[0])).unwrap();
    let missing = common::browser::open(&dir.join("pages/index.html"));
    assert_eq!(missing.broken.len(), 1, "{missing:?}");
    assert_eq!(missing.errors.len(), 1, "{missing:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The `src` of every `<img>` of an HTML page.
fn image_links(page: &str) -> Vec<String> {
    page.split("<img src=\"")
        .skip(1)
        .map(|rest| rest.split('"').next().unwrap().replace("%20", " "))
        .collect()
}

#[test]
fn a_failing_server_is_set_aside() {
    let target = model_of("bench.scad", &bench());
    let bad = start(target.clone(), Mode::Fails);
    let good = start(target, Mode::Good);
    let dir = folder("aside");
    let out = explore(
        &dir,
        &[&bad, &good],
        &["--prompt", "bench", "--rounds", "2"],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let tried = bad.requests.load(std::sync::atomic::Ordering::SeqCst);
    let served = good.requests.load(std::sync::atomic::Ordering::SeqCst);
    assert_eq!(
        served, 10,
        "every view of both rounds served by the good server"
    );
    assert!((1..=10).contains(&tried), "{tried}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_malformed_answer_stops_the_run_and_keeps_finished_rounds() {
    let target = model_of("bench.scad", &bench());
    let srv = start(target.clone(), Mode::MalformedAfter(5));
    let dir = folder("malformed");
    let out = explore(&dir, &[&srv], &["--prompt", "bench", "--rounds", "3"]);
    assert_eq!(out.status.code(), Some(4), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(
        err.contains(&srv.url)
            && err.contains("prompt `bench`, round 2")
            && err.contains("malformed JSON"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(state(&dir)["prompts"][0]["round"], 1);
    assert!(!dir.join("chair_param.scad").exists());
    // Images of the wrong size are refused the same way.
    let wrong = start(target, Mode::WrongSize);
    let dir2 = folder("wrong_size");
    let out = explore(
        &dir2,
        &[&wrong],
        &["--prompt", "bench", "--rounds", "1", "--views", "1"],
    );
    assert_eq!(out.status.code(), Some(4));
    assert!(
        stderr(&out).contains("32×32, but 64×64 was asked for"),
        "{}",
        stderr(&out)
    );
    // A server that answers HTTP 500: retried once after a backoff, then named.
    let failing = start(model_of("bench.scad", &bench()), Mode::Fails);
    let dir4 = folder("http500");
    let out = explore(
        &dir4,
        &[&failing],
        &["--prompt", "bench", "--rounds", "1", "--views", "1"],
    );
    assert_eq!(out.status.code(), Some(4));
    assert!(
        stderr(&out).contains("answered HTTP 500"),
        "{}",
        stderr(&out)
    );
    assert_eq!(
        failing.requests.load(std::sync::atomic::Ordering::SeqCst),
        2
    );
    std::fs::remove_dir_all(&dir4).unwrap();
    // A server nobody listens on: unreachable, retried, then named.
    let dir3 = folder("unreachable");
    let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let url = format!("http://{}", listener.local_addr().unwrap());
    drop(listener);
    let gone = Server {
        url: url.clone(),
        requests: Default::default(),
    };
    let out = explore(
        &dir3,
        &[&gone],
        &["--prompt", "bench", "--rounds", "1", "--views", "1"],
    );
    assert_eq!(out.status.code(), Some(4));
    assert!(
        stderr(&out).contains(&format!("{url}: cannot reach")),
        "{}",
        stderr(&out)
    );
    for d in [dir, dir2, dir3] {
        std::fs::remove_dir_all(&d).unwrap();
    }
}

#[test]
fn an_interrupted_run_resumed_ends_where_an_uninterrupted_one_does() {
    let srv = start(model_of("bench.scad", &bench()), Mode::Good);
    let args = ["--prompt", "bench", "--rounds", "4", "--views", "3"];
    let whole = folder("whole");
    let out = explore(&whole, &[&srv], &args);
    assert!(out.status.success(), "{}", stderr(&out));
    // Interrupted (Ctrl-C) once the first round is saved, then resumed.
    let cut = folder("cut");
    let mut child = command(&cut, &[&srv], &args)
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let state_file = cut.join("run/state.json");
    let saved_one = || {
        std::fs::read_to_string(&state_file)
            .ok()
            .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
            .is_some_and(|s| s["prompts"][0]["round"].as_u64() >= Some(1))
    };
    while !saved_one() {
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    let _ = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status();
    let code = child.wait().unwrap().code();
    eprintln!("interrupted run exited with {code:?}");
    let partial: Vec<_> = walk(&cut.join("run"))
        .into_iter()
        .filter(|p| p.to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(partial.is_empty(), "half-written files left: {partial:?}");
    if code != Some(0) {
        assert!(state(&cut)["prompts"][0]["round"].as_u64() < Some(4));
        let out = explore(
            &cut,
            &[&srv],
            &["--resume", "--rounds", "4", "--views", "3"],
        );
        assert!(out.status.success(), "{}", stderr(&out));
    }
    assert_eq!(state(&cut)["prompts"], state(&whole)["prompts"]);
    let text = |d: &Path| std::fs::read_to_string(d.join("run/bench.scad")).unwrap();
    assert_eq!(text(&cut), text(&whole));
    for d in [whole, cut] {
        std::fs::remove_dir_all(&d).unwrap();
    }
}

/// Every file under `dir`.
fn walk(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            out.extend(walk(&p));
        } else {
            out.push(p);
        }
    }
    out
}

#[test]
fn three_prompts_each_recover_their_own_kind() {
    let targets = three_kinds();
    let models: Vec<(String, Model)> = targets
        .iter()
        .map(|(k, t)| (k.to_string(), model_of("t.scad", t)))
        .collect();
    let srv = start_for(models.clone(), Mode::Good);
    let dir = folder("three");
    let mut args = vec!["--rounds", "60"];
    for (k, _) in &targets {
        args.extend(["--prompt", k]);
    }
    let out = explore(&dir, &[&srv], &args);
    assert!(out.status.success(), "{}", stderr(&out));
    // Sixty rounds at 64 pixels (the default is 400 at 256): each variation is recovered,
    // IoU ≥ 0.9 with its hidden kind (the chair starts at 0.33, 0.76 and 0.75; measured
    // 0.987, 0.979, 0.980 as the mean of the last stage's rounds, 0.933, 0.947, 0.922 as
    // the last round's numbers).
    let chair = model_of("chair.scad", CHAIR);
    for ((kind, target), name) in models.iter().zip(["bench", "stool", "bar_stool"]) {
        let text = std::fs::read_to_string(dir.join(format!("run/{name}.scad"))).unwrap();
        let (b, a) = (
            iou_of(&chair, target),
            iou_of(&model_of("v.scad", &text), target),
        );
        eprintln!("{kind}: IoU {b:.3} -> {a:.3}");
        assert!(a >= 0.9, "{kind}: IoU {b:.3} -> {a:.3}");
    }
    let presets: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("chair_param.json")).unwrap())
            .unwrap();
    let sets = presets["parameterSets"].as_object().unwrap();
    for ((kind, target), name) in models.iter().zip(["bench", "stool", "bar_stool"]) {
        assert!(sets.contains_key(name), "{presets}");
        // Presets stand where the input stands (centred, on its floor): compared so.
        let preset = preset_model(&dir, name);
        let (a, b) = (
            common::anchored(&preset.parts),
            common::anchored(&target.parts),
        );
        let reached = iou((&a, &preset.csg), (&b, &target.csg));
        eprintln!("{kind}: preset IoU {reached:.3}");
        // Issue 19's bar; measured 0.978, 0.981, 0.989 (0.891, 0.926, 0.949 from the
        // last round's numbers instead of the last stage's mean).
        assert!(reached >= 0.95, "{kind}: preset IoU {reached:.3}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The output's preset `name` as OpenSCAD evaluates it (its `.csg` export, loaded).
fn preset_model(dir: &Path, name: &str) -> Model {
    let (out, csg) = common::openscad_preset(&dir.join("chair_param.scad"), name);
    assert!(out.status.success(), "{}", stderr(&out));
    model_of("preset.csg", &csg.expect("openscad wrote no .csg"))
}
