//! The wgpu backend: the per-pixel soft-silhouette kernel in WGSL (`shaders/soft.wgsl`).
//!
//! The CPU prepares what every pixel shares (camera frames, silhouette hulls, item
//! programs) exactly as for the CPU backend; the GPU evaluates every pixel of every view in
//! one dispatch and appends gradient entries; the loss and the chain to part parameters run
//! on the CPU with the same code as the CPU backend, so both backends compute the same
//! numbers (up to `f32` rounding). On a machine without a GPU, Mesa's lavapipe provides a
//! Vulkan device that runs the shader on the CPU.

use super::scene::{Kind, NSHADE, NTHETA, Op, Scene};
use super::soft::{Entries, Entry, HardImage, SoftImage, SurfaceEntry, ViewPrep, theta_gradient};
use super::{Backend, LossOut};
use crate::fit::loss::{LossSpec, Target, view_loss};
use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

const SHADER: &str = include_str!("../../shaders/soft.wgsl");
const WORKGROUP: u32 = 64;

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct GParams {
    view_count: u32,
    item_count: u32,
    part_count: u32,
    total_pixels: u32,
    sigma: f32,
    hard: u32,
    want_entries: u32,
    entry_capacity: u32,
    surface_capacity: u32,
    pad: [u32; 3],
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct GView {
    eye: [f32; 4],
    right: [f32; 4],
    up: [f32; 4],
    forward: [f32; 4],
    shade_a: [f32; 4],
    shade_b: [f32; 4],
    dims: [u32; 4],
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct GPart {
    inv0: [f32; 4],
    inv1: [f32; 4],
    inv2: [f32; 4],
    lo: [f32; 4],
    hi: [f32; 4],
    center: [f32; 4],
    flags: [u32; 4],
    l0: [f32; 4],
    l1: [f32; 4],
    l2: [f32; 4],
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct GItem {
    a: [u32; 4],
    b: [u32; 4],
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct GSurfaceEntry {
    a: [u32; 4],
    b: [f32; 4],
    n: [f32; 4],
    q: [f32; 4],
    l: [f32; 4],
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct GEntry {
    a: [u32; 4],
    b: [f32; 4],
    c: [f32; 4],
}

/// The wgpu renderer.
pub struct GpuBackend {
    device: wgpu::Device,
    queue: wgpu::Queue,
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    info: String,
    /// Entries the last dispatch needed (the next one reserves at least this many).
    capacity: usize,
    surface_capacity: usize,
}

/// Whether this machine may have a hardware GPU worth probing for (on Linux: a DRM render
/// node or an NVIDIA device). Probing creates a Vulkan instance, which is slow and, on a
/// headless machine, makes the platform libraries print warnings.
pub fn hardware_likely() -> bool {
    if !cfg!(target_os = "linux") {
        return true;
    }
    let any = |dir: &str, prefix: &str| {
        std::fs::read_dir(dir).is_ok_and(|r| {
            r.filter_map(|e| e.ok())
                .any(|e| e.file_name().to_string_lossy().starts_with(prefix))
        })
    };
    any("/dev/dri", "renderD") || any("/dev", "nvidia")
}

impl GpuBackend {
    /// Finds a Vulkan adapter (a GPU, or lavapipe) and compiles the shader.
    pub fn new() -> Result<GpuBackend, String> {
        GpuBackend::with_software(true)
    }

    /// Like [`GpuBackend::new`]; a software adapter (lavapipe) only if `software` is true.
    pub fn with_software(software: bool) -> Result<GpuBackend, String> {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends: wgpu::Backends::VULKAN,
            ..wgpu::InstanceDescriptor::new_without_display_handle()
        });
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            ..Default::default()
        }))
        .map_err(|e| format!("no Vulkan adapter: {e}"))?;
        let info = adapter.get_info();
        if !software && info.device_type == wgpu::DeviceType::Cpu {
            return Err(format!("only a software adapter ({})", info.name));
        }
        let limits = adapter.limits();
        if limits.max_storage_buffers_per_shader_stage < 13 {
            return Err(format!(
                "{} allows only {} storage buffers per shader stage",
                info.name, limits.max_storage_buffers_per_shader_stage
            ));
        }
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("reparamc"),
            required_features: wgpu::Features::empty(),
            required_limits: limits,
            ..Default::default()
        }))
        .map_err(|e| format!("cannot open {}: {e}", info.name))?;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("soft.wgsl"),
            source: wgpu::ShaderSource::Wgsl(SHADER.into()),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("soft"),
            layout: None,
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(format!("the shader does not compile on {}: {e}", info.name));
        }
        let layout = pipeline.get_bind_group_layout(0);
        Ok(GpuBackend {
            device,
            queue,
            pipeline,
            layout,
            info: format!("wgpu ({}, {:?})", info.name, info.backend),
            capacity: 1 << 16,
            surface_capacity: 1 << 12,
        })
    }

    /// Runs the kernel over every view.
    fn dispatch(
        &mut self,
        scene: &Scene,
        views: &[ViewPrep],
        sigma: Option<f64>,
        shades: &[[f64; NSHADE]],
        want_entries: bool,
    ) -> (Vec<SoftImage>, Vec<HardImage>, Vec<Entries>) {
        loop {
            let (soft, hard, entries, needed, needed_s) =
                self.dispatch_once(scene, views, sigma, shades, want_entries);
            if needed <= self.capacity && needed_s <= self.surface_capacity {
                return (soft, hard, entries);
            }
            self.capacity = self.capacity.max(needed + needed / 4);
            self.surface_capacity = self.surface_capacity.max(needed_s + needed_s / 4);
        }
    }

    fn dispatch_once(
        &mut self,
        scene: &Scene,
        views: &[ViewPrep],
        sigma: Option<f64>,
        shades: &[[f64; NSHADE]],
        want_entries: bool,
    ) -> (Vec<SoftImage>, Vec<HardImage>, Vec<Entries>, usize, usize) {
        let np = scene.parts.len();
        let ni = scene.items.len();
        // Views.
        let mut gviews = Vec::with_capacity(views.len());
        let mut offset = 0u32;
        for (v, sh) in views.iter().zip(shades) {
            let f = &v.frame;
            let v4 = |a: [f64; 3], w: f64| [a[0] as f32, a[1] as f32, a[2] as f32, w as f32];
            gviews.push(GView {
                eye: v4(f.eye, f.focal),
                right: v4(f.right, if f.ortho { 1.0 } else { 0.0 }),
                up: v4(f.up, 0.0),
                forward: v4(f.forward, 0.0),
                shade_a: [sh[0] as f32, sh[1] as f32, sh[2] as f32, sh[3] as f32],
                shade_b: [sh[4] as f32, 0.0, 0.0, 0.0],
                dims: [f.width, f.height, offset, 0],
            });
            offset += f.width * f.height;
        }
        let total = offset;
        // Parts.
        let gparts: Vec<GPart> = scene
            .parts
            .iter()
            .map(|p| {
                let lrow = |i: usize| {
                    [
                        p.l[i][0] as f32,
                        p.l[i][1] as f32,
                        p.l[i][2] as f32,
                        p.t[i] as f32,
                    ]
                };
                let row = |i: usize| {
                    [
                        p.inv[i][0] as f32,
                        p.inv[i][1] as f32,
                        p.inv[i][2] as f32,
                        p.inv_t[i] as f32,
                    ]
                };
                GPart {
                    inv0: row(0),
                    inv1: row(1),
                    inv2: row(2),
                    lo: [p.lo[0] as f32, p.lo[1] as f32, p.lo[2] as f32, p.r1 as f32],
                    hi: [p.hi[0] as f32, p.hi[1] as f32, p.hi[2] as f32, p.r2 as f32],
                    center: [
                        p.center[0] as f32,
                        p.center[1] as f32,
                        p.center[2] as f32,
                        0.0,
                    ],
                    flags: [
                        match p.kind {
                            Kind::Box => 0,
                            Kind::Frustum => 1,
                            Kind::Sphere => 2,
                        },
                        p.valid as u32,
                        p.centered as u32,
                        0,
                    ],
                    l0: lrow(0),
                    l1: lrow(1),
                    l2: lrow(2),
                }
            })
            .collect();
        // Hulls and rectangles.
        let mut hulls: Vec<[u32; 4]> = Vec::with_capacity(views.len() * np);
        let mut edges: Vec<[f32; 4]> = Vec::new();
        let mut verts: Vec<[f32; 2]> = Vec::new();
        let mut rects: Vec<[i32; 4]> = Vec::with_capacity(views.len() * ni);
        for v in views {
            for h in &v.hulls {
                match h {
                    Some(h) => {
                        hulls.push([edges.len() as u32, h.edges.len() as u32, 1, 0]);
                        for (k, &(n, c)) in h.edges.iter().enumerate() {
                            edges.push([n[0] as f32, n[1] as f32, c as f32, 0.0]);
                            verts.push([h.verts[k][0] as f32, h.verts[k][1] as f32]);
                        }
                    }
                    None => hulls.push([0, 0, 0, 0]),
                }
            }
            for r in &v.rects {
                rects.push(match r {
                    Some(r) => [r[0] as i32, r[1] as i32, r[2] as i32, r[3] as i32],
                    None => [-1, 0, 0, 0],
                });
            }
        }
        // Item programs.
        let mut code: Vec<u32> = Vec::new();
        let mut items: Vec<GItem> = Vec::with_capacity(ni);
        let mut progs = Vec::with_capacity(ni);
        for it in &scene.items {
            let start = code.len() as u32;
            for op in &it.program {
                code.push(match *op {
                    Op::Part(i) => i,
                    Op::Union(n) => 1 << 24 | n,
                    Op::Difference(n) => 2 << 24 | n,
                    Op::Intersection(n) => 3 << 24 | n,
                });
            }
            progs.push((start, it.program.len() as u32));
        }
        for (it, (start, len)) in scene.items.iter().zip(progs) {
            let pstart = code.len() as u32;
            code.extend(it.parts.iter().map(|&p| p as u32));
            let albedo = (scene.albedo_of(items.len()) as f32).to_bits();
            let b = match &it.split {
                Some((k, negs)) => {
                    let nstart = code.len() as u32;
                    code.extend(negs.iter().map(|&p| p as u32));
                    [*k as u32, nstart, negs.len() as u32, albedo]
                }
                None => [0, 0, 0, albedo],
            };
            items.push(GItem {
                a: [start, len, pstart, it.parts.len() as u32],
                b,
            });
        }
        let capacity = if want_entries { self.capacity } else { 1 };
        let scapacity = if want_entries {
            self.surface_capacity
        } else {
            1
        };
        let params = GParams {
            view_count: views.len() as u32,
            item_count: ni as u32,
            part_count: np as u32,
            total_pixels: total,
            sigma: sigma.unwrap_or(1.0) as f32,
            hard: sigma.is_none() as u32,
            want_entries: want_entries as u32,
            entry_capacity: capacity as u32,
            surface_capacity: scapacity as u32,
            pad: [0; 3],
        };
        let dev = &self.device;
        let init = |label: &str, bytes: &[u8], usage: wgpu::BufferUsages| {
            // Bindings need at least one element.
            let pad = [0u8; 16];
            dev.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: if bytes.is_empty() { &pad } else { bytes },
                usage,
            })
        };
        let storage = wgpu::BufferUsages::STORAGE;
        let b_params = init(
            "params",
            bytemuck::bytes_of(&params),
            wgpu::BufferUsages::UNIFORM,
        );
        let b_views = init("views", bytemuck::cast_slice(&gviews), storage);
        let b_parts = init("parts", bytemuck::cast_slice(&gparts), storage);
        let b_hulls = init("hulls", bytemuck::cast_slice(&hulls), storage);
        let b_edges = init("edges", bytemuck::cast_slice(&edges), storage);
        let b_verts = init("verts", bytemuck::cast_slice(&verts), storage);
        let b_rects = init("rects", bytemuck::cast_slice(&rects), storage);
        let b_items = init("items", bytemuck::cast_slice(&items), storage);
        let b_code = init("code", bytemuck::cast_slice(&code), storage);
        let out = |label: &str, size: u64| {
            dev.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(16),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        let n = total as u64;
        let b_soft = out("soft", n * 8);
        let b_hard = out("hard", n * 16);
        let b_item = out("item", n * 4);
        let entry_bytes = 16 + capacity as u64 * std::mem::size_of::<GEntry>() as u64;
        let sentry_bytes = 16 + scapacity as u64 * std::mem::size_of::<GSurfaceEntry>() as u64;
        let b_sentries = init(
            "surface-entries",
            &vec![0u8; sentry_bytes as usize],
            storage | wgpu::BufferUsages::COPY_SRC,
        );
        let b_entries = init(
            "entries",
            &vec![0u8; entry_bytes as usize],
            storage | wgpu::BufferUsages::COPY_SRC,
        );
        let bind = dev.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("soft"),
            layout: &self.layout,
            entries: &[
                &b_params,
                &b_views,
                &b_parts,
                &b_hulls,
                &b_edges,
                &b_verts,
                &b_rects,
                &b_items,
                &b_code,
                &b_soft,
                &b_hard,
                &b_item,
                &b_entries,
                &b_sentries,
            ]
            .iter()
            .enumerate()
            .map(|(i, b)| wgpu::BindGroupEntry {
                binding: i as u32,
                resource: b.as_entire_binding(),
            })
            .collect::<Vec<_>>(),
        });
        let read = |label: &str, size: u64| {
            dev.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(16),
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let r_soft = read("soft-read", n * 8);
        let r_hard = read("hard-read", n * 16);
        let r_item = read("item-read", n * 4);
        let r_entries = read("entries-read", if want_entries { entry_bytes } else { 16 });
        let r_sentries = read(
            "surface-entries-read",
            if want_entries { sentry_bytes } else { 16 },
        );
        let mut enc = dev.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
        {
            let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("soft"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &bind, &[]);
            let groups = total.div_ceil(WORKGROUP).max(1);
            let x = groups.min(65535);
            let y = groups.div_ceil(x);
            pass.dispatch_workgroups(x, y, 1);
        }
        enc.copy_buffer_to_buffer(&b_soft, 0, &r_soft, 0, n * 8);
        enc.copy_buffer_to_buffer(&b_hard, 0, &r_hard, 0, n * 16);
        enc.copy_buffer_to_buffer(&b_item, 0, &r_item, 0, n * 4);
        if want_entries {
            enc.copy_buffer_to_buffer(&b_entries, 0, &r_entries, 0, entry_bytes);
            enc.copy_buffer_to_buffer(&b_sentries, 0, &r_sentries, 0, sentry_bytes);
        }
        self.queue.submit([enc.finish()]);
        let mapped = |b: &wgpu::Buffer| {
            b.map_async(wgpu::MapMode::Read, .., |_| {});
        };
        mapped(&r_soft);
        mapped(&r_hard);
        mapped(&r_item);
        if want_entries {
            mapped(&r_entries);
            mapped(&r_sentries);
        }
        let _ = dev.poll(wgpu::PollType::Wait {
            submission_index: None,
            timeout: None,
        });
        let bytes = |b: &wgpu::Buffer| -> Vec<u8> {
            b.get_mapped_range(..)
                .map(|v| v.to_vec())
                .unwrap_or_default()
        };
        let soft_raw: Vec<[f32; 2]> = bytemuck::pod_collect_to_vec(&bytes(&r_soft));
        let hard_raw: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&bytes(&r_hard));
        let item_raw: Vec<i32> = bytemuck::pod_collect_to_vec(&bytes(&r_item));
        let mut per_view_entries: Vec<Entries> = vec![Entries::default(); views.len()];
        let mut needed = 0usize;
        let mut needed_s = 0usize;
        if want_entries {
            let raw = bytes(&r_entries);
            let count = u32::from_le_bytes([raw[0], raw[1], raw[2], raw[3]]) as usize;
            needed = count;
            let body: Vec<GEntry> = bytemuck::pod_collect_to_vec(&raw[16..]);
            for e in body.iter().take(count.min(capacity)) {
                per_view_entries[e.a[3] as usize].edges.push(Entry {
                    pixel: e.a[0],
                    part: e.a[1],
                    edge: e.a[2],
                    dm: e.b[0] as f64,
                    ds: e.b[1] as f64,
                    ga: [e.b[2] as f64, e.b[3] as f64],
                    gb: [e.c[0] as f64, e.c[1] as f64],
                });
            }
        }
        if want_entries {
            let raw = bytes(&r_sentries);
            let count = u32::from_le_bytes([raw[0], raw[1], raw[2], raw[3]]) as usize;
            needed_s = count;
            let body: Vec<GSurfaceEntry> = bytemuck::pod_collect_to_vec(&raw[16..]);
            let v3 = |a: [f32; 4]| [a[0] as f64, a[1] as f64, a[2] as f64];
            for e in body.iter().take(count.min(scapacity)) {
                per_view_entries[e.a[2] as usize]
                    .surfaces
                    .push(SurfaceEntry {
                        pixel: e.a[0],
                        part: e.a[1],
                        dm: e.b[0] as f64,
                        ds: e.b[1] as f64,
                        n: v3(e.n),
                        q: v3(e.q),
                        ldq: v3(e.l),
                    });
            }
        }
        for b in [&r_soft, &r_hard, &r_item] {
            b.unmap();
        }
        if want_entries {
            r_entries.unmap();
            r_sentries.unmap();
        }
        let mut softs = Vec::with_capacity(views.len());
        let mut hards = Vec::with_capacity(views.len());
        for gv in &gviews {
            let (w, h, off) = (gv.dims[0], gv.dims[1], gv.dims[2] as usize);
            let len = (w * h) as usize;
            let range = off..off + len;
            let get = |i: usize| soft_raw.get(i).copied().unwrap_or([0.0; 2]);
            softs.push(SoftImage {
                width: w,
                height: h,
                m: range.clone().map(|i| get(i)[0]).collect(),
                s: range.clone().map(|i| get(i)[1]).collect(),
            });
            hards.push(HardImage {
                width: w,
                height: h,
                item: range
                    .clone()
                    .map(|i| item_raw.get(i).copied().unwrap_or(-1))
                    .collect(),
                normal: range
                    .clone()
                    .map(|i| {
                        let v = hard_raw.get(i).copied().unwrap_or([0.0; 4]);
                        [v[0], v[1], v[2]]
                    })
                    .collect(),
                depth: range
                    .map(|i| hard_raw.get(i).map_or(f32::INFINITY, |v| v[3]))
                    .collect(),
            });
        }
        (softs, hards, per_view_entries, needed, needed_s)
    }
}

