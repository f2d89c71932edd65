//! The bee world as `u32` words for the sensing kernels (`shaders/bee_world.wgsl` reads them in
//! the same layout; `shaders/bee_sense.wgsl` senses with them): the volume, the ranges, the
//! grids' shapes, every obstacle, target and target particle, in the scalar `S` of the bees
//! that sense them, each value converted on the host exactly as `host-sim/src/bees/sense.rs`
//! and `world.rs` convert it (`S::from_f32` of the scenario's `f32` values, the neighbour range
//! squared in `S`, a box's or shaft's open faces decided in `f32` against the world's bounds as
//! `Shape3::surface` decides them), so the GPU computes from the same bits as the CPU.
//!
//! One buffer, five parts, each at the offset the header gives:
//!
//! | part | words |
//! |---|---|
//! | header ([`HEADER_WORDS`]) | the counts and offsets of the other parts, the volume's bounds, the neighbour range and its square, the obstacle sensing range, the bees' grid and the particles' grid ([`GRID_WORDS`] each: origin, 1 / cell, cells along x, y and z, query margin) |
//! | obstacles ([`OBSTACLE_WORDS`] each) | shape, id, active, open faces (a bit per face), the bounding box, then a sphere's centre and radius, a box's corners, or a shaft's axis (x, z), radius, bottom and top |
//! | targets ([`TARGET_WORDS`] each) | id, active, centre, radius (the goals: `BeeWorld::target_center`) |
//! | particles ([`PARTICLE_WORDS`] each) | the active targets' virtual particles sorted by their cell of the particles' grid (then by index): the point in `S` and the particle's index in `BeeWorld::particles` (the tie key of the CPU's selection) |
//! | particle cells | the particles' grid's `starts`: the particles of cell `c` are `starts[c]..starts[c + 1]` |
//!
//! The sensed bees travel as struct-of-arrays words ([`sensed_words`]: positions, velocities,
//! densities as the CPU converts them, ids), and what each bee's frame takes besides the world
//! as two more arrays ([`input_words`]: its clock `t` and its group's goal, a target id).
//!
//! Both grids are the GPU's own: uniform grids whose cell key is computed in `S`
//! (`bee_world_cell_xyz` in `bee_world.wgsl`: `floor((x - origin) · (1 / cell))` per axis,
//! clamped to the grid; the key `(z · ny + y) · nx + x`). That function is monotonic in each
//! coordinate (a saturating subtraction, a product by a positive constant rounded to nearest, a
//! floor and a clamp all are, in `Fx` and in IEEE `f32`), so the cells between the keys of
//! `p - r` and `p + r` hold every point within `r` of `p` on each axis, whatever the rounding:
//! a query by radius `r` plus the margin (which covers the rounding of the exact tests' own
//! arithmetic) sees every candidate the CPU's grid sees, and the selection is by exact key. The
//! bees' grid is sorted on the GPU (`GpuGrid`); the particles, which change only with the
//! targets, are sorted here with the same key computed in `S` on the host ([`GridShape3::cell_of`],
//! the same operations, so the same bits, as the WGSL).
//!
//! What the CPU's frame computes in `f32` or `f64` only narrows its candidates, so the GPU need
//! not (and does not) reproduce it: the `f32` pre-selection of neighbours and particles (a
//! rounding margin past the range), the test of whether a bee is near a target's sphere at all
//! (the particles lie on the spheres), and an obstacle's `may_be_within` (its bounding box
//! widened by the range and a margin; the GPU has its own, in `S`, over the bounding box in
//! `S` widened by the range and the grid margin). Every decision that can change a frame is
//! made in `S` on both sides.

use swarm_core::{Scalar, Vec3};

use super::layout::Word;
use crate::bees::{BeeWorld, Shape3};
use crate::scalar::{SimScalar, v3};

/// Words of the header (`BEE_WORLD_HEADER_WORDS`).
pub const HEADER_WORDS: usize = 32;
/// Words of a grid's shape in the header (`BEE_WORLD_GRID_WORDS`): origin (x, y, z), 1 / cell,
/// cells along x, y and z, query margin.
pub const GRID_WORDS: usize = 8;
/// Words of an obstacle (`BEE_WORLD_OBSTACLE_WORDS`).
pub const OBSTACLE_WORDS: usize = 16;
/// Words of a target (`BEE_WORLD_TARGET_WORDS`).
pub const TARGET_WORDS: usize = 6;
/// Words of a target particle (`BEE_WORLD_PARTICLE_WORDS`).
pub const PARTICLE_WORDS: usize = 4;

