//! The bee world: the volume, its obstacles and targets, and the *sensed* state of every bee
//! (struct of arrays, `f64`, as of the previous step) from which sensor frames are built.
//!
//! Obstacle geometry is computed in `f64`: the closest point of a surface and its outward unit
//! normal, for points outside and inside the solid ([`Surface`]).

use rayon::prelude::*;
use swarm_core::bee::BeeState;

use crate::grid::Grid;
use crate::scalar::{SimScalar, a3};
use crate::scenario::ObjectKind;

/// How far outside the surface the world puts a bee it pushes out of an obstacle.
pub const SURFACE_OFFSET: f64 = 1e-3;

/// The closest point of an obstacle's surface to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// The closest point on the surface.
    pub point: [f64; 3],
    /// The outward unit normal there (for a point outside: the unit vector from `point` to the
    /// query point, which is the surface normal on faces and the bisecting direction on edges and
    /// corners).
    pub normal: [f64; 3],
    /// The distance from the query point to `point`.
    pub distance: f64,
    /// Whether the query point lies inside the solid (on an open surface: not inside).
    pub inside: bool,
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn f64s(a: [f32; 3]) -> [f64; 3] {
    a.map(f64::from)
}

/// A surface point seen from outside: `p` is off the solid, `q` the closest solid point.
fn from_outside(p: [f64; 3], q: [f64; 3]) -> Surface {
    let d = sub(p, q);
    let len = norm(d);
    Surface {
        point: q,
        normal: [d[0] / len, d[1] / len, d[2] / len],
        distance: len,
        inside: false,
    }
}

/// The sphere (`center`, `radius`): the radial projection of `p` and the radial normal (the
/// centre itself: the top point, normal up).
pub fn sphere_surface(center: [f64; 3], radius: f64, p: [f64; 3]) -> Surface {
    let d = sub(p, center);
    let len = norm(d);
    let normal = if len > 0.0 {
        [d[0] / len, d[1] / len, d[2] / len]
    } else {
        [0.0, 1.0, 0.0]
    };
    Surface {
        point: [
            center[0] + normal[0] * radius,
            center[1] + normal[1] * radius,
            center[2] + normal[2] * radius,
        ],
        normal,
        distance: (len - radius).abs(),
        inside: len < radius,
    }
}

/// The axis-aligned box `[min, max]` with every face open (see [`box_surface_open`]).
pub fn box_surface(min: [f64; 3], max: [f64; 3], p: [f64; 3]) -> Surface {
    box_surface_open(min, max, p, [true; 6])
}

/// The axis-aligned box `[min, max]`. Outside: the clamped point, the normal from it to `p`
/// (face, edge or corner). Inside: the nearest *open* face (faces `-x, +x, -y, +y, -z, +z`;
/// ties in that order), its normal; a closed face is one the bee cannot leave through (it lies
/// on the world's boundary) and a point on it counts as inside. With no face open, all are.
pub fn box_surface_open(min: [f64; 3], max: [f64; 3], p: [f64; 3], open: [bool; 6]) -> Surface {
    let q: [f64; 3] = std::array::from_fn(|k| p[k].clamp(min[k], max[k]));
    if q != p {
        return from_outside(p, q);
    }
    let open = if open.contains(&true) {
        open
    } else {
        [true; 6]
    };
    let mut best = (f64::INFINITY, 0usize);
    for (face, &is_open) in open.iter().enumerate() {
        let axis = face / 2;
        let dist = if face % 2 == 0 {
            p[axis] - min[axis]
        } else {
            max[axis] - p[axis]
        };
        if is_open && dist < best.0 {
            best = (dist, face);
        }
    }
    let (distance, face) = best;
    let axis = face / 2;
    let mut point = p;
    let mut normal = [0.0; 3];
    if face % 2 == 0 {
        point[axis] = min[axis];
        normal[axis] = -1.0;
    } else {
        point[axis] = max[axis];
        normal[axis] = 1.0;
    }
    let inside = (0..3).all(|k| {
        let lo = if open[2 * k] {
            p[k] > min[k]
        } else {
            p[k] >= min[k]
        };
        let hi = if open[2 * k + 1] {
            p[k] < max[k]
        } else {
            p[k] <= max[k]
        };
        lo && hi
    });
    Surface {
        point,
        normal,
        distance,
        inside,
    }
}

