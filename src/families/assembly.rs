//! Random assemblies: tables, carcasses with shelves, wagons, lamps, hollow boxes and tubes,
//! stacks, placed side by side or on each other.
//!
//! Every builder draws its dimensions from the parameter pool (`intent`) and places parts
//! so that contacts hold by construction: legs under a top (sometimes through it, an
//! overlap on purpose), rails between legs, wheels on an axle through them (coaxial), a
//! body resting on its axles, shelves and a thin back board inside a carcass, a hollow cut
//! with its top flush, a stem sunk into a shade. Each builder lists the forms that must stay
//! positive (sizes, clearances) for a variation to keep the assembly's meaning.

use super::intent::{Kind, Params};
use super::lin::Lin;
use super::part::{Part, Shape, bounds};
use super::rng::Rng;

/// An assembly being built.
pub struct Asm {
    pub params: Params,
    pub parts: Vec<Part>,
    /// Forms every variation keeps positive.
    pub positive: Vec<Lin>,
    /// Each group's frame origin (for nested `.csg` frames).
    pub origins: Vec<[Lin; 3]>,
    repeats: usize,
}

/// The builders, by name.
const BUILDERS: [&str; 6] = ["table", "carcass", "wagon", "lamp", "hollow", "stack"];

impl Asm {
    fn new(params: Params) -> Asm {
        Asm {
            params,
            parts: Vec::new(),
            positive: Vec::new(),
            origins: Vec::new(),
            repeats: 0,
        }
    }

    fn get(&mut self, rng: &mut Rng, kind: Kind, role: &str) -> Lin {
        self.params.get(rng, kind, role)
    }

    /// Keeps `form` positive in every variation; a form that is zero by intent (two
    /// faces flush through a shared parameter) stays zero and is not a clearance.
    fn keep_positive(&mut self, form: Lin) {
        if !form.terms.is_empty() || form.constant != 0.0 {
            self.positive.push(form);
        }
    }

    fn group(&mut self, origin: &[Lin; 3]) -> usize {
        self.origins.push(origin.clone());
        self.origins.len() - 1
    }

    fn repeat_class(&mut self) -> usize {
        self.repeats += 1;
        self.repeats - 1
    }

    fn push(&mut self, name: String, shape: Shape, group: usize) -> &mut Part {
        let sizes = Part {
            name: String::new(),
            shape: shape.clone(),
            cut: false,
            optional: false,
            group,
            repeat: None,
        }
        .sizes();
        self.positive.extend(sizes);
        self.parts.push(Part {
            name,
            shape,
            cut: false,
            optional: false,
            group,
            repeat: None,
        });
        let last = self.parts.len() - 1;
        &mut self.parts[last]
    }

    fn cube(&mut self, name: String, lo: [Lin; 3], size: [Lin; 3], group: usize) -> &mut Part {
        self.push(name, Shape::Box { lo, size }, group)
    }

    #[allow(clippy::too_many_arguments)]
    fn cyl(
        &mut self,
        name: String,
        axis: usize,
        base: [Lin; 3],
        h: Lin,
        r1: Lin,
        r2: Lin,
        group: usize,
    ) -> &mut Part {
        let shape = Shape::Cylinder {
            axis,
            base,
            h,
            r1,
            r2,
        };
        self.push(name, shape, group)
    }
}