/// Header word: the number of obstacles (`BEE_WORLD_H_OBSTACLES`).
pub const H_OBSTACLES: usize = 0;
/// Header word: where the obstacles start.
pub const H_OBSTACLES_AT: usize = 1;
/// Header word: the number of targets.
pub const H_TARGETS: usize = 2;
/// Header word: where the targets start.
pub const H_TARGETS_AT: usize = 3;
/// Header word: the number of target particles.
pub const H_PARTICLES: usize = 4;
/// Header word: where the particles start.
pub const H_PARTICLES_AT: usize = 5;
/// Header word: where the particles' grid's `starts` start.
pub const H_PARTICLE_STARTS_AT: usize = 6;
/// Header words: the volume's bounds (min x, y, z, max x, y, z).
pub const H_BOUNDS: usize = 7;
/// Header word: the neighbour range h + 2r (`BeeWorld::range`).
pub const H_RANGE: usize = 13;
/// Header word: the neighbour range squared in `S` (the selection key's limit, strict).
pub const H_RANGE2: usize = 14;
/// Header word: the obstacle sensing range 2·d0 (`BeeWorld::sense_range`).
pub const H_SENSE: usize = 15;
/// Header words: the bees' grid ([`GRID_WORDS`]).
pub const H_GRID: usize = 16;
/// Header words: the particles' grid ([`GRID_WORDS`]).
pub const H_PARTICLE_GRID: usize = 24;

/// Grid word: the origin (x, y, z) (`BEE_WORLD_G_ORIGIN`).
pub const G_ORIGIN: usize = 0;
/// Grid word: 1 / the cell's edge.
pub const G_INV_CELL: usize = 3;
/// Grid words: the cells along x, y and z.
pub const G_SIZE: usize = 4;
/// Grid word: what a query adds to its radius.
pub const G_MARGIN: usize = 7;

/// Obstacle shape: a ball (`BEE_WORLD_SPHERE`).
pub const SHAPE_SPHERE: u32 = 0;
/// Obstacle shape: an axis-aligned box.
pub const SHAPE_BOX: u32 = 1;
/// Obstacle shape: a vertical cylinder.
pub const SHAPE_SHAFT: u32 = 2;
/// A bee's goal word when its group has none (`BEE_WORLD_NO_GOAL`; target ids are `u16`).
pub const NO_GOAL: u32 = u32::MAX;

/// Words per sensed bee ([`sensed_words`]).
pub const SENSED_WORDS: usize = 8;
/// Where the sensed bees' arrays start, in multiples of the bee count: positions (three words
/// a bee), velocities (three), densities, ids (`BEE_SENSED_*` in `bee_sense.wgsl`).
pub const SENSED_POS: usize = 0;
/// See [`SENSED_POS`].
pub const SENSED_VEL: usize = 3;
/// See [`SENSED_POS`].
pub const SENSED_DENSITY: usize = 6;
/// See [`SENSED_POS`].
pub const SENSED_ID: usize = 7;

/// Words per bee of a frame's inputs ([`input_words`]).
pub const INPUT_WORDS: usize = 2;
/// Where the inputs' arrays start, in multiples of the bee count: the frame times (`S`), the
/// goals (a target id, [`NO_GOAL`] for none) (`BEE_INPUT_*` in `bee_sense.wgsl`).
pub const INPUT_T: usize = 0;
/// See [`INPUT_T`].
pub const INPUT_GOAL: usize = 1;