/// The vertical cylinder with axis `center = [x, z]`, `radius`, from `y_min` to `y_max`, both
/// caps open (see [`shaft_surface_open`]).
pub fn shaft_surface(
    center: [f64; 2],
    radius: f64,
    y_min: f64,
    y_max: f64,
    p: [f64; 3],
) -> Surface {
    shaft_surface_open(center, radius, y_min, y_max, p, [true; 2])
}

/// The vertical cylinder with axis `center = [x, z]`, `radius`, from `y_min` to `y_max`.
/// Outside: the closest point on the side, a cap or the rim edge between them, the normal from
/// it to `p`. Inside: the nearest of the side (radial normal; on the axis, +x) and the open caps
/// (`open = [bottom, top]`; ties: side, bottom, top); a point on a closed cap counts as inside.
pub fn shaft_surface_open(
    center: [f64; 2],
    radius: f64,
    y_min: f64,
    y_max: f64,
    p: [f64; 3],
    open: [bool; 2],
) -> Surface {
    let (dx, dz) = (p[0] - center[0], p[2] - center[1]);
    let rho = dx.hypot(dz);
    let radial = if rho > 0.0 {
        [dx / rho, dz / rho]
    } else {
        [1.0, 0.0]
    };
    if rho > radius || p[1] < y_min || p[1] > y_max {
        let r = rho.min(radius);
        let q = [
            center[0] + radial[0] * r,
            p[1].clamp(y_min, y_max),
            center[1] + radial[1] * r,
        ];
        return from_outside(p, q);
    }
    let side = Surface {
        point: [
            center[0] + radial[0] * radius,
            p[1],
            center[1] + radial[1] * radius,
        ],
        normal: [radial[0], 0.0, radial[1]],
        distance: radius - rho,
        inside: false,
    };
    let bottom = Surface {
        point: [p[0], y_min, p[2]],
        normal: [0.0, -1.0, 0.0],
        distance: p[1] - y_min,
        inside: false,
    };
    let top = Surface {
        point: [p[0], y_max, p[2]],
        normal: [0.0, 1.0, 0.0],
        distance: y_max - p[1],
        inside: false,
    };
    let mut best = side;
    for (s, is_open) in [(bottom, open[0]), (top, open[1])] {
        if is_open && s.distance < best.distance {
            best = s;
        }
    }
    let lo = if open[0] { p[1] > y_min } else { p[1] >= y_min };
    let hi = if open[1] { p[1] < y_max } else { p[1] <= y_max };
    best.inside = rho < radius && lo && hi;
    best
}

/// The shape of a bee-world obstacle (scenario coordinates, y up).
#[derive(Clone, Debug, PartialEq)]
pub enum Shape3 {
    /// A ball.
    Sphere {
        /// Centre.
        center: [f32; 3],
        /// Radius.
        radius: f32,
    },
    /// An axis-aligned box.
    Box {
        /// Lower corner.
        min: [f32; 3],
        /// Upper corner.
        max: [f32; 3],
    },
    /// A vertical cylinder.
    Shaft {
        /// Axis position `[x, z]`.
        center: [f32; 2],
        /// Radius.
        radius: f32,
        /// Bottom.
        y_min: f32,
        /// Top.
        y_max: f32,
    },
}

impl Shape3 {
    /// The shape of an obstacle kind of the scenario (`None` for other kinds).
    pub fn of(kind: &ObjectKind) -> Option<Shape3> {
        Some(match *kind {
            ObjectKind::Sphere { center, radius } => Shape3::Sphere { center, radius },
            ObjectKind::Box { min, max } => Shape3::Box { min, max },
            ObjectKind::Shaft {
                center,
                radius,
                y_min,
                y_max,
            } => Shape3::Shaft {
                center,
                radius,
                y_min,
                y_max,
            },
            _ => return None,
        })
    }

