//! Writing the files a command produces.
//!
//! Invariants: an output file is either written whole or not at all (a temporary file in
//! the same folder, then a rename, removed on an interrupt), and callers can ask whether an
//! output path names one of their inputs, or can be written at all, before they run.
//! Imports nothing of the crate.

use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Temporary files being written: what an interrupt (Ctrl-C) removes before the process
/// exits, so it leaves no partial file behind.
static UNFINISHED: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn track(tmp: &Path, on: bool) {
    if let Ok(mut list) = UNFINISHED.lock() {
        list.retain(|p| p != tmp);
        if on {
            list.push(tmp.to_path_buf());
        }
    }
}

/// Removes every temporary file a write has not finished; for an interrupt handler.
pub fn remove_unfinished() {
    if let Ok(list) = UNFINISHED.lock() {
        for p in list.iter() {
            let _ = std::fs::remove_file(p);
        }
    }
}

fn folder_of(path: &Path) -> &Path {
    path.parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
}

fn temporary_for(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map_or("out".into(), |n| n.to_string_lossy().into_owned());
    folder_of(path).join(format!(".{name}.{}.tmp", std::process::id()))
}

/// Writes `bytes` to `path` through a temporary file in the same folder and a rename, so a
/// failure never leaves a partial file.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let tmp = temporary_for(path);
    track(&tmp, true);
    let done = std::fs::write(&tmp, bytes).and_then(|()| std::fs::rename(&tmp, path));
    if done.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    track(&tmp, false);
    done
}

/// Whether `path` can be written as an output file, checked before a job runs: not a
/// folder, not one of `inputs`, in a folder that exists and takes a new file. The error
/// names the path and says why.
pub fn check_output(path: &Path, inputs: &[PathBuf]) -> Result<(), String> {
    let shown = path.display();
    if path.is_dir() {
        return Err(format!(
            "the output `{shown}` is a folder; give a file name"
        ));
    }
    if let Some(input) = inputs.iter().find(|i| same_file(path, i)) {
        return Err(format!(
            "the output `{shown}` is the input `{}`; choose another file",
            input.display()
        ));
    }
    let folder = folder_of(path);
    if !folder.is_dir() {
        return Err(format!(
            "cannot write `{shown}`: the folder `{}` does not exist",
            folder.display()
        ));
    }
    let probe = temporary_for(path);
    std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)
        .map(|_| {
            let _ = std::fs::remove_file(&probe);
        })
        .map_err(|e| format!("cannot write `{shown}`: {e}"))
}

/// Whether two paths name the same existing file (through symlinks and `./`); `false`
/// when either does not exist.
pub fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(x), Ok(y)) => x == y,
        _ => false,
    }
}
