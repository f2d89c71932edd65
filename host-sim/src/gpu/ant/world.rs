//! The ant world as `u32` words for the sensing kernels (`shaders/ant_world.wgsl` reads them in
//! the same layout; `shaders/ant_sense.wgsl` senses with them): the arena, the ranges, the
//! route, the grid's shape and every object, in the scalar `S` of the ants that sense them, each
//! value converted on the host exactly as `host-sim/src/ants/sense.rs` and `world.rs` convert
//! it (`S::from_f32` of the scenario's `f32` values, a range squared in `S`, a polygon edge's
//! normal computed in `f32` by `edge_normal` and then converted), so the GPU computes from the
//! same bits as the CPU.
//!
//! One buffer, four parts, each at the offset the header gives:
//!
//! | part | words |
//! |---|---|
//! | header ([`HEADER_WORDS`]) | the counts and offsets of the other parts, the arena's bounds, the contact range and its square, the collision range and its square, the sensing range, the step reach, the grid (origin, 1 / cell, cells across, cells up, query margin) |
//! | objects ([`OBJECT_WORDS`] each) | kind, id, active, extra (a food's amount, [`AMOUNT_ENDLESS`] for none; a way point's order), shape, then a circle's centre and radius or a polygon's first vertex and vertex count |
//! | vertices ([`VERTEX_WORDS`] each) | every polygon's vertices in order, each with the edge from it to the next: the edge's outward unit normal, its unit direction and length in `S` and whether it has one (`Vec2::normalized` and `length` of `b - a`, what `closest_on_segment` computes for every ant, computed once with the same functions) |
//! | route | the way points' ids in visiting order |
//!
//! The sensed ants travel as struct-of-arrays words too ([`sensed_words`]: positions, arrivals,
//! ids, labels, nests, origins, each an array over the ants), and the predictions of the plan
//! phase as an array of positions ([`predicted_words`]).
//!
//! The grid ([`GridShape`]) is the GPU's own: a uniform grid over the arena whose cell key is
//! computed in `S` (`ant_world_cell` in `ant_world.wgsl`: `floor((x - origin) · (1 / cell))`
//! per axis, clamped to the grid). That function is monotonic in each coordinate (a saturating
//! subtraction, a product by a positive constant rounded to nearest, a floor and a clamp all
//! are, in `Fx` and in IEEE `f32`), so the cells between the keys of `p - r` and `p + r` hold
//! every ant within `r` of `p` on each axis, whatever the rounding: a query by radius `r` plus
//! the margin (which covers the rounding of the exact tests' own arithmetic) sees every
//! candidate the CPU's grid sees, and the selection is by exact key.

use swarm_core::Vec2;

use super::layout::Word;
use crate::ants::{AntObjectKind, AntWorld, Shape2, edge_normal};
use crate::scalar::{SimScalar, v2};

/// Words of the header (`ANT_WORLD_HEADER_WORDS`).
pub const HEADER_WORDS: usize = 24;
/// Words of an object (`ANT_WORLD_OBJECT_WORDS`).
pub const OBJECT_WORDS: usize = 8;
/// Words of a polygon vertex (`ANT_WORLD_VERTEX_WORDS`): the vertex, and of the edge from it to
/// the next the outward normal, the unit direction, the length and whether the edge has a
/// direction (a flag).
pub const VERTEX_WORDS: usize = 8;

