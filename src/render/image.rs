//! Images: RGB buffers, PNG reading and writing, grids, and turning soft channels into
//! pictures.

use super::soft::SoftImage;
use crate::tolerance::{RESAMPLE_OVERLAP_FLOOR, RESAMPLE_WEIGHT_FLOOR};
use std::path::Path;

/// An RGB image with channels in `0..=1`, rows top to bottom.
#[derive(Debug, Clone, PartialEq)]
pub struct Rgb {
    pub width: u32,
    pub height: u32,
    pub data: Vec<[f32; 3]>,
}

/// Background of rendered pictures.
pub const BACKGROUND: [f32; 3] = [1.0, 1.0, 1.0];
/// Base colour of rendered surfaces (multiplied by the shade).
pub const SURFACE: [f32; 3] = [0.98, 0.82, 0.25];

impl Rgb {
    pub fn new(width: u32, height: u32, fill: [f32; 3]) -> Rgb {
        Rgb {
            width,
            height,
            data: vec![fill; (width * height) as usize],
        }
    }

    pub fn get(&self, x: u32, y: u32) -> [f32; 3] {
        self.data[(y * self.width + x) as usize]
    }

    /// Luminance (Rec. 709 weights on the stored values).
    pub fn luminance(&self) -> Vec<f32> {
        self.data
            .iter()
            .map(|c| 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2])
            .collect()
    }

    /// Encodes as an 8-bit RGB PNG.
    pub fn encode_png(&self) -> Vec<u8> {
        let mut out = Vec::new();
        {
            let mut enc = png::Encoder::new(&mut out, self.width, self.height);
            enc.set_color(png::ColorType::Rgb);
            enc.set_depth(png::BitDepth::Eight);
            let bytes: Vec<u8> = self
                .data
                .iter()
                .flat_map(|c| c.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8))
                .collect();
            // Writing to memory cannot fail for a well-formed header.
            if let Ok(mut w) = enc.write_header() {
                let _ = w.write_image_data(&bytes);
            }
        }
        out
    }

    /// Decodes a PNG (any bit depth and colour type; alpha is composited onto white).
    pub fn decode_png(bytes: &[u8]) -> Result<Rgb, String> {
        let mut dec = png::Decoder::new(std::io::Cursor::new(bytes));
        dec.set_transformations(png::Transformations::normalize_to_color8());
        let mut reader = dec.read_info().map_err(|e| describe_png_error(&e))?;
        let size = reader
            .output_buffer_size()
            .ok_or_else(|| "the image is too large".to_string())?;
        let mut buf = vec![0u8; size];
        let info = reader
            .next_frame(&mut buf)
            .map_err(|e| describe_png_error(&e))?;
        let (w, h) = (info.width, info.height);
        if w == 0 || h == 0 {
            return Err("the image is empty".into());
        }
        let ch = match info.color_type {
            png::ColorType::Grayscale => 1,
            png::ColorType::GrayscaleAlpha => 2,
            png::ColorType::Rgb => 3,
            png::ColorType::Rgba => 4,
            png::ColorType::Indexed => return Err("unsupported palette image".into()),
        };
        let mut data = Vec::with_capacity((w * h) as usize);
        for y in 0..h as usize {
            let row = &buf[y * info.line_size..];
            for x in 0..w as usize {
                let px = &row[x * ch..x * ch + ch];
                let f = |v: u8| v as f32 / 255.0;
                let (rgb, a) = match ch {
                    1 => ([f(px[0]); 3], 1.0),
                    2 => ([f(px[0]); 3], f(px[1])),
                    3 => ([f(px[0]), f(px[1]), f(px[2])], 1.0),
                    _ => ([f(px[0]), f(px[1]), f(px[2])], f(px[3])),
                };
                data.push(rgb.map(|c| c * a + (1.0 - a)));
            }
        }
        Ok(Rgb {
            width: w,
            height: h,
            data,
        })
    }

    /// Reads a PNG file; the error says what is wrong (not the file name).
    pub fn read_png(path: &Path) -> Result<Rgb, String> {
        let bytes = std::fs::read(path).map_err(|e| format!("cannot read it: {e}"))?;
        if bytes.is_empty() {
            return Err("the file is empty".into());
        }
        if !bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
            return Err("not a PNG image".into());
        }
        Rgb::decode_png(&bytes)
    }

    /// Reads a PNG, JPEG or WebP picture, told apart by its content, not its name.
    pub fn read_picture(path: &Path) -> Result<Rgb, String> {
        let bytes = std::fs::read(path).map_err(|e| format!("cannot read it: {e}"))?;
        if bytes.is_empty() {
            return Err("the file is empty".into());
        }
        Rgb::decode_picture(&bytes)
    }

    /// Decodes a PNG, JPEG or WebP picture, told apart by its content.
    pub fn decode_picture(bytes: &[u8]) -> Result<Rgb, String> {
        if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
            return Rgb::decode_png(bytes);
        }
        let format = match image::guess_format(bytes) {
            Ok(f @ (image::ImageFormat::Jpeg | image::ImageFormat::WebP)) => f,
            _ => return Err("not a PNG, JPEG or WebP image".into()),
        };
        let img = image::load_from_memory_with_format(bytes, format)
            .map_err(|e| format!("cannot decode it: {e}"))?
            .to_rgb8();
        Ok(Rgb {
            width: img.width(),
            height: img.height(),
            data: img
                .pixels()
                .map(|p| p.0.map(|v| f32::from(v) / 255.0))
                .collect(),
        })
    }

    /// Resamples to another size (box filter when shrinking, bilinear when growing).
    pub fn resize(&self, width: u32, height: u32) -> Rgb {
        if width == self.width && height == self.height {
            return self.clone();
        }
        let mut out = Rgb::new(width, height, [0.0; 3]);
        // Each output pixel averages the source pixels its square overlaps, weighted by the
        // overlap: a product of a column weight and a row weight, worked out once per column
        // and per row.
        let columns = overlaps(self.width, width);
        let rows = overlaps(self.height, height);
        for (y, (iy0, wys)) in rows.iter().enumerate() {
            for (x, (ix0, wxs)) in columns.iter().enumerate() {
                let mut acc = [0.0f64; 3];
                let mut wsum = 0.0;
                for (iy, &wy) in (*iy0..).zip(wys) {
                    for (ix, &wx) in (*ix0..).zip(wxs) {
                        let c = self.get(ix, iy);
                        for k in 0..3 {
                            acc[k] += wx * wy * c[k] as f64;
                        }
                        wsum += wx * wy;
                    }
                }
                out.data[y * width as usize + x] =
                    acc.map(|v| (v / wsum.max(RESAMPLE_WEIGHT_FLOOR)) as f32);
            }
        }
        out
    }
}

