// Soft silhouettes, one invocation per pixel: the wgpu twin of `src/render/soft.rs`.
//
// For every item (operand of the top-level union) whose pixel rectangle holds the pixel:
// each part's soft coverage from its silhouette hull, its exact ray interval, the item's
// visible surface (booleans by classifying the ray's segments), then front-to-back
// compositing into coverage `m` and premultiplied shade `s`. Pixels near a silhouette
// append gradient entries (how `m` and `s` change with a hull edge's two vertices).

struct Params {
    view_count: u32,
    item_count: u32,
    part_count: u32,
    total_pixels: u32,
    sigma: f32,
    hard: u32,
    want_entries: u32,
    entry_capacity: u32,
    surface_capacity: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

struct View {
    eye: vec4<f32>,      // xyz, w = focal (pixels per unit at depth 1, or per unit)
    right: vec4<f32>,    // xyz, w = 1 for orthographic
    up: vec4<f32>,
    forward: vec4<f32>,
    shade_a: vec4<f32>,  // shading coefficients 0..3
    shade_b: vec4<f32>,  // coefficient 4
    dims: vec4<u32>,     // width, height, first pixel, 0
}

struct Part {
    inv0: vec4<f32>,     // rows of [L⁻¹ | −L⁻¹t]
    inv1: vec4<f32>,
    inv2: vec4<f32>,
    lo: vec4<f32>,       // xyz, w = r1
    hi: vec4<f32>,       // xyz, w = r2
    center: vec4<f32>,   // world center
    flags: vec4<u32>,    // kind (0 box, 1 frustum, 2 sphere), valid, centered
    l0: vec4<f32>,       // rows of [L | t]
    l1: vec4<f32>,
    l2: vec4<f32>,
}

struct Item {
    a: vec4<u32>,        // program offset, program length, parts offset, parts count
    b: vec4<u32>,        // split difference: first operand's program length (0: none),
                         // subtracted parts offset, count; the item's albedo (f32 bits)
}

struct Entry {
    a: vec4<u32>,        // pixel (within its view), part, edge, view
    b: vec4<f32>,        // dm, ds, ga.x, ga.y
    c: vec4<f32>,        // gb.x, gb.y
}

struct Entries {
    count: atomic<u32>,
    pad0: u32,
    pad1: u32,
    pad2: u32,
    data: array<Entry>,
}

// A subtracted part's surface where it cuts the visible surface.
struct SEntry {
    a: vec4<u32>,        // pixel (within its view), part, view
    b: vec4<f32>,        // dm, ds
    n: vec4<f32>,        // world unit normal
    q: vec4<f32>,        // local material point
    l: vec4<f32>,        // N·(L·∂q/∂prim)
}

struct SEntries {
    count: atomic<u32>,
    pad0: u32,
    pad1: u32,
    pad2: u32,
    data: array<SEntry>,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> views: array<View>;
@group(0) @binding(2) var<storage, read> parts: array<Part>;
// Per (view, part): first edge, edge count, has hull.
@group(0) @binding(3) var<storage, read> hulls: array<vec4<u32>>;
// Per edge: outward normal, offset (d = n·u − c).
@group(0) @binding(4) var<storage, read> edges: array<vec4<f32>>;
// Per edge: its start vertex.
@group(0) @binding(5) var<storage, read> verts: array<vec2<f32>>;
// Per (view, item): pixel rectangle [x0, y0, x1, y1), x0 < 0 for none.
@group(0) @binding(6) var<storage, read> rects: array<vec4<i32>>;
// Per item: its program and parts (into `code`), and its split.
@group(0) @binding(7) var<storage, read> items: array<Item>;
// Programs (op << 24 | argument) and item part lists.
@group(0) @binding(8) var<storage, read> code: array<u32>;
// Per pixel: m, s.
@group(0) @binding(9) var<storage, read_write> out_soft: array<vec2<f32>>;
// Per pixel: eye normal xyz, depth; item in `out_item`.
@group(0) @binding(10) var<storage, read_write> out_hard: array<vec4<f32>>;
@group(0) @binding(11) var<storage, read_write> out_item: array<i32>;
@group(0) @binding(12) var<storage, read_write> entries: Entries;
@group(0) @binding(13) var<storage, read_write> sentries: SEntries;

const CUTOFF: f32 = 9.0;
const HULL_MARGIN: f32 = 1.5;
const MAXL: u32 = 24u;       // layers per pixel
const MAXS: u32 = 48u;       // part states per pixel
const MAXSTACK: u32 = 16u;
const MAXN: u32 = 16u;       // subtracted parts near front points, per pixel
const NONE: u32 = 0xffffffffu;
const INF: f32 = 3.0e38;

const OP_PART: u32 = 0u;
const OP_UNION: u32 = 1u;
const OP_DIFF: u32 = 2u;
const OP_INTER: u32 = 3u;

// Per-part state at this pixel.
var<private> s_part: array<u32, MAXS>;
var<private> s_alpha: array<f32, MAXS>;
var<private> s_hull: array<bool, MAXS>;
var<private> s_covn: array<u32, MAXS>;
var<private> s_e0: array<u32, MAXS>;
var<private> s_w0: array<f32, MAXS>;
var<private> s_e1: array<u32, MAXS>;
var<private> s_w1: array<f32, MAXS>;
var<private> s_hit: array<bool, MAXS>;
var<private> s_t0: array<f32, MAXS>;
var<private> s_t1: array<f32, MAXS>;
var<private> s_n0: array<vec3<f32>, MAXS>;
var<private> s_n1: array<vec3<f32>, MAXS>;
var<private> s_count: u32;

// Layers at this pixel (see `Layer` in soft.rs).
var<private> l_depth: array<f32, MAXL>;
var<private> l_alpha: array<f32, MAXL>;
var<private> l_premult: array<f32, MAXL>;
var<private> l_keep: array<f32, MAXL>;
var<private> l_item: array<u32, MAXL>;
var<private> l_first: array<u32, MAXL>;
var<private> l_end: array<u32, MAXL>;
var<private> l_split: array<bool, MAXL>;
var<private> l_alpha_a: array<f32, MAXL>;
var<private> l_kappa: array<f32, MAXL>;
var<private> l_cavity: array<f32, MAXL>;
var<private> l_shf: array<f32, MAXL>;
var<private> l_shc: array<f32, MAXL>;
var<private> l_nfirst: array<u32, MAXL>;
var<private> l_nend: array<u32, MAXL>;
var<private> l_order: array<u32, MAXL>;
var<private> l_count: u32;

// Subtracted parts near front points (see `Neg` in soft.rs).
var<private> n_part: array<u32, MAXN>;
var<private> n_kappa: array<f32, MAXN>;
var<private> n_dk: array<f32, MAXN>;
var<private> n_n: array<vec3<f32>, MAXN>;
var<private> n_q: array<vec3<f32>, MAXN>;
var<private> n_l: array<vec3<f32>, MAXN>;
var<private> n_fpart: array<u32, MAXN>;
var<private> n_along: array<f32, MAXN>;
var<private> n_fn: array<vec3<f32>, MAXN>;
var<private> n_fq: array<vec3<f32>, MAXN>;
var<private> n_fl: array<vec3<f32>, MAXN>;
var<private> n_count: u32;

fn logistic(x: f32) -> f32 {
    return 1.0 / (1.0 + exp(-x));
}

fn hull_info(view: u32, part: u32) -> vec4<u32> {
    return hulls[view * params.part_count + part];
}

// Signed distance (positive inside) to the hull and the deciding edge.
fn signed_distance(h: vec4<u32>, u: vec2<f32>) -> vec2<f32> {
    var best = -INF;
    var at = 0u;
    for (var i = 0u; i < h.y; i = i + 1u) {
        let e = edges[h.x + i];
        let d = e.x * u.x + e.y * u.y - e.z;
        if (d > best) {
            best = d;
            at = i;
        }
    }
    return vec2<f32>(-best, bitcast<f32>(at));
}

// ∂s/∂a and ∂s/∂b for edge i of hull h (xy: a, zw: b).
fn edge_gradient(h: vec4<u32>, i: u32, u: vec2<f32>) -> vec4<f32> {
    let a = verts[h.x + i];
    let b = verts[h.x + (i + 1u) % h.y];
    let e = b - a;
    let len2 = dot(e, e);
    let len = sqrt(len2);
    let w = u - a;
    let d = (w.x * e.y - w.y * e.x) / len;
    let n = vec2<f32>(e.y / len, -e.x / len);
    let dd_db = vec2<f32>(-w.y / len - d * e.x / len2, w.x / len - d * e.y / len2);
    let dd_da = -n - dd_db;
    return vec4<f32>(-dd_da, -dd_db);
}

fn to_local(p: Part, x: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(p.inv0.xyz, x) + p.inv0.w, dot(p.inv1.xyz, x) + p.inv1.w, dot(p.inv2.xyz, x) + p.inv2.w);
}

fn dir_to_local(p: Part, d: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(p.inv0.xyz, d), dot(p.inv1.xyz, d), dot(p.inv2.xyz, d));
}