/// A random assembly of 3–60 parts whose numbers use at most `budget` parameters.
pub fn assemble(rng: &mut Rng, budget: usize) -> Asm {
    let params = Params::new(budget, rng);
    let mut asm = Asm::new(params);
    let units = rng.int(1, 4);
    let mut origin = [Lin::zero(), Lin::zero(), Lin::zero()];
    for u in 0..units {
        let name = BUILDERS[rng.int(0, BUILDERS.len() - 1)];
        let start = asm.parts.len();
        build(&mut asm, name, &origin, rng, u);
        let end = asm.parts.len();
        let theta = asm.params.base();
        let b = bounds(&asm.parts[start..end], &theta);
        let gap = if rng.chance(0.3) {
            asm.get(rng, Kind::Gap, "gap")
        } else {
            Default::default()
        };
        // A row of the same unit (tables side by side), each the last one moved along x.
        let copies = if rng.chance(0.25) { rng.int(1, 2) } else { 0 };
        let step = b[0].1.sub(&b[0].0).add(&gap);
        for c in 1..=copies {
            if asm.parts.len() + (end - start) > 60 {
                break;
            }
            copy(&mut asm, start..end, &step.scale(c as f64), c);
        }
        let theta = asm.params.base();
        let b = bounds(&asm.parts[start..], &theta);
        origin = [b[0].1.add(&gap), b[1].0.clone(), Lin::zero()];
        // Sometimes the next unit stands on this one instead of beside it.
        if matches!(name, "table" | "carcass" | "stack") && rng.chance(0.35) {
            origin = [b[0].0.clone(), b[1].0.clone(), b[2].1.clone()];
        }
        if asm.parts.len() > 45 {
            break;
        }
    }
    asm
}

/// Copies `parts` moved by `dx` along x, as a new group with its own repeat classes.
fn copy(asm: &mut Asm, parts: std::ops::Range<usize>, dx: &Lin, c: usize) {
    let first = &asm.origins[asm.parts[parts.start].group];
    let origin = [first[0].add(dx), first[1].clone(), first[2].clone()];
    let g = asm.group(&origin);
    let mut classes: Vec<(usize, usize)> = Vec::new();
    for i in parts {
        let mut p = asm.parts[i].clone();
        match &mut p.shape {
            Shape::Box { lo, .. } => lo[0] = lo[0].add(dx),
            Shape::Cylinder { base, .. } => base[0] = base[0].add(dx),
        }
        p.name = format!("{}_copy{c}", p.name);
        p.group = g;
        if let Some(r) = p.repeat {
            let new = match classes.iter().find(|(old, _)| *old == r) {
                Some(&(_, n)) => n,
                None => {
                    let n = asm.repeat_class();
                    classes.push((r, n));
                    n
                }
            };
            p.repeat = Some(new);
        }
        asm.parts.push(p);
    }
}

fn build(asm: &mut Asm, name: &str, o: &[Lin; 3], rng: &mut Rng, unit: usize) {
    match name {
        "table" => table(asm, o, rng, unit),
        "carcass" => carcass(asm, o, rng, unit),
        "wagon" => wagon(asm, o, rng, unit),
        "lamp" => lamp(asm, o, rng, unit),
        "hollow" => hollow(asm, o, rng, unit),
        _ => stack(asm, o, rng, unit),
    }
}

/// `o + (dx, dy, dz)`.
fn at(o: &[Lin; 3], d: [&Lin; 3]) -> [Lin; 3] {
    std::array::from_fn(|a| o[a].add(d[a]))
}