/// Header word: the number of objects (`ANT_WORLD_H_OBJECTS`).
pub const H_OBJECTS: usize = 0;
/// Header word: where the objects start.
pub const H_OBJECTS_AT: usize = 1;
/// Header word: the number of polygon vertices.
pub const H_VERTICES: usize = 2;
/// Header word: where the vertices start.
pub const H_VERTICES_AT: usize = 3;
/// Header word: the number of way points on the route.
pub const H_ROUTE: usize = 4;
/// Header word: where the route starts.
pub const H_ROUTE_AT: usize = 5;
/// Header words: the arena's bounds (min x, min y, max x, max y) as a robot senses them.
pub const H_BOUNDS: usize = 6;
/// Header word: the contact range (the plan frame's neighbours).
pub const H_CONTACT: usize = 10;
/// Header word: the contact range squared in `S` (their selection key's limit).
pub const H_CONTACT2: usize = 11;
/// Header word: the collision range (the resolve frame's neighbours).
pub const H_COLLISION: usize = 12;
/// Header word: the collision range squared in `S`.
pub const H_COLLISION2: usize = 13;
/// Header word: the sensing range of objects.
pub const H_SENSE: usize = 14;
/// Header word: the step reach (the resolve frame's obstacle pieces).
pub const H_STEP_REACH: usize = 15;
/// Header words: the grid's origin (x, y).
pub const H_GRID_ORIGIN: usize = 16;
/// Header word: 1 / the grid's cell size.
pub const H_GRID_INV_CELL: usize = 18;
/// Header word: cells across.
pub const H_GRID_NX: usize = 19;
/// Header word: cells up.
pub const H_GRID_NY: usize = 20;
/// Header word: what a grid query adds to its radius.
pub const H_GRID_MARGIN: usize = 21;

/// Object kind: a nest (`ANT_WORLD_NEST`).
pub const KIND_NEST: u32 = 0;
/// Object kind: a food source.
pub const KIND_FOOD: u32 = 1;
/// Object kind: an obstacle.
pub const KIND_OBSTACLE: u32 = 2;
/// Object kind: a disturbance.
pub const KIND_DISTURBANCE: u32 = 3;
/// Object kind: a way point.
pub const KIND_WAYPOINT: u32 = 4;
/// Shape: a disc (`ANT_WORLD_CIRCLE`).
pub const SHAPE_CIRCLE: u32 = 0;
/// Shape: a polygon.
pub const SHAPE_POLYGON: u32 = 1;
/// A food source's extra word when it is endless.
pub const AMOUNT_ENDLESS: u32 = u32::MAX;

/// Words per sensed ant ([`sensed_words`]).
pub const SENSED_WORDS: usize = 8;
/// Where the sensed ants' arrays start, in multiples of the stride ([`sensed_stride`]):
/// positions (two words an ant), arrivals (two), ids, labels, nests, origins (`ANT_SENSED_*`
/// in `ant_sense.wgsl`).
pub const SENSED_POS: usize = 0;
/// See [`SENSED_POS`].
pub const SENSED_ARRIVAL: usize = 2;
/// See [`SENSED_POS`].
pub const SENSED_ID: usize = 4;
/// See [`SENSED_POS`].
pub const SENSED_LABEL: usize = 5;
/// See [`SENSED_POS`].
pub const SENSED_NEST: usize = 6;
/// See [`SENSED_POS`].
pub const SENSED_ORIGIN: usize = 7;