fn normal_to_world(p: Part, n: vec3<f32>) -> vec3<f32> {
    let w = p.inv0.xyz * n.x + p.inv1.xyz * n.y + p.inv2.xyz * n.z;
    let l = length(w);
    if (l > 0.0) {
        return w / l;
    }
    return w;
}

struct LocalHit {
    ok: bool,
    t0: f32,
    t1: f32,
    n0: vec3<f32>,
    n1: vec3<f32>,
}

fn miss() -> LocalHit {
    return LocalHit(false, 0.0, 0.0, vec3<f32>(0.0), vec3<f32>(0.0));
}

fn axis_vec(a: u32, s: f32) -> vec3<f32> {
    var v = vec3<f32>(0.0);
    v[a] = s;
    return v;
}

fn hit_box(o: vec3<f32>, d: vec3<f32>, lo: vec3<f32>, hi: vec3<f32>) -> LocalHit {
    var t0 = -INF;
    var t1 = INF;
    var n0 = vec3<f32>(0.0);
    var n1 = vec3<f32>(0.0);
    for (var a = 0u; a < 3u; a = a + 1u) {
        if (d[a] == 0.0) {
            if (o[a] < lo[a] || o[a] > hi[a]) {
                return miss();
            }
            continue;
        }
        let ta = (lo[a] - o[a]) / d[a];
        let tb = (hi[a] - o[a]) / d[a];
        var near = tb;
        var far = ta;
        var sgn = 1.0;
        if (ta < tb) {
            near = ta;
            far = tb;
            sgn = -1.0;
        }
        if (near > t0) {
            t0 = near;
            n0 = axis_vec(a, sgn);
        }
        if (far < t1) {
            t1 = far;
            n1 = axis_vec(a, -sgn);
        }
    }
    if (t0 <= t1 && t0 > -INF && t1 < INF) {
        return LocalHit(true, t0, t1, n0, n1);
    }
    return miss();
}

fn hit_sphere(o_in: vec3<f32>, d: vec3<f32>, r: f32) -> LocalHit {
    let a = dot(d, d);
    if (a <= 0.0) {
        return miss();
    }
    // Solve from the point of closest approach (better conditioned in f32).
    let tc = -dot(o_in, d) / a;
    let o = o_in + tc * d;
    let c = dot(o, o) - r * r;
    let disc = -a * c;
    if (disc < 0.0) {
        return miss();
    }
    let q = sqrt(disc);
    let t0 = -q / a;
    let t1 = q / a;
    return LocalHit(true, tc + t0, tc + t1, o + t0 * d, o + t1 * d);
}

