//! Writers: a family's model as OpenSCAD text in the styles people write — flat literals,
//! top-level variables, modules with arguments, `for` loops over repeated parts — and in
//! the flat style of OpenSCAD's own `.csg` export (nested `multmatrix`).
//!
//! A writer makes a [`Program`]: text with holes, and for each hole the [`Number`] that
//! fills it (an affine form over the intent parameters, how far one unit of it moves a
//! face, and the part whose dropping sets it to 0). Rendering the same program with other
//! values gives a variation file: the same program with other numbers, token for token.

use super::lin::Lin;
use super::part::{Part, Shape};

/// How a family's model is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    Flat,
    Variables,
    Modules,
    Loops,
    Csg,
}

impl Style {
    pub const ALL: [Style; 5] = [
        Style::Flat,
        Style::Variables,
        Style::Modules,
        Style::Loops,
        Style::Csg,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Style::Flat => "flat",
            Style::Variables => "variables",
            Style::Modules => "modules",
            Style::Loops => "loops",
            Style::Csg => "csg",
        }
    }
}

/// One number of a program: its form over θ, its leverage (world units per unit), and the
/// part whose dropping sets it to 0.
#[derive(Debug, Clone)]
pub struct Number {
    pub lin: Lin,
    pub leverage: f64,
    pub drop: Option<usize>,
}

#[derive(Debug, Clone)]
enum Piece {
    Text(String),
    Number(usize),
}

/// A model's text with its numbers left as holes.
#[derive(Debug, Clone, Default)]
pub struct Program {
    pieces: Vec<Piece>,
    pub numbers: Vec<Number>,
}

/// A number as a literal: integers plain, others to six decimals.
pub fn literal(v: f64) -> String {
    if v == v.round() && v.abs() < 1e15 {
        return format!("{}", v as i64);
    }
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

impl Program {
    fn text(&mut self, s: &str) {
        match self.pieces.last_mut() {
            Some(Piece::Text(t)) => t.push_str(s),
            _ => self.pieces.push(Piece::Text(s.to_string())),
        }
    }

    fn number(&mut self, lin: Lin, leverage: f64, drop: Option<usize>) {
        self.numbers.push(Number {
            lin,
            leverage,
            drop,
        });
        self.pieces.push(Piece::Number(self.numbers.len() - 1));
    }

    /// Each number's value at `theta`, 0 for the numbers of `dropped` parts.
    pub fn values(&self, theta: &[f64], dropped: &[usize]) -> Vec<f64> {
        self.numbers
            .iter()
            .map(|n| match n.drop {
                Some(p) if dropped.contains(&p) => 0.0,
                _ => n.lin.eval(theta),
            })
            .collect()
    }

    /// The text with `values` in its holes.
    pub fn render(&self, values: &[f64]) -> String {
        let mut s = String::new();
        for p in &self.pieces {
            match p {
                Piece::Text(t) => s.push_str(t),
                Piece::Number(i) => s.push_str(&literal(values[*i])),
            }
        }
        s
    }
}

/// The parts as `style` writes them, with the input's parameter values `theta` (they
/// choose which radius bounds a cone and which side a dropped box loses).
pub fn write(style: Style, parts: &[Part], names: &[String], theta: &[f64]) -> Program {
    let mut w = Writer {
        p: Program::default(),
        parts,
        names,
        theta,
        style,
        own: Vec::new(),
    };
    match style {
        Style::Flat | Style::Csg => w.flat(),
        Style::Variables | Style::Loops => w.variables(),
        Style::Modules => w.modules(),
    }
    w.p
}

struct Writer<'a> {
    p: Program,
    parts: &'a [Part],
    names: &'a [String],
    theta: &'a [f64],
    style: Style,
    /// Optional parts' own variables (their drop size), by part.
    own: Vec<(usize, String)>,
}