/// The WGSL constants of the layout and their values (checked against `ant_world.wgsl` and
/// `ant_sense.wgsl` by a test).
pub const WGSL_CONSTANTS: &[(&str, u32)] = &[
    ("ANT_WORLD_HEADER_WORDS", HEADER_WORDS as u32),
    ("ANT_WORLD_OBJECT_WORDS", OBJECT_WORDS as u32),
    ("ANT_WORLD_VERTEX_WORDS", VERTEX_WORDS as u32),
    ("ANT_WORLD_H_OBJECTS", H_OBJECTS as u32),
    ("ANT_WORLD_H_OBJECTS_AT", H_OBJECTS_AT as u32),
    ("ANT_WORLD_H_VERTICES", H_VERTICES as u32),
    ("ANT_WORLD_H_VERTICES_AT", H_VERTICES_AT as u32),
    ("ANT_WORLD_H_ROUTE", H_ROUTE as u32),
    ("ANT_WORLD_H_ROUTE_AT", H_ROUTE_AT as u32),
    ("ANT_WORLD_H_BOUNDS", H_BOUNDS as u32),
    ("ANT_WORLD_H_CONTACT", H_CONTACT as u32),
    ("ANT_WORLD_H_CONTACT2", H_CONTACT2 as u32),
    ("ANT_WORLD_H_COLLISION", H_COLLISION as u32),
    ("ANT_WORLD_H_COLLISION2", H_COLLISION2 as u32),
    ("ANT_WORLD_H_SENSE", H_SENSE as u32),
    ("ANT_WORLD_H_STEP_REACH", H_STEP_REACH as u32),
    ("ANT_WORLD_H_GRID_ORIGIN", H_GRID_ORIGIN as u32),
    ("ANT_WORLD_H_GRID_INV_CELL", H_GRID_INV_CELL as u32),
    ("ANT_WORLD_H_GRID_NX", H_GRID_NX as u32),
    ("ANT_WORLD_H_GRID_NY", H_GRID_NY as u32),
    ("ANT_WORLD_H_GRID_MARGIN", H_GRID_MARGIN as u32),
    ("ANT_WORLD_NEST", KIND_NEST),
    ("ANT_WORLD_FOOD", KIND_FOOD),
    ("ANT_WORLD_OBSTACLE", KIND_OBSTACLE),
    ("ANT_WORLD_DISTURBANCE", KIND_DISTURBANCE),
    ("ANT_WORLD_WAYPOINT", KIND_WAYPOINT),
    ("ANT_WORLD_CIRCLE", SHAPE_CIRCLE),
    ("ANT_WORLD_POLYGON", SHAPE_POLYGON),
    ("ANT_WORLD_AMOUNT_ENDLESS", AMOUNT_ENDLESS),
    ("ANT_SENSED_POS", SENSED_POS as u32),
    ("ANT_SENSED_ARRIVAL", SENSED_ARRIVAL as u32),
    ("ANT_SENSED_ID", SENSED_ID as u32),
    ("ANT_SENSED_LABEL", SENSED_LABEL as u32),
    ("ANT_SENSED_NEST", SENSED_NEST as u32),
    ("ANT_SENSED_ORIGIN", SENSED_ORIGIN as u32),
];

/// Cells of the GPU grid at most, across or up.
const MAX_CELLS_PER_AXIS: f32 = 4096.0;

/// The GPU's neighbour grid over the arena: `nx × ny` square cells from `origin`; the cell of a
/// point is computed in the ants' scalar (see the module's documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridShape {
    /// The lower-left corner of cell 0.
    pub origin: [f32; 2],
    /// The cells' side.
    pub cell: f32,
    /// Cells across.
    pub nx: u32,
    /// Cells up.
    pub ny: u32,
}

impl GridShape {
    /// The grid for `n` ants in `w`: cells no smaller than the query ranges (and half a unit),
    /// about one ant per cell when the ants are sparse (as [`AntWorld::size_grids`]), at most
    /// 4,096 cells across and up.
    pub fn of(w: &AntWorld, n: usize) -> GridShape {
        let (width, height) = (w.max[0] - w.min[0], w.max[1] - w.min[1]);
        let range = w.contact_range.max(w.collision_range).max(0.5);
        let sparse = (width * height / n.max(1) as f32).sqrt();
        let widest = width.max(height) / MAX_CELLS_PER_AXIS;
        let cell = range.max(sparse).max(widest);
        let cells =
            |extent: f32| ((extent / cell).ceil() as u32).clamp(1, MAX_CELLS_PER_AXIS as u32);
        GridShape {
            origin: w.min,
            cell,
            nx: cells(width),
            ny: cells(height),
        }
    }

    /// Its cells.
    pub fn cells(&self) -> u32 {
        self.nx * self.ny
    }
}

/// `r` squared in `S`, as `sense.rs` computes a range's limit.
fn squared<S: Word>(r: f32) -> S {
    let r = S::from_f32(r);
    r * r
}