fn hit_frustum(o_in: vec3<f32>, d: vec3<f32>, z0: f32, z1: f32, r1: f32, r2: f32) -> LocalHit {
    // Shift the origin to the closest approach to the axis's middle.
    let mid = vec3<f32>(0.0, 0.0, 0.5 * (z0 + z1));
    let dd = dot(d, d);
    var tc = 0.0;
    if (dd > 0.0) {
        tc = -dot(o_in - mid, d) / dd;
    }
    let o = o_in + tc * d;
    var s0 = -INF;
    var s1 = INF;
    var sn0 = vec3<f32>(0.0);
    var sn1 = vec3<f32>(0.0);
    if (d.z == 0.0) {
        if (o.z < z0 || o.z > z1) {
            return miss();
        }
    } else {
        let ta = (z0 - o.z) / d.z;
        let tb = (z1 - o.z) / d.z;
        if (ta < tb) {
            s0 = ta; s1 = tb;
            sn0 = vec3<f32>(0.0, 0.0, -1.0); sn1 = vec3<f32>(0.0, 0.0, 1.0);
        } else {
            s0 = tb; s1 = ta;
            sn0 = vec3<f32>(0.0, 0.0, 1.0); sn1 = vec3<f32>(0.0, 0.0, -1.0);
        }
    }
    let k = (r2 - r1) / (z1 - z0);
    let c0 = r1 - k * z0;
    let rho_o = c0 + k * o.z;
    let a = d.x * d.x + d.y * d.y - k * k * d.z * d.z;
    let b = 2.0 * (o.x * d.x + o.y * d.y - rho_o * k * d.z);
    let c = o.x * o.x + o.y * o.y - rho_o * rho_o;
    let scale_a = d.x * d.x + d.y * d.y + k * k * d.z * d.z;
    var p0a = 0.0; var p0b = 0.0; var has0 = false;
    var p1a = 0.0; var p1b = 0.0; var has1 = false;
    if (abs(a) <= 1e-6 * scale_a) {
        if (abs(b) <= 1e-30) {
            if (c > 0.0) {
                return miss();
            }
            p0a = -INF; p0b = INF; has0 = true;
        } else if (b > 0.0) {
            p0a = -INF; p0b = -c / b; has0 = true;
        } else {
            p0a = -c / b; p0b = INF; has0 = true;
        }
    } else {
        let disc = b * b - 4.0 * a * c;
        if (disc < 0.0) {
            if (a > 0.0) {
                return miss();
            }
            p0a = -INF; p0b = INF; has0 = true;
        } else {
            let q = sqrt(disc);
            var sb = 1.0;
            if (b < 0.0) {
                sb = -1.0;
            }
            let qq = -0.5 * (b + sb * q);
            var ra = 0.0;
            var rb = 0.0;
            if (qq != 0.0) {
                ra = qq / a;
                rb = c / qq;
            }
            if (ra > rb) {
                let t = ra; ra = rb; rb = t;
            }
            if (a > 0.0) {
                p0a = ra; p0b = rb; has0 = true;
            } else {
                p0a = -INF; p0b = ra; has0 = true;
                p1a = rb; p1b = INF; has1 = true;
            }
        }
    }
    var best_lo = 0.0;
    var best_hi = 0.0;
    var found = false;
    if (has0) {
        let lo = max(p0a, s0);
        let hi = min(p0b, s1);
        if (lo <= hi) {
            best_lo = lo; best_hi = hi; found = true;
        }
    }
    if (has1) {
        let lo = max(p1a, s0);
        let hi = min(p1b, s1);
        if (lo <= hi && (!found || hi - lo > best_hi - best_lo)) {
            best_lo = lo; best_hi = hi; found = true;
        }
    }
    if (!found || best_lo <= -INF || best_hi >= INF) {
        return miss();
    }
    var n0 = sn0;
    if (best_lo != s0) {
        let p = o + best_lo * d;
        n0 = vec3<f32>(p.x, p.y, -k * (c0 + k * p.z));
    }
    var n1 = sn1;
    if (best_hi != s1) {
        let p = o + best_hi * d;
        n1 = vec3<f32>(p.x, p.y, -k * (c0 + k * p.z));
    }
    return LocalHit(true, tc + best_lo, tc + best_hi, n0, n1);
}

fn intersect(pi: u32, o: vec3<f32>, d: vec3<f32>) -> LocalHit {
    let p = parts[pi];
    if (p.flags.y == 0u) {
        return miss();
    }
    let ol = to_local(p, o);
    let dl = dir_to_local(p, d);
    var h: LocalHit;
    if (p.flags.x == 0u) {
        h = hit_box(ol, dl, p.lo.xyz, p.hi.xyz);
    } else if (p.flags.x == 1u) {
        h = hit_frustum(ol, dl, p.lo.z, p.hi.z, p.lo.w, p.hi.w);
    } else {
        h = hit_sphere(ol, dl, p.lo.w);
    }
    if (h.ok) {
        h.n0 = normal_to_world(p, h.n0);
        h.n1 = normal_to_world(p, h.n1);
    }
    return h;
}

fn near_normal(pi: u32, o: vec3<f32>, d_w: vec3<f32>) -> vec3<f32> {
    let p = parts[pi];
    let ol = to_local(p, o);
    let d = dir_to_local(p, d_w);
    var n = vec3<f32>(0.0, 0.0, 1.0);
    if (p.flags.x == 0u) {
        var best = -INF;
        for (var a = 0u; a < 3u; a = a + 1u) {
            if (d[a] == 0.0) {
                continue;
            }
            let ta = (p.lo[a] - ol[a]) / d[a];
            let tb = (p.hi[a] - ol[a]) / d[a];
            var near = tb;
            var sgn = 1.0;
            if (ta < tb) {
                near = ta;
                sgn = -1.0;
            }
            if (near > best) {
                best = near;
                n = axis_vec(a, sgn);
            }
        }
    } else if (p.flags.x == 1u) {
        let z0 = p.lo.z;
        let z1 = p.hi.z;
        let dd = d.x * d.x + d.y * d.y;
        if (dd <= 1e-12 * dot(d, d)) {
            if (d.z > 0.0) {
                n = vec3<f32>(0.0, 0.0, -1.0);
            } else {
                n = vec3<f32>(0.0, 0.0, 1.0);
            }
        } else {
            let ts = -(ol.x * d.x + ol.y * d.y) / dd;
            let q = ol + ts * d;
            if (q.z < z0 && d.z > 0.0) {
                n = vec3<f32>(0.0, 0.0, -1.0);
            } else if (q.z > z1 && d.z < 0.0) {
                n = vec3<f32>(0.0, 0.0, 1.0);
            } else {
                let k = (p.hi.w - p.lo.w) / (z1 - z0);
                let r = max(sqrt(q.x * q.x + q.y * q.y), 1e-30);
                n = vec3<f32>(q.x / r, q.y / r, -k);
            }
        }
    } else {
        let dd = max(dot(d, d), 1e-30);
        let ts = -dot(ol, d) / dd;
        n = ol + ts * d;
    }
    return normal_to_world(p, n);
}