/// A top on four legs (boxes or round), legs sometimes through the top, rails under it.
fn table(asm: &mut Asm, o: &[Lin; 3], rng: &mut Rng, unit: usize) {
    let g = asm.group(o);
    let w = asm.get(rng, Kind::Length, "top_width");
    let d = asm.get(rng, Kind::Length, "top_depth");
    let t = asm.get(rng, Kind::Thick, "top_thickness");
    let h = asm.get(rng, Kind::Height, "leg_height");
    let l = asm.get(rng, Kind::Thick, "leg_size");
    let through = rng.chance(0.3);
    let round = rng.chance(0.3);
    let z0 = Lin::zero();
    asm.cube(
        format!("top{unit}"),
        at(o, [&z0, &z0, &h]),
        [w.clone(), d.clone(), t.clone()],
        g,
    );
    let leg_h = if through { h.add(&t) } else { h.clone() };
    let class = asm.repeat_class();
    let half = l.scale(0.5);
    for (k, (fx, fy)) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)]
        .into_iter()
        .enumerate()
    {
        let x = w.sub(&l).scale(fx);
        let y = d.sub(&l).scale(fy);
        let name = format!("leg{unit}_{k}");
        let part = if round {
            let base = at(o, [&x.add(&half), &y.add(&half), &z0]);
            asm.cyl(name, 2, base, leg_h.clone(), half.clone(), half.clone(), g)
        } else {
            asm.cube(
                name,
                at(o, [&x, &y, &z0]),
                [l.clone(), l.clone(), leg_h.clone()],
                g,
            )
        };
        part.repeat = Some(class);
    }
    asm.keep_positive(w.plus(-2.0, &l));
    asm.keep_positive(d.plus(-2.0, &l));
    if rng.chance(0.5) {
        let r = asm.get(rng, Kind::Thick, "rail_thickness");
        let rh = asm.get(rng, Kind::Gap, "rail_height");
        let optional = rng.chance(0.6);
        let class = asm.repeat_class();
        for (k, y) in [Lin::zero(), d.sub(&r)].into_iter().enumerate() {
            let lo = at(o, [&l, &y, &h.sub(&rh)]);
            let size = [w.plus(-2.0, &l), r.clone(), rh.clone()];
            let part = asm.cube(format!("rail{unit}_{k}"), lo, size, g);
            part.optional = optional;
            part.repeat = (!optional).then_some(class);
        }
        asm.keep_positive(h.sub(&rh));
        asm.keep_positive(l.sub(&r));
    }
}

/// Two sides, a bottom and a top between them, a thin back board, shelves inside.
fn carcass(asm: &mut Asm, o: &[Lin; 3], rng: &mut Rng, unit: usize) {
    let g = asm.group(o);
    let w = asm.get(rng, Kind::Length, "carcass_width");
    let d = asm.get(rng, Kind::Length, "carcass_depth");
    let h = asm.get(rng, Kind::Height, "carcass_height").scale(2.0);
    let t = asm.get(rng, Kind::Thick, "board");
    let back = asm.get(rng, Kind::Thin, "back_board");
    let z0 = Lin::zero();
    let class = asm.repeat_class();
    for (k, x) in [Lin::zero(), w.sub(&t)].into_iter().enumerate() {
        let part = asm.cube(
            format!("side{unit}_{k}"),
            at(o, [&x, &z0, &z0]),
            [t.clone(), d.clone(), h.clone()],
            g,
        );
        part.repeat = Some(class);
    }
    let inner = w.plus(-2.0, &t);
    asm.cube(
        format!("bottom{unit}"),
        at(o, [&t, &z0, &z0]),
        [inner.clone(), d.clone(), t.clone()],
        g,
    );
    asm.cube(
        format!("lid{unit}"),
        at(o, [&t, &z0, &h.sub(&t)]),
        [inner.clone(), d.clone(), t.clone()],
        g,
    );
    asm.cube(
        format!("back{unit}"),
        at(o, [&z0, &d, &z0]),
        [w.clone(), back, h.clone()],
        g,
    );
    asm.keep_positive(inner.clone());
    asm.keep_positive(h.plus(-2.0, &t));
    let shelves = rng.int(0, 5);
    let mut below = t.clone();
    for k in 0..shelves {
        let gap = asm.get(rng, Kind::Gap, "shelf_gap");
        let ts = if rng.chance(0.7) {
            t.clone()
        } else {
            asm.get(rng, Kind::Thin, "shelf_board")
        };
        let z = below.add(&gap);
        let theta = asm.params.base();
        if h.sub(&t).sub(&z.add(&ts)).eval(&theta) < gap.eval(&theta) {
            break;
        }
        let size = [inner.clone(), d.clone(), ts.clone()];
        let part = asm.cube(format!("shelf{unit}_{k}"), at(o, [&t, &z0, &z]), size, g);
        part.optional = rng.chance(0.6);
        asm.keep_positive(gap);
        below = z.add(&ts);
    }
    asm.keep_positive(h.sub(&t).sub(&below));
}

