//! The bee world: the volume, its obstacles and targets, and the *sensed* state of every bee
//! (struct of arrays, `f64`, as of the previous step) from which sensor frames are built.
//!
//! Obstacle geometry is computed in the scalar of the bee that senses it (`f32`, or `Fx`
//! arithmetic only in fixed point, so the GPU backend reproduces every bit; `docs/gpu.md`):
//! the closest point of a surface and its outward unit normal, for points outside and inside
//! the solid ([`Surface`]).

use rayon::prelude::*;
use swarm_core::bee::BeeState;
use swarm_core::{Scalar, Vec2, Vec3};

use crate::grid::Grid;
use crate::scalar::{SimScalar, a3};
use crate::scenario::ObjectKind;

/// How far outside the surface the world puts a bee it pushes out of an obstacle.
pub const SURFACE_OFFSET: f32 = 1e-3;

/// The closest point of an obstacle's surface to a query point, in scalar `S`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface<S> {
    /// The closest point on the surface.
    pub point: Vec3<S>,
    /// The outward unit normal there (for a point outside: the unit vector from `point` to the
    /// query point, which is the surface normal on faces and the bisecting direction on edges and
    /// corners).
    pub normal: Vec3<S>,
    /// The distance from the query point to `point`.
    pub distance: S,
    /// Whether the query point lies inside the solid (on an open surface: not inside).
    pub inside: bool,
}

/// A scenario point (`f32`) in the scalar `S`.
fn at<S: Scalar>(p: [f32; 3]) -> Vec3<S> {
    Vec3::new(S::from_f32(p[0]), S::from_f32(p[1]), S::from_f32(p[2]))
}

/// Straight up, the normal of last resort.
fn up<S: Scalar>() -> Vec3<S> {
    Vec3::new(S::ZERO, S::ONE, S::ZERO)
}

/// A surface point seen from outside: `p` is off the solid, `q` the closest solid point.
fn from_outside<S: Scalar>(p: Vec3<S>, q: Vec3<S>) -> Surface<S> {
    let d = p - q;
    Surface {
        point: q,
        normal: d.normalized().unwrap_or_else(up),
        distance: d.length(),
        inside: false,
    }
}

/// The sphere (`center`, `radius`): the radial projection of `p` and the radial normal (the
/// centre itself: the top point, normal up).
pub fn sphere_surface<S: Scalar>(center: Vec3<S>, radius: S, p: Vec3<S>) -> Surface<S> {
    let d = p - center;
    let len = d.length();
    let normal = d.normalized().unwrap_or_else(up);
    Surface {
        point: center + normal * radius,
        normal,
        distance: (len - radius).abs(),
        inside: len < radius,
    }
}

/// The axis-aligned box `[min, max]` with every face open (see [`box_surface_open`]).
pub fn box_surface<S: Scalar>(min: Vec3<S>, max: Vec3<S>, p: Vec3<S>) -> Surface<S> {
    box_surface_open(min, max, p, [true; 6])
}

/// Component `k` of `v`.
fn axis<S: Copy>(v: Vec3<S>, k: usize) -> S {
    match k {
        0 => v.x,
        1 => v.y,
        _ => v.z,
    }
}

/// `v` with component `k` set to `x`.
fn with_axis<S>(mut v: Vec3<S>, k: usize, x: S) -> Vec3<S> {
    match k {
        0 => v.x = x,
        1 => v.y = x,
        _ => v.z = x,
    }
    v
}