/// How far one unit of parameter `i` moves a face of `parts`.
fn leverage(parts: &[&Part], i: usize, theta: &[f64]) -> f64 {
    let mut lev: f64 = 0.0;
    for p in parts {
        for (lo, hi) in p.world(theta) {
            lev = lev
                .max(lo.coefficient(i).abs())
                .max(hi.coefficient(i).abs());
        }
    }
    lev
}

/// The rotation that lays a cylinder's local z along world `axis`, as `rotate` and as the
/// rows of a `.csg` matrix.
fn rotation(axis: usize) -> (&'static str, [[i32; 3]; 3]) {
    match axis {
        0 => ("rotate([0, 90, 0]) ", [[0, 0, 1], [0, 1, 0], [-1, 0, 0]]),
        1 => ("rotate([-90, 0, 0]) ", [[1, 0, 0], [0, 0, 1], [0, -1, 0]]),
        _ => ("", [[1, 0, 0], [0, 1, 0], [0, 0, 1]]),
    }
}

impl Writer<'_> {
    /// A number: a literal hole in the literal styles, an expression of the parameters'
    /// names otherwise.
    fn num(&mut self, lin: &Lin, drop: Option<usize>) {
        if matches!(self.style, Style::Flat | Style::Csg) {
            self.p.number(lin.clone(), 1.0, drop);
            return;
        }
        if let Some(name) = drop.and_then(|d| self.own.iter().find(|(p, _)| *p == d)) {
            let name = name.1.clone();
            self.p.text(&name);
            return;
        }
        let e = expression(lin, self.names);
        self.p.text(&e);
    }

    fn nums(&mut self, lins: &[&Lin], drop_at: Option<(usize, usize)>) {
        for (k, l) in lins.iter().enumerate() {
            if k > 0 {
                self.p.text(", ");
            }
            let drop = drop_at.and_then(|(at, part)| (at == k).then_some(part));
            self.num(l, drop);
        }
    }

    /// The drop number of part `i`: which of its sizes, if it is optional.
    fn drop_of(&self, i: usize) -> Option<(usize, usize)> {
        let p = &self.parts[i];
        p.optional.then(|| (p.drop_size(self.theta), i))
    }

    /// One part as `translate(…) [rotate(…)] primitive;` (or a `.csg` `multmatrix`).
    fn part(&mut self, i: usize, origin: Option<&[Lin; 3]>) {
        let p = &self.parts[i];
        let (place, axis) = match &p.shape {
            Shape::Box { lo, .. } => (lo.clone(), 2),
            Shape::Cylinder { axis, base, .. } => (base.clone(), *axis),
        };
        let place: [Lin; 3] = match origin {
            Some(o) => std::array::from_fn(|a| place[a].sub(&o[a])),
            None => place,
        };
        let (rotate, matrix) = rotation(axis);
        if self.style == Style::Csg {
            self.p.text("multmatrix([");
            for (r, row) in matrix.iter().enumerate() {
                self.p
                    .text(&format!("[{}, {}, {}, ", row[0], row[1], row[2]));
                self.num(&place[r], None);
                self.p.text("], ");
            }
            self.p.text("[0, 0, 0, 1]]) { ");
        } else {
            self.p.text("translate([");
            self.nums(&[&place[0], &place[1], &place[2]], None);
            self.p.text("]) ");
            self.p.text(rotate);
        }
        self.primitive(i);
        self.p.text(if self.style == Style::Csg {
            " }\n"
        } else {
            "\n"
        });
    }

    fn primitive(&mut self, i: usize) {
        let drop = self.drop_of(i);
        let csg = self.style == Style::Csg;
        match &self.parts[i].shape {
            Shape::Box { size, .. } => {
                self.p.text(if csg { "cube(size = [" } else { "cube([" });
                self.nums(&[&size[0], &size[1], &size[2]], drop);
                self.p.text(if csg { "], center = false);" } else { "]);" });
            }
            Shape::Cylinder { h, r1, r2, .. } => {
                self.p.text(if csg {
                    "cylinder($fn = 0, $fa = 12, $fs = 2, h = "
                } else {
                    "cylinder(h = "
                });
                self.num(h, drop.map(|d| d.1));
                if r1 == r2 && !csg {
                    self.p.text(", r = ");
                    self.num(r1, None);
                } else {
                    self.p.text(", r1 = ");
                    self.num(r1, None);
                    self.p.text(", r2 = ");
                    self.num(r2, None);
                }
                self.p.text(if csg { ", center = false);" } else { ");" });
            }
        }
    }

    /// Parts `from..to` in order, each cut part inside a `difference` with the part
    /// before it; `loops` writes runs of a repeat class as one `for`.
    fn body(&mut self, from: usize, to: usize, indent: &str, origin: Option<&[Lin; 3]>) {
        let mut i = from;
        while i < to {
            let cut = i + 1 < to && self.parts[i + 1].cut;
            if cut {
                self.p.text(&format!("{indent}difference() {{\n{indent}  "));
                self.part(i, origin);
                self.p.text(&format!("{indent}  "));
                self.part(i + 1, origin);
                self.p.text(&format!("{indent}}}\n"));
                i += 2;
                continue;
            }
            let run = self.run(i, to);
            self.p.text(indent);
            if run > 1 {
                self.for_loop(i, run);
            } else {
                self.part(i, origin);
            }
            i += run;
        }
    }

    /// How many parts from `i` a `for` loop writes (1 when not in the loops style).
    fn run(&self, i: usize, to: usize) -> usize {
        let p = &self.parts[i];
        if self.style != Style::Loops || p.optional || p.repeat.is_none() {
            return 1;
        }
        let mut n = 1;
        while i + n < to
            && self.parts[i + n].repeat == p.repeat
            && !self.parts[i + n].optional
            && !(i + n + 1 < to && self.parts[i + n + 1].cut)
        {
            n += 1;
        }
        n
    }

    fn for_loop(&mut self, i: usize, n: usize) {
        self.p.text("for (p = [");
        for k in i..i + n {
            if k > i {
                self.p.text(", ");
            }
            let place = match &self.parts[k].shape {
                Shape::Box { lo, .. } => lo.clone(),
                Shape::Cylinder { base, .. } => base.clone(),
            };
            self.p.text("[");
            self.nums(&[&place[0], &place[1], &place[2]], None);
            self.p.text("]");
        }
        let axis = match &self.parts[i].shape {
            Shape::Cylinder { axis, .. } => *axis,
            Shape::Box { .. } => 2,
        };
        self.p
            .text(&format!("]) translate(p) {}", rotation(axis).0));
        self.primitive(i);
        self.p.text("\n");
    }

    /// Flat literals, or `.csg`'s nested frames (one `multmatrix` per group).
    fn flat(&mut self) {
        if self.style == Style::Flat {
            self.body(0, self.parts.len(), "", None);
            return;
        }
        let mut i = 0;
        while i < self.parts.len() {
            let g = self.parts[i].group;
            let end = (i..self.parts.len())
                .find(|&k| self.parts[k].group != g)
                .unwrap_or(self.parts.len());
            let theta = self.theta;
            let o = frame_origin(&self.parts[i..end], theta);
            self.p.text("multmatrix([[1, 0, 0, ");
            self.num(&o[0], None);
            self.p.text("], [0, 1, 0, ");
            self.num(&o[1], None);
            self.p.text("], [0, 0, 1, ");
            self.num(&o[2], None);
            self.p.text("], [0, 0, 0, 1]]) {\n");
            self.body(i, end, "  ", Some(&o));
            self.p.text("}\n");
            i = end;
        }
    }

    /// Top-level variables: one per parameter, one per optional part's drop size.
    fn variables(&mut self) {
        let all: Vec<&Part> = self.parts.iter().collect();
        for (i, name) in self.names.iter().enumerate() {
            let lev = leverage(&all, i, self.theta);
            self.p.text(&format!("{name} = "));
            self.p.number(Lin::param(i), lev, None);
            self.p.text(";\n");
        }
        self.own_variables();
        self.p.text("\n");
        self.body(0, self.parts.len(), "", None);
    }

    /// Each optional part gets a top-level variable of its own for its drop size.
    fn own_variables(&mut self) {
        for i in 0..self.parts.len() {
            if let Some((at, _)) = self.drop_of(i) {
                let name = format!("{}_size", self.parts[i].name);
                let lin = self.parts[i].sizes()[at].clone();
                self.p.text(&format!("{name} = "));
                self.p.number(lin, 1.0, Some(i));
                self.p.text(";\n");
                self.own.push((i, name));
            }
        }
    }

    /// A module per group, its parameters as arguments, called once with the values.
    fn modules(&mut self) {
        let mut i = 0;
        while i < self.parts.len() {
            let g = self.parts[i].group;
            let end = (i..self.parts.len())
                .find(|&k| self.parts[k].group != g)
                .unwrap_or(self.parts.len());
            let group: Vec<&Part> = self.parts[i..end].iter().collect();
            let used: Vec<usize> = (0..self.names.len())
                .filter(|&k| leverage(&group, k, self.theta) > 0.0)
                .collect();
            let own: Vec<String> = (i..end)
                .filter(|&k| self.parts[k].optional)
                .map(|k| format!("{}_size", self.parts[k].name))
                .collect();
            let args: Vec<String> = used
                .iter()
                .map(|&k| self.names[k].clone())
                .chain(own.iter().cloned())
                .collect();
            self.p
                .text(&format!("module unit{g}({}) {{\n", args.join(", ")));
            for k in i..end {
                if self.parts[k].optional {
                    self.own.push((k, format!("{}_size", self.parts[k].name)));
                }
            }
            self.body(i, end, "  ", None);
            self.p.text(&format!("}}\nunit{g}("));
            let mut sep = "";
            for &k in &used {
                self.p.text(&format!("{sep}{} = ", self.names[k]));
                self.p
                    .number(Lin::param(k), leverage(&group, k, self.theta), None);
                sep = ", ";
            }
            for k in i..end {
                if let Some((at, _)) = self.drop_of(k) {
                    let lin = self.parts[k].sizes()[at].clone();
                    self.p.text(&format!("{sep}{}_size = ", self.parts[k].name));
                    self.p.number(lin, 1.0, Some(k));
                    sep = ", ";
                }
            }
            self.p.text(");\n\n");
            i = end;
        }
    }
}

