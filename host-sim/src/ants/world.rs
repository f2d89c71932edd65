//! The ant world: the arena, its objects, and the *sensed* state of every ant (struct of
//! arrays, `f64`, as of the previous step) from which sensor frames are built.

use rayon::prelude::*;
use swarm_core::ant::{AntState, Label};
use swarm_core::{Scalar, Vec2};

use crate::grid::Grid;
use crate::scalar::{SimScalar, a2};

/// The shape of an ant-world object.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape2 {
    /// A disc.
    Circle {
        /// Centre.
        center: [f32; 2],
        /// Radius.
        radius: f32,
    },
    /// A simple polygon (obstacles only).
    Polygon {
        /// Vertices in order.
        points: Vec<[f32; 2]>,
    },
}

/// What an ant-world object is.
#[derive(Clone, Debug, PartialEq)]
pub enum AntObjectKind {
    /// A nest.
    Nest,
    /// A food source with the food left (`None`: endless).
    Food {
        /// Food left.
        amount: Option<u32>,
    },
    /// An obstacle.
    Obstacle,
    /// An external disturbance (a dangerous circle).
    Disturbance,
    /// A way point of the route (xiang2018 Fig. 14), visited in increasing `order`.
    Waypoint {
        /// Place on the route.
        order: u32,
    },
}

/// An object of the ant world.
#[derive(Clone, Debug, PartialEq)]
pub struct AntObjectDef {
    /// Id carried in sensor frames (nest and food ids).
    pub id: u16,
    /// Name (from the scenario).
    pub name: String,
    /// What it is.
    pub kind: AntObjectKind,
    /// Where it is.
    pub shape: Shape2,
    /// Present now.
    pub active: bool,
}

impl AntObjectDef {
    /// The point of the object's boundary closest to `p`, and whether `p` is inside it, in the
    /// scalar `S` of the ant that senses it: the same bits on every backend (in fixed point,
    /// integer arithmetic only; see `docs/gpu.md`).
    pub fn closest<S: Scalar>(&self, p: Vec2<S>) -> (Vec2<S>, bool) {
        match &self.shape {
            Shape2::Circle { center, radius } => {
                let (c, r) = (at::<S>(*center), S::from_f32(*radius));
                let d = p - c;
                match d.normalized() {
                    Some(u) => (c + u * r, d.length() <= r),
                    None => (c + Vec2::new(r, S::ZERO), true),
                }
            }
            Shape2::Polygon { points } => {
                let (q, inside, _, _) = closest_on_polygon_edge(points, p);
                (q, inside)
            }
        }
    }

    /// The object's surface as an ant at `p` senses it: the closest boundary point, the unit
    /// outward normal there (pointing into free space; for `p` inside, from `p` through the
    /// closest point, the way out), and whether `p` is inside.
    pub fn surface<S: Scalar>(&self, p: Vec2<S>) -> (Vec2<S>, Vec2<S>, bool) {
        match &self.shape {
            Shape2::Circle { center, .. } => {
                let (q, inside) = self.closest(p);
                let n = (q - at::<S>(*center))
                    .normalized()
                    .unwrap_or(Vec2::new(S::ONE, S::ZERO));
                (q, n, inside)
            }
            Shape2::Polygon { points } => {
                let (q, inside, edge, on_edge) = closest_on_polygon_edge(points, p);
                let d = if inside { q - p } else { p - q };
                (q, facing(d, on_edge, points, edge), inside)
            }
        }
    }

    /// The convex pieces of the obstacle within `reach` of `p`, as sensed surfaces
    /// `(closest, outward normal, distance)`: a disc is one piece, a polygon one per edge (so
    /// that staying in front of each keeps an ant out of a concave polygon too; edges meeting
    /// at a vertex may give the same point twice). From inside, the one way out: the closest
    /// boundary point.
    pub fn pieces_within<S: Scalar>(
        &self,
        p: Vec2<S>,
        reach: S,
        mut f: impl FnMut(Vec2<S>, Vec2<S>, S),
    ) {
        let (q, n, inside) = self.surface(p);
        let points = match &self.shape {
            Shape2::Polygon { points } if !inside => points,
            _ => {
                let d = if inside { S::ZERO } else { (p - q).length() };
                if d <= reach {
                    f(q, n, d);
                }
                return;
            }
        };
        let k = points.len();
        for e in 0..k {
            let (q, on_edge) = closest_on_segment(at(points[e]), at(points[(e + 1) % k]), p);
            let d = (p - q).length();
            if d <= reach {
                f(q, facing(p - q, on_edge, points, e), d);
            }
        }
    }