// Part coverage at pixel u: fills one state slot.
fn part_state(k: u32, view: u32, pi: u32, u: vec2<f32>, o: vec3<f32>, d: vec3<f32>) {
    s_part[k] = pi;
    s_alpha[k] = 0.0;
    s_hull[k] = false;
    s_covn[k] = 0u;
    s_hit[k] = false;
    if (parts[pi].flags.y == 0u) {
        return;
    }
    let h = hull_info(view, pi);
    var test = true;
    var s1 = -INF;
    if (h.z != 0u) {
        s_hull[k] = true;
        let sd = signed_distance(h, u);
        s1 = sd.x;
        let e1 = bitcast<u32>(sd.y);
        s_e0[k] = e1;
        test = s1 > -HULL_MARGIN;
        if (params.hard == 0u) {
            let sigma = params.sigma;
            let band = CUTOFF * sigma;
            if (s1 >= band) {
                s_alpha[k] = 1.0;
            } else if (s1 > -band) {
                let n1 = edges[h.x + e1].xy;
                var d2 = -INF;
                var e2 = 0xffffffffu;
                for (var i = 0u; i < h.y; i = i + 1u) {
                    let e = edges[h.x + i];
                    if (e.x * n1.x + e.y * n1.y < -0.7) {
                        let dd = e.x * u.x + e.y * u.y - e.z;
                        if (dd > d2) {
                            d2 = dd;
                            e2 = i;
                        }
                    }
                }
                let f1 = logistic(-s1 / sigma);
                var f2 = 0.0;
                var use2 = false;
                if (e2 != 0xffffffffu && d2 > -band) {
                    f2 = logistic(d2 / sigma);
                    use2 = true;
                }
                let a = 1.0 - f1 - f2;
                if (a > 0.0) {
                    s_alpha[k] = a;
                    s_w0[k] = f1 * (1.0 - f1) / sigma;
                    s_covn[k] = 1u;
                    if (use2) {
                        s_e1[k] = e2;
                        s_w1[k] = f2 * (1.0 - f2) / sigma;
                        s_covn[k] = 2u;
                    }
                }
            }
        }
    }
    if (test) {
        let hit = intersect(pi, o, d);
        if (hit.ok && hit.t1 > 0.0) {
            s_hit[k] = true;
            s_t0[k] = hit.t0;
            s_t1[k] = hit.t1;
            s_n0[k] = hit.n0;
            s_n1[k] = hit.n1;
        }
    }
    if (params.hard != 0u || !s_hull[k]) {
        if (s_hit[k]) {
            s_alpha[k] = 1.0;
        } else {
            s_alpha[k] = 0.0;
        }
    }
}

fn state_of(first: u32, end: u32, part: u32) -> u32 {
    for (var k = first; k < end; k = k + 1u) {
        if (s_part[k] == part) {
            return k;
        }
    }
    return 0xffffffffu;
}

// Membership of a point given a bitmask of which states are inside.
fn eval_inside(item: vec4<u32>, first: u32, end: u32, inside: u32) -> bool {
    var stack: array<bool, MAXSTACK>;
    var top = 0u;
    for (var i = 0u; i < item.y; i = i + 1u) {
        let op = code[item.x + i];
        let kind = op >> 24u;
        let arg = op & 0xffffffu;
        if (kind == OP_PART) {
            let k = state_of(first, end, arg);
            var v = false;
            if (k != 0xffffffffu) {
                v = ((inside >> (k - first)) & 1u) == 1u;
            }
            if (top < MAXSTACK) {
                stack[top] = v;
                top = top + 1u;
            }
        } else {
            let at = top - arg;
            var v = stack[at];
            for (var j = at + 1u; j < top; j = j + 1u) {
                if (kind == OP_UNION) {
                    v = v || stack[j];
                } else if (kind == OP_DIFF) {
                    v = v && !stack[j];
                } else {
                    v = v && stack[j];
                }
            }
            top = at;
            stack[top] = v;
            top = top + 1u;
        }
    }
    if (top == 0u) {
        return false;
    }
    return stack[top - 1u];
}

// Soft coverage of an item with the derivative for the part in state `seed`.
fn eval_soft(item: vec4<u32>, first: u32, end: u32, seed: u32) -> vec2<f32> {
    var sv: array<f32, MAXSTACK>;
    var sd: array<f32, MAXSTACK>;
    var top = 0u;
    for (var i = 0u; i < item.y; i = i + 1u) {
        let op = code[item.x + i];
        let kind = op >> 24u;
        let arg = op & 0xffffffu;
        if (kind == OP_PART) {
            let k = state_of(first, end, arg);
            var a = 0.0;
            var da = 0.0;
            if (k != 0xffffffffu) {
                a = s_alpha[k];
                if (k == seed) {
                    da = 1.0;
                }
            }
            if (top < MAXSTACK) {
                sv[top] = a;
                sd[top] = da;
                top = top + 1u;
            }
        } else {
            let at = top - arg;
            var p = 1.0;
            var dp = 0.0;
            if (kind == OP_UNION) {
                for (var j = at; j < top; j = j + 1u) {
                    dp = dp * (1.0 - sv[j]) - p * sd[j];
                    p = p * (1.0 - sv[j]);
                }
                p = 1.0 - p;
                dp = -dp;
            } else if (kind == OP_DIFF) {
                p = sv[at];
                dp = sd[at];
            } else {
                for (var j = at; j < top; j = j + 1u) {
                    dp = dp * sv[j] + p * sd[j];
                    p = p * sv[j];
                }
            }
            top = at;
            sv[top] = p;
            sd[top] = dp;
            top = top + 1u;
        }
    }
    if (top == 0u) {
        return vec2<f32>(0.0);
    }
    return vec2<f32>(sv[top - 1u], sd[top - 1u]);
}

struct Visible {
    ok: bool,
    t: f32,
    n: vec3<f32>,
    k: u32,
}