/// A `.csg` frame's origin: its parts' lowest corner (as forms, picked at `theta`).
fn frame_origin(parts: &[Part], theta: &[f64]) -> [Lin; 3] {
    let b = super::part::bounds(parts, theta);
    [b[0].0.clone(), b[1].0.clone(), b[2].0.clone()]
}

/// `lin` as OpenSCAD arithmetic over the parameters' `names` (`w - 2 * t`, `d / 2`).
pub fn expression(lin: &Lin, names: &[String]) -> String {
    let mut s = String::new();
    for &(i, k) in &lin.terms {
        let (sign, k) = if k < 0.0 { ("-", -k) } else { ("+", k) };
        let term = if k == 1.0 {
            names[i].clone()
        } else if (1.0 / k).fract() == 0.0 && k < 1.0 {
            format!("{} / {}", names[i], literal(1.0 / k))
        } else {
            format!("{} * {}", names[i], literal(k))
        };
        if s.is_empty() {
            s = if sign == "-" {
                format!("-{term}")
            } else {
                term
            };
        } else {
            s.push_str(&format!(" {sign} {term}"));
        }
    }
    if lin.constant != 0.0 || s.is_empty() {
        let c = literal(lin.constant);
        s = if s.is_empty() {
            c
        } else {
            format!("{s} + {c}")
        };
    }
    s
}
