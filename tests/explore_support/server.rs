//! A stand-in for the servers `reparamc explore` talks to, on `std::net` threads: an
//! OpenAI-compatible `/v1/chat/completions` that answers a numbered list, and a WebUI
//! `/sdapi/v1/img2img` that answers `batch_size` renders of a hidden target model from the
//! camera in the request's `"reparamc"` field (the CPU renderer), perturbed as diffusion
//! samples are (see [`sample`]).

#![allow(dead_code)]

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use reparamc::front::source::SourceMap;
use reparamc::ir::Model;
use reparamc::render::camera::{Camera, CameraSpec};
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
    start_for(vec![(String::new(), target)], mode)
}

/// Starts a server whose img2img renders, for each prompt, the target named by it (the
/// prompt before its view word), else the first.
pub fn start_for(targets: Vec<(String, Model)>, mode: Mode) -> Server {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let url = format!("http://{}", listener.local_addr().unwrap());
    let requests = Arc::new(AtomicUsize::new(0));
    let count = requests.clone();
    let target = Arc::new(targets);
    std::thread::spawn(move || {
        for stream in listener.incoming().flatten() {
            let (target, count) = (target.clone(), count.clone());
            std::thread::spawn(move || serve(stream, &target, mode, &count));
        }
    });
    Server { url, requests }
}

/// Answers the requests of one connection (kept alive) until it closes.
fn serve(stream: TcpStream, target: &[(String, Model)], mode: Mode, count: &AtomicUsize) {
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
    targets: &[(String, Model)],
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
    let seed = request["seed"].as_u64().unwrap_or(0);
    let prompt = request["prompt"].as_str().unwrap_or("");
    let kind = prompt.split(", ").next().unwrap_or("");
    let target = targets
        .iter()
        .find(|(k, _)| k.eq_ignore_ascii_case(kind))
        .map_or(&targets[0].1, |(_, m)| m);
    let camera = spec.camera(None).unwrap().with_size(size, size);
    let images: Vec<String> = (0..batch)
        .map(|i| STANDARD.encode(sample(target, &camera, seed, i)))
        .collect();
    let a = serde_json::json!({"images": images, "parameters": {}, "info": "{}"});
    ("200 OK".into(), a.to_string())
}

/// Jitter of each number of the target in a sample, relative.
const JITTER: f64 = 0.02;

/// Sample `i` of a batch, as diffusion samples differ from the truth and from each other:
/// every number of the target off by up to [`JITTER`] (differently in every view and
/// sample), drawn at twice the size and shrunk (antialiased); the second sample is lit
/// and tinted otherwise, and in a third of the requests misses the first part (a thin
/// leg); the third is a JPEG.
fn sample(target: &Model, camera: &Camera, seed: u64, i: usize) -> Vec<u8> {
    let mut state = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ (i as u64 + 1);
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..4 {
        next();
    }
    let values: Vec<f64> = target
        .slot_values()
        .iter()
        .map(|v| v * (1.0 + JITTER * (2.0 * next() - 1.0)))
        .collect();
    let parts = target.parts_at(&values).unwrap();
    let csg = if i == 1 && seed.is_multiple_of(3) {
        target.csg.without(&[0]).unwrap()
    } else {
        target.csg.clone()
    };
    let big = camera.with_size(camera.width * 2, camera.height * 2);
    let mut img = picture(&render_hard(&parts, &csg, &big), DEFAULT_SHADE)
        .resize(camera.width, camera.height);
    if i == 1 {
        for c in &mut img.data {
            *c = [(c[0] * 1.1).min(1.0), c[1] * 0.9, c[2] * 0.75];
        }
    }
    if i == 2 { jpeg(&img) } else { img.encode_png() }
}

/// `img` as a JPEG of middling quality (with its artefacts).
fn jpeg(img: &Rgb) -> Vec<u8> {
    let bytes: Vec<u8> = img
        .data
        .iter()
        .flat_map(|c| c.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8))
        .collect();
    let mut out = Vec::new();
    jpeg_encoder::Encoder::new(&mut out, 70)
        .encode(
            &bytes,
            img.width as u16,
            img.height as u16,
            jpeg_encoder::ColorType::Rgb,
        )
        .unwrap();
    out
}
