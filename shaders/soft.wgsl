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
    flags: vec4<u32>,    // kind (0 box, 1 frustum, 2 sphere), valid
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
// Per item: program offset, program length, parts offset, parts count (into `code`).
@group(0) @binding(7) var<storage, read> items: array<vec4<u32>>;
// Programs (op << 24 | argument) and item part lists.
@group(0) @binding(8) var<storage, read> code: array<u32>;
// Per pixel: m, s.
@group(0) @binding(9) var<storage, read_write> out_soft: array<vec2<f32>>;
// Per pixel: eye normal xyz, depth; item in `out_item`.
@group(0) @binding(10) var<storage, read_write> out_hard: array<vec4<f32>>;
@group(0) @binding(11) var<storage, read_write> out_item: array<i32>;
@group(0) @binding(12) var<storage, read_write> entries: Entries;

const CUTOFF: f32 = 9.0;
const HULL_MARGIN: f32 = 1.5;
const MAXL: u32 = 24u;       // layers per pixel
const MAXS: u32 = 48u;       // part states per pixel
const MAXSTACK: u32 = 16u;
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

// Layers at this pixel.
var<private> l_depth: array<f32, MAXL>;
var<private> l_alpha: array<f32, MAXL>;
var<private> l_shade: array<f32, MAXL>;
var<private> l_keep: array<f32, MAXL>;
var<private> l_item: array<u32, MAXL>;
var<private> l_first: array<u32, MAXL>;
var<private> l_end: array<u32, MAXL>;
var<private> l_count: u32;

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
        return Visible(false, 0.0, vec3<f32>(0.0));
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
                return Visible(true, ev_t[i], s_n0[k]);
            }
            return Visible(true, ev_t[i], -s_n1[k]);
        }
        was = now;
    }
    return Visible(false, 0.0, vec3<f32>(0.0));
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
    s_count = 0u;
    l_count = 0u;
    var best_t = INF;
    var best_item = -1;
    var best_n = vec3<f32>(0.0);
    for (var it = 0u; it < params.item_count; it = it + 1u) {
        let r = rects[view * params.item_count + it];
        if (r.x < 0 || i32(px) < r.x || i32(px) >= r.z || i32(py) < r.y || i32(py) >= r.w) {
            continue;
        }
        let item = items[it];
        if (s_count + item.w > MAXS || l_count >= MAXL) {
            continue;
        }
        let first = s_count;
        for (var j = 0u; j < item.w; j = j + 1u) {
            part_state(s_count, view, code[item.z + j], u, o, d);
            s_count = s_count + 1u;
        }
        let end = s_count;
        let single = item.y == 1u;
        var vis: Visible;
        if (single) {
            vis = Visible(s_hit[first] && s_t0[first] > 0.0, s_t0[first], s_n0[first]);
        } else {
            vis = visible_surface(item, first, end);
        }
        if (vis.ok && vis.t < best_t) {
            best_t = vis.t;
            best_item = i32(it);
            best_n = vis.n;
        }
        var alpha = 0.0;
        var keep = 1.0;
        if (params.hard != 0u) {
            if (vis.ok) {
                alpha = 1.0;
            }
        } else if (single) {
            alpha = s_alpha[first];
        } else {
            let a = eval_soft(item, first, end, 0xffffffffu).x;
            var hits = 0u;
            for (var k = first; k < end; k = k + 1u) {
                if (s_hit[k]) {
                    hits = hits | (1u << (k - first));
                }
            }
            let support = eval_inside(item, first, end, hits);
            if (support && !vis.ok) {
                keep = 0.0;
            }
            alpha = a * keep;
        }
        if (alpha <= 0.0) {
            s_count = first;
            continue;
        }
        var depth = 0.0;
        var nw = vec3<f32>(0.0);
        if (vis.ok) {
            depth = vis.t;
            nw = vis.n;
        } else {
            // The item's first part continues its face past the silhouette.
            let fp = code[item.z];
            let k = state_of(first, end, fp);
            if (k != 0xffffffffu && s_hit[k]) {
                nw = s_n0[k];
            } else {
                nw = near_normal(fp, o, d);
            }
            depth = dot(v.forward.xyz, parts[fp].center.xyz - v.eye.xyz);
        }
        let l = l_count;
        l_depth[l] = depth;
        l_alpha[l] = alpha;
        l_shade[l] = shade_of(v, nw);
        l_keep[l] = keep;
        l_item[l] = it;
        l_first[l] = first;
        l_end[l] = end;
        l_count = l_count + 1u;
    }
    // Sort layers front to back.
    for (var i = 1u; i < l_count; i = i + 1u) {
        let dd = l_depth[i]; let a = l_alpha[i]; let sh = l_shade[i]; let kp = l_keep[i];
        let im = l_item[i]; let f = l_first[i]; let e = l_end[i];
        var j = i;
        while (j > 0u && l_depth[j - 1u] > dd) {
            l_depth[j] = l_depth[j - 1u]; l_alpha[j] = l_alpha[j - 1u]; l_shade[j] = l_shade[j - 1u];
            l_keep[j] = l_keep[j - 1u]; l_item[j] = l_item[j - 1u]; l_first[j] = l_first[j - 1u];
            l_end[j] = l_end[j - 1u];
            j = j - 1u;
        }
        l_depth[j] = dd; l_alpha[j] = a; l_shade[j] = sh; l_keep[j] = kp;
        l_item[j] = im; l_first[j] = f; l_end[j] = e;
    }
    var m = 0.0;
    var s = 0.0;
    var t = 1.0;
    for (var i = 0u; i < l_count; i = i + 1u) {
        s = s + t * l_alpha[i] * l_shade[i];
        m = m + t * l_alpha[i];
        t = t * (1.0 - l_alpha[i]);
    }
    out_soft[index] = vec2<f32>(m, s);
    out_hard[index] = vec4<f32>(to_eye(v, best_n), best_t);
    out_item[index] = best_item;
    if (params.want_entries == 0u || params.hard != 0u || l_count == 0u) {
        return;
    }
    // What lies behind each layer.
    var mb: array<f32, 25>;
    var sb: array<f32, 25>;
    mb[l_count] = 0.0;
    sb[l_count] = 0.0;
    for (var i = l_count; i > 0u; i = i - 1u) {
        let k = i - 1u;
        mb[k] = l_alpha[k] + (1.0 - l_alpha[k]) * mb[k + 1u];
        sb[k] = l_alpha[k] * l_shade[k] + (1.0 - l_alpha[k]) * sb[k + 1u];
    }
    var tk = 1.0;
    for (var k = 0u; k < l_count; k = k + 1u) {
        let dm_da = tk * (1.0 - mb[k + 1u]);
        let ds_da = tk * (l_shade[k] - sb[k + 1u]);
        tk = tk * (1.0 - l_alpha[k]);
        if (dm_da == 0.0 && ds_da == 0.0) {
            continue;
        }
        let item = items[l_item[k]];
        for (var q = l_first[k]; q < l_end[k]; q = q + 1u) {
            if (!s_hull[q] || s_covn[q] == 0u) {
                continue;
            }
            var da_item = 1.0;
            if (item.y != 1u) {
                da_item = eval_soft(item, l_first[k], l_end[k], q).y * l_keep[k];
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
                    entries.data[slot].b = vec4<f32>(dm_da * f, ds_da * f, g.x, g.y);
                    entries.data[slot].c = vec4<f32>(g.z, g.w, 0.0, 0.0);
                }
            }
        }
    }
}