// First point where a boolean item's solid begins along the ray.
fn visible_surface(item: vec4<u32>, first: u32, end: u32) -> Visible {
    var ev_t: array<f32, 64>;
    var ev_k: array<u32, 64>;
    var ev_in: array<bool, 64>;
    var n_ev = 0u;
    var inside = 0u;
    for (var k = first; k < end && k - first < 32u; k = k + 1u) {
        if (s_hit[k]) {
            if (s_t0[k] > 0.0) {
                ev_t[n_ev] = s_t0[k]; ev_k[n_ev] = k; ev_in[n_ev] = true;
                n_ev = n_ev + 1u;
            } else {
                inside = inside | (1u << (k - first));
            }
            ev_t[n_ev] = s_t1[k]; ev_k[n_ev] = k; ev_in[n_ev] = false;
            n_ev = n_ev + 1u;
        }
    }
    if (n_ev == 0u) {
        return Visible(false, 0.0, vec3<f32>(0.0), NONE);
    }
    // Insertion sort by t.
    for (var i = 1u; i < n_ev; i = i + 1u) {
        let t = ev_t[i]; let kk = ev_k[i]; let e = ev_in[i];
        var j = i;
        while (j > 0u && ev_t[j - 1u] > t) {
            ev_t[j] = ev_t[j - 1u]; ev_k[j] = ev_k[j - 1u]; ev_in[j] = ev_in[j - 1u];
            j = j - 1u;
        }
        ev_t[j] = t; ev_k[j] = kk; ev_in[j] = e;
    }
    var was = eval_inside(item, first, end, inside);
    for (var i = 0u; i < n_ev; i = i + 1u) {
        let k = ev_k[i];
        let bit = 1u << (k - first);
        if (ev_in[i]) {
            inside = inside | bit;
        } else {
            inside = inside & ~bit;
        }
        let now = eval_inside(item, first, end, inside);
        if (now && !was && ev_t[i] > 0.0) {
            if (ev_in[i]) {
                return Visible(true, ev_t[i], s_n0[k], k);
            }
            return Visible(true, ev_t[i], -s_n1[k], k);
        }
        was = now;
    }
    return Visible(false, 0.0, vec3<f32>(0.0), NONE);
}

// `first_solid_from` in soft.rs.
fn first_solid_from(item: vec4<u32>, first: u32, end: u32, ts: f32) -> Visible {
    var inside = 0u;
    for (var k = first; k < end && k - first < 32u; k = k + 1u) {
        if (s_hit[k] && s_t0[k] <= ts && ts < s_t1[k]) {
            inside = inside | (1u << (k - first));
        }
    }
    if (eval_inside(item, first, end, inside)) {
        for (var k = first; k < end; k = k + 1u) {
            if (s_hit[k] && s_t1[k] == ts) {
                return Visible(true, ts, -s_n1[k], k);
            }
        }
        return Visible(false, 0.0, vec3<f32>(0.0), NONE);
    }
    var ev_t: array<f32, 64>;
    var ev_k: array<u32, 64>;
    var ev_in: array<bool, 64>;
    var n_ev = 0u;
    for (var k = first; k < end && k - first < 32u; k = k + 1u) {
        if (s_hit[k]) {
            if (s_t0[k] > ts) {
                ev_t[n_ev] = s_t0[k]; ev_k[n_ev] = k; ev_in[n_ev] = true;
                n_ev = n_ev + 1u;
            }
            if (s_t1[k] > ts) {
                ev_t[n_ev] = s_t1[k]; ev_k[n_ev] = k; ev_in[n_ev] = false;
                n_ev = n_ev + 1u;
            }
        }
    }
    for (var i = 1u; i < n_ev; i = i + 1u) {
        let t = ev_t[i]; let kk = ev_k[i]; let e = ev_in[i];
        var j = i;
        while (j > 0u && ev_t[j - 1u] > t) {
            ev_t[j] = ev_t[j - 1u]; ev_k[j] = ev_k[j - 1u]; ev_in[j] = ev_in[j - 1u];
            j = j - 1u;
        }
        ev_t[j] = t; ev_k[j] = kk; ev_in[j] = e;
    }
    for (var i = 0u; i < n_ev; i = i + 1u) {
        let k = ev_k[i];
        let bit = 1u << (k - first);
        if (ev_in[i]) {
            inside = inside | bit;
        } else {
            inside = inside & ~bit;
        }
        if (eval_inside(item, first, end, inside)) {
            if (ev_in[i]) {
                return Visible(true, ev_t[i], s_n0[k], k);
            }
            return Visible(true, ev_t[i], -s_n1[k], k);
        }
    }
    return Visible(false, 0.0, vec3<f32>(0.0), NONE);
}

struct SP {
    ok: bool,
    sd: f32,
    q: vec3<f32>,
    n: vec3<f32>,
    l: vec3<f32>,
}

fn mat_l(p: Part, v: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(p.l0.xyz, v), dot(p.l1.xyz, v), dot(p.l2.xyz, v));
}

// World unit normal of a local normal (xyz) and the local-to-world distance factor (w).
fn world_normal(p: Part, nl: vec3<f32>) -> vec4<f32> {
    let w = p.inv0.xyz * nl.x + p.inv1.xyz * nl.y + p.inv2.xyz * nl.z;
    let l = max(length(w), 1e-30);
    return vec4<f32>(w / l, l);
}

fn sp_make(p: Part, sd: f32, q: vec3<f32>, n: vec3<f32>, dq0: vec3<f32>, dq1: vec3<f32>, dq2: vec3<f32>) -> SP {
    return SP(true, sd, q, n, vec3<f32>(dot(n, mat_l(p, dq0)), dot(n, mat_l(p, dq1)), dot(n, mat_l(p, dq2))));
}

