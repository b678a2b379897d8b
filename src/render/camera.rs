//! Cameras: explicit pinhole (or orthographic) cameras that reproduce OpenSCAD's views.
//!
//! A [`Camera`] is an eye, a point looked at, an up direction, a vertical field of view and
//! an image size. OpenSCAD 2021.01 draws with `gluPerspective(22.5°, w/h, …)` after placing
//! its camera, so a vertical field of view of 22.5° and the same eye reproduce its pixels;
//! its orthographic view shows a half-height of `distance · tan(fov/2)`, which is what
//! [`Projection::Orthographic`] means here too.
//!
//! OpenSCAD's `--camera` comes in two forms, both handled by [`Camera::from_openscad`]:
//! - the gimbal form `tx,ty,tz,rx,ry,rz,dist`: the camera looks at `(tx,ty,tz)` from
//!   `dist` away; at zero rotation it looks straight down −z with +y up, and the camera frame
//!   is then turned by `rotate([rx,ry,rz])` (x first, then y, then z);
//! - the eye form `ex,ey,ez,cx,cy,cz`: from the eye towards the center, with no roll (+z
//!   up on screen).
//!
//! `cameras.json` is a list of cameras (or `{"cameras": [...]}`); see [`CameraSpec`]. It
//! writes points as arrays of three numbers ([`Vec3`]); cameras and frames compute with
//! `glam`'s `DVec3`.

use crate::tolerance::{
    LENGTH_FLOOR, MIN_FRAMED_RADIUS, NEAR_DEPTH, PARALLEL_SINE, RENDER_ROUNDOFF,
};
use glam::{DMat3, DVec3};
use serde::{Deserialize, Serialize};

/// OpenSCAD's field of view (degrees, vertical).
pub const OPENSCAD_FOV: f64 = 22.5;

/// A point or direction as three numbers, as `cameras.json` writes it.
pub type Vec3 = [f64; 3];

/// `a` scaled to unit length (`a` itself when it has none).
pub(crate) fn unit(a: DVec3) -> DVec3 {
    a.normalize_or(a)
}

/// How the camera projects.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Projection {
    #[default]
    Perspective,
    /// Parallel rays; the visible half-height is `|eye − center| · tan(fov/2)` (OpenSCAD's).
    #[serde(alias = "ortho", alias = "orthogonal")]
    Orthographic,
}

/// An explicit camera.
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    pub name: String,
    pub eye: DVec3,
    pub center: DVec3,
    /// The up direction on screen (made orthogonal to the view direction).
    pub up: DVec3,
    /// Vertical field of view, degrees.
    pub fov: f64,
    pub projection: Projection,
    pub width: u32,
    pub height: u32,
}

/// The camera's orthonormal frame and projection constants, ready for per-pixel work.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    pub eye: DVec3,
    pub right: DVec3,
    pub up: DVec3,
    /// Unit view direction (from the eye towards the center).
    pub forward: DVec3,
    /// Pixels per unit at depth 1 (perspective) or per world unit (orthographic).
    pub focal: f64,
    pub ortho: bool,
    pub width: u32,
    pub height: u32,
}

/// A ray: `origin + t · dir`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PixelRay {
    pub origin: DVec3,
    pub dir: DVec3,
}

/// Problems with a camera description.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CameraError {
    #[error("`--camera` needs 6 numbers (eye, center) or 7 (translate, rotate, distance), got {0}")]
    Count(usize),
    #[error("`{0}` is not a number")]
    NotANumber(String),
    #[error("{0}")]
    Invalid(String),
}

