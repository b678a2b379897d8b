//! The chair example and the kinds the zero-shot tests hide behind the stand-in server:
//! a bench (wider, with a lower back), a stool and a bar stool (other legs and backs),
//! and the command that explores the chair.

use std::path::Path;
use std::process::Command;

pub const CHAIR: &str = include_str!("../../examples/chair.scad");

/// The hidden target: the chair made into a bench (wider, with a lower back).
pub fn bench() -> String {
    CHAIR
        .replace("translate([-50, -50, -70])", "translate([-80, -50, -70])")
        .replace("translate([35, -50, -70])", "translate([65, -50, -70])")
        .replace("translate([-50, 35, -70])", "translate([-80, 35, -70])")
        .replace("translate([35, 35, -70])", "translate([65, 35, -70])")
        .replace(
            "translate([-50, -50, 0]) cube([100, 100, 15])",
            "translate([-80, -50, 0]) cube([160, 100, 15])",
        )
        .replace(
            "translate([-50, 35, 15]) cube([100, 15, 70])",
            "translate([-80, 35, 15]) cube([160, 15, 45])",
        )
        .replace("translate([-50, -50, 15])", "translate([-80, -50, 15])")
        .replace("translate([35, -50, 15])", "translate([65, -50, 15])")
}

/// The chair with legs `legs` high and a back `back` high: a stool, a bar stool.
pub fn legs_and_back(legs: u32, back: u32) -> String {
    let mut t = CHAIR.to_string();
    for (x, y) in [(-50, -50), (35, -50), (-50, 35), (35, 35)] {
        t = t.replace(
            &format!("translate([{x}, {y}, -70]) cube([15, 15, 70])"),
            &format!("translate([{x}, {y}, -{legs}]) cube([15, 15, {legs}])"),
        );
    }
    t.replace("cube([100, 15, 70])", &format!("cube([100, 15, {back}])"))
}

/// The three kinds the loop is asked for, by prompt: a bench, a stool and a bar stool.
pub fn three_kinds() -> [(&'static str, String); 3] {
    [
        ("bench", bench()),
        ("stool", legs_and_back(40, 25)),
        ("bar stool", legs_and_back(130, 30)),
    ]
}

/// `reparamc explore` on `dir`'s `chair.scad`, writing `chair_param.scad` and the run
/// folder `run/` there, guided by the img2img servers at `urls`, every other setting the
/// command's own (no API key passed on).
pub fn explore_chair(dir: &Path, urls: &[&str]) -> Command {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_reparamc"));
    cmd.arg("explore")
        .arg(dir.join("chair.scad"))
        .args(["--object", "chair", "-o"])
        .arg(dir.join("chair_param.scad"))
        .arg("--run")
        .arg(dir.join("run"));
    for u in urls {
        cmd.args(["--diffusion", u]);
    }
    cmd.env_remove("OPENAI_API_KEY");
    cmd
}