// `PartGeom::surface_distance`.
fn surface_distance(pi: u32, pw: vec3<f32>) -> SP {
    let p = parts[pi];
    if (p.flags.y == 0u) {
        return SP(false, 0.0, vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0));
    }
    let q = to_local(p, pw);
    let z = vec3<f32>(0.0);
    let centered = p.flags.z != 0u;
    if (p.flags.x == 0u) {
        var best = -INF;
        var ab = 0u;
        var high = false;
        let rows = array<vec3<f32>, 3>(p.inv0.xyz, p.inv1.xyz, p.inv2.xyz);
        for (var a = 0u; a < 3u; a = a + 1u) {
            let l = max(length(rows[a]), 1e-30);
            let dlo = (p.lo[a] - q[a]) / l;
            let dhi = (q[a] - p.hi[a]) / l;
            if (dlo > best) {
                best = dlo; ab = a; high = false;
            }
            if (dhi > best) {
                best = dhi; ab = a; high = true;
            }
        }
        var qs = q;
        var sgn = -1.0;
        if (high) {
            qs[ab] = p.hi[ab];
            sgn = 1.0;
        } else {
            qs[ab] = p.lo[ab];
        }
        let n = world_normal(p, axis_vec(ab, sgn)).xyz;
        var f = 0.0;
        if (centered) {
            f = 0.5 * sgn;
        } else if (high) {
            f = 1.0;
        }
        var dq = array<vec3<f32>, 3>(z, z, z);
        dq[ab] = axis_vec(ab, f);
        return sp_make(p, best, qs, n, dq[0], dq[1], dq[2]);
    } else if (p.flags.x == 1u) {
        let z0 = p.lo.z;
        let z1 = p.hi.z;
        var dz0 = 0.0;
        var dz1 = 1.0;
        if (centered) {
            dz0 = -0.5;
            dz1 = 0.5;
        }
        let h = z1 - z0;
        let r1 = p.lo.w;
        let r2 = p.hi.w;
        let k = (r2 - r1) / h;
        let rho = sqrt(q.x * q.x + q.y * q.y);
        var c = 1.0;
        var sn = 0.0;
        if (rho > 1e-30) {
            c = q.x / rho;
            sn = q.y / rho;
        }
        let rs = r1 + k * (q.z - z0);
        let kk = sqrt(1.0 + k * k);
        let ws = world_normal(p, vec3<f32>(c / kk, sn / kk, -k / kk));
        let side = (rho - rs) / kk / ws.w;
        let l2 = max(length(p.inv2.xyz), 1e-30);
        let bottom = (z0 - q.z) / l2;
        let top = (q.z - z1) / l2;
        if (side >= bottom && side >= top) {
            let vv = (q.z - z0) / h;
            return sp_make(p, side, vec3<f32>(rs * c, rs * sn, q.z), ws.xyz,
                vec3<f32>(0.0, 0.0, dz0 + vv * (dz1 - dz0)),
                vec3<f32>((1.0 - vv) * c, (1.0 - vv) * sn, 0.0),
                vec3<f32>(vv * c, vv * sn, 0.0));
        } else if (bottom >= top) {
            let n = world_normal(p, vec3<f32>(0.0, 0.0, -1.0)).xyz;
            return sp_make(p, bottom, vec3<f32>(q.x, q.y, z0), n, vec3<f32>(0.0, 0.0, dz0), z, z);
        }
        let n = world_normal(p, vec3<f32>(0.0, 0.0, 1.0)).xyz;
        return sp_make(p, top, vec3<f32>(q.x, q.y, z1), n, vec3<f32>(0.0, 0.0, dz1), z, z);
    }
    let r = p.lo.w;
    let rho = max(length(q), 1e-30);
    let nl = q / rho;
    let wn = world_normal(p, nl);
    return sp_make(p, (rho - r) / wn.w, nl * r, wn.xyz, nl, z, z);
}

// `pixel_scale` in soft.rs.
fn pixel_scale(v: View, d: vec3<f32>, t: f32, na: vec3<f32>, nb: vec3<f32>) -> f32 {
    let dd = dot(na, d);
    let f = v.eye.w;
    let ortho = v.right.w > 0.5;
    var g2 = 0.0;
    for (var i = 0u; i < 2u; i = i + 1u) {
        var dv = v.right.xyz / f;
        if (i == 1u) {
            dv = -v.up.xyz / f;
        }
        var dp: vec3<f32>;
        if (abs(dd) < 1e-12) {
            if (ortho) {
                dp = dv;
            } else {
                dp = dv * t;
            }
        } else if (ortho) {
            dp = dv + (-dot(na, dv) / dd) * d;
        } else {
            dp = t * dv + (-t * dot(na, dv) / dd) * d;
        }
        let c = dot(nb, dp);
        g2 = g2 + c * c;
    }
    return max(sqrt(g2), 1e-12);
}

fn to_eye(v: View, n: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(n, v.right.xyz), dot(n, v.up.xyz), -dot(n, v.forward.xyz));
}

fn shade_of(v: View, n_world: vec3<f32>) -> f32 {
    let n = to_eye(v, n_world);
    let k = 0.57735026919;
    let f4 = abs(k * (-n.x - n.y + n.z));
    return v.shade_a.x + v.shade_a.y * n.x + v.shade_a.z * n.y + v.shade_a.w * n.z + v.shade_b.x * f4;
}