    /// The bounding box.
    pub fn aabb(&self) -> ([f32; 3], [f32; 3]) {
        match *self {
            Shape3::Sphere { center, radius } => {
                (center.map(|c| c - radius), center.map(|c| c + radius))
            }
            Shape3::Box { min, max } => (min, max),
            Shape3::Shaft {
                center,
                radius,
                y_min,
                y_max,
            } => (
                [center[0] - radius, y_min, center[1] - radius],
                [center[0] + radius, y_max, center[1] + radius],
            ),
        }
    }

    /// The closest surface point to `p`, with the faces lying on or beyond the world bounds
    /// `[lo, hi]` closed (a bee is never pushed out of the world through them).
    pub fn surface(&self, p: [f64; 3], lo: [f32; 3], hi: [f32; 3]) -> Surface {
        match *self {
            Shape3::Sphere { center, radius } => sphere_surface(f64s(center), f64::from(radius), p),
            Shape3::Box { min, max } => {
                let open = std::array::from_fn(|face| {
                    let k = face / 2;
                    if face % 2 == 0 {
                        min[k] > lo[k]
                    } else {
                        max[k] < hi[k]
                    }
                });
                box_surface_open(f64s(min), f64s(max), p, open)
            }
            Shape3::Shaft {
                center,
                radius,
                y_min,
                y_max,
            } => shaft_surface_open(
                center.map(f64::from),
                f64::from(radius),
                f64::from(y_min),
                f64::from(y_max),
                p,
                [y_min > lo[1], y_max < hi[1]],
            ),
        }
    }

    /// Moves the centre (sphere `[x, y, z]`, shaft `[x, z]`); `false` for boxes or a wrong
    /// number of coordinates.
    pub fn set_center(&mut self, to: &[f32]) -> bool {
        match (self, to) {
            (Shape3::Sphere { center, .. }, &[x, y, z]) => *center = [x, y, z],
            (Shape3::Shaft { center, .. }, &[x, z]) => *center = [x, z],
            _ => return false,
        }
        true
    }
}

/// An obstacle of the bee world.
#[derive(Clone, Debug, PartialEq)]
pub struct BeeObstacle {
    /// Object id (its index in the scenario).
    pub id: u16,
    /// Name.
    pub name: String,
    /// Geometry.
    pub shape: Shape3,
    /// Present now.
    pub active: bool,
    aabb: ([f32; 3], [f32; 3]),
}

impl BeeObstacle {
    /// An obstacle.
    pub fn new(id: u16, name: impl Into<String>, shape: Shape3, active: bool) -> Self {
        BeeObstacle {
            id,
            name: name.into(),
            aabb: shape.aabb(),
            shape,
            active,
        }
    }

    /// A cheap test: false only if `p` is certainly farther than `range` from the obstacle.
    #[inline]
    pub fn may_be_within(&self, p: [f64; 3], range: f64) -> bool {
        let (lo, hi) = self.aabb;
        (0..3).all(|k| p[k] >= f64::from(lo[k]) - range && p[k] <= f64::from(hi[k]) + range)
    }

    /// Moves the centre (see [`Shape3::set_center`]).
    pub fn set_center(&mut self, to: &[f32]) -> bool {
        let moved = self.shape.set_center(to);
        self.aabb = self.shape.aabb();
        moved
    }
}

/// A target (nest, flower) of the bee world: a sphere sampled into static virtual particles.
#[derive(Clone, Debug, PartialEq)]
pub struct BeeTarget {
    /// Object id (its index in the scenario).
    pub id: u16,
    /// Name.
    pub name: String,
    /// Centre (the goal of the groups flying to it).
    pub center: [f32; 3],
    /// Radius of the sphere the particles lie on.
    pub radius: f32,
    /// Number of virtual particles.
    pub particles: u32,
    /// Present now.
    pub active: bool,
}

impl BeeTarget {
    /// A target present from the start: `particles` virtual particles on the sphere of
    /// `radius` around `center`.
    pub fn new(
        id: u16,
        name: impl Into<String>,
        center: [f32; 3],
        radius: f32,
        particles: u32,
    ) -> Self {
        BeeTarget {
            id,
            name: name.into(),
            center,
            radius,
            particles,
            active: true,
        }
    }