/// The WGSL constants of the layout and their values (checked against `bee_world.wgsl` and
/// `bee_sense.wgsl` by a test).
pub const WGSL_CONSTANTS: &[(&str, u32)] = &[
    ("BEE_WORLD_HEADER_WORDS", HEADER_WORDS as u32),
    ("BEE_WORLD_GRID_WORDS", GRID_WORDS as u32),
    ("BEE_WORLD_OBSTACLE_WORDS", OBSTACLE_WORDS as u32),
    ("BEE_WORLD_TARGET_WORDS", TARGET_WORDS as u32),
    ("BEE_WORLD_PARTICLE_WORDS", PARTICLE_WORDS as u32),
    ("BEE_WORLD_H_OBSTACLES", H_OBSTACLES as u32),
    ("BEE_WORLD_H_OBSTACLES_AT", H_OBSTACLES_AT as u32),
    ("BEE_WORLD_H_TARGETS", H_TARGETS as u32),
    ("BEE_WORLD_H_TARGETS_AT", H_TARGETS_AT as u32),
    ("BEE_WORLD_H_PARTICLES", H_PARTICLES as u32),
    ("BEE_WORLD_H_PARTICLES_AT", H_PARTICLES_AT as u32),
    (
        "BEE_WORLD_H_PARTICLE_STARTS_AT",
        H_PARTICLE_STARTS_AT as u32,
    ),
    ("BEE_WORLD_H_BOUNDS", H_BOUNDS as u32),
    ("BEE_WORLD_H_RANGE", H_RANGE as u32),
    ("BEE_WORLD_H_RANGE2", H_RANGE2 as u32),
    ("BEE_WORLD_H_SENSE", H_SENSE as u32),
    ("BEE_WORLD_H_GRID", H_GRID as u32),
    ("BEE_WORLD_H_PARTICLE_GRID", H_PARTICLE_GRID as u32),
    ("BEE_WORLD_G_ORIGIN", G_ORIGIN as u32),
    ("BEE_WORLD_G_INV_CELL", G_INV_CELL as u32),
    ("BEE_WORLD_G_SIZE", G_SIZE as u32),
    ("BEE_WORLD_G_MARGIN", G_MARGIN as u32),
    ("BEE_WORLD_SPHERE", SHAPE_SPHERE),
    ("BEE_WORLD_BOX", SHAPE_BOX),
    ("BEE_WORLD_SHAFT", SHAPE_SHAFT),
    ("BEE_WORLD_NO_GOAL", NO_GOAL),
    ("BEE_SENSED_POS", SENSED_POS as u32),
    ("BEE_SENSED_VEL", SENSED_VEL as u32),
    ("BEE_SENSED_DENSITY", SENSED_DENSITY as u32),
    ("BEE_SENSED_ID", SENSED_ID as u32),
    ("BEE_INPUT_T", INPUT_T as u32),
    ("BEE_INPUT_GOAL", INPUT_GOAL as u32),
];

/// Cells of a GPU grid at most along an axis.
const MAX_CELLS_PER_AXIS: f32 = 1024.0;
/// Cells of the particles' grid at most along an axis.
const MAX_PARTICLE_CELLS_PER_AXIS: f32 = 64.0;

/// A uniform grid of cubic cells over a box: `size[0] × size[1] × size[2]` cells of edge `cell`
/// from `origin`; the cell of a point is computed in the bees' scalar (see the module's
/// documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridShape3 {
    /// The lower corner of cell 0.
    pub origin: [f32; 3],
    /// The cells' edge.
    pub cell: f32,
    /// Cells along x, y and z.
    pub size: [u32; 3],
    /// What a query adds to its radius (the rounding of the exact tests).
    pub margin: f32,
}

impl GridShape3 {
    /// A grid over `[lo, hi]` with cells of edge at least `cell` and at most `max` cells along
    /// an axis.
    fn over(lo: [f32; 3], hi: [f32; 3], cell: f32, max: f32, margin: f32) -> GridShape3 {
        let extent: [f32; 3] = std::array::from_fn(|k| (hi[k] - lo[k]).max(0.0));
        let widest = extent.iter().fold(0.0f32, |m, &e| m.max(e)) / max;
        let cell = cell.max(widest).max(1.0 / 64.0);
        GridShape3 {
            origin: lo,
            cell,
            size: extent.map(|e| ((e / cell).ceil() as u32).clamp(1, max as u32)),
            margin,
        }
    }

    /// The bees' grid for `n` bees in `w`: cells no smaller than the neighbour range and its
    /// margin (a query reads at most 3 × 3 × 3 cells), about one bee per cell when the bees are
    /// sparse (as [`BeeWorld::size_grids`]), at most 1,024 cells along an axis.
    pub fn of(w: &BeeWorld, n: usize) -> GridShape3 {
        let margin = margin(w);
        let volume: f32 = (0..3).map(|k| (w.max[k] - w.min[k]).max(1e-3)).product();
        let sparse = (volume / n.max(1) as f32).cbrt();
        let cell = (w.range + margin).max(sparse);
        GridShape3::over(w.min, w.max, cell, MAX_CELLS_PER_AXIS, margin)
    }