/// For each of `to` output pixels along an axis of `from` source pixels: the first source
/// pixel its interval overlaps and the overlap with each source pixel from there on.
fn overlaps(from: u32, to: u32) -> Vec<(u32, Vec<f64>)> {
    let scale = from as f64 / to as f64;
    (0..to)
        .map(|i| {
            let a = i as f64 * scale;
            let b = a + scale;
            let first = a.floor() as u32;
            let end = (b.ceil() as u32).min(from).max(first + 1).min(from);
            let w = (first..end)
                .map(|j| (b.min(j as f64 + 1.0) - a.max(j as f64)).max(RESAMPLE_OVERLAP_FLOOR))
                .collect();
            (first, w)
        })
        .collect()
}

fn describe_png_error(e: &png::DecodingError) -> String {
    match e {
        png::DecodingError::IoError(io) if io.kind() == std::io::ErrorKind::UnexpectedEof => {
            "the PNG is truncated".into()
        }
        png::DecodingError::IoError(io) => format!("cannot read it: {io}"),
        png::DecodingError::Format(f) => {
            let text = f.to_string();
            if text.to_lowercase().contains("eof") || text.to_lowercase().contains("end of") {
                format!("the PNG is truncated ({text})")
            } else {
                format!("not a valid PNG ({text})")
            }
        }
        other => format!("cannot decode the PNG ({other})"),
    }
}

/// A picture of soft channels: surfaces in [`SURFACE`] times their shade on [`BACKGROUND`].
pub fn picture(soft: &SoftImage) -> Rgb {
    let data = soft
        .m
        .iter()
        .zip(&soft.s)
        .map(|(&m, &s)| std::array::from_fn(|k| BACKGROUND[k] * (1.0 - m) + SURFACE[k] * s))
        .collect();
    Rgb {
        width: soft.width,
        height: soft.height,
        data,
    }
}

/// Images laid out left to right, top to bottom, `cols` per row, with a 2-pixel gap.
pub fn grid(images: &[Rgb], cols: usize) -> Rgb {
    let cols = cols.max(1).min(images.len().max(1));
    let rows = images.len().div_ceil(cols);
    let cw = images.iter().map(|i| i.width).max().unwrap_or(1);
    let ch = images.iter().map(|i| i.height).max().unwrap_or(1);
    let gap = 2;
    let w = cols as u32 * cw + (cols as u32 - 1) * gap;
    let h = rows as u32 * ch + (rows.max(1) as u32 - 1) * gap;
    let mut out = Rgb::new(w.max(1), h.max(1), [0.6, 0.6, 0.6]);
    for (k, img) in images.iter().enumerate() {
        let ox = (k % cols) as u32 * (cw + gap);
        let oy = (k / cols) as u32 * (ch + gap);
        for y in 0..img.height {
            for x in 0..img.width {
                out.data[((oy + y) * out.width + ox + x) as usize] = img.get(x, y);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn png_round_trip() {
        let mut img = Rgb::new(3, 2, [0.0; 3]);
        img.data[4] = [1.0, 0.5, 0.0];
        let bytes = img.encode_png();
        let back = Rgb::decode_png(&bytes).unwrap();
        assert_eq!(back.width, 3);
        assert!((back.data[4][1] - 128.0 / 255.0).abs() < 1e-6);
        assert!(Rgb::decode_png(&bytes[..bytes.len() / 2]).is_err());
    }
}