    /// Its virtual particles (the scenario's Fibonacci sphere).
    pub fn sample(&self) -> Vec<[f32; 3]> {
        ObjectKind::Target {
            center: self.center,
            radius: self.radius,
            particles: self.particles,
        }
        .sample_particles()
    }
}

/// What a bee's neighbours can sense of it: struct of arrays, indexed by slot.
#[derive(Clone, Debug, Default)]
pub struct Sensed {
    /// Positions.
    pub pos: Vec<[f64; 3]>,
    /// Velocities.
    pub vel: Vec<[f64; 3]>,
    /// Broadcast densities ρ (eq. 10, from the bee's last step).
    pub density: Vec<f64>,
    /// Stable bee ids.
    pub id: Vec<u32>,
}

impl Sensed {
    /// Writes the sensed state of slot `i`, bee `id`.
    #[inline]
    pub fn set<S: SimScalar>(&mut self, i: usize, id: u32, s: &BeeState<S>) {
        self.pos[i] = a3(s.pos);
        self.vel[i] = a3(s.vel);
        self.density[i] = s.density.to_f64();
        self.id[i] = id;
    }

    /// Writes slots `first..first + states.len()` (bees `ids`), in parallel.
    pub fn write<S: SimScalar>(&mut self, first: usize, ids: &[u32], states: &[BeeState<S>]) {
        let r = first..first + states.len();
        self.pos[r.clone()]
            .par_iter_mut()
            .zip(self.vel[r.clone()].par_iter_mut())
            .zip(self.density[r.clone()].par_iter_mut())
            .zip(self.id[r].par_iter_mut())
            .zip(states.par_iter().zip(ids.par_iter()))
            .with_min_len(4096)
            .for_each(|((((p, v), d), i), (s, &id))| {
                *p = a3(s.pos);
                *v = a3(s.vel);
                *d = s.density.to_f64();
                *i = id;
            });
    }

    /// Room for `n` bees.
    pub fn resize(&mut self, n: usize) {
        self.pos.resize(n, [0.0; 3]);
        self.vel.resize(n, [0.0; 3]);
        self.density.resize(n, 0.0);
        self.id.resize(n, 0);
    }
}

/// The volume, its obstacles and targets, and the sensed bees.
#[derive(Clone, Debug, Default)]
pub struct BeeWorld {
    /// Lower corner of the volume.
    pub min: [f32; 3],
    /// Upper corner.
    pub max: [f32; 3],
    /// Obstacles (inactive ones included; frames and physics skip them).
    pub obstacles: Vec<BeeObstacle>,
    /// Targets (inactive ones included). After changing them call [`BeeWorld::index_targets`].
    pub targets: Vec<BeeTarget>,
    /// Neighbour range: the largest h + 2r of any group (capsule gap below h).
    pub range: f32,
    /// Obstacle sensing range: the largest 2·d0 of any group.
    pub sense_range: f32,
    /// Sensed state of every bee at the previous step.
    pub sensed: Sensed,
    /// The virtual particles of the active targets.
    pub particles: Vec<[f32; 3]>,
    /// Centre and radius of each active target's particle sphere (quick rejection).
    pub(crate) target_spheres: Vec<([f32; 3], f32)>,
    pub(crate) grid: Grid,
    pub(crate) particle_grid: Grid,
}

impl BeeWorld {
    /// An empty world over `[min, max]` with neighbour range `range` (h + 2r) and obstacle
    /// sensing range `sense_range` (2·d0).
    pub fn new(min: [f32; 3], max: [f32; 3], range: f32, sense_range: f32) -> Self {
        let range = if range.is_finite() && range > 0.0 {
            range
        } else {
            1.0
        };
        let mut w = BeeWorld {
            min,
            max,
            obstacles: Vec::new(),
            targets: Vec::new(),
            range,
            sense_range,
            sensed: Sensed::default(),
            particles: Vec::new(),
            target_spheres: Vec::new(),
            grid: Grid::default(),
            particle_grid: Grid::new(min, min, range),
        };
        w.size_grids(0);
        w
    }

