//! The wgpu backend: the per-pixel soft-silhouette kernel in WGSL (`shaders/soft.wgsl`).
//!
//! The CPU prepares what every pixel shares (camera frames, silhouette hulls, item
//! programs) exactly as for the CPU backend; the GPU evaluates every pixel of every view in
//! one dispatch and appends gradient entries; the image function and the chain to part
//! parameters run on the CPU with the same code as the CPU backend, so both backends
//! compute the same numbers (up to `f32` rounding). A dispatch lays the inputs out as the
//! shader's buffers (`gpu_*`), runs once, reads the outputs back and cuts them per view; it
//! runs again with more room when the entry buffers overflowed. On a machine without a GPU, Mesa's lavapipe provides a
//! Vulkan device that runs the shader on the CPU.

use super::scene::{Kind, NSHADE, Op, PartGeom, Scene, is_box};
use super::soft::{Entries, Entry, HardImage, SoftImage, SurfaceEntry, ViewPrep};
use super::{Backend, CpuBackend, ImageFunction, ImageValues, sum_views, view_value};
use bytemuck::{Pod, Zeroable};
use glam::DVec3;
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
        let capacity = if want_entries { self.capacity } else { 1 };
        let scapacity = if want_entries {
            self.surface_capacity
        } else {
            1
        };
        let (gviews, total) = gpu_views(views, shades);
        let (code, items) = gpu_items(scene);
        let (hulls, edges, verts, rects) = gpu_hulls(views, scene.parts.len(), scene.items.len());
        let inputs = Inputs {
            params: GParams {
                view_count: views.len() as u32,
                item_count: scene.items.len() as u32,
                part_count: scene.parts.len() as u32,
                total_pixels: total,
                sigma: sigma.unwrap_or(1.0) as f32,
                hard: sigma.is_none() as u32,
                want_entries: want_entries as u32,
                entry_capacity: capacity as u32,
                surface_capacity: scapacity as u32,
                pad: [0; 3],
            },
            views: gviews,
            parts: scene.parts.iter().map(gpu_part).collect(),
            hulls,
            edges,
            verts,
            rects,
            items,
            code,
        };
        let raw = self.run(&inputs, want_entries);
        let mut per_view_entries: Vec<Entries> = vec![Entries::default(); views.len()];
        let (mut needed, mut needed_s) = (0, 0);
        if want_entries {
            needed = read_edge_entries(&raw.entries, capacity, &mut per_view_entries);
            needed_s = read_surface_entries(&raw.sentries, scapacity, &mut per_view_entries);
        }
        let (softs, hards) = images(&inputs.views, &raw);
        (softs, hards, per_view_entries, needed, needed_s)
    }

    /// Uploads the inputs, runs the kernel once and reads its outputs back (the entry
    /// buffers only with `want_entries`).
    fn run(&self, inp: &Inputs, want_entries: bool) -> Outputs {
        let dev = &self.device;
        let storage = wgpu::BufferUsages::STORAGE;
        let n = inp.params.total_pixels as u64;
        let entry_bytes =
            16 + inp.params.entry_capacity as u64 * std::mem::size_of::<GEntry>() as u64;
        let sentry_bytes =
            16 + inp.params.surface_capacity as u64 * std::mem::size_of::<GSurfaceEntry>() as u64;
        let out = |label: &str, size: u64| {
            dev.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(16),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        let zeroed = |label: &str, size: u64| {
            init(
                dev,
                label,
                &vec![0u8; size as usize],
                storage | wgpu::BufferUsages::COPY_SRC,
            )
        };
        // In binding order: the inputs, then soft, hard, item, entries, surface entries.
        let mut buffers = self.input_buffers(inp);
        buffers.extend([
            out("soft", n * 8),
            out("hard", n * 16),
            out("item", n * 4),
            zeroed("entries", entry_bytes),
            zeroed("surface-entries", sentry_bytes),
        ]);
        let bind = dev.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("soft"),
            layout: &self.layout,
            entries: &buffers
                .iter()
                .enumerate()
                .map(|(i, b)| wgpu::BindGroupEntry {
                    binding: i as u32,
                    resource: b.as_entire_binding(),
                })
                .collect::<Vec<_>>(),
        });
        let sizes = [n * 8, n * 16, n * 4, entry_bytes, sentry_bytes];
        let outputs = &buffers[buffers.len() - 5..];
        let groups = inp.params.total_pixels.div_ceil(WORKGROUP).max(1);
        let bytes = self.submit(&bind, outputs, sizes, groups, want_entries);
        let mut bytes = bytes.into_iter();
        let mut next = || bytes.next().unwrap_or_default();
        Outputs {
            soft: bytemuck::pod_collect_to_vec(&next()),
            hard: bytemuck::pod_collect_to_vec(&next()),
            item: bytemuck::pod_collect_to_vec(&next()),
            entries: next(),
            sentries: next(),
        }
    }

    /// Runs `groups` workgroups over the bound buffers and copies the outputs (`sizes`
    /// bytes each; the entry buffers only with `want_entries`) back: their bytes.
    fn submit(
        &self,
        bind: &wgpu::BindGroup,
        outputs: &[wgpu::Buffer],
        sizes: [u64; 5],
        groups: u32,
        want_entries: bool,
    ) -> Vec<Vec<u8>> {
        let dev = &self.device;
        let read = |label: &str, size: u64| {
            dev.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(16),
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let labels = [
            "soft-read",
            "hard-read",
            "item-read",
            "entries-read",
            "surface-entries-read",
        ];
        // The entry buffers are read back only when asked for.
        let copied = if want_entries { 5 } else { 3 };
        let reads: Vec<wgpu::Buffer> = (0..5)
            .map(|k| read(labels[k], if k < copied { sizes[k] } else { 16 }))
            .collect();
        let mut enc = dev.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
        {
            let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("soft"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, bind, &[]);
            let x = groups.min(65535);
            let y = groups.div_ceil(x);
            pass.dispatch_workgroups(x, y, 1);
        }
        for k in 0..copied {
            enc.copy_buffer_to_buffer(&outputs[k], 0, &reads[k], 0, sizes[k]);
        }
        self.queue.submit([enc.finish()]);
        for r in &reads[..copied] {
            r.map_async(wgpu::MapMode::Read, .., |_| {});
        }
        let _ = dev.poll(wgpu::PollType::Wait {
            submission_index: None,
            timeout: None,
        });
        let bytes = reads[..copied]
            .iter()
            .map(|b| {
                b.get_mapped_range(..)
                    .map(|v| v.to_vec())
                    .unwrap_or_default()
            })
            .collect();
        for r in &reads[..copied] {
            r.unmap();
        }
        bytes
    }

    /// The kernel's input buffers, in binding order (the uniform parameters first).
    fn input_buffers(&self, inp: &Inputs) -> Vec<wgpu::Buffer> {
        let dev = &self.device;
        let storage = wgpu::BufferUsages::STORAGE;
        vec![
            init(
                dev,
                "params",
                bytemuck::bytes_of(&inp.params),
                wgpu::BufferUsages::UNIFORM,
            ),
            init(dev, "views", bytemuck::cast_slice(&inp.views), storage),
            init(dev, "parts", bytemuck::cast_slice(&inp.parts), storage),
            init(dev, "hulls", bytemuck::cast_slice(&inp.hulls), storage),
            init(dev, "edges", bytemuck::cast_slice(&inp.edges), storage),
            init(dev, "verts", bytemuck::cast_slice(&inp.verts), storage),
            init(dev, "rects", bytemuck::cast_slice(&inp.rects), storage),
            init(dev, "items", bytemuck::cast_slice(&inp.items), storage),
            init(dev, "code", bytemuck::cast_slice(&inp.code), storage),
        ]
    }
}