impl Camera {
    /// OpenSCAD's `--camera` numbers (7: gimbal, 6: eye and center).
    pub fn from_openscad(
        name: &str,
        params: &[f64],
        projection: Projection,
        width: u32,
        height: u32,
    ) -> Result<Camera, CameraError> {
        let (eye, center, up) = match *params {
            [tx, ty, tz, rx, ry, rz, dist] => {
                let r = rotation_xyz(rx, ry, rz);
                let back = r.col(2);
                let up = r.col(1);
                let center = DVec3::new(tx, ty, tz);
                (center + back * dist, center, up)
            }
            [ex, ey, ez, cx, cy, cz] => (DVec3::new(ex, ey, ez), DVec3::new(cx, cy, cz), DVec3::Z),
            _ => return Err(CameraError::Count(params.len())),
        };
        let cam = Camera {
            name: name.to_string(),
            eye,
            center,
            up,
            fov: OPENSCAD_FOV,
            projection,
            width,
            height,
        };
        cam.validate()?;
        Ok(cam)
    }

    /// Parses OpenSCAD's `--camera` text (`"0,0,0,55,0,25,500"`).
    pub fn parse_openscad(
        name: &str,
        text: &str,
        projection: Projection,
        width: u32,
        height: u32,
    ) -> Result<Camera, CameraError> {
        let params = text
            .split(',')
            .map(|s| {
                let s = s.trim();
                s.parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| CameraError::NotANumber(s.to_string()))
            })
            .collect::<Result<Vec<f64>, _>>()?;
        Camera::from_openscad(name, &params, projection, width, height)
    }

    /// OpenSCAD's gimbal form of this camera: `tx,ty,tz,rx,ry,rz,dist` (any roll included).
    pub fn openscad_gimbal(&self) -> [f64; 7] {
        let f = self.frame();
        let back = f.forward * -1.0;
        // R = Rz(γ)·Ry(β)·Rx(α) with columns (right, up, back).
        let r = [
            [f.right[0], f.up[0], back[0]],
            [f.right[1], f.up[1], back[1]],
            [f.right[2], f.up[2], back[2]],
        ];
        let beta = (-r[2][0]).clamp(-1.0, 1.0).asin();
        let (alpha, gamma) = if r[2][0].abs() < 1.0 - RENDER_ROUNDOFF {
            (r[2][1].atan2(r[2][2]), r[1][0].atan2(r[0][0]))
        } else {
            // Gimbal lock: put the whole turn about x.
            ((-r[1][2]).atan2(r[1][1]), 0.0)
        };
        let d = (self.eye - self.center).length();
        [
            self.center[0],
            self.center[1],
            self.center[2],
            alpha.to_degrees(),
            beta.to_degrees(),
            gamma.to_degrees(),
            d,
        ]
    }

    /// The command-line arguments that make `openscad -o x.png` render this view.
    pub fn openscad_args(&self) -> Vec<String> {
        let g = self.openscad_gimbal();
        let nums: Vec<String> = g.iter().map(|v| format!("{v:.9}")).collect();
        vec![
            format!("--camera={}", nums.join(",")),
            format!("--imgsize={},{}", self.width, self.height),
            format!(
                "--projection={}",
                match self.projection {
                    Projection::Perspective => "p",
                    Projection::Orthographic => "o",
                }
            ),
        ]
    }

    /// Checks that the camera describes a view: distinct eye and center, an up direction
    /// not along the view, a sensible field of view and a non-empty image.
    pub fn validate(&self) -> Result<(), CameraError> {
        let all = [self.eye, self.center, self.up];
        if !all.iter().all(|v| v.is_finite()) || !self.fov.is_finite() {
            return Err(CameraError::Invalid(format!(
                "camera `{}` has a number that is not finite",
                self.name
            )));
        }
        let dir = self.center - self.eye;
        if dir.length() <= 0.0 {
            return Err(CameraError::Invalid(format!(
                "camera `{}`: eye and center are the same point",
                self.name
            )));
        }
        // An up along the view is no error: frame() falls back to another axis.
        if !(self.fov > 0.0 && self.fov < 180.0) {
            return Err(CameraError::Invalid(format!(
                "camera `{}`: field of view {}° is not between 0 and 180",
                self.name, self.fov
            )));
        }
        if self.width == 0 || self.height == 0 || self.width > 16384 || self.height > 16384 {
            return Err(CameraError::Invalid(format!(
                "camera `{}`: image size {}×{} is not between 1 and 16384",
                self.name, self.width, self.height
            )));
        }
        Ok(())
    }

    /// The orthonormal frame. An `up` parallel to the view direction falls back to +y
    /// (or +x), as OpenSCAD does when looking straight down.
    pub fn frame(&self) -> Frame {
        let forward = unit(self.center - self.eye);
        let mut right = forward.cross(self.up);
        let up_length = self.up.length();
        if right.length() < PARALLEL_SINE * up_length.max(LENGTH_FLOOR) || up_length == 0.0 {
            right = forward.cross(DVec3::Y);
            if right.length() < PARALLEL_SINE {
                right = forward.cross(DVec3::X);
            }
        }
        let right = unit(right);
        let up = right.cross(forward);
        let half = (self.fov.to_radians() / 2.0).tan();
        let h2 = self.height as f64 / 2.0;
        let (focal, ortho) = match self.projection {
            Projection::Perspective => (h2 / half, false),
            Projection::Orthographic => {
                let d = (self.center - self.eye).length();
                (h2 / (d * half), true)
            }
        };
        Frame {
            eye: self.eye,
            right,
            up,
            forward,
            focal,
            ortho,
            width: self.width,
            height: self.height,
        }
    }

    /// The same view seen through an image `px` pixels wider on every side: the field of
    /// view grows so that everything keeps its place and size in pixels, shifted by `px`.
    pub fn with_border(&self, px: u32) -> Camera {
        if px == 0 {
            return self.clone();
        }
        let grow = (self.height + 2 * px) as f64 / self.height as f64;
        let half = (self.fov.to_radians() / 2.0).tan() * grow;
        Camera {
            width: self.width + 2 * px,
            height: self.height + 2 * px,
            fov: 2.0 * half.atan().to_degrees(),
            ..self.clone()
        }
    }

    /// World units per pixel at the camera's center (its finest detail there).
    pub fn pixel_size(&self) -> f64 {
        let f = self.frame();
        if f.ortho {
            1.0 / f.focal
        } else {
            (self.eye - self.center).length() / f.focal
        }
    }

    /// The same view with another image size (the field of view is kept).
    pub fn with_size(&self, width: u32, height: u32) -> Camera {
        Camera {
            width,
            height,
            ..self.clone()
        }
    }
}