    /// The particles' grid of `w`: over the particles' bounding box (as the CPU's
    /// `particle_grid`), cells no smaller than the neighbour range and its margin, at most 64
    /// along an axis; one cell at the volume's corner if there are no particles.
    pub fn particles(w: &BeeWorld) -> GridShape3 {
        let (mut lo, mut hi) = (w.min, w.min);
        if let Some(first) = w.particles.first() {
            (lo, hi) = (*first, *first);
            for p in &w.particles {
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
        let margin = margin(w);
        GridShape3::over(
            lo,
            hi,
            w.range + margin,
            MAX_PARTICLE_CELLS_PER_AXIS,
            margin,
        )
    }

    /// Its cells.
    pub fn cells(&self) -> u32 {
        self.size.iter().product()
    }

    /// The cell of `p` as `bee_world_cell_xyz` computes it in `S`: per axis
    /// `floor((x - origin) · (1 / cell))` clamped to the grid.
    pub fn cell_xyz<S: Scalar>(&self, p: Vec3<S>) -> [u32; 3] {
        let inv = S::from_f32(1.0 / self.cell);
        let axis = |x: S, o: f32, n: u32| {
            let c = ((x - S::from_f32(o)) * inv).floor_i32();
            c.clamp(0, n as i32 - 1) as u32
        };
        [
            axis(p.x, self.origin[0], self.size[0]),
            axis(p.y, self.origin[1], self.size[1]),
            axis(p.z, self.origin[2], self.size[2]),
        ]
    }

    /// The key of `p`'s cell in the grid's sort (`bee_world_cell_of`): `(z · ny + y) · nx + x`.
    pub fn cell_of<S: Scalar>(&self, p: Vec3<S>) -> u32 {
        let [x, y, z] = self.cell_xyz(p);
        (z * self.size[1] + y) * self.size[0] + x
    }

    /// Its [`GRID_WORDS`] words over `S`.
    fn words<S: Word>(&self) -> [u32; GRID_WORDS] {
        let s = |v: f32| S::from_f32(v).to_word();
        [
            s(self.origin[0]),
            s(self.origin[1]),
            s(self.origin[2]),
            s(1.0 / self.cell),
            self.size[0],
            self.size[1],
            self.size[2],
            s(self.margin),
        ]
    }
}

/// What a grid query of `w` adds to its radius: 1/64 and a few ulps of the largest coordinate
/// of the volume (the rounding of the exact tests in `S`, of `p ± r`, of the cell key).
fn margin(w: &BeeWorld) -> f32 {
    let extent = [w.min, w.max]
        .iter()
        .flatten()
        .fold(0.0f32, |m, c| m.max(c.abs()));
    1.0 / 64.0 + 4.0 * (1e-3 + extent * 1e-6)
}

/// `r` squared in `S`, as `sense.rs` computes a range's limit.
fn squared<S: Scalar>(r: f32) -> S {
    let r = S::from_f32(r);
    r * r
}

/// The open faces of obstacle shape `shape` in the world `[lo, hi]`, a bit per face, as
/// `Shape3::surface` decides them (in `f32`): a box's `-x, +x, -y, +y, -z, +z` (bits 0 to 5),
/// a shaft's bottom and top caps (bits 0 and 1); 0 for a sphere.
pub fn open_faces(shape: &Shape3, lo: [f32; 3], hi: [f32; 3]) -> u32 {
    match *shape {
        Shape3::Sphere { .. } => 0,
        Shape3::Box { min, max } => (0..6)
            .filter(|&face| {
                let k = face / 2;
                if face % 2 == 0 {
                    min[k] > lo[k]
                } else {
                    max[k] < hi[k]
                }
            })
            .fold(0, |m, face| m | 1 << face),
        Shape3::Shaft { y_min, y_max, .. } => {
            u32::from(y_min > lo[1]) | u32::from(y_max < hi[1]) << 1
        }
    }
}

/// The world `w` as words over `S`, with the bees' grid `grid` (the particles' grid is
/// [`GridShape3::particles`] of `w`, its particles sorted here).
pub fn world_words<S: Word>(w: &BeeWorld, grid: &GridShape3) -> Vec<u32> {
    let s = |v: f32| S::from_f32(v).to_word();
    let mut obstacles = Vec::with_capacity(w.obstacles.len() * OBSTACLE_WORDS);
    for o in &w.obstacles {
        let (lo, hi) = o.shape.aabb();
        let (shape, params) = match o.shape {
            Shape3::Sphere { center, radius } => (
                SHAPE_SPHERE,
                [center[0], center[1], center[2], radius, 0.0, 0.0],
            ),
            Shape3::Box { min, max } => {
                (SHAPE_BOX, [min[0], min[1], min[2], max[0], max[1], max[2]])
            }
            Shape3::Shaft {
                center,
                radius,
                y_min,
                y_max,
            } => (
                SHAPE_SHAFT,
                [center[0], center[1], radius, y_min, y_max, 0.0],
            ),
        };
        obstacles.extend([
            shape,
            o.id.into(),
            o.active.into(),
            open_faces(&o.shape, w.min, w.max),
        ]);
        obstacles.extend(lo.map(s));
        obstacles.extend(hi.map(s));
        obstacles.extend(params.map(s));
    }
    let mut targets = Vec::with_capacity(w.targets.len() * TARGET_WORDS);
    for t in &w.targets {
        targets.extend([u32::from(t.id), u32::from(t.active)]);
        targets.extend(t.center.map(s));
        targets.push(s(t.radius));
    }
    // The particles sorted by cell, then index (a stable sort), and the cells' starts.
    let pgrid = GridShape3::particles(w);
    let cells: Vec<u32> = w
        .particles
        .iter()
        .map(|p| pgrid.cell_of::<S>(Vec3::from_f32(p[0], p[1], p[2])))
        .collect();
    let mut order: Vec<usize> = (0..w.particles.len()).collect();
    order.sort_by_key(|&j| cells[j]);
    let mut starts = vec![0u32; pgrid.cells() as usize + 1];
    for &c in &cells {
        starts[c as usize + 1] += 1;
    }
    for c in 1..starts.len() {
        starts[c] += starts[c - 1];
    }
    let mut particles = Vec::with_capacity(w.particles.len() * PARTICLE_WORDS);
    for j in order {
        let p = w.particles[j];
        particles.extend([s(p[0]), s(p[1]), s(p[2]), j as u32]);
    }

    let mut h = vec![0u32; HEADER_WORDS];
    let mut at = HEADER_WORDS;
    h[H_OBSTACLES] = w.obstacles.len() as u32;
    h[H_OBSTACLES_AT] = at as u32;
    at += obstacles.len();
    h[H_TARGETS] = w.targets.len() as u32;
    h[H_TARGETS_AT] = at as u32;
    at += targets.len();
    h[H_PARTICLES] = w.particles.len() as u32;
    h[H_PARTICLES_AT] = at as u32;
    at += particles.len();
    h[H_PARTICLE_STARTS_AT] = at as u32;
    h[H_BOUNDS..H_BOUNDS + 3].copy_from_slice(&w.min.map(s));
    h[H_BOUNDS + 3..H_BOUNDS + 6].copy_from_slice(&w.max.map(s));
    h[H_RANGE] = s(w.range);
    h[H_RANGE2] = squared::<S>(w.range).to_word();
    h[H_SENSE] = s(w.sense_range);
    h[H_GRID..H_GRID + GRID_WORDS].copy_from_slice(&grid.words::<S>());
    h[H_PARTICLE_GRID..H_PARTICLE_GRID + GRID_WORDS].copy_from_slice(&pgrid.words::<S>());
    h.extend(obstacles);
    h.extend(targets);
    h.extend(particles);
    h.extend(starts);
    h
}

/// The sensed bees of `w` as words over `S`, [`SENSED_WORDS`] per bee: one array per field
/// (see [`SENSED_POS`]), exactly as the CPU's frame converts them (`v3`, `S::from_f64`).
pub fn sensed_words<S: Word + SimScalar>(w: &BeeWorld) -> Vec<u32> {
    let s = &w.sensed;
    let mut out = Vec::with_capacity(s.pos.len() * SENSED_WORDS);
    let point = |out: &mut Vec<u32>, p: [f64; 3]| {
        let v: Vec3<S> = v3(p);
        out.extend([v.x.to_word(), v.y.to_word(), v.z.to_word()]);
    };
    s.pos.iter().for_each(|&p| point(&mut out, p));
    s.vel.iter().for_each(|&p| point(&mut out, p));
    out.extend(s.density.iter().map(|&d| S::from_f64(d).to_word()));
    out.extend(&s.id);
    out
}

/// What the frame of a bee takes besides the world (`bee_frame`'s `t` and `group_goal`): its
/// own clock, and the object id of its group's target, whose centre is the goal while the
/// target is active (`BeeWorld::target_center`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameInput<S> {
    /// The frame time.
    pub t: S,
    /// The group's target.
    pub goal: Option<u16>,
}

/// The inputs of the bees' frames (by slot) as words, [`INPUT_WORDS`] per bee: the times, then
/// the goals (see [`INPUT_T`]).
pub fn input_words<S: Word>(inputs: &[FrameInput<S>]) -> Vec<u32> {
    let mut out = Vec::with_capacity(inputs.len() * INPUT_WORDS);
    out.extend(inputs.iter().map(|i| i.t.to_word()));
    out.extend(inputs.iter().map(|i| i.goal.map_or(NO_GOAL, u32::from)));
    out
}