/// The world `w` as words over `S`, with the grid `grid`.
pub fn world_words<S: Word>(w: &AntWorld, grid: &GridShape) -> Vec<u32> {
    let s = |v: f32| S::from_f32(v).to_word();
    let mut objects = Vec::with_capacity(w.objects.len() * OBJECT_WORDS);
    let mut vertices = Vec::new();
    for o in &w.objects {
        let (kind, extra) = match o.kind {
            AntObjectKind::Nest => (KIND_NEST, 0),
            AntObjectKind::Food { amount } => (KIND_FOOD, amount.unwrap_or(AMOUNT_ENDLESS)),
            AntObjectKind::Obstacle => (KIND_OBSTACLE, 0),
            AntObjectKind::Disturbance => (KIND_DISTURBANCE, 0),
            AntObjectKind::Waypoint { order } => (KIND_WAYPOINT, order),
        };
        objects.extend([kind, o.id.into(), o.active.into(), extra]);
        match &o.shape {
            Shape2::Circle { center, radius } => {
                objects.extend([SHAPE_CIRCLE, s(center[0]), s(center[1]), s(*radius)]);
            }
            Shape2::Polygon { points } => {
                let first = (vertices.len() / VERTEX_WORDS) as u32;
                objects.extend([SHAPE_POLYGON, first, points.len() as u32, 0]);
                let at = |p: [f32; 2]| Vec2::new(S::from_f32(p[0]), S::from_f32(p[1]));
                for k in 0..points.len() {
                    let (a, b) = (at(points[k]), at(points[(k + 1) % points.len()]));
                    let n: Vec2<S> = edge_normal(points, k);
                    let ab = b - a;
                    let u = ab.normalized();
                    let d = u.unwrap_or(Vec2::zero());
                    vertices.extend([
                        a.x.to_word(),
                        a.y.to_word(),
                        n.x.to_word(),
                        n.y.to_word(),
                        d.x.to_word(),
                        d.y.to_word(),
                        ab.length().to_word(),
                        u.is_some().into(),
                    ]);
                }
            }
        }
    }
    let margin = 1.0 / 64.0 + 4.0 * w.rounding_margin();
    let mut h = vec![0u32; HEADER_WORDS];
    h[H_OBJECTS] = w.objects.len() as u32;
    h[H_OBJECTS_AT] = HEADER_WORDS as u32;
    h[H_VERTICES] = (vertices.len() / VERTEX_WORDS) as u32;
    h[H_VERTICES_AT] = (HEADER_WORDS + objects.len()) as u32;
    h[H_ROUTE] = w.route.len() as u32;
    h[H_ROUTE_AT] = (HEADER_WORDS + objects.len() + vertices.len()) as u32;
    h[H_BOUNDS..H_BOUNDS + 4].copy_from_slice(&[
        s(w.min[0]),
        s(w.min[1]),
        s(w.max[0]),
        s(w.max[1]),
    ]);
    h[H_CONTACT] = s(w.contact_range);
    h[H_CONTACT2] = squared::<S>(w.contact_range).to_word();
    h[H_COLLISION] = s(w.collision_range);
    h[H_COLLISION2] = squared::<S>(w.collision_range).to_word();
    h[H_SENSE] = s(w.sense_range);
    h[H_STEP_REACH] = s(w.step_reach);
    h[H_GRID_ORIGIN] = s(grid.origin[0]);
    h[H_GRID_ORIGIN + 1] = s(grid.origin[1]);
    h[H_GRID_INV_CELL] = s(1.0 / grid.cell);
    h[H_GRID_NX] = grid.nx;
    h[H_GRID_NY] = grid.ny;
    h[H_GRID_MARGIN] = s(margin);
    h.extend(objects);
    h.extend(vertices);
    h.extend(w.route.iter().map(|&id| u32::from(id)));
    h
}