    /// Sizes the neighbour grid for `n` bees: cells a little larger than the neighbour range
    /// (a query reads 3×3×3 cells, and a bee two cells away is out of range even after `f32`
    /// rounding), and about one bee per cell in sparse worlds.
    pub fn size_grids(&mut self, n: usize) {
        let volume: f32 = (0..3)
            .map(|k| (self.max[k] - self.min[k]).max(1e-3))
            .product();
        let cell = (self.range * 1.001).max((volume / n.max(1) as f32).cbrt());
        self.grid = Grid::new(self.min, self.max, cell);
    }

    /// The number of bees.
    pub fn len(&self) -> usize {
        self.sensed.pos.len()
    }

    /// Whether there are no bees.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Rebuilds the neighbour grid from the sensed positions.
    pub fn index_positions(&mut self) {
        self.grid.rebuild(&self.sensed.pos, |p| {
            [p[0] as f32, p[1] as f32, p[2] as f32]
        });
    }

    /// Samples the active targets into particles and indexes them.
    pub fn index_targets(&mut self) {
        self.particles = self
            .targets
            .iter()
            .filter(|t| t.active)
            .flat_map(BeeTarget::sample)
            .collect();
        self.target_spheres = self
            .targets
            .iter()
            .filter(|t| t.active)
            .map(|t| (t.center, t.radius))
            .collect();
        // Over the particles' bounding box, not the world's: a few cells whatever the world's
        // size (queries from outside it read its border cells).
        let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
        for p in &self.particles {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        if self.particles.is_empty() {
            (lo, hi) = (self.min, self.min);
        }
        self.particle_grid = Grid::new(lo, hi, self.range);
        self.particle_grid.rebuild(&self.particles, |p| *p);
    }

    /// The centre of the active target with object id `id`.
    pub fn target_center(&self, id: u16) -> Option<[f32; 3]> {
        self.targets
            .iter()
            .find(|t| t.id == id && t.active)
            .map(|t| t.center)
    }

    /// The closest surface point of obstacle `o` to `p` (faces on the world bounds closed).
    #[inline]
    pub fn surface(&self, o: &BeeObstacle, p: [f64; 3]) -> Surface {
        o.shape.surface(p, self.min, self.max)
    }

    /// Keeps a bee's new state physical: out of every active obstacle (put back on the surface,
    /// [`SURFACE_OFFSET`] along the normal, the inward normal velocity removed) and inside the
    /// bounds (clamped, the outward velocity removed). Returns what was corrected: bit 0 an
    /// obstacle, bit 1 the bounds.
    pub fn confine<S: SimScalar>(&self, s: &mut BeeState<S>) -> u8 {
        let (mut p, mut v) = (a3(s.pos), a3(s.vel));
        let mut flags = 0u8;
        for _ in 0..4 {
            let mut moved = false;
            for o in self.obstacles.iter().filter(|o| o.active) {
                if !o.may_be_within(p, 0.0) {
                    continue;
                }
                let surf = self.surface(o, p);
                if !surf.inside {
                    continue;
                }
                let n = surf.normal;
                p = std::array::from_fn(|k| surf.point[k] + n[k] * SURFACE_OFFSET);
                let vn = dot(v, n);
                if vn < 0.0 {
                    v = std::array::from_fn(|k| v[k] - n[k] * vn);
                }
                flags |= 1;
                moved = true;
            }
            for k in 0..3 {
                let (lo, hi) = (f64::from(self.min[k]), f64::from(self.max[k]));
                if p[k] < lo {
                    p[k] = lo;
                    v[k] = v[k].max(0.0);
                    flags |= 2;
                    moved = true;
                } else if p[k] > hi {
                    p[k] = hi;
                    v[k] = v[k].min(0.0);
                    flags |= 2;
                    moved = true;
                }
            }
            if !moved {
                break;
            }
        }
        if flags != 0 {
            s.pos = crate::scalar::v3(p);
            s.vel = crate::scalar::v3(v);
        }
        flags
    }

    /// Whether `p` lies inside an active obstacle (strictly; see [`Shape3::surface`]).
    pub fn inside_obstacle(&self, p: [f64; 3]) -> Option<&BeeObstacle> {
        self.obstacles
            .iter()
            .filter(|o| o.active && o.may_be_within(p, 0.0))
            .find(|o| self.surface(o, p).inside)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() < 1e-12)
    }

