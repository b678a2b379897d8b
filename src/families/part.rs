//! A family's parts: boxes and cylinders (cones when the radii differ), axis-aligned, each
//! number an affine form over the intent parameters.
//!
//! A box is its low corner and its size; a cylinder the centre of its low end, the world
//! axis it lies along, its length and its two radii (`r1` at the low end). A part may be
//! cut from the part before it (`difference`), be optional (a variation may drop it, by
//! setting its drop number to 0), and belong to a repeat class (identical sizes, other
//! places: what a writer may put in a `for` loop).

use super::lin::Lin;

#[derive(Debug, Clone)]
pub enum Shape {
    Box {
        lo: [Lin; 3],
        size: [Lin; 3],
    },
    Cylinder {
        axis: usize,
        base: [Lin; 3],
        h: Lin,
        r1: Lin,
        r2: Lin,
    },
}

#[derive(Debug, Clone)]
pub struct Part {
    pub name: String,
    pub shape: Shape,
    /// Subtracted from the part before it.
    pub cut: bool,
    /// A variation may do without it.
    pub optional: bool,
    /// Which builder placed it (a module of the `modules` style, a nested frame of `.csg`).
    pub group: usize,
    /// Parts of one class have equal sizes and are written consecutively.
    pub repeat: Option<usize>,
}

impl Part {
    /// The world interval on each axis, as forms; for a cone across its axis the larger
    /// radius (at the input values `theta`) bounds it.
    pub fn world(&self, theta: &[f64]) -> [(Lin, Lin); 3] {
        match &self.shape {
            Shape::Box { lo, size } => {
                std::array::from_fn(|a| (lo[a].clone(), lo[a].add(&size[a])))
            }
            Shape::Cylinder {
                axis,
                base,
                h,
                r1,
                r2,
            } => {
                let r = if r2.eval(theta) > r1.eval(theta) {
                    r2
                } else {
                    r1
                };
                std::array::from_fn(|a| {
                    if a == *axis {
                        (base[a].clone(), base[a].add(h))
                    } else {
                        (base[a].sub(r), base[a].add(r))
                    }
                })
            }
        }
    }

    /// Every size of the part (extents, length, radii).
    pub fn sizes(&self) -> Vec<Lin> {
        match &self.shape {
            Shape::Box { size, .. } => size.to_vec(),
            Shape::Cylinder { h, r1, r2, .. } => vec![h.clone(), r1.clone(), r2.clone()],
        }
    }

    /// The size a variation sets to 0 to drop the part: a box's thinnest side (at `theta`),
    /// a cylinder's length.
    pub fn drop_size(&self, theta: &[f64]) -> usize {
        match &self.shape {
            Shape::Box { size, .. } => (0..3)
                .min_by(|&a, &b| size[a].eval(theta).total_cmp(&size[b].eval(theta)))
                .unwrap_or(0),
            Shape::Cylinder { .. } => 0,
        }
    }

    pub fn is_cylinder(&self) -> bool {
        matches!(self.shape, Shape::Cylinder { .. })
    }
}

/// The bounding box of `parts` at `theta`, as forms (the extreme faces).
pub fn bounds(parts: &[Part], theta: &[f64]) -> [(Lin, Lin); 3] {
    let mut out: [(Lin, Lin); 3] = Default::default();
    for (a, side) in out.iter_mut().enumerate() {
        let mut lo: Option<Lin> = None;
        let mut hi: Option<Lin> = None;
        for p in parts.iter().filter(|p| !p.cut) {
            let (l, h) = p.world(theta)[a].clone();
            if lo.as_ref().is_none_or(|x| l.eval(theta) < x.eval(theta)) {
                lo = Some(l);
            }
            if hi.as_ref().is_none_or(|x| h.eval(theta) > x.eval(theta)) {
                hi = Some(h);
            }
        }
        *side = (lo.unwrap_or_default(), hi.unwrap_or_default());
    }
    out
}