fn push_layer(depth: f32, alpha: f32, premult: f32, keep: f32, it: u32, first: u32, end: u32) -> u32 {
    let l = l_count;
    l_depth[l] = depth;
    l_alpha[l] = alpha;
    l_premult[l] = premult;
    l_keep[l] = keep;
    l_item[l] = it;
    l_first[l] = first;
    l_end[l] = end;
    l_split[l] = false;
    l_alpha_a[l] = 1.0;
    l_kappa[l] = 1.0;
    l_cavity[l] = 0.0;
    l_shf[l] = 0.0;
    l_shc[l] = 0.0;
    l_nfirst[l] = 0u;
    l_nend[l] = 0u;
    l_count = l_count + 1u;
    return l;
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>) {
    let index = gid.x + gid.y * nwg.x * 64u;
    if (index >= params.total_pixels) {
        return;
    }
    // Which view.
    var view = 0u;
    for (var i = 1u; i < params.view_count; i = i + 1u) {
        if (index >= views[i].dims.z) {
            view = i;
        }
    }
    let v = views[view];
    let local = index - v.dims.z;
    let px = local % v.dims.x;
    let py = local / v.dims.x;
    let u = vec2<f32>(f32(px) + 0.5, f32(py) + 0.5);
    let x = u.x - f32(v.dims.x) / 2.0;
    let y = f32(v.dims.y) / 2.0 - u.y;
    let focal = v.eye.w;
    var o = v.eye.xyz;
    var d = v.forward.xyz;
    if (v.right.w > 0.5) {
        o = o + v.right.xyz * (x / focal) + v.up.xyz * (y / focal);
    } else {
        d = d + v.right.xyz * (x / focal) + v.up.xyz * (y / focal);
    }
    let hard = params.hard != 0u;
    let sigma = params.sigma;
    let band = CUTOFF * sigma;
    s_count = 0u;
    l_count = 0u;
    n_count = 0u;
    var best_t = INF;
    var best_item = -1;
    var best_n = vec3<f32>(0.0);
    for (var it = 0u; it < params.item_count; it = it + 1u) {
        let r = rects[view * params.item_count + it];
        if (r.x < 0 || i32(px) < r.x || i32(px) >= r.z || i32(py) < r.y || i32(py) >= r.w) {
            continue;
        }
        let item = items[it];
        let ia = item.a;
        let albedo = bitcast<f32>(item.b.w);
        if (s_count + ia.w > MAXS || l_count >= MAXL) {
            continue;
        }
        let first = s_count;
        for (var j = 0u; j < ia.w; j = j + 1u) {
            part_state(s_count, view, code[ia.z + j], u, o, d);
            s_count = s_count + 1u;
        }
        let end = s_count;
        let single = ia.y == 1u;
        var vis: Visible;
        if (single) {
            vis = Visible(s_hit[first] && s_t0[first] > 0.0, s_t0[first], s_n0[first], first);
        } else {
            vis = visible_surface(ia, first, end);
        }
        if (vis.ok && vis.t < best_t) {
            best_t = vis.t;
            best_item = i32(it);
            best_n = vis.n;
        }
        // The continuation of the first part's face past the silhouette.
        let fp = code[ia.z];
        let kf = state_of(first, end, fp);
        var fb_n = vec3<f32>(0.0);
        if (kf != NONE && s_hit[kf]) {
            fb_n = s_n0[kf];
        } else {
            fb_n = near_normal(fp, o, d);
        }
        let fb_depth = dot(v.forward.xyz, parts[fp].center.xyz - v.eye.xyz);
        if (item.b.x != 0u) {
            // A difference with soft cut edges (see the split branch in soft.rs).
            let pos = vec4<u32>(ia.x, item.b.x, ia.z, ia.w);
            var fr: Visible;
            if (item.b.x == 1u) {
                fr = Visible(s_hit[first] && s_t0[first] > 0.0, s_t0[first], s_n0[first], first);
            } else {
                fr = visible_surface(pos, first, end);
            }
            var alpha_a = 0.0;
            if (hard) {
                if (fr.ok) {
                    alpha_a = 1.0;
                }
            } else {
                alpha_a = eval_soft(pos, first, end, NONE).x;
            }
            if (alpha_a <= 0.0) {
                s_count = first;
                continue;
            }
            if (!fr.ok) {
                push_layer(fb_depth, alpha_a, alpha_a * albedo * shade_of(v, fb_n), 1.0, it, first, end);
                continue;
            }
            let pa = o + fr.t * d;
            let part_a = s_part[fr.k];
            let spa = surface_distance(part_a, pa);
            let na_d = dot(fr.n, d);
            let nfirst = n_count;
            var kappa = 1.0;
            var deep_v = 2.0;
            var deep_k = NONE;
            for (var j = 0u; j < item.b.z; j = j + 1u) {
                let b = code[item.b.y + j];
                let ks = state_of(first, end, b);
                if (ks == NONE) {
                    continue;
                }
                var kb = 1.0;
                if (hard) {
                    if (s_hit[ks] && s_t0[ks] <= fr.t && fr.t <= s_t1[ks]) {
                        kb = 0.0;
                    }
                } else {
                    let sp = surface_distance(b, pa);
                    if (!sp.ok) {
                        continue;
                    }
                    let g = pixel_scale(v, d, fr.t, fr.n, sp.n);
                    let sv = sp.sd / g;
                    if (sv <= -band) {
                        kb = 0.0;
                    } else if (sv < band) {
                        kb = logistic(sv / sigma);
                        if (n_count < MAXN) {
                            let nn = n_count;
                            n_part[nn] = b;
                            n_kappa[nn] = kb;
                            n_dk[nn] = kb * (1.0 - kb) / (sigma * g);
                            n_n[nn] = sp.n;
                            n_q[nn] = sp.q;
                            n_l[nn] = sp.l;
                            n_fpart[nn] = NONE;
                            n_along[nn] = 0.0;
                            if (spa.ok) {
                                n_fpart[nn] = part_a;
                                if (abs(na_d) > 1e-12) {
                                    n_along[nn] = -dot(sp.n, d) / na_d;
                                }
                                n_fn[nn] = spa.n;
                                n_fq[nn] = spa.q;
                                n_fl[nn] = spa.l;
                            }
                            n_count = n_count + 1u;
                        }
                    }
                }
                kappa = kappa * kb;
                if (kb < deep_v) {
                    deep_v = kb;
                    deep_k = ks;
                }
            }
            let sh_front = albedo * shade_of(v, fr.n);
            var cavity = 1.0;
            var sh_cav = sh_front;
            if (kappa < 1.0 && deep_k != NONE && s_hit[deep_k] && s_t1[deep_k] > fr.t) {
                let c = first_solid_from(ia, first, end, s_t1[deep_k]);
                if (c.ok) {
                    sh_cav = albedo * shade_of(v, c.n);
                } else {
                    cavity = 0.0;
                    sh_cav = 0.0;
                }
            }
            let alpha = alpha_a * (kappa + (1.0 - kappa) * cavity);
            if (alpha > 0.0) {
                let l = push_layer(fr.t, alpha,
                    alpha_a * (kappa * sh_front + (1.0 - kappa) * cavity * sh_cav), 1.0, it, first, end);
                l_split[l] = true;
                l_alpha_a[l] = alpha_a;
                l_kappa[l] = kappa;
                l_cavity[l] = cavity;
                l_shf[l] = sh_front;
                l_shc[l] = sh_cav;
                l_nfirst[l] = nfirst;
                l_nend[l] = n_count;
            } else {
                s_count = first;
                n_count = nfirst;
            }
            continue;
        }
        var alpha = 0.0;
        var keep = 1.0;
        if (hard) {
            if (vis.ok) {
                alpha = 1.0;
            }
        } else if (single) {
            alpha = s_alpha[first];
        } else {
            let a = eval_soft(ia, first, end, NONE).x;
            var hits = 0u;
            for (var k = first; k < end; k = k + 1u) {
                if (s_hit[k]) {
                    hits = hits | (1u << (k - first));
                }
            }
            let support = eval_inside(ia, first, end, hits);
            if (support && !vis.ok) {
                keep = 0.0;
            }
            alpha = a * keep;
        }
        if (alpha <= 0.0) {
            s_count = first;
            continue;
        }
        var depth = fb_depth;
        var nw = fb_n;
        if (vis.ok) {
            depth = vis.t;
            nw = vis.n;
        }
        push_layer(depth, alpha, alpha * albedo * shade_of(v, nw), keep, it, first, end);
    }
    // Sort layers front to back (by index).
    for (var i = 0u; i < l_count; i = i + 1u) {
        l_order[i] = i;
    }
    for (var i = 1u; i < l_count; i = i + 1u) {
        let li = l_order[i];
        let dd = l_depth[li];
        var j = i;
        while (j > 0u && l_depth[l_order[j - 1u]] > dd) {
            l_order[j] = l_order[j - 1u];
            j = j - 1u;
        }
        l_order[j] = li;
    }
    var m = 0.0;
    var s = 0.0;
    var t = 1.0;
    for (var i = 0u; i < l_count; i = i + 1u) {
        let l = l_order[i];
        s = s + t * l_premult[l];
        m = m + t * l_alpha[l];
        t = t * (1.0 - l_alpha[l]);
    }
    out_soft[index] = vec2<f32>(m, s);
    out_hard[index] = vec4<f32>(to_eye(v, best_n), best_t);
    out_item[index] = best_item;
    if (params.want_entries == 0u || hard || l_count == 0u) {
        return;
    }
    // What lies behind each layer (in sorted order).
    var mb: array<f32, 25>;
    var sb: array<f32, 25>;
    mb[l_count] = 0.0;
    sb[l_count] = 0.0;
    for (var i = l_count; i > 0u; i = i - 1u) {
        let k = i - 1u;
        let l = l_order[k];
        mb[k] = l_alpha[l] + (1.0 - l_alpha[l]) * mb[k + 1u];
        sb[k] = l_premult[l] + (1.0 - l_alpha[l]) * sb[k + 1u];
    }
    var tk = 1.0;
    for (var i = 0u; i < l_count; i = i + 1u) {
        let k = l_order[i];
        let dm_da = tk * (1.0 - mb[i + 1u]);
        let ds_da = -tk * sb[i + 1u];
        let ds_dp = tk;
        tk = tk * (1.0 - l_alpha[k]);
        if (dm_da == 0.0 && ds_da == 0.0 && ds_dp == 0.0) {
            continue;
        }
        let item = items[l_item[k]];
        var prog = item.a;
        var a_factor = 1.0;
        var p_factor = l_premult[k] / l_alpha[k];
        if (l_split[k]) {
            prog = vec4<u32>(item.a.x, item.b.x, item.a.z, item.a.w);
            a_factor = l_kappa[k] + (1.0 - l_kappa[k]) * l_cavity[k];
            p_factor = l_kappa[k] * l_shf[k] + (1.0 - l_kappa[k]) * l_cavity[k] * l_shc[k];
        }
        let dm_dc = dm_da * a_factor;
        let ds_dc = ds_da * a_factor + ds_dp * p_factor;
        for (var q = l_first[k]; q < l_end[k]; q = q + 1u) {
            if (!s_hull[q] || s_covn[q] == 0u) {
                continue;
            }
            var da_item = 1.0;
            if (item.a.y != 1u) {
                da_item = eval_soft(prog, l_first[k], l_end[k], q).y * l_keep[k];
            }
            if (da_item == 0.0) {
                continue;
            }
            let h = hull_info(view, s_part[q]);
            for (var c = 0u; c < s_covn[q]; c = c + 1u) {
                var edge = s_e0[q];
                var w = s_w0[q];
                if (c == 1u) {
                    edge = s_e1[q];
                    w = s_w1[q];
                }
                let f = da_item * w;
                let g = edge_gradient(h, edge, u);
                let slot = atomicAdd(&entries.count, 1u);
                if (slot < params.entry_capacity) {
                    entries.data[slot].a = vec4<u32>(local, s_part[q], edge, view);
                    entries.data[slot].b = vec4<f32>(dm_dc * f, ds_dc * f, g.x, g.y);
                    entries.data[slot].c = vec4<f32>(g.z, g.w, 0.0, 0.0);
                }
            }
        }
        if (!l_split[k]) {
            continue;
        }
        let aa = l_alpha_a[k];
        let dm_dk = dm_da * aa * (1.0 - l_cavity[k]);
        let ds_dk = ds_da * aa * (1.0 - l_cavity[k]) + ds_dp * aa * (l_shf[k] - l_cavity[k] * l_shc[k]);
        if (dm_dk == 0.0 && ds_dk == 0.0) {
            continue;
        }
        for (var nn = l_nfirst[k]; nn < l_nend[k]; nn = nn + 1u) {
            var others = 0.0;
            if (n_kappa[nn] > 0.0) {
                others = l_kappa[k] / n_kappa[nn];
            }
            let f = others * n_dk[nn];
            if (f == 0.0) {
                continue;
            }
            let slot = atomicAdd(&sentries.count, 1u);
            if (slot < params.surface_capacity) {
                sentries.data[slot].a = vec4<u32>(local, n_part[nn], view, 0u);
                sentries.data[slot].b = vec4<f32>(dm_dk * f, ds_dk * f, 0.0, 0.0);
                sentries.data[slot].n = vec4<f32>(n_n[nn], 0.0);
                sentries.data[slot].q = vec4<f32>(n_q[nn], 0.0);
                sentries.data[slot].l = vec4<f32>(n_l[nn], 0.0);
            }
            if (n_fpart[nn] != NONE && n_along[nn] != 0.0) {
                let al = n_along[nn];
                let slot2 = atomicAdd(&sentries.count, 1u);
                if (slot2 < params.surface_capacity) {
                    sentries.data[slot2].a = vec4<u32>(local, n_fpart[nn], view, 0u);
                    sentries.data[slot2].b = vec4<f32>(dm_dk * f * al, ds_dk * f * al, 0.0, 0.0);
                    sentries.data[slot2].n = vec4<f32>(n_fn[nn], 0.0);
                    sentries.data[slot2].q = vec4<f32>(n_fq[nn], 0.0);
                    sentries.data[slot2].l = vec4<f32>(n_fl[nn], 0.0);
                }
            }
        }
    }
}