impl Frame {
    /// The ray through the point `(px, py)` of the image (pixel centers are at `i + 0.5`).
    #[inline]
    pub fn ray(&self, px: f64, py: f64) -> PixelRay {
        let x = px - self.width as f64 / 2.0;
        let y = self.height as f64 / 2.0 - py;
        if self.ortho {
            let origin = self.eye + (self.right * (x / self.focal) + self.up * (y / self.focal));
            PixelRay {
                origin,
                dir: self.forward,
            }
        } else {
            let dir = self.forward + (self.right * (x / self.focal) + self.up * (y / self.focal));
            PixelRay {
                origin: self.eye,
                dir,
            }
        }
    }

    /// Projects a world point to pixel coordinates and returns them with the derivative
    /// `∂(px, py)/∂P` (2×3); `None` behind (or too near) the eye.
    pub fn project(&self, p: DVec3) -> Option<([f64; 2], [DVec3; 2])> {
        let v = p - self.eye;
        let x = self.right.dot(v);
        let y = self.up.dot(v);
        let w2 = self.width as f64 / 2.0;
        let h2 = self.height as f64 / 2.0;
        if self.ortho {
            let f = self.focal;
            return Some(([w2 + f * x, h2 - f * y], [self.right * f, self.up * -f]));
        }
        let z = self.forward.dot(v);
        if z <= NEAR_DEPTH {
            return None;
        }
        let f = self.focal;
        let u = [w2 + f * x / z, h2 - f * y / z];
        let du = self.right * (f / z) - self.forward * (f * x / (z * z));
        let dv = self.forward * (f * y / (z * z)) - self.up * (f / z);
        Some((u, [du, dv]))
    }

