//! Guidance: img2img requests to AUTOMATIC1111 WebUI-compatible servers (Forge and SD.Next
//! share its API: `POST {URL}/sdapi/v1/img2img`), spread over several servers.
//!
//! A [`Request`] is one view: the current render (base64 PNG in `init_images`), the prompt
//! with the view's word (`"bench, front view"`), the sampler's settings, `batch_size`
//! samples, and an extra field `"reparamc": {"camera": …}` (the view's `cameras.json`
//! entry) that real servers ignore and a stand-in server can read. [`Pool::run`] sends a
//! round's requests at once (bounded), each first to server `i mod n`; a server that fails
//! is set aside for the rest of the round and the request goes to another; when every
//! server is set aside, a transient failure (unreachable, timed out, 5xx) is retried after
//! a backoff that doubles, a bounded number of times, and any other failure stops.
//!
//! Invariant: every image returned was PNG or JPEG, decoded, and of the size asked for.

use super::net::{ServerError, agent, join, post_json};
use crate::render::camera::CameraSpec;
use crate::render::image::Rgb;
use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

/// The sampler's settings, the same for every request of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct Sampler {
    pub negative_prompt: String,
    pub denoising_strength: f64,
    pub steps: u32,
    pub cfg_scale: f64,
    /// Side of the square images asked for.
    pub size: u32,
    /// Samples per request (best-of-k).
    pub batch_size: u32,
}

impl Default for Sampler {
    fn default() -> Self {
        Sampler {
            negative_prompt: "blurry, text, watermark, people, cropped, frame".into(),
            denoising_strength: 0.75,
            steps: 50,
            cfg_scale: 7.0,
            size: 512,
            batch_size: 3,
        }
    }
}

/// One view's request.
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    /// The prompt with the view's word already appended.
    pub prompt: String,
    pub seed: u64,
    /// The current render, sent as `init_images`.
    pub init: Rgb,
    pub camera: CameraSpec,
}

/// Where to send, and how patiently.
#[derive(Debug, Clone, PartialEq)]
pub struct Pool {
    pub servers: Vec<String>,
    pub timeout: Duration,
    /// Further tries of a request after every server has failed it transiently.
    pub retries: u32,
    /// The first wait before such a try (doubled each time).
    pub backoff: Duration,
    /// Requests in flight at once, at most.
    pub parallel: usize,
}

/// The word for a view from its azimuth: the model's front faces −y (OpenSCAD's front
/// view), so an eye within 45° of −y sees the front, within 45° of +y the rear.
pub fn view_word(camera: &crate::render::camera::Camera) -> &'static str {
    let d = camera.eye - camera.center;
    let azimuth = d.x.atan2(-d.y).to_degrees().abs();
    if azimuth <= 45.0 {
        "front"
    } else if azimuth >= 135.0 {
        "rear"
    } else {
        "side"
    }
}

/// The JSON body of `request`.
pub fn body(request: &Request, sampler: &Sampler) -> serde_json::Value {
    let png = STANDARD.encode(request.init.encode_png());
    serde_json::json!({
        "init_images": [png],
        "prompt": request.prompt,
        "negative_prompt": sampler.negative_prompt,
        "denoising_strength": sampler.denoising_strength,
        "steps": sampler.steps,
        "cfg_scale": sampler.cfg_scale,
        "seed": request.seed,
        "width": sampler.size,
        "height": sampler.size,
        "batch_size": sampler.batch_size,
        "n_iter": 1,
        "reparamc": {"camera": request.camera},
    })
}

/// The images of an img2img answer, each PNG or JPEG of `size`×`size`.
pub fn parse_answer(
    server: &str,
    answer: &serde_json::Value,
    size: u32,
) -> Result<Vec<Rgb>, ServerError> {
    let bad = |what: String| ServerError::new(server, what, false);
    let list = answer
        .get("images")
        .and_then(|v| v.as_array())
        .ok_or_else(|| bad("the answer has no `images` list".into()))?;
    if list.is_empty() {
        return Err(bad("the answer's `images` list is empty".into()));
    }
    let mut images = Vec::with_capacity(list.len());
    for (i, item) in list.iter().enumerate() {
        let text = item
            .as_str()
            .ok_or_else(|| bad(format!("image {} is not a base64 string", i + 1)))?;
        // Some servers send a data URL.
        let text = text.split_once("base64,").map_or(text, |(_, b)| b);
        let bytes = STANDARD
            .decode(text.trim())
            .map_err(|e| bad(format!("image {} is not base64 ({e})", i + 1)))?;
        let img = decode_image(&bytes).map_err(|e| bad(format!("image {}: {e}", i + 1)))?;
        if img.width != size || img.height != size {
            let what = format!(
                "image {} is {}×{}, but {size}×{size} was asked for",
                i + 1,
                img.width,
                img.height
            );
            return Err(bad(what));
        }
        images.push(img);
    }
    Ok(images)
}

/// A PNG or JPEG image.
pub fn decode_image(bytes: &[u8]) -> Result<Rgb, String> {
    let png = bytes.starts_with(b"\x89PNG\r\n\x1a\n");
    if !png && !bytes.starts_with(&[0xff, 0xd8, 0xff]) {
        return Err("not a PNG or JPEG image".into());
    }
    Rgb::decode_picture(bytes)
}

/// One request's images, or why there are none.
type Answer = Result<Vec<Rgb>, ServerError>;

