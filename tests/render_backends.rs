//! The wgpu backend computes what the CPU backend computes: the same pictures (≥ 99.5% of
//! pixels), the same loss (within 1e-3 relative), and the same gradient direction, with
//! items of different albedos.

#![cfg(feature = "gpu")]

use reparamc::fit::Parametric;
use reparamc::fit::loss::{LossSpec, Target, image_loss};
use reparamc::render::camera::default_views;
use reparamc::render::gpu::GpuBackend;
use reparamc::render::scene::DEFAULT_SHADE;
use reparamc::render::soft::prepare_view;
use reparamc::render::{Backend, CpuBackend};
use std::path::PathBuf;

fn model(rel: &str) -> reparamc::ir::Model {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(rel);
    let mut sources = reparamc::front::source::SourceMap::new();
    reparamc::load_model(&mut sources, &path)
        .unwrap_or_else(|d| panic!("{rel}: {}", d.message))
        .model
}

#[test]
fn cpu_and_wgpu_agree() {
    let mut gpu = match GpuBackend::new() {
        Ok(g) => g,
        Err(e) => {
            eprintln!("skipped: no wgpu adapter ({e}); run scripts/setup for lavapipe");
            return;
        }
    };
    eprintln!("{}", gpu.name());
    let mut cpu = CpuBackend::new();
    for rel in [
        "examples/chair.scad",
        "examples/toy_cart.scad",
        "examples/lamp.scad",
        "examples/mug.scad",
        "examples/bookshelf.scad",
        "examples/paper/bottle.scad",
        "examples/paper/camera.scad",
    ] {
        let m = model(rel);
        let p = Parametric::new(&m);
        let (lo, hi) = m.bounds().unwrap();
        let cams = default_views(lo, hi, 3, 96, 80).unwrap();
        let albedo: Vec<f64> = (0..m.parts.len())
            .map(|i| 0.6 + 0.15 * (i % 4) as f64)
            .collect();
        let scene = p.scene(&p.x0).with_albedo(&albedo);
        let shades = vec![DEFAULT_SHADE; cams.len()];
        // Pictures, hard and soft.
        for sigma in [None, Some(0.7)] {
            let views: Vec<_> = cams
                .iter()
                .map(|c| prepare_view(&scene, c, sigma))
                .collect();
            let a = cpu.render(&scene, &views, sigma, &shades);
            let b = gpu.render(&scene, &views, sigma, &shades);
            for ((sa, ha), (sb, hb)) in a.iter().zip(&b) {
                let n = sa.m.len();
                let same_mask = ha.mask().zip(hb.mask()).filter(|(x, y)| x == y).count();
                let close = (0..n)
                    .filter(|&i| {
                        (sa.m[i] - sb.m[i]).abs() < 0.02 && (sa.s[i] - sb.s[i]).abs() < 0.02
                    })
                    .count();
                let (fm, fc) = (same_mask as f64 / n as f64, close as f64 / n as f64);
                assert!(
                    fm >= 0.995,
                    "{rel} σ={sigma:?}: masks agree on {:.2}% of pixels",
                    100.0 * fm
                );
                assert!(
                    fc >= 0.995,
                    "{rel} σ={sigma:?}: channels agree on {:.2}% of pixels",
                    100.0 * fc
                );
            }
        }
        // Loss and gradient against a target made from moved slots.
        let xt: Vec<f64> =
            p.x0.iter()
                .enumerate()
                .map(|(i, v)| v + p.scale * 0.015 * (((i * 5) % 7) as f64 - 3.0) / 3.0)
                .collect();
        let st = p.scene(&xt);
        let targets: Vec<Target> = cams
            .iter()
            .map(|c| {
                let v = prepare_view(&st, c, Some(0.5));
                Target::from_soft(&cpu.render(&st, &[v], Some(0.5), &[DEFAULT_SHADE])[0].0)
            })
            .collect();
        let sigma = 1.0;
        let views: Vec<_> = cams
            .iter()
            .map(|c| prepare_view(&scene, c, Some(sigma)))
            .collect();
        let spec = LossSpec::default();
        let la = image_loss(
            &mut cpu, &scene, &views, sigma, &shades, &targets, &spec, true,
        );
        let lb = image_loss(
            &mut gpu, &scene, &views, sigma, &shades, &targets, &spec, true,
        );
        let rel_err = (la.total() - lb.total()).abs() / la.total();
        assert!(
            rel_err < 1e-3,
            "{rel}: loss {} (CPU) vs {} (wgpu)",
            la.total(),
            lb.total()
        );
        let ga = p.chain(&la.dtheta);
        let gb = p.chain(&lb.dtheta);
        let dot: f64 = ga.iter().zip(&gb).map(|(a, b)| a * b).sum();
        let na = ga.iter().map(|a| a * a).sum::<f64>().sqrt();
        let nb = gb.iter().map(|a| a * a).sum::<f64>().sqrt();
        let cos = dot / (na * nb);
        assert!(cos > 0.999, "{rel}: gradients differ (cosine {cos})");
        eprintln!(
            "{rel}: loss {:.6} vs {:.6} (rel. {:.1e}), gradient cosine {:.6}",
            la.total(),
            lb.total(),
            rel_err,
            cos
        );
    }
}