/// The stride of the sensed ants' arrays for `n` ants: `n` rounded up to a multiple of 64 (at
/// least 64), so that every array starts 256-byte aligned and can be bound on its own.
pub fn sensed_stride(n: usize) -> usize {
    n.next_multiple_of(64).max(64)
}

/// The sensed ants of `w` as words over `S`, [`SENSED_WORDS`] arrays of [`sensed_stride`]
/// words (positions and arrivals two arrays each; see [`SENSED_POS`]), positions in `S`
/// exactly as the CPU converts them (`v2`); zero words past the last ant.
pub fn sensed_words<S: Word + SimScalar>(w: &AntWorld) -> Vec<u32> {
    let s = &w.sensed;
    let stride = sensed_stride(s.pos.len());
    let mut out = Vec::with_capacity(stride * SENSED_WORDS);
    let mut array = |words: &mut dyn Iterator<Item = u32>, len: usize| {
        let at = out.len();
        out.extend(words);
        out.resize(at + len, 0);
    };
    let point = |p: &[f64; 2]| {
        let v: Vec2<S> = v2(*p);
        [v.x.to_word(), v.y.to_word()]
    };
    array(&mut s.pos.iter().flat_map(point), 2 * stride);
    array(&mut s.arrival.iter().flat_map(point), 2 * stride);
    array(&mut s.id.iter().copied(), stride);
    array(&mut s.label.iter().map(|&l| l as u32), stride);
    array(&mut s.nest.iter().map(|&x| u32::from(x)), stride);
    array(&mut s.origin.iter().map(|&x| u32::from(x)), stride);
    out
}

/// The bindings of the sensed ants' arrays in `ant_sense.wgsl` (positions, arrivals, ids,
/// labels, nests, origins), ranges of `buffer` (written by [`sensed_words`] for `n` ants).
pub fn sensed_bindings(buffer: &wgpu::Buffer, n: usize) -> [(u32, wgpu::BindingResource<'_>); 6] {
    sensed_ranges(buffer, n, [2, 24, 25, 26, 27, 28])
}

/// [`sensed_bindings`] of `sensed` (for `n` ants) and the whole `buffers` at their bindings.
pub fn with_sensed<'a>(
    sensed: &'a wgpu::Buffer,
    n: usize,
    buffers: &[(u32, &'a wgpu::Buffer)],
) -> Vec<(u32, wgpu::BindingResource<'a>)> {
    let mut entries = sensed_bindings(sensed, n).to_vec();
    entries.extend(buffers.iter().map(|&(k, b)| (k, b.as_entire_binding())));
    entries
}

/// The same ranges at the bindings `at` (positions, arrivals, ids, labels, nests, origins).
pub fn sensed_ranges(
    buffer: &wgpu::Buffer,
    n: usize,
    at: [u32; 6],
) -> [(u32, wgpu::BindingResource<'_>); 6] {
    let stride = 4 * sensed_stride(n) as u64;
    let range = |first: usize, arrays: u64| {
        wgpu::BindingResource::Buffer(wgpu::BufferBinding {
            buffer,
            offset: first as u64 * stride,
            size: std::num::NonZeroU64::new(arrays * stride),
        })
    };
    [
        (at[0], range(SENSED_POS, 2)),
        (at[1], range(SENSED_ARRIVAL, 2)),
        (at[2], range(SENSED_ID, 1)),
        (at[3], range(SENSED_LABEL, 1)),
        (at[4], range(SENSED_NEST, 1)),
        (at[5], range(SENSED_ORIGIN, 1)),
    ]
}

/// The predictions p*(t+1) of `w` as words over `S`, two an ant.
pub fn predicted_words<S: Word + SimScalar>(w: &AntWorld) -> Vec<u32> {
    w.predicted
        .iter()
        .flat_map(|&p| {
            let v: Vec2<S> = v2(p);
            [v.x.to_word(), v.y.to_word()]
        })
        .collect()
}