impl Backend for GpuBackend {
    fn name(&self) -> String {
        self.info.clone()
    }

    fn render(
        &mut self,
        scene: &Scene,
        views: &[ViewPrep],
        sigma: Option<f64>,
        shades: &[[f64; NSHADE]],
    ) -> Vec<(SoftImage, HardImage)> {
        let (s, h, _) = self.dispatch(scene, views, sigma, shades, false);
        s.into_iter().zip(h).collect()
    }

    fn loss(
        &mut self,
        scene: &Scene,
        views: &[ViewPrep],
        sigma: f64,
        shades: &[[f64; NSHADE]],
        targets: &[Target],
        spec: &LossSpec,
        grad: bool,
    ) -> LossOut {
        let (softs, _, entries) = self.dispatch(scene, views, Some(sigma), shades, grad);
        let mut per_view = Vec::with_capacity(views.len());
        let mut dtheta = if grad {
            vec![[0.0; NTHETA]; scene.parts.len()]
        } else {
            Vec::new()
        };
        for (k, (img, t)) in softs.iter().zip(targets).enumerate() {
            let l = view_loss(img, t, spec, grad);
            per_view.push(l.loss);
            if grad {
                let g = theta_gradient(scene, &views[k], &entries[k], &l.gm, &l.gs);
                for (acc, gp) in dtheta.iter_mut().zip(g) {
                    for q in 0..NTHETA {
                        acc[q] += gp[q];
                    }
                }
            }
        }
        LossOut { per_view, dtheta }
    }
}