    /// Depth of a world point along the view direction.
    #[inline]
    pub fn depth(&self, p: DVec3) -> f64 {
        self.forward.dot(p - self.eye)
    }

    /// A world direction in eye coordinates (x right, y up, z towards the viewer).
    #[inline]
    pub fn to_eye(&self, n: DVec3) -> DVec3 {
        DVec3::new(n.dot(self.right), n.dot(self.up), -n.dot(self.forward))
    }
}

/// `Rz(z)·Ry(y)·Rx(x)` (degrees).
fn rotation_xyz(x: f64, y: f64, z: f64) -> DMat3 {
    let (sx, cx) = x.to_radians().sin_cos();
    let (sy, cy) = y.to_radians().sin_cos();
    let (sz, cz) = z.to_radians().sin_cos();
    DMat3::from_rows(
        DVec3::new(cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx),
        DVec3::new(sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx),
        DVec3::new(-sy, cy * sx, cy * cx),
    )
}

/// One entry of `cameras.json`.
///
/// ```json
/// {"name": "front", "eye": [0, -500, 100], "center": [0, 0, 0], "up": [0, 0, 1],
///  "fov": 22.5, "projection": "perspective", "width": 128, "height": 128,
///  "image": "front.png"}
/// ```
/// Instead of `eye`/`center`/`up`, `"openscad": "0,0,0,55,0,25,500"` gives OpenSCAD's
/// `--camera` numbers. `up` defaults to +z, `fov` to 22.5, `projection` to perspective,
/// `image` to `<name>.png`; `width`/`height` default to the image's.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraSpec {
    pub name: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub eye: Option<Vec3>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub center: Option<Vec3>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub up: Option<Vec3>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub openscad: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fov: Option<f64>,
    #[serde(default)]
    pub projection: Projection,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width: Option<u32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<u32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub image: Option<String>,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum CamerasFile {
    List(Vec<CameraSpec>),
    Object { cameras: Vec<CameraSpec> },
}

impl CameraSpec {
    pub fn of(cam: &Camera, image: Option<String>) -> CameraSpec {
        CameraSpec {
            name: cam.name.clone(),
            eye: Some(cam.eye.to_array()),
            center: Some(cam.center.to_array()),
            up: Some(cam.up.to_array()),
            openscad: None,
            fov: Some(cam.fov),
            projection: cam.projection,
            width: Some(cam.width),
            height: Some(cam.height),
            image,
        }
    }

    /// The image file this camera's picture is in (relative to `cameras.json`).
    pub fn image_name(&self) -> String {
        self.image
            .clone()
            .unwrap_or_else(|| format!("{}.png", self.name))
    }

    /// The camera, with the image size given when the spec has none.
    pub fn camera(&self, size: Option<(u32, u32)>) -> Result<Camera, CameraError> {
        let (w, h) = match (self.width, self.height, size) {
            (Some(w), Some(h), _) => (w, h),
            (_, _, Some((w, h))) => (self.width.unwrap_or(w), self.height.unwrap_or(h)),
            _ => {
                return Err(CameraError::Invalid(format!(
                    "camera `{}` has no `width` and `height`",
                    self.name
                )));
            }
        };
        let mut cam = match (&self.openscad, self.eye, self.center) {
            (Some(text), None, None) => {
                Camera::parse_openscad(&self.name, text, self.projection, w, h).map_err(|e| {
                    CameraError::Invalid(format!("camera `{}`: `openscad`: {e}", self.name))
                })?
            }
            (Some(_), _, _) => {
                return Err(CameraError::Invalid(format!(
                    "camera `{}` has both `openscad` and `eye`/`center`; give one",
                    self.name
                )));
            }
            (None, Some(eye), Some(center)) => Camera {
                name: self.name.clone(),
                eye: DVec3::from(eye),
                center: DVec3::from(center),
                up: self.up.map_or(DVec3::Z, DVec3::from),
                fov: OPENSCAD_FOV,
                projection: self.projection,
                width: w,
                height: h,
            },
            (None, eye, _) => {
                return Err(CameraError::Invalid(format!(
                    "camera `{}` has no `{}` (give `eye` and `center`, or `openscad`)",
                    self.name,
                    if eye.is_none() { "eye" } else { "center" }
                )));
            }
        };
        if let Some(fov) = self.fov {
            cam.fov = fov;
        }
        cam.validate()?;
        Ok(cam)
    }
}