    #[test]
    fn sphere_closest_point_and_normal() {
        let c = [1.0, 2.0, 3.0];
        let s = sphere_surface(c, 2.0, [1.0, 2.0, 7.0]);
        assert!(close(s.point, [1.0, 2.0, 5.0]) && close(s.normal, [0.0, 0.0, 1.0]));
        assert!(!s.inside && (s.distance - 2.0).abs() < 1e-12);
        // Inside: the radial projection, normal still outward.
        let s = sphere_surface(c, 2.0, [1.5, 2.0, 3.0]);
        assert!(close(s.point, [3.0, 2.0, 3.0]) && close(s.normal, [1.0, 0.0, 0.0]));
        assert!(s.inside && (s.distance - 1.5).abs() < 1e-12);
        let s = sphere_surface(c, 2.0, c);
        assert!(s.inside && close(s.normal, [0.0, 1.0, 0.0]) && close(s.point, [1.0, 4.0, 3.0]));
    }

    #[test]
    fn box_closest_point_and_normal_outside_and_inside() {
        let (lo, hi) = ([0.0, 0.0, 0.0], [4.0, 2.0, 6.0]);
        // Face.
        let s = box_surface(lo, hi, [2.0, 5.0, 3.0]);
        assert!(close(s.point, [2.0, 2.0, 3.0]) && close(s.normal, [0.0, 1.0, 0.0]));
        assert!(!s.inside && (s.distance - 3.0).abs() < 1e-12);
        // Edge: the normal bisects.
        let s = box_surface(lo, hi, [5.0, 3.0, 3.0]);
        let r = 0.5f64.sqrt();
        assert!(close(s.point, [4.0, 2.0, 3.0]) && close(s.normal, [r, r, 0.0]));
        // Corner.
        let s = box_surface(lo, hi, [-1.0, -1.0, -1.0]);
        let r = 1.0 / 3f64.sqrt();
        assert!(close(s.point, [0.0; 3]) && close(s.normal, [-r, -r, -r]));
        // Inside: the nearest face.
        let s = box_surface(lo, hi, [3.5, 1.0, 3.0]);
        assert!(s.inside && close(s.point, [4.0, 1.0, 3.0]) && close(s.normal, [1.0, 0.0, 0.0]));
        assert!((s.distance - 0.5).abs() < 1e-12);
        let s = box_surface(lo, hi, [2.0, 0.2, 3.0]);
        assert!(s.inside && close(s.point, [2.0, 0.0, 3.0]) && close(s.normal, [0.0, -1.0, 0.0]));
        // On the surface: not inside, distance 0.
        let s = box_surface(lo, hi, [2.0, 2.0, 3.0]);
        assert!(!s.inside && s.distance == 0.0 && close(s.normal, [0.0, 1.0, 0.0]));
        // Closed faces: only the top is open, like a ground slab spanning the world.
        let open = [false, false, false, true, false, false];
        let s = box_surface_open(lo, hi, [0.1, 0.5, 3.0], open);
        assert!(s.inside && close(s.point, [0.1, 2.0, 3.0]) && close(s.normal, [0.0, 1.0, 0.0]));
        let s = box_surface_open(lo, hi, [2.0, 0.0, 3.0], open);
        assert!(s.inside, "a point on a closed face is inside");
    }