/// What servers have failed this round.
struct Round<'p> {
    pool: &'p Pool,
    agent: ureq::Agent,
    aside: Mutex<Vec<bool>>,
}

impl Round<'_> {
    /// Server to try for request `i`: its own (`i mod n`) or the next one not set aside.
    fn server_for(&self, i: usize) -> Option<usize> {
        let aside = self.aside.lock().ok()?;
        let n = aside.len();
        (0..n).map(|k| (i + k) % n).find(|&s| !aside[s])
    }

    fn set_aside(&self, s: usize) {
        if let Ok(mut aside) = self.aside.lock() {
            aside[s] = true;
        }
    }

    /// Gives every server another chance (after a backoff).
    fn restore(&self) {
        if let Ok(mut aside) = self.aside.lock() {
            aside.iter_mut().for_each(|a| *a = false);
        }
    }

    /// One request, over the servers, with retries.
    fn send(&self, i: usize, body: &serde_json::Value, size: u32) -> Answer {
        let mut wait = self.pool.backoff;
        let mut tries = 0;
        loop {
            let mut last: Option<ServerError> = None;
            while let Some(s) = self.server_for(i) {
                let server = &self.pool.servers[s];
                let url = join(server, "sdapi/v1/img2img");
                let answer = post_json(&self.agent, server, &url, body, None)
                    .and_then(|a| parse_answer(server, &a, size));
                match answer {
                    Ok(images) => return Ok(images),
                    Err(e) => {
                        self.set_aside(s);
                        last = Some(e);
                    }
                }
            }
            let e = last.unwrap_or_else(|| {
                ServerError::new(&self.pool.servers.join(", "), "every server failed", true)
            });
            if !e.transient || tries >= self.pool.retries {
                return Err(e);
            }
            tries += 1;
            std::thread::sleep(wait);
            wait *= 2;
            self.restore();
        }
    }
}

impl Pool {
    /// Sends every request (at most [`Pool::parallel`] at once) and returns each one's
    /// images, in order; the first failure that could not be got round, if any.
    pub fn run(
        &self,
        requests: &[Request],
        sampler: &Sampler,
    ) -> Result<Vec<Vec<Rgb>>, ServerError> {
        if self.servers.is_empty() {
            return Err(ServerError::new("--diffusion", "no server given", false));
        }
        let round = Round {
            pool: self,
            agent: agent(self.timeout),
            aside: Mutex::new(vec![false; self.servers.len()]),
        };
        let bodies: Vec<serde_json::Value> = requests.iter().map(|r| body(r, sampler)).collect();
        let results: Vec<Mutex<Option<Answer>>> =
            requests.iter().map(|_| Mutex::new(None)).collect();
        let next = AtomicUsize::new(0);
        let workers = self.parallel.clamp(1, requests.len().max(1));
        std::thread::scope(|scope| {
            for _ in 0..workers {
                scope.spawn(|| {
                    loop {
                        let i = next.fetch_add(1, Ordering::SeqCst);
                        if i >= requests.len() {
                            break;
                        }
                        let r = round.send(i, &bodies[i], sampler.size);
                        if let Ok(mut slot) = results[i].lock() {
                            *slot = Some(r);
                        }
                    }
                });
            }
        });
        results
            .into_iter()
            .map(|m| {
                m.into_inner().ok().flatten().unwrap_or_else(|| {
                    Err(ServerError::new(
                        &self.servers.join(", "),
                        "a request was lost",
                        false,
                    ))
                })
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::camera::{Camera, Projection};

    fn camera(rz: f64) -> Camera {
        Camera::from_openscad(
            "v",
            &[0.0, 0.0, 0.0, 70.0, 0.0, rz, 100.0],
            Projection::Perspective,
            8,
            8,
        )
        .unwrap()
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(256))]
        /// Any bytes after a JPEG or PNG signature give an image or an error, never a panic.
        #[test]
        fn bad_images_are_errors(tail in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..400), png in proptest::prelude::any::<bool>()) {
            let mut bytes = if png { b"\x89PNG\r\n\x1a\n".to_vec() } else { vec![0xff, 0xd8, 0xff] };
            bytes.extend(tail);
            let _ = decode_image(&bytes);
        }
    }

    #[test]
    fn views_are_named_by_azimuth() {
        assert_eq!(view_word(&camera(0.0)), "front");
        assert_eq!(view_word(&camera(30.0)), "front");
        assert_eq!(view_word(&camera(90.0)), "side");
        assert_eq!(view_word(&camera(-100.0)), "side");
        assert_eq!(view_word(&camera(180.0)), "rear");
    }

    #[test]
    fn answers_are_checked() {
        let img = Rgb::new(4, 4, [1.0, 0.0, 0.0]);
        let png = STANDARD.encode(img.encode_png());
        let ok =
            serde_json::json!({"images": [png.clone(), format!("data:image/png;base64,{png}")]});
        assert_eq!(parse_answer("s", &ok, 4).unwrap().len(), 2);
        let e = parse_answer("s", &ok, 8).unwrap_err();
        assert!(e.what.contains("4×4") && !e.transient, "{e}");
        let gif = serde_json::json!({"images": [STANDARD.encode(b"GIF89a....")]});
        assert!(
            parse_answer("s", &gif, 4)
                .unwrap_err()
                .what
                .contains("not a PNG or JPEG")
        );
        let none = serde_json::json!({"detail": "x"});
        assert!(
            parse_answer("s", &none, 4)
                .unwrap_err()
                .what
                .contains("no `images`")
        );
    }
}
