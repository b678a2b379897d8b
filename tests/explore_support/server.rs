//! A stand-in for the servers `reparamc explore` talks to, on `std::net` threads: an
//! OpenAI-compatible `/v1/chat/completions` that answers a numbered list, and a WebUI
//! `/sdapi/v1/img2img` that answers `batch_size` renders of a hidden target model from the
//! camera in the request's `"reparamc"` field (the CPU renderer), the first exact and the
//! others as diffusion samples differ: shifted a pixel or two and tinted.

#![allow(dead_code)]

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use reparamc::front::source::SourceMap;
use reparamc::ir::Model;
use reparamc::render::camera::CameraSpec;
use reparamc::render::cpu::{picture, render_hard};
use reparamc::render::image::Rgb;
use reparamc::render::scene::DEFAULT_SHADE;
use std::io::{BufRead, BufReader, Read, Write};
use std::net::{TcpListener, TcpStream};
use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

/// How the img2img endpoint behaves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Mode {
    /// Renders of the target.
    Good,
    /// HTTP 500 to every request.
    Fails,
    /// Good for this many requests, then JSON that is not.
    MalformedAfter(usize),
    /// Images of half the size asked for.
    WrongSize,
}

/// A running stand-in server.
pub struct Server {
    pub url: String,
    /// img2img requests answered so far.
    pub requests: Arc<AtomicUsize>,
}

/// The model of `text` (a file named `path`).
pub fn model_of(path: &str, text: &str) -> Model {
    let mut sources = SourceMap::new();
    reparamc::load_model_text(&mut sources, Path::new(path), text.as_bytes())
        .unwrap()
        .model
}

/// Starts a server whose img2img renders `target`.
pub fn start(target: Model, mode: Mode) -> Server {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let url = format!("http://{}", listener.local_addr().unwrap());
    let requests = Arc::new(AtomicUsize::new(0));
    let count = requests.clone();
    let target = Arc::new(target);
    std::thread::spawn(move || {
        for stream in listener.incoming().flatten() {
            let (target, count) = (target.clone(), count.clone());
            std::thread::spawn(move || serve(stream, &target, mode, &count));
        }
    });
    Server { url, requests }
}

/// Answers the requests of one connection (kept alive) until it closes.
fn serve(stream: TcpStream, target: &Model, mode: Mode, count: &AtomicUsize) {
    let mut reader = BufReader::new(stream.try_clone().unwrap());
    let mut out = stream;
    loop {
        let mut line = String::new();
        if reader.read_line(&mut line).unwrap_or(0) == 0 {
            return;
        }
        let path = line.split_whitespace().nth(1).unwrap_or("").to_string();
        let mut length = 0;
        loop {
            let mut h = String::new();
            if reader.read_line(&mut h).unwrap_or(0) == 0 {
                return;
            }
            if h.trim().is_empty() {
                break;
            }
            if let Some((k, v)) = h.split_once(':')
                && k.eq_ignore_ascii_case("content-length")
            {
                length = v.trim().parse().unwrap_or(0);
            }
        }
        let mut body = vec![0; length];
        if reader.read_exact(&mut body).is_err() {
            return;
        }
        let (status, text) = answer(&path, &body, target, mode, count);
        let head = format!(
            "HTTP/1.1 {status}\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n",
            text.len()
        );
        if out.write_all(head.as_bytes()).is_err() || out.write_all(text.as_bytes()).is_err() {
            return;
        }
    }
}

const KINDS: &str = "Sure! Here are some different types of chair:\n\n\
    1. **Bench**: a long seat for several people.\n\
    2. Stool - a seat without a back or arms.\n\
    3. Bar stool: a tall stool.\n";

fn answer(
    path: &str,
    body: &[u8],
    target: &Model,
    mode: Mode,
    count: &AtomicUsize,
) -> (String, String) {
    if path.ends_with("/chat/completions") {
        let a =
            serde_json::json!({"choices": [{"message": {"role": "assistant", "content": KINDS}}]});
        return ("200 OK".into(), a.to_string());
    }
    if !path.ends_with("/sdapi/v1/img2img") {
        return ("404 Not Found".into(), "{}".into());
    }
    let n = count.fetch_add(1, Ordering::SeqCst);
    match mode {
        Mode::Fails => {
            return (
                "500 Internal Server Error".into(),
                "{\"error\":\"out of memory\"}".into(),
            );
        }
        Mode::MalformedAfter(k) if n >= k => return ("200 OK".into(), "{\"images\": [".into()),
        _ => {}
    }
    let request: serde_json::Value = serde_json::from_slice(body).unwrap();
    let spec: CameraSpec = serde_json::from_value(request["reparamc"]["camera"].clone()).unwrap();
    let size = request["width"].as_u64().unwrap() as u32;
    let size = if mode == Mode::WrongSize {
        size / 2
    } else {
        size
    };
    let batch = request["batch_size"].as_u64().unwrap_or(1) as usize;
    let camera = spec.camera(None).unwrap().with_size(size, size);
    let exact = picture(
        &render_hard(&target.parts, &target.csg, &camera),
        DEFAULT_SHADE,
    );
    let images: Vec<String> = (0..batch)
        .map(|i| STANDARD.encode(sample(&exact, i).encode_png()))
        .collect();
    let a = serde_json::json!({"images": images, "parameters": {}, "info": "{}"});
    ("200 OK".into(), a.to_string())
}

/// Sample `i` of a batch: the render itself, or shifted by `i` pixels to the right and
/// tinted, as diffusion samples differ from each other.
fn sample(exact: &Rgb, i: usize) -> Rgb {
    if i == 0 {
        return exact.clone();
    }
    let mut img = Rgb::new(exact.width, exact.height, [1.0; 3]);
    for y in 0..exact.height {
        for x in 0..exact.width {
            let from = x.saturating_sub(2 * i as u32);
            let c = exact.get(from, y);
            img.data[(y * exact.width + x) as usize] = [c[0], c[1] * 0.9, c[2] * 0.8];
        }
    }
    img
}