/// Parses the text of a `cameras.json`.
pub fn parse_cameras_json(text: &str) -> Result<Vec<CameraSpec>, CameraError> {
    let file: CamerasFile = serde_json::from_str(text).map_err(|e| {
        CameraError::Invalid(format!(
            "not a list of cameras ({e}); expected [{{\"name\", \"eye\", \"center\", \"up\", \"fov\", \"width\", \"height\"}}, ...]"
        ))
    })?;
    let list = match file {
        CamerasFile::List(l) | CamerasFile::Object { cameras: l } => l,
    };
    if list.is_empty() {
        return Err(CameraError::Invalid("the list of cameras is empty".into()));
    }
    let mut names = std::collections::BTreeSet::new();
    for c in &list {
        if c.name.trim().is_empty() {
            return Err(CameraError::Invalid("a camera has an empty `name`".into()));
        }
        if !names.insert(c.name.clone()) {
            return Err(CameraError::Invalid(format!(
                "two cameras are named `{}`",
                c.name
            )));
        }
    }
    Ok(list)
}

/// Writes cameras as `cameras.json` text.
pub fn cameras_json(specs: &[CameraSpec]) -> String {
    serde_json::to_string_pretty(specs).unwrap_or_else(|_| "[]".into()) + "\n"
}

/// Where a perspective camera of `width` × `height` pixels looks and from how far, from
/// any direction, to see a bounding box whole with a margin: the box's centre, and the
/// distance at which a sphere around it fits with 10% to spare. An error when the box is
/// too large (or not finite) to frame.
pub fn framing(lo: Vec3, hi: Vec3, width: u32, height: u32) -> Result<(DVec3, f64), CameraError> {
    let (low, high) = (DVec3::from(lo), DVec3::from(hi));
    let center = (low + high) * 0.5;
    let radius = ((high - low).length() / 2.0).max(MIN_FRAMED_RADIUS);
    let aspect = width as f64 / height as f64;
    let half = (OPENSCAD_FOV.to_radians() / 2.0).tan() * aspect.min(1.0);
    let dist = radius * 1.1 / half.atan().sin();
    if !(center.is_finite() && dist.is_finite()) {
        return Err(CameraError::Invalid(format!(
            "a box from {lo:?} to {hi:?} is too large to frame with a camera"
        )));
    }
    Ok((center, dist))
}