    /// A cheap test in `f32`: false only if `p` is certainly farther than `range` from the
    /// object. Callers add `AntWorld::rounding_margin` to `range` for the rounding of a
    /// fixed-point position to `f32`.
    pub fn may_be_within(&self, p: [f32; 2], range: f32) -> bool {
        match &self.shape {
            Shape2::Circle { center, radius } => {
                let d2 = (p[0] - center[0]).powi(2) + (p[1] - center[1]).powi(2);
                d2 <= (radius + range).powi(2)
            }
            Shape2::Polygon { .. } => true,
        }
    }

    /// The smallest axis-aligned box holding the object: (lower, upper corner).
    pub fn bounding_box(&self) -> ([f32; 2], [f32; 2]) {
        match &self.shape {
            Shape2::Circle { center, radius } => (
                [center[0] - radius, center[1] - radius],
                [center[0] + radius, center[1] + radius],
            ),
            Shape2::Polygon { points } => points.iter().fold(
                ([f32::INFINITY; 2], [f32::NEG_INFINITY; 2]),
                |(lo, hi), p| {
                    (
                        [lo[0].min(p[0]), lo[1].min(p[1])],
                        [hi[0].max(p[0]), hi[1].max(p[1])],
                    )
                },
            ),
        }
    }

    /// Centre and radius, for circles.
    pub fn circle(&self) -> Option<([f32; 2], f32)> {
        match self.shape {
            Shape2::Circle { center, radius } => Some((center, radius)),
            Shape2::Polygon { .. } => None,
        }
    }
}

/// A scenario point (`f32`) in the scalar `S`.
fn at<S: Scalar>(p: [f32; 2]) -> Vec2<S> {
    Vec2::new(S::from_f32(p[0]), S::from_f32(p[1]))
}

/// The closest boundary point of a polygon to `p`, whether `p` is inside (even-odd rule), the
/// edge (from vertex `k` to `k + 1`) the point is on, and whether it lies strictly between the
/// edge's ends (see [`closest_on_segment`]).
fn closest_on_polygon_edge<S: Scalar>(
    points: &[[f32; 2]],
    p: Vec2<S>,
) -> (Vec2<S>, bool, usize, bool) {
    let mut best: Option<(S, Vec2<S>, usize, bool)> = None;
    let mut inside = false;
    let n = points.len();
    for k in 0..n {
        let (a, b) = (at::<S>(points[k]), at::<S>(points[(k + 1) % n]));
        let (q, on_edge) = closest_on_segment(a, b, p);
        let d = (p - q).length();
        if best.is_none_or(|(bd, ..)| d < bd) {
            best = Some((d, q, k, on_edge));
        }
        // The edge crosses the horizontal through p (so b.y ≠ a.y, and the fraction is in
        // [0, 1]), to the right of p.
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            inside = !inside;
        }
    }
    let (_, q, k, on_edge) = best.unwrap_or((S::ZERO, p, 0, false));
    (q, inside, k, on_edge)
}

/// The point of segment `a`-`b` closest to `p`, and whether it lies strictly between `a` and
/// `b` (else it is one of them, exactly): the projection on the segment's unit direction,
/// clamped to its length (no squared lengths, which overflow fixed point on long edges).
///
/// Between the ends the sensed normal is the edge's own ([`edge_normal`]), not the direction
/// from the point to `p`: the point carries the rounding of the projection along the edge, and
/// seen from an ant a margin away that tilts the direction by degrees in fixed point.
fn closest_on_segment<S: Scalar>(a: Vec2<S>, b: Vec2<S>, p: Vec2<S>) -> (Vec2<S>, bool) {
    let ab = b - a;
    let Some(u) = ab.normalized() else {
        return (a, false);
    };
    let len = ab.length();
    let t = (p - a).dot(u);
    if t <= S::ZERO {
        (a, false)
    } else if t >= len {
        (b, false)
    } else {
        (a + u * t, true)
    }
}

/// The unit normal of a sensed polygon piece, pointing along `d` (from the piece toward the
/// ant, or the way out): for a point between the ends of edge `k` the edge's own normal turned
/// toward `d` (see [`closest_on_segment`]), for a vertex `d` itself; the edge's outward normal
/// when `d` is zero.
fn facing<S: Scalar>(d: Vec2<S>, on_edge: bool, points: &[[f32; 2]], k: usize) -> Vec2<S> {
    let out = edge_normal::<S>(points, k);
    if on_edge {
        if d.dot(out) < S::ZERO { -out } else { out }
    } else {
        d.normalized().unwrap_or(out)
    }
}