    #[test]
    fn shaft_closest_point_and_normal_side_caps_edges_inside() {
        let (c, r, y0, y1) = ([10.0, 20.0], 2.0, 1.0, 9.0);
        // Side.
        let s = shaft_surface(c, r, y0, y1, [15.0, 5.0, 20.0]);
        assert!(close(s.point, [12.0, 5.0, 20.0]) && close(s.normal, [1.0, 0.0, 0.0]));
        assert!(!s.inside && (s.distance - 3.0).abs() < 1e-12);
        let s = shaft_surface(c, r, y0, y1, [10.0, 5.0, 16.0]);
        assert!(close(s.point, [10.0, 5.0, 18.0]) && close(s.normal, [0.0, 0.0, -1.0]));
        // Caps.
        let s = shaft_surface(c, r, y0, y1, [10.5, 12.0, 20.5]);
        assert!(close(s.point, [10.5, 9.0, 20.5]) && close(s.normal, [0.0, 1.0, 0.0]));
        let s = shaft_surface(c, r, y0, y1, [9.0, 0.0, 20.0]);
        assert!(close(s.point, [9.0, 1.0, 20.0]) && close(s.normal, [0.0, -1.0, 0.0]));
        // Rim edge.
        let s = shaft_surface(c, r, y0, y1, [13.0, 10.0, 20.0]);
        let h = 0.5f64.sqrt();
        assert!(close(s.point, [12.0, 9.0, 20.0]) && close(s.normal, [h, h, 0.0]));
        // Inside, nearest the side.
        let s = shaft_surface(c, r, y0, y1, [11.5, 5.0, 20.0]);
        assert!(s.inside && close(s.point, [12.0, 5.0, 20.0]) && close(s.normal, [1.0, 0.0, 0.0]));
        // Inside, nearest the top cap.
        let s = shaft_surface(c, r, y0, y1, [10.2, 8.8, 20.0]);
        assert!(s.inside && close(s.point, [10.2, 9.0, 20.0]) && close(s.normal, [0.0, 1.0, 0.0]));
        // The top closed (the shaft reaches the ceiling): the side instead.
        let s = shaft_surface_open(c, r, y0, y1, [10.2, 8.8, 20.0], [true, false]);
        assert!(s.inside && close(s.point, [12.0, 8.8, 20.0]) && close(s.normal, [1.0, 0.0, 0.0]));
        // On the axis: +x.
        let s = shaft_surface(c, r, y0, y1, [10.0, 5.0, 20.0]);
        assert!(s.inside && close(s.normal, [1.0, 0.0, 0.0]));
        // Normals are unit length everywhere.
        for p in [[3.0, -4.0, 25.0], [10.0, 20.0, 20.0], [11.0, 1.5, 21.0]] {
            let s = shaft_surface(c, r, y0, y1, p);
            assert!((norm(s.normal) - 1.0).abs() < 1e-12, "{p:?}");
        }
    }

    #[test]
    fn confine_puts_bees_back_on_the_surface_and_in_bounds() {
        let mut w = BeeWorld::new([0.0; 3], [20.0, 10.0, 20.0], 3.5, 4.0);
        w.obstacles.push(BeeObstacle::new(
            0,
            "shaft",
            Shape3::Shaft {
                center: [10.0, 10.0],
                radius: 1.0,
                y_min: 0.0,
                y_max: 10.0,
            },
            true,
        ));
        let mut s = BeeState::new(
            swarm_core::Vec3::new(10.5f32, 9.9, 10.0),
            swarm_core::Vec3::new(-1.0, 0.5, 1.0),
        );
        assert_eq!(w.confine(&mut s), 1);
        // Out through the side (the top lies on the ceiling), inward velocity removed.
        assert!((s.pos.x - (11.0 + 1e-3)).abs() < 1e-5 && s.pos.y == 9.9);
        assert_eq!((s.vel.x, s.vel.y, s.vel.z), (0.0, 0.5, 1.0));
        assert!(w.inside_obstacle(a3(s.pos)).is_none());
        let mut s = BeeState::new(
            swarm_core::Vec3::new(-1.0f32, 12.0, 3.0),
            swarm_core::Vec3::new(-1.0, 2.0, 1.0),
        );
        assert_eq!(w.confine(&mut s), 2);
        assert_eq!((s.pos.x, s.pos.y, s.pos.z), (0.0, 10.0, 3.0));
        assert_eq!((s.vel.x, s.vel.y, s.vel.z), (0.0, 0.0, 1.0));
    }
}