/// `n` views around a bounding box, framed so the whole box is visible with a margin:
/// OpenSCAD's default view first, then front, right, back-left from above, and top. An
/// error when the box is too large (or not finite) to frame, or the image size is invalid.
pub fn default_views(
    lo: Vec3,
    hi: Vec3,
    n: usize,
    width: u32,
    height: u32,
) -> Result<Vec<Camera>, CameraError> {
    const VIEWS: [(&str, f64, f64); 8] = [
        ("default", 55.0, 25.0),
        ("front", 80.0, 0.0),
        ("right", 75.0, 90.0),
        ("back_left", 60.0, 215.0),
        ("top", 20.0, 10.0),
        ("left", 75.0, 270.0),
        ("back", 70.0, 180.0),
        ("front_left", 65.0, -35.0),
    ];
    let (center, dist) = framing(lo, hi, width, height)?;
    (0..n)
        .map(|i| {
            let (name, rx, rz) = VIEWS[i % VIEWS.len()];
            let name = if i < VIEWS.len() {
                name.to_string()
            } else {
                format!("{name}{}", i / VIEWS.len() + 1)
            };
            let rz = rz + 360.0 * (i / VIEWS.len()) as f64 / 7.0;
            let params = [center[0], center[1], center[2], rx, 0.0, rz, dist];
            Camera::from_openscad(&name, &params, Projection::Perspective, width, height)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: DVec3, b: [f64; 3]) -> bool {
        (0..3).all(|i| (a[i] - b[i]).abs() < 1e-9)
    }

    #[test]
    fn a_border_keeps_every_point_on_its_pixel() {
        for projection in [Projection::Perspective, Projection::Orthographic] {
            let c = Camera::from_openscad(
                "t",
                &[1.0, 2.0, 3.0, 60.0, 0.0, 30.0, 50.0],
                projection,
                64,
                48,
            )
            .unwrap();
            let b = c.with_border(8);
            assert_eq!((b.width, b.height), (80, 64));
            let (f, g) = (c.frame(), b.frame());
            for p in [[0.0, 0.0, 0.0], [5.0, -3.0, 7.0], [-4.0, 6.0, 1.0]].map(DVec3::from) {
                let (u, v) = (f.project(p).unwrap().0, g.project(p).unwrap().0);
                assert!((v[0] - u[0] - 8.0).abs() < 1e-9 && (v[1] - u[1] - 8.0).abs() < 1e-9);
            }
            assert!((b.pixel_size() - c.pixel_size()).abs() < 1e-12 * c.pixel_size());
        }
    }

    #[test]
    fn gimbal_zero_looks_down() {
        let c = Camera::from_openscad(
            "t",
            &[0.0; 6].iter().copied().chain([10.0]).collect::<Vec<_>>(),
            Projection::Perspective,
            10,
            10,
        )
        .unwrap();
        assert!(close(c.eye, [0.0, 0.0, 10.0]));
        let f = c.frame();
        assert!(close(f.forward, [0.0, 0.0, -1.0]));
        assert!(close(f.up, [0.0, 1.0, 0.0]));
        assert!(close(f.right, [1.0, 0.0, 0.0]));
    }

    #[test]
    fn gimbal_front_view() {
        let c = Camera::from_openscad(
            "t",
            &[0.0, 0.0, 0.0, 90.0, 0.0, 0.0, 10.0],
            Projection::Perspective,
            10,
            10,
        )
        .unwrap();
        assert!(close(c.eye, [0.0, -10.0, 0.0]));
        assert!(close(c.frame().up, [0.0, 0.0, 1.0]));
    }

    #[test]
    fn gimbal_round_trip() {
        let p = [1.0, 2.0, 3.0, 55.0, 10.0, 25.0, 300.0];
        let c = Camera::from_openscad("t", &p, Projection::Perspective, 10, 10).unwrap();
        let g = c.openscad_gimbal();
        for i in 0..7 {
            assert!((g[i] - p[i]).abs() < 1e-9, "{g:?} vs {p:?}");
        }
    }

    #[test]
    fn projection_matches_ray() {
        let c = Camera::from_openscad(
            "t",
            &[5.0, 0.0, 0.0, 55.0, 0.0, 25.0, 300.0],
            Projection::Perspective,
            64,
            48,
        )
        .unwrap();
        let f = c.frame();
        let r = f.ray(10.5, 20.25);
        let p = r.origin + r.dir * 280.0;
        let (u, _) = f.project(p).unwrap();
        assert!((u[0] - 10.5).abs() < 1e-9 && (u[1] - 20.25).abs() < 1e-9);
    }

    #[test]
    fn bad_specs_are_reported() {
        assert!(parse_cameras_json("[]").is_err());
        assert!(parse_cameras_json("{").is_err());
        let two = r#"[{"name":"a","eye":[0,0,1],"center":[0,0,0]},{"name":"a","eye":[0,0,1],"center":[0,0,0]}]"#;
        assert!(
            parse_cameras_json(two)
                .unwrap_err()
                .to_string()
                .contains("two cameras")
        );
        let s = parse_cameras_json(r#"[{"name":"a","eye":[0,0,1],"center":[0,0,1]}]"#).unwrap();
        assert!(s[0].camera(Some((8, 8))).is_err());
    }
}