/// The outward unit normal of edge `k` of a polygon (for a point exactly on it): scenario
/// geometry, computed in `f32` and then converted, so every backend gets the same bits.
pub(crate) fn edge_normal<S: Scalar>(points: &[[f32; 2]], k: usize) -> Vec2<S> {
    let n = points.len();
    let (a, b) = (points[k], points[(k + 1) % n]);
    // Twice the signed area: positive for counter-clockwise vertices, whose outside is on the
    // right of each edge.
    let area: f32 = (0..n)
        .map(|i| {
            let (p, q) = (points[i], points[(i + 1) % n]);
            p[0] * q[1] - q[0] * p[1]
        })
        .sum();
    let right = [b[1] - a[1], a[0] - b[0]];
    let out = if area >= 0.0 {
        right
    } else {
        [-right[0], -right[1]]
    };
    let l = out[0].hypot(out[1]);
    if l > 1e-12 {
        at([out[0] / l, out[1] / l])
    } else {
        Vec2::new(S::ONE, S::ZERO)
    }
}

/// The arena, its objects and the sensed ants.
#[derive(Clone, Debug, Default)]
pub struct AntWorld {
    /// Arena lower-left corner.
    pub min: [f32; 2],
    /// Arena upper-right corner.
    pub max: [f32; 2],
    /// Every object (inactive ones included; frames skip them).
    pub objects: Vec<AntObjectDef>,
    /// Objects whose boundary is within this distance are sensed.
    pub sense_range: f32,
    /// Largest contact range of any group (neighbour query radius of the plan frame).
    pub contact_range: f32,
    /// Largest collision range of any group (query radius of the resolve frame).
    pub collision_range: f32,
    /// The longest move of any group's ant in one tick, and some for the rounding: the
    /// resolve frame senses the obstacle pieces within this distance.
    pub step_reach: f32,
    /// The way points in visiting order (object ids; empty: no route). See [`AntWorld::target_of`].
    pub route: Vec<u16>,
    /// Sensed state of every ant at the previous step.
    pub sensed: Sensed,
    /// Predicted positions p*(t+1) of the current step's plans.
    pub predicted: Vec<[f64; 2]>,
    /// The largest distance between an ant's prediction and its sensed position, this step:
    /// a resolve frame that asks the grid widens its query by this much.
    pub(crate) max_shift: f32,
    /// The sensed positions, by cell (both phases query it).
    pub(crate) grid: Grid,
    /// Per grid cell, bit `k` set if object `k` may be within sensing range of a point of the
    /// cell (the engine's plan frames visit only those objects); empty when the world has
    /// more than 64 objects. Rebuilt with the grid, each tick.
    pub(crate) object_cells: Vec<u64>,
    /// The cells marked in `object_cells` (cleared one by one: objects cover few cells).
    object_marked: Vec<u32>,
    /// Bit `k` set if object `k` is an active obstacle (with the index, up to 64 objects).
    pub(crate) obstacle_bits: u64,
}

/// What an ant's neighbours can sense of it: struct of arrays, indexed by agent.
#[derive(Clone, Debug, Default)]
pub struct Sensed {
    /// Positions.
    pub pos: Vec<[f64; 2]>,
    /// Latest arrival positions.
    pub arrival: Vec<[f64; 2]>,
    /// Stable ant ids.
    pub id: Vec<u32>,
    /// Labels S_c.
    pub label: Vec<Label>,
    /// Home nests.
    pub nest: Vec<u16>,
    /// Label origins.
    pub origin: Vec<u16>,
}

impl Sensed {
    /// Writes the sensed state of slots `first..first + states.len()`, ants `ids`, in parallel.
    pub fn write<S: SimScalar>(&mut self, first: usize, ids: &[u32], states: &[AntState<S>]) {
        let r = first..first + states.len();
        (
            self.pos[r.clone()].par_iter_mut(),
            self.arrival[r.clone()].par_iter_mut(),
            self.id[r.clone()].par_iter_mut(),
            self.label[r.clone()].par_iter_mut(),
            self.nest[r.clone()].par_iter_mut(),
            self.origin[r].par_iter_mut(),
            ids.par_iter().zip(states),
        )
            .into_par_iter()
            .for_each(|(pos, arrival, id, label, nest, origin, (&i, s))| {
                *pos = a2(s.pos);
                *arrival = a2(s.arrival);
                *id = i;
                *label = s.label;
                *nest = s.nest;
                *origin = s.origin;
            });
    }

    /// Room for `n` ants.
    pub fn resize(&mut self, n: usize) {
        self.pos.resize(n, [0.0; 2]);
        self.arrival.resize(n, [0.0; 2]);
        self.id.resize(n, 0);
        self.label.resize(n, Label::Nothing);
        self.nest.resize(n, 0);
        self.origin.resize(n, 0);
    }
}