/// The axis-aligned box `[min, max]`. Outside: the clamped point, the normal from it to `p`
/// (face, edge or corner). Inside: the nearest *open* face (faces `-x, +x, -y, +y, -z, +z`;
/// ties in that order), its normal; a closed face is one the bee cannot leave through (it lies
/// on the world's boundary) and a point on it counts as inside. With no face open, all are.
pub fn box_surface_open<S: Scalar>(
    min: Vec3<S>,
    max: Vec3<S>,
    p: Vec3<S>,
    open: [bool; 6],
) -> Surface<S> {
    let q = Vec3::new(
        p.x.clamp_to(min.x, max.x),
        p.y.clamp_to(min.y, max.y),
        p.z.clamp_to(min.z, max.z),
    );
    if q != p {
        return from_outside(p, q);
    }
    let open = if open.contains(&true) {
        open
    } else {
        [true; 6]
    };
    let mut best: Option<(S, usize)> = None;
    for (face, &is_open) in open.iter().enumerate() {
        let k = face / 2;
        let dist = if face % 2 == 0 {
            axis(p, k) - axis(min, k)
        } else {
            axis(max, k) - axis(p, k)
        };
        if is_open && best.is_none_or(|(b, _)| dist < b) {
            best = Some((dist, face));
        }
    }
    let (distance, face) = best.unwrap_or((S::ZERO, 0));
    let k = face / 2;
    let (point, normal) = if face % 2 == 0 {
        (
            with_axis(p, k, axis(min, k)),
            with_axis(Vec3::zero(), k, -S::ONE),
        )
    } else {
        (
            with_axis(p, k, axis(max, k)),
            with_axis(Vec3::zero(), k, S::ONE),
        )
    };
    let inside = (0..3).all(|k| {
        let (x, lo, hi) = (axis(p, k), axis(min, k), axis(max, k));
        let above = if open[2 * k] { x > lo } else { x >= lo };
        let below = if open[2 * k + 1] { x < hi } else { x <= hi };
        above && below
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
pub fn shaft_surface<S: Scalar>(
    center: Vec2<S>,
    radius: S,
    y_min: S,
    y_max: S,
    p: Vec3<S>,
) -> Surface<S> {
    shaft_surface_open(center, radius, y_min, y_max, p, [true; 2])
}

/// The vertical cylinder with axis `center = [x, z]`, `radius`, from `y_min` to `y_max`.
/// Outside: the closest point on the side, a cap or the rim edge between them, the normal from
/// it to `p`. Inside: the nearest of the side (radial normal; on the axis, +x) and the open caps
/// (`open = [bottom, top]`; ties: side, bottom, top); a point on a closed cap counts as inside.
pub fn shaft_surface_open<S: Scalar>(
    center: Vec2<S>,
    radius: S,
    y_min: S,
    y_max: S,
    p: Vec3<S>,
    open: [bool; 2],
) -> Surface<S> {
    let d = Vec2::new(p.x - center.x, p.z - center.y);
    let rho = d.length();
    let radial = d.normalized().unwrap_or(Vec2::new(S::ONE, S::ZERO));
    if rho > radius || p.y < y_min || p.y > y_max {
        let r = rho.min(radius);
        let q = Vec3::new(
            center.x + radial.x * r,
            p.y.clamp_to(y_min, y_max),
            center.y + radial.y * r,
        );
        return from_outside(p, q);
    }
    let side = Surface {
        point: Vec3::new(
            center.x + radial.x * radius,
            p.y,
            center.y + radial.y * radius,
        ),
        normal: Vec3::new(radial.x, S::ZERO, radial.y),
        distance: radius - rho,
        inside: false,
    };
    let bottom = Surface {
        point: Vec3::new(p.x, y_min, p.z),
        normal: -up::<S>(),
        distance: p.y - y_min,
        inside: false,
    };
    let top = Surface {
        point: Vec3::new(p.x, y_max, p.z),
        normal: up(),
        distance: y_max - p.y,
        inside: false,
    };
    let mut best = side;
    for (s, is_open) in [(bottom, open[0]), (top, open[1])] {
        if is_open && s.distance < best.distance {
            best = s;
        }
    }
    let lo = if open[0] { p.y > y_min } else { p.y >= y_min };
    let hi = if open[1] { p.y < y_max } else { p.y <= y_max };
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
    pub fn surface<S: Scalar>(&self, p: Vec3<S>, lo: [f32; 3], hi: [f32; 3]) -> Surface<S> {
        match *self {
            Shape3::Sphere { center, radius } => sphere_surface(at(center), S::from_f32(radius), p),
            Shape3::Box { min, max } => {
                let open = std::array::from_fn(|face| {
                    let k = face / 2;
                    if face % 2 == 0 {
                        min[k] > lo[k]
                    } else {
                        max[k] < hi[k]
                    }
                });
                box_surface_open(at(min), at(max), p, open)
            }
            Shape3::Shaft {
                center,
                radius,
                y_min,
                y_max,
            } => shaft_surface_open(
                Vec2::new(S::from_f32(center[0]), S::from_f32(center[1])),
                S::from_f32(radius),
                S::from_f32(y_min),
                S::from_f32(y_max),
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

    /// A cheap test: false only if `p` is certainly farther than `range` from the obstacle
    /// (with a margin for the rounding of the scenario's `f32` geometry to the bee's scalar).
    #[inline]
    pub fn may_be_within(&self, p: [f64; 3], range: f64) -> bool {
        let (lo, hi) = self.aabb;
        let range = range + 1e-3;
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
    pub fn surface<S: Scalar>(&self, o: &BeeObstacle, p: Vec3<S>) -> Surface<S> {
        o.shape.surface(p, self.min, self.max)
    }

    /// Keeps a bee's new state physical: out of every active obstacle (put back on the surface,
    /// [`SURFACE_OFFSET`] along the normal, the inward normal velocity removed) and inside the
    /// bounds (clamped, the outward velocity removed), in the bee's scalar. Returns what was
    /// corrected: bit 0 an obstacle, bit 1 the bounds.
    pub fn confine<S: SimScalar>(&self, s: &mut BeeState<S>) -> u8 {
        confine(&self.obstacles, self.min, self.max, &mut s.pos, &mut s.vel)
    }

    /// Whether `p` lies inside an active obstacle (strictly; see [`Shape3::surface`]), in the
    /// scalar `S`.
    pub fn inside_obstacle<S: SimScalar>(&self, p: Vec3<S>) -> Option<&BeeObstacle> {
        self.obstacles
            .iter()
            .filter(|o| o.active && o.may_be_within(a3(p), 0.0))
            .find(|o| self.surface(o, p).inside)
    }
}

/// Keeps a point physical: out of every active obstacle of `obstacles` (put back on the
/// surface, [`SURFACE_OFFSET`] along the normal, the inward normal velocity removed) and inside
/// the bounds `[min, max]` (clamped, the outward velocity removed), in the point's scalar.
/// Returns what was corrected: bit 0 an obstacle, bit 1 the bounds. Shared by the 3D models
/// (the bee world's [`BeeWorld::confine`]).
pub fn confine<S: SimScalar>(
    obstacles: &[BeeObstacle],
    min: [f32; 3],
    max: [f32; 3],
    pos: &mut Vec3<S>,
    vel: &mut Vec3<S>,
) -> u8 {
    let (mut p, mut v) = (*pos, *vel);
    let offset = S::from_f32(SURFACE_OFFSET);
    let (lo, hi) = (at::<S>(min), at::<S>(max));
    let mut flags = 0u8;
    for _ in 0..4 {
        let mut moved = false;
        for o in obstacles.iter().filter(|o| o.active) {
            if !o.may_be_within(a3(p), 0.0) {
                continue;
            }
            let surf = o.shape.surface(p, min, max);
            if !surf.inside {
                continue;
            }
            let n = surf.normal;
            p = surf.point + n * offset;
            let vn = v.dot(n);
            if vn < S::ZERO {
                v -= n * vn;
            }
            flags |= 1;
            moved = true;
        }
        for k in 0..3 {
            let (x, min, max) = (axis(p, k), axis(lo, k), axis(hi, k));
            if x < min {
                p = with_axis(p, k, min);
                v = with_axis(v, k, axis(v, k).max(S::ZERO));
                flags |= 2;
                moved = true;
            } else if x > max {
                p = with_axis(p, k, max);
                v = with_axis(v, k, axis(v, k).min(S::ZERO));
                flags |= 2;
                moved = true;
            }
        }
        if !moved {
            break;
        }
    }
    if flags != 0 {
        *pos = p;
        *vel = v;
    }
    flags
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3<f32>, b: [f32; 3]) -> bool {
        (a.x - b[0]).abs() < 1e-6 && (a.y - b[1]).abs() < 1e-6 && (a.z - b[2]).abs() < 1e-6
    }

    fn v(p: [f32; 3]) -> Vec3<f32> {
        Vec3::new(p[0], p[1], p[2])
    }

    #[test]
    fn sphere_closest_point_and_normal() {
        let c = v([1.0, 2.0, 3.0]);
        let s = sphere_surface(c, 2.0, v([1.0, 2.0, 7.0]));
        assert!(close(s.point, [1.0, 2.0, 5.0]) && close(s.normal, [0.0, 0.0, 1.0]));
        assert!(!s.inside && (s.distance - 2.0).abs() < 1e-6);
        // Inside: the radial projection, normal still outward.
        let s = sphere_surface(c, 2.0, v([1.5, 2.0, 3.0]));
        assert!(close(s.point, [3.0, 2.0, 3.0]) && close(s.normal, [1.0, 0.0, 0.0]));
        assert!(s.inside && (s.distance - 1.5).abs() < 1e-6);
        let s = sphere_surface(c, 2.0, c);
        assert!(s.inside && close(s.normal, [0.0, 1.0, 0.0]) && close(s.point, [1.0, 4.0, 3.0]));
    }

    #[test]
    fn box_closest_point_and_normal_outside_and_inside() {
        let (lo, hi) = (v([0.0, 0.0, 0.0]), v([4.0, 2.0, 6.0]));
        // Face.
        let s = box_surface(lo, hi, v([2.0, 5.0, 3.0]));
        assert!(close(s.point, [2.0, 2.0, 3.0]) && close(s.normal, [0.0, 1.0, 0.0]));
        assert!(!s.inside && (s.distance - 3.0).abs() < 1e-6);
        // Edge: the normal bisects.
        let s = box_surface(lo, hi, v([5.0, 3.0, 3.0]));
        let r = 0.5f32.sqrt();
        assert!(close(s.point, [4.0, 2.0, 3.0]) && close(s.normal, [r, r, 0.0]));
        // Corner.
        let s = box_surface(lo, hi, v([-1.0, -1.0, -1.0]));
        let r = 1.0 / 3f32.sqrt();
        assert!(close(s.point, [0.0; 3]) && close(s.normal, [-r, -r, -r]));
        // Inside: the nearest face.
        let s = box_surface(lo, hi, v([3.5, 1.0, 3.0]));
        assert!(s.inside && close(s.point, [4.0, 1.0, 3.0]) && close(s.normal, [1.0, 0.0, 0.0]));
        assert!((s.distance - 0.5).abs() < 1e-6);
        let s = box_surface(lo, hi, v([2.0, 0.2, 3.0]));
        assert!(s.inside && close(s.point, [2.0, 0.0, 3.0]) && close(s.normal, [0.0, -1.0, 0.0]));
        // On the surface: not inside, distance 0.
        let s = box_surface(lo, hi, v([2.0, 2.0, 3.0]));
        assert!(!s.inside && s.distance == 0.0 && close(s.normal, [0.0, 1.0, 0.0]));
        // Closed faces: only the top is open, like a ground slab spanning the world.
        let open = [false, false, false, true, false, false];
        let s = box_surface_open(lo, hi, v([0.1, 0.5, 3.0]), open);
        assert!(s.inside && close(s.point, [0.1, 2.0, 3.0]) && close(s.normal, [0.0, 1.0, 0.0]));
        let s = box_surface_open(lo, hi, v([2.0, 0.0, 3.0]), open);
        assert!(s.inside, "a point on a closed face is inside");
    }

    #[test]
    fn shaft_closest_point_and_normal_side_caps_edges_inside() {
        let (c, r, y0, y1) = (Vec2::new(10.0, 20.0), 2.0, 1.0, 9.0);
        // Side.
        let s = shaft_surface(c, r, y0, y1, v([15.0, 5.0, 20.0]));
        assert!(close(s.point, [12.0, 5.0, 20.0]) && close(s.normal, [1.0, 0.0, 0.0]));
        assert!(!s.inside && (s.distance - 3.0).abs() < 1e-6);
        let s = shaft_surface(c, r, y0, y1, v([10.0, 5.0, 16.0]));
        assert!(close(s.point, [10.0, 5.0, 18.0]) && close(s.normal, [0.0, 0.0, -1.0]));
        // Caps.
        let s = shaft_surface(c, r, y0, y1, v([10.5, 12.0, 20.5]));
        assert!(close(s.point, [10.5, 9.0, 20.5]) && close(s.normal, [0.0, 1.0, 0.0]));
        let s = shaft_surface(c, r, y0, y1, v([9.0, 0.0, 20.0]));
        assert!(close(s.point, [9.0, 1.0, 20.0]) && close(s.normal, [0.0, -1.0, 0.0]));
        // Rim edge.
        let s = shaft_surface(c, r, y0, y1, v([13.0, 10.0, 20.0]));
        let h = 0.5f32.sqrt();
        assert!(close(s.point, [12.0, 9.0, 20.0]) && close(s.normal, [h, h, 0.0]));
        // Inside, nearest the side.
        let s = shaft_surface(c, r, y0, y1, v([11.5, 5.0, 20.0]));
        assert!(s.inside && close(s.point, [12.0, 5.0, 20.0]) && close(s.normal, [1.0, 0.0, 0.0]));
        // Inside, nearest the top cap.
        let s = shaft_surface(c, r, y0, y1, v([10.2, 8.8, 20.0]));
        assert!(s.inside && close(s.point, [10.2, 9.0, 20.0]) && close(s.normal, [0.0, 1.0, 0.0]));
        // The top closed (the shaft reaches the ceiling): the side instead.
        let s = shaft_surface_open(c, r, y0, y1, v([10.2, 8.8, 20.0]), [true, false]);
        assert!(s.inside && close(s.point, [12.0, 8.8, 20.0]) && close(s.normal, [1.0, 0.0, 0.0]));
        // On the axis: +x.
        let s = shaft_surface(c, r, y0, y1, v([10.0, 5.0, 20.0]));
        assert!(s.inside && close(s.normal, [1.0, 0.0, 0.0]));
        // Normals are unit length everywhere.
        for p in [[3.0, -4.0, 25.0], [10.0, 20.0, 20.0], [11.0, 1.5, 21.0]] {
            let s = shaft_surface(c, r, y0, y1, v(p));
            assert!((s.normal.length() - 1.0).abs() < 1e-6, "{p:?}");
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
        assert!(w.inside_obstacle(s.pos).is_none());
        let mut s = BeeState::new(
            swarm_core::Vec3::new(-1.0f32, 12.0, 3.0),
            swarm_core::Vec3::new(-1.0, 2.0, 1.0),
        );
        assert_eq!(w.confine(&mut s), 2);
        assert_eq!((s.pos.x, s.pos.y, s.pos.z), (0.0, 10.0, 3.0));
        assert_eq!((s.vel.x, s.vel.y, s.vel.z), (0.0, 0.0, 1.0));
    }
}