/// A body on two axles, each through a pair of wheels; a handle in front, sometimes.
fn wagon(asm: &mut Asm, o: &[Lin; 3], rng: &mut Rng, unit: usize) {
    let g = asm.group(o);
    let len = asm.get(rng, Kind::Length, "body_length");
    let wid = asm.get(rng, Kind::Length, "body_width");
    let hb = asm.get(rng, Kind::Height, "body_height");
    let r = asm.get(rng, Kind::Radius, "wheel_radius");
    let ww = asm.get(rng, Kind::Thick, "wheel_width");
    let ra = asm.get(rng, Kind::Thick, "axle_radius").scale(0.5);
    let z0 = Lin::zero();
    let xs = [r.clone(), len.sub(&r)];
    let wheels = asm.repeat_class();
    for (i, x) in xs.iter().enumerate() {
        for (j, y) in [ww.scale(-1.0), wid.clone()].into_iter().enumerate() {
            let base = at(o, [x, &y, &r]);
            let part = asm.cyl(
                format!("wheel{unit}_{i}{j}"),
                1,
                base,
                ww.clone(),
                r.clone(),
                r.clone(),
                g,
            );
            part.repeat = Some(wheels);
        }
    }
    let axles = asm.repeat_class();
    for (i, x) in xs.iter().enumerate() {
        let base = at(o, [x, &ww.scale(-1.0), &r]);
        let part = asm.cyl(
            format!("axle{unit}_{i}"),
            1,
            base,
            wid.plus(2.0, &ww),
            ra.clone(),
            ra.clone(),
            g,
        );
        part.repeat = Some(axles);
    }
    let bottom = r.add(&ra);
    asm.cube(
        format!("body{unit}"),
        at(o, [&z0, &z0, &bottom]),
        [len.clone(), wid.clone(), hb.clone()],
        g,
    );
    asm.keep_positive(len.plus(-2.0, &r));
    asm.keep_positive(r.sub(&ra));
    if rng.chance(0.5) {
        let lh = asm.get(rng, Kind::Gap, "handle_length");
        let th = asm.get(rng, Kind::Thick, "handle_thickness");
        let y = wid.sub(&th).scale(0.5);
        let z = bottom.add(&hb.sub(&th).scale(0.5));
        let part = asm.cube(
            format!("handle{unit}"),
            at(o, [&len, &y, &z]),
            [lh, th.clone(), th.clone()],
            g,
        );
        part.optional = rng.chance(0.5);
        asm.keep_positive(wid.sub(&th));
        asm.keep_positive(hb.sub(&th));
    }
}

/// A round base, a stem on it, a cone shade on the stem (or the stem through the shade).
fn lamp(asm: &mut Asm, o: &[Lin; 3], rng: &mut Rng, unit: usize) {
    let g = asm.group(o);
    let rb = asm.get(rng, Kind::Radius, "base_radius");
    let hb = asm.get(rng, Kind::Thick, "base_height");
    let rs = asm.get(rng, Kind::Thick, "stem_radius").scale(0.5);
    let hs = asm.get(rng, Kind::Height, "stem_height");
    let r1 = asm.get(rng, Kind::Radius, "shade_radius");
    let r2 = r1.scale(0.5);
    let hc = asm.get(rng, Kind::Gap, "shade_height");
    // The centre is where the wider of base and shade touches the unit's frame.
    let theta = asm.params.base();
    let (c, other) = if rb.eval(&theta) >= r1.eval(&theta) {
        (rb.clone(), r1.clone())
    } else {
        (r1.clone(), rb.clone())
    };
    asm.keep_positive(c.sub(&other));
    let z0 = Lin::zero();
    asm.cyl(
        format!("base{unit}"),
        2,
        at(o, [&c, &c, &z0]),
        hb.clone(),
        rb.clone(),
        rb.clone(),
        g,
    );
    let through = rng.chance(0.4);
    asm.cyl(
        format!("stem{unit}"),
        2,
        at(o, [&c, &c, &hb]),
        hs.clone(),
        rs.clone(),
        rs.clone(),
        g,
    );
    let top = hb.add(&hs);
    let shade_z = if through { top.sub(&hc) } else { top.clone() };
    asm.cyl(
        format!("shade{unit}"),
        2,
        at(o, [&c, &c, &shade_z]),
        hc.clone(),
        r1.clone(),
        r2.clone(),
        g,
    );
    asm.keep_positive(rb.sub(&rs));
    asm.keep_positive(r2.sub(&rs));
    if through {
        asm.keep_positive(hs.sub(&hc));
    }
    if rng.chance(0.4) {
        let z = if through { top.clone() } else { top.add(&hc) };
        let base = at(o, [&c, &c, &z]);
        let part = asm.cyl(
            format!("finial{unit}"),
            2,
            base,
            hb.clone(),
            rs.clone(),
            rs.clone(),
            g,
        );
        part.optional = true;
    }
}