impl AntWorld {
    /// An empty world over `[min, max]`.
    pub fn new(min: [f32; 2], max: [f32; 2], contact_range: f32, collision_range: f32) -> Self {
        let cell = contact_range.max(collision_range).max(0.5);
        let grid = Grid::new([min[0], min[1], 0.0], [max[0], max[1], 0.0], cell);
        AntWorld {
            min,
            max,
            objects: Vec::new(),
            sense_range: 2.0 * contact_range.max(collision_range),
            contact_range,
            collision_range,
            step_reach: 1.1,
            route: Vec::new(),
            sensed: Sensed::default(),
            predicted: Vec::new(),
            max_shift: 0.0,
            grid,
            object_cells: Vec::new(),
            object_marked: Vec::new(),
            obstacle_bits: 0,
        }
    }

    /// Sizes the neighbour grid for `n` ants: cells no smaller than the query ranges, and about
    /// one ant per cell in sparse worlds (fewer, fuller cells: less to clear and scan per
    /// rebuild, while a query still reads a few contiguous rows).
    pub fn size_grids(&mut self, n: usize) {
        let range = self.contact_range.max(self.collision_range).max(0.5);
        let area = (self.max[0] - self.min[0]) * (self.max[1] - self.min[1]);
        let cell = range.max((area / n.max(1) as f32).sqrt());
        let (lo, hi) = (
            [self.min[0], self.min[1], 0.0],
            [self.max[0], self.max[1], 0.0],
        );
        self.grid = Grid::new(lo, hi, cell);
    }

    /// Sets the route from the world's way points, in increasing `order`.
    pub fn set_route(&mut self) {
        let mut wps: Vec<(u32, u16)> = self
            .objects
            .iter()
            .filter_map(|o| match o.kind {
                AntObjectKind::Waypoint { order } => Some((order, o.id)),
                _ => None,
            })
            .collect();
        wps.sort_unstable();
        self.route = wps.into_iter().map(|(_, id)| id).collect();
    }

    /// Way points (xiang2018 Fig. 14: "the way points act as intermediate transit
    /// destinations"): the route nest → way point 1 → … → way point n → food is travelled leg by
    /// leg, each leg foraged like a nest and a food source (§4). An ant's leg is given by its
    /// nest: the destination of an ant whose nest is `home` is the next way point after `home`
    /// (the first one for a real nest), or `None` past the last one: the food sources. Without a
    /// route every ant's destination is the food.
    pub fn target_of(&self, home: u16) -> Option<u16> {
        match self.route.iter().position(|&w| w == home) {
            Some(k) => self.route.get(k + 1).copied(),
            None => self.route.first().copied(),
        }
    }

    /// The number of ants.
    pub fn len(&self) -> usize {
        self.sensed.pos.len()
    }

    /// Whether there are no ants.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Rebuilds the neighbour grid from the sensed positions, and the objects' cells.
    pub fn index_positions(&mut self) {
        self.grid
            .rebuild(&self.sensed.pos, |p| [p[0] as f32, p[1] as f32, 0.0]);
        self.index_objects();
    }

    /// Marks in [`AntWorld::object_cells`] the cells within sensing range of each active object's
    /// bounding box (and a margin for rounding).
    fn index_objects(&mut self) {
        let n = self.grid.cells();
        if self.objects.len() > 64 || self.object_cells.len() != n {
            self.object_cells.clear();
            self.object_marked.clear();
            if self.objects.len() > 64 {
                return;
            }
            self.object_cells.resize(n, 0);
        }
        for c in self.object_marked.drain(..) {
            self.object_cells[c as usize] = 0;
        }
        let reach = self.sense_range + self.rounding_margin();
        self.obstacle_bits = self
            .objects
            .iter()
            .enumerate()
            .filter(|(_, o)| o.active && o.kind == AntObjectKind::Obstacle)
            .fold(0, |bits, (k, _)| bits | 1 << k);
        let (cells, marked) = (&mut self.object_cells, &mut self.object_marked);
        for (k, o) in self.objects.iter().enumerate().filter(|(_, o)| o.active) {
            let (lo, hi) = o.bounding_box();
            let lo = [lo[0] - reach, lo[1] - reach, 0.0];
            let hi = [hi[0] + reach, hi[1] + reach, 0.0];
            self.grid.for_each_cell_in(lo, hi, |c| {
                if cells[c] == 0 {
                    marked.push(c as u32);
                }
                cells[c] |= 1 << k;
            });
        }
    }

    /// The objects that may be within sensing range of `p` (bit `k`: object `k`), if indexed.
    pub(crate) fn objects_near(&self, p: [f32; 2]) -> Option<u64> {
        let cell = self.grid.cell_of([p[0], p[1], 0.0]) as usize;
        self.object_cells.get(cell).copied()
    }

    /// What a grid query adds to its radius for the rounding of positions to `f32` (a few
    /// ulps of the largest coordinate, and some).
    pub(crate) fn rounding_margin(&self) -> f32 {
        let extent = [self.min, self.max]
            .iter()
            .flatten()
            .fold(0.0f32, |m, c| m.max(c.abs()));
        1e-3 + extent * 1e-6
    }
}
