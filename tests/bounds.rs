//! Bounds: a program that would make millions of parts, or recurse without end, stops
//! within seconds with a located message and in bounded memory (the limits are in
//! `front::eval`: `MAX_STEPS`, `MAX_PARTS`, `MAX_CALL_DEPTH`).

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Peak resident memory of a running process, in kB (`VmHWM` of `/proc/<pid>/status`).
fn peak_kb(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// Runs `reparamc inspect` on `text`: (exit code, stderr, seconds, peak memory in MB).
fn inspect(name: &str, text: &str) -> (Option<i32>, String, f64, u64) {
    let path = std::env::temp_dir().join(format!(
        "reparamc-bounds-{}-{name}.scad",
        std::process::id()
    ));
    std::fs::write(&path, text).unwrap();
    let start = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_reparamc"))
        .arg("inspect")
        .arg(&path)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut peak = 0;
    while child.try_wait().unwrap().is_none() {
        peak = peak.max(peak_kb(child.id()).unwrap_or(0));
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "{name}: still running"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
    let out = child.wait_with_output().unwrap();
    let _ = std::fs::remove_file(&path);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    (
        out.status.code(),
        err,
        start.elapsed().as_secs_f64(),
        peak / 1024,
    )
}

#[test]
fn runaway_programs_stop_in_seconds_and_bounded_memory() {
    let cases = [
        (
            "parts",
            "for (i = [0 : 1e7]) translate([i, 0, 0]) cube(1);\n",
            "E0304",
        ),
        (
            "doubling",
            "module t(n) { if (n > 0) { t(n - 1); t(n - 1); } else cube(1); }\nt(40);\n",
            "E0304",
        ),
        ("list", "x = [for (i = [0 : 1e8]) i];\ncube(1);\n", "E0304"),
        (
            "loop",
            "x = [for (i = 0; i >= 0; i = i + 1) i];\ncube(1);\n",
            "E030",
        ),
        ("module", "module m() { m(); }\nm();\n", "E0301"),
        (
            "function",
            "function f(n) = f(n + 1);\ncube(f(0));\n",
            "E0301",
        ),
    ];
    for (name, text, code) in cases {
        let (status, err, secs, mb) = inspect(name, text);
        eprintln!("{name}: {secs:.1} s, {mb} MB");
        assert_eq!(status, Some(1), "{name}: {err}");
        assert!(err.contains(&format!("error[{code}")), "{name}: {err}");
        assert!(err.contains(".scad:"), "{name}: no place in {err}");
        assert!(secs < 60.0, "{name}: {secs:.1} s");
        assert!(mb < 600, "{name}: {mb} MB");
    }
}
