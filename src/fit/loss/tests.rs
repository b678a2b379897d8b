//! Unit tests of the image loss: its filters, its derivatives by pixel, and how pictures
//! are read as targets.

use super::*;

#[test]
fn a_border_is_background_around_the_same_picture() {
    let (w, h) = (3u32, 2u32);
    let m: Vec<f32> = vec![1.0, 0.5, 0.0, 0.25, 1.0, 1.0];
    let t = Target {
        width: w,
        height: h,
        s: m.iter().map(|v| v * 0.5).collect(),
        grey: vec![0.5; 6],
        m,
        background: [1.0; 3],
        border: 0,
        hard_edges: false,
    };
    let b = t.with_border(2);
    assert_eq!((b.width, b.height), (7, 6));
    assert_eq!(b.picture_share(), 6.0 / 42.0);
    assert_eq!(b.pooled().border, 1);
    for y in 0..6 {
        for x in 0..7 {
            let k = y * 7 + x;
            let inside = (2..5).contains(&x) && (2..4).contains(&y);
            let want = if inside {
                t.m[(y - 2) * 3 + x - 2]
            } else {
                0.0
            };
            assert_eq!(b.m[k], want, "({x}, {y})");
            assert_eq!(b.s[k], want * 0.5, "({x}, {y})");
        }
    }
}

#[test]
fn sharpening_only_near_the_object_equals_sharpening_everywhere() {
    let (w, h) = (23usize, 17usize);
    let mut img = vec![0.0f32; w * h];
    for (i, v) in img.iter_mut().enumerate() {
        let (x, y) = (i % w, i / w);
        if (6..11).contains(&x) && (1..9).contains(&y) {
            *v = ((i * 37) % 11) as f32 / 11.0 - 0.4;
        }
    }
    let spec = LossSpec::default();
    let kernel = gaussian_kernel(spec.blur);
    let whole = blur(&img, w, h, &kernel);
    let want: Vec<f32> = img.iter().zip(&whole).map(|(v, b)| v - 0.2 * b).collect();
    assert_eq!(sharpen(&img, w as u32, h as u32, &spec), want);
    // Twice, as the gradient does: the first sharpening's support has grown.
    let again = sharpen(&want, w as u32, h as u32, &spec);
    let whole2 = blur(&want, w, h, &kernel);
    let want2: Vec<f32> = want.iter().zip(&whole2).map(|(v, b)| v - 0.2 * b).collect();
    assert_eq!(again, want2);
    assert_eq!(sharpen(&[0.0; 12], 4, 3, &spec), vec![0.0; 12]);
}

#[test]
fn blur_is_the_zero_padded_convolution() {
    let kernel = gaussian_kernel(1.0);
    let r = (kernel.len() / 2) as isize;
    // Narrower and wider than the kernel.
    for (w, h) in [(3usize, 2usize), (11, 9)] {
        let img: Vec<f32> = (0..w * h).map(|i| ((i * 37) % 11) as f32 / 11.0).collect();
        let at = |x: isize, y: isize| {
            let inside = (0..w as isize).contains(&x) && (0..h as isize).contains(&y);
            if inside {
                img[y as usize * w + x as usize]
            } else {
                0.0
            }
        };
        let got = blur(&img, w, h, &kernel);
        for y in 0..h as isize {
            for x in 0..w as isize {
                let mut want = 0.0f32;
                for (j, &kj) in kernel.iter().enumerate() {
                    for (i, &ki) in kernel.iter().enumerate() {
                        want += kj * ki * at(x + i as isize - r, y + j as isize - r);
                    }
                }
                let g = got[y as usize * w + x as usize];
                assert!((g - want).abs() < 1e-5, "({x}, {y}): {g} vs {want}");
            }
        }
    }
}

#[test]
fn sharpen_is_symmetric() {
    let (w, h) = (7u32, 5u32);
    let spec = LossSpec::default();
    let a: Vec<f32> = (0..35).map(|i| ((i * 37) % 11) as f32 / 11.0).collect();
    let b: Vec<f32> = (0..35).map(|i| ((i * 13) % 7) as f32 / 7.0).collect();
    let sa = sharpen(&a, w, h, &spec);
    let sb = sharpen(&b, w, h, &spec);
    let l: f32 = sa.iter().zip(&b).map(|(x, y)| x * y).sum();
    let r: f32 = a.iter().zip(&sb).map(|(x, y)| x * y).sum();
    assert!((l - r).abs() < 1e-4);
}