/// A box or a tube hollowed by `difference`, the hollow's top flush with the outside's.
fn hollow(asm: &mut Asm, o: &[Lin; 3], rng: &mut Rng, unit: usize) {
    let g = asm.group(o);
    let h = asm.get(rng, Kind::Height, "hollow_height");
    let depth = asm.get(rng, Kind::Height, "hollow_depth").scale(0.5);
    let z0 = Lin::zero();
    if rng.chance(0.5) {
        let r = asm.get(rng, Kind::Radius, "tube_radius");
        let ri = asm.get(rng, Kind::Radius, "bore_radius").scale(0.5);
        asm.cyl(
            format!("tube{unit}"),
            2,
            at(o, [&r, &r, &z0]),
            h.clone(),
            r.clone(),
            r.clone(),
            g,
        );
        let part = asm.cyl(
            format!("bore{unit}"),
            2,
            at(o, [&r, &r, &h.sub(&depth)]),
            depth.clone(),
            ri.clone(),
            ri.clone(),
            g,
        );
        part.cut = true;
        asm.keep_positive(r.sub(&ri));
    } else {
        let w = asm.get(rng, Kind::Length, "box_width");
        let d = asm.get(rng, Kind::Length, "box_depth");
        let wi = asm.get(rng, Kind::Length, "inner_width").scale(0.5);
        let di = asm.get(rng, Kind::Length, "inner_depth").scale(0.5);
        asm.cube(
            format!("box{unit}"),
            at(o, [&z0, &z0, &z0]),
            [w.clone(), d.clone(), h.clone()],
            g,
        );
        let x = w.sub(&wi).scale(0.5);
        let y = d.sub(&di).scale(0.5);
        let part = asm.cube(
            format!("cavity{unit}"),
            at(o, [&x, &y, &h.sub(&depth)]),
            [wi.clone(), di.clone(), depth.clone()],
            g,
        );
        part.cut = true;
        asm.keep_positive(w.sub(&wi));
        asm.keep_positive(d.sub(&di));
    }
    asm.keep_positive(h.sub(&depth));
}

/// Two to four boxes, each centred on the one below.
fn stack(asm: &mut Asm, o: &[Lin; 3], rng: &mut Rng, unit: usize) {
    let g = asm.group(o);
    let n = rng.int(2, 4);
    let w0 = asm.get(rng, Kind::Length, "block_width");
    let d0 = asm.get(rng, Kind::Length, "block_depth");
    let mut z = Lin::zero();
    for k in 0..n {
        let (w, d) = if k == 0 {
            (w0.clone(), d0.clone())
        } else {
            (
                asm.get(rng, Kind::Length, "block_width").scale(0.5),
                asm.get(rng, Kind::Length, "block_depth").scale(0.5),
            )
        };
        let h = asm.get(rng, Kind::Thick, "block_height").scale(2.0);
        let x = w0.sub(&w).scale(0.5);
        let y = d0.sub(&d).scale(0.5);
        let part = asm.cube(
            format!("block{unit}_{k}"),
            at(o, [&x, &y, &z]),
            [w.clone(), d.clone(), h.clone()],
            g,
        );
        part.optional = k > 0 && k == n - 1 && rng.chance(0.4);
        asm.keep_positive(w0.sub(&w));
        asm.keep_positive(d0.sub(&d));
        z = z.add(&h);
    }
}