/// What the kernel reads, laid out as the shader's buffers.
struct Inputs {
    params: GParams,
    views: Vec<GView>,
    parts: Vec<GPart>,
    hulls: Vec<[u32; 4]>,
    edges: Vec<[f32; 4]>,
    verts: Vec<[f32; 2]>,
    rects: Vec<[i32; 4]>,
    items: Vec<GItem>,
    code: Vec<u32>,
}

/// What the kernel wrote: soft channels, hard surface and item per pixel, and the raw
/// entry buffers (a count, padding, then the entries; empty unless asked for).
struct Outputs {
    soft: Vec<[f32; 2]>,
    hard: Vec<[f32; 4]>,
    item: Vec<i32>,
    entries: Vec<u8>,
    sentries: Vec<u8>,
}

/// A buffer holding `bytes` (bindings need at least one element, so an empty one holds
/// sixteen zero bytes).
fn init(dev: &wgpu::Device, label: &str, bytes: &[u8], usage: wgpu::BufferUsages) -> wgpu::Buffer {
    let pad = [0u8; 16];
    dev.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: if bytes.is_empty() { &pad } else { bytes },
        usage,
    })
}

/// The views' cameras and shading, each with its offset among all pixels; and the total.
fn gpu_views(views: &[ViewPrep], shades: &[[f64; NSHADE]]) -> (Vec<GView>, u32) {
    let mut gviews = Vec::with_capacity(views.len());
    let mut offset = 0u32;
    for (v, sh) in views.iter().zip(shades) {
        let f = &v.frame;
        let v4 = |a: DVec3, w: f64| [a.x as f32, a.y as f32, a.z as f32, w as f32];
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
    (gviews, offset)
}

/// A part's geometry as the shader reads it.
fn gpu_part(p: &PartGeom) -> GPart {
    // Rows of the maps, with the translation last.
    let lrow = |i: usize| p.l.row(i).extend(p.t[i]).as_vec4().to_array();
    let row = |i: usize| p.inv.row(i).extend(p.inv_t[i]).as_vec4().to_array();
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
}

/// Hulls and rectangles.
type GHulls = (Vec<[u32; 4]>, Vec<[f32; 4]>, Vec<[f32; 2]>, Vec<[i32; 4]>);

/// Every view's hulls (offset, edge count, present) with their edges and vertices, and
/// its items' pixel rectangles.
fn gpu_hulls(views: &[ViewPrep], np: usize, ni: usize) -> GHulls {
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
    (hulls, edges, verts, rects)
}

/// The items' programs and part lists as one code buffer, and each item's place in it.
fn gpu_items(scene: &Scene) -> (Vec<u32>, Vec<GItem>) {
    let ni = scene.items.len();
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
    (code, items)
}

/// The count at the head of an entry buffer (the kernel counts every entry it wanted to
/// write, also those beyond the capacity) and the entries written.
fn entry_buffer<T: Pod>(raw: &[u8], capacity: usize) -> (usize, Vec<T>) {
    let count = raw
        .get(..4)
        .map_or(0, |b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize);
    let mut body: Vec<T> = bytemuck::pod_collect_to_vec(raw.get(16..).unwrap_or_default());
    body.truncate(count.min(capacity));
    (count, body)
}

/// Edge entries to their views; the number the kernel wanted to write.
fn read_edge_entries(raw: &[u8], capacity: usize, per_view: &mut [Entries]) -> usize {
    let (count, body) = entry_buffer::<GEntry>(raw, capacity);
    for e in &body {
        per_view[e.a[3] as usize].edges.push(Entry {
            pixel: e.a[0],
            part: e.a[1],
            edge: e.a[2],
            dm: e.b[0] as f64,
            ds: e.b[1] as f64,
            ga: [e.b[2] as f64, e.b[3] as f64],
            gb: [e.c[0] as f64, e.c[1] as f64],
        });
    }
    count
}

/// Surface entries to their views; the number the kernel wanted to write.
fn read_surface_entries(raw: &[u8], capacity: usize, per_view: &mut [Entries]) -> usize {
    let (count, body) = entry_buffer::<GSurfaceEntry>(raw, capacity);
    let v3 = |a: [f32; 4]| DVec3::new(a[0] as f64, a[1] as f64, a[2] as f64);
    for e in &body {
        per_view[e.a[2] as usize].surfaces.push(SurfaceEntry {
            pixel: e.a[0],
            part: e.a[1],
            dm: e.b[0] as f64,
            ds: e.b[1] as f64,
            n: v3(e.n),
            q: v3(e.q),
            ldq: v3(e.l).to_array(),
        });
    }
    count
}

/// Each view's soft and hard image, cut from the kernel's per-pixel outputs.
fn images(gviews: &[GView], raw: &Outputs) -> (Vec<SoftImage>, Vec<HardImage>) {
    let mut softs = Vec::with_capacity(gviews.len());
    let mut hards = Vec::with_capacity(gviews.len());
    for gv in gviews {
        let (w, h, off) = (gv.dims[0], gv.dims[1], gv.dims[2] as usize);
        let len = (w * h) as usize;
        let range = off..off + len;
        let get = |i: usize| raw.soft.get(i).copied().unwrap_or([0.0; 2]);
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
                .map(|i| raw.item.get(i).copied().unwrap_or(-1))
                .collect(),
            normal: range
                .clone()
                .map(|i| {
                    let v = raw.hard.get(i).copied().unwrap_or([0.0; 4]);
                    [v[0], v[1], v[2]]
                })
                .collect(),
            depth: range
                .map(|i| raw.hard.get(i).map_or(f32::INFINITY, |v| v[3]))
                .collect(),
        });
    }
    (softs, hards)
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
        if sigma.is_some_and(is_box) {
            // The shader has no box filter: the CPU reference draws it.
            return CpuBackend::new().render(scene, views, sigma, shades);
        }
        let (s, h, _) = self.dispatch(scene, views, sigma, shades, false);
        s.into_iter().zip(h).collect()
    }

    fn evaluate(
        &mut self,
        scene: &Scene,
        views: &[ViewPrep],
        sigma: f64,
        shades: &[[f64; NSHADE]],
        f: &dyn ImageFunction,
        grad: bool,
    ) -> ImageValues {
        if is_box(sigma) {
            return CpuBackend::new().evaluate(scene, views, sigma, shades, f, grad);
        }
        let (softs, _, entries) = self.dispatch(scene, views, Some(sigma), shades, grad);
        let outs = softs
            .iter()
            .zip(views.iter().zip(&entries))
            .enumerate()
            .map(|(k, (img, (v, e)))| view_value(scene, v, k, img, e, f, grad));
        sum_views(scene.parts.len(), grad, outs)
    }
}