#[test]
fn the_derivative_by_pixel_holds_with_both_images_blurred() {
    // A render and a target that differ on a patch; every pixel's derivative against
    // central differences of the loss (the loss is quadratic in the pixels: exact up
    // to round-off), at full size and pooled once.
    let (w, h) = (19u32, 14u32);
    let n = (w * h) as usize;
    let wave = |i: usize, a: usize, b: usize| ((i * a) % b) as f32 / b as f32;
    let patch = |i: usize| (4..12).contains(&(i % 19)) && (3..10).contains(&(i / 19));
    let channel = |a: usize| -> Vec<f32> {
        (0..n)
            .map(|i| if patch(i) { wave(i, a, 11) } else { 0.0 })
            .collect()
    };
    let render = SoftImage {
        width: w,
        height: h,
        m: channel(37),
        s: channel(13),
    };
    let target = Target::from_soft(&SoftImage {
        m: channel(29),
        s: channel(7),
        ..render.clone()
    });
    for level in [0, 1] {
        let spec = LossSpec {
            smooth: 1.3,
            shading: 0.7,
            level,
            ..LossSpec::default()
        };
        let got = view_loss(&render, &target, &spec, true);
        let step = 1e-2f32;
        for i in (0..n).step_by(5) {
            for shade in [false, true] {
                let moved = |d: f32| {
                    let mut r = render.clone();
                    let c = if shade { &mut r.s } else { &mut r.m };
                    c[i] += d;
                    view_loss(&r, &target, &spec, false).value
                };
                let fd = (moved(step) - moved(-step)) / (2.0 * f64::from(step));
                let g = f64::from(if shade { got.ds[i] } else { got.dm[i] });
                assert!(
                    (fd - g).abs() < 1e-3 * (fd.abs() + 1e-4),
                    "level {level} pixel {i} shade {shade}: {g:e} vs {fd:e}"
                );
            }
        }
    }
}

#[test]
fn unpool_is_the_transpose_of_pool() {
    let (w, h) = (5u32, 3u32);
    let a: Vec<f32> = (0..15).map(|i| ((i * 37) % 11) as f32).collect();
    let b: Vec<f32> = (0..6).map(|i| ((i * 13) % 7) as f32).collect();
    let pa = pool(&a, w, h).0;
    let ub = unpool(&b, w, h);
    let l: f32 = pa.iter().zip(&b).map(|(x, y)| x * y).sum();
    let r: f32 = a.iter().zip(&ub).map(|(x, y)| x * y).sum();
    assert!((l - r).abs() < 1e-3);
}

#[test]
fn pictures_from_one_renderer_are_told_hard_together() {
    // Drawn with hard edges on OpenSCAD's cream: a bar three pixels wide whose right
    // facet is paler, half-way to the background (a mix, to look at it alone), and a
    // plain square. Alone the bar reads as antialiased and its pale facet as half
    // covered; with the square, the two silhouettes together show hard edges and the
    // facet reads whole.
    let b = [1.0f32, 1.0, 0.9];
    let grey = [0.45f32, 0.45, 0.42];
    let pale: [f32; 3] = std::array::from_fn(|k| 0.5 * (grey[k] + b[k]));
    let mut bar = Rgb::new(12, 14, b);
    for y in 2..12 {
        for x in 2..5 {
            bar.data[y * 12 + x] = if x == 4 { pale } else { grey };
        }
    }
    let mut square = Rgb::new(14, 14, b);
    for y in 2..12 {
        for x in 2..12 {
            square.data[y * 14 + x] = grey;
        }
    }
    let facet = 5 * 12 + 4;
    let alone = Target::from_rgb(&bar);
    assert!(!alone.hard_edges);
    assert!((alone.m[facet] - 0.5).abs() < 0.05, "{}", alone.m[facet]);
    let both = Target::set_from_rgb(&[bar, square]);
    assert!(both.iter().all(|t| t.hard_edges));
    assert_eq!(both[0].m[facet], 1.0);
    assert_eq!(both[0].foreground(), 30);
}

/// A picture of something larger than the view: the frame cuts it along a third of its
/// border, on a background with some noise. Its foreground is still found.
#[test]
fn an_object_the_frame_cuts_is_still_foreground() {
    let mut img = Rgb::new(30, 30, [1.0; 3]);
    for (i, c) in img.data.iter_mut().enumerate() {
        // Background noise of up to 0.01 per channel.
        let n = ((i * 37 % 11) as f32) / 1000.0;
        *c = [1.0 - n, 1.0 - n, 1.0];
    }
    // A box from the top edge down, across all but the outer three columns: 24 of the
    // 116 border pixels are the box's.
    for y in 0..20 {
        for x in 3..27 {
            img.data[y * 30 + x] = [0.5, 0.4, 0.1];
        }
    }
    let t = Target::from_rgb(&img);
    assert_eq!(t.foreground(), 20 * 24);
}

#[test]
fn background_is_the_border_colour() {
    let mut img = Rgb::new(10, 10, [1.0, 1.0, 0.9]);
    for y in 3..7 {
        for x in 3..7 {
            img.data[y * 10 + x] = [0.9, 0.8, 0.2];
        }
    }
    let t = Target::from_rgb(&img);
    assert_eq!(t.foreground(), 16);
    assert!((t.background[2] - 0.9).abs() < 1e-6);
}
