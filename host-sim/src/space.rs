//! Solid geometry of the 3D worlds, shared by every 3D model: the closest point of an
//! obstacle's surface (sphere, box, vertical shaft) with its outward normal and distance,
//! computed in the sensing agent's scalar (`f32`, or `Fx` arithmetic only in fixed point, so the
//! GPU backend reproduces every bit; `docs/gpu.md`), and [`confine`], which keeps a point out
//! of the obstacles and inside the bounds.

use swarm_core::{Scalar, Vec2, Vec3};

use crate::obstacle_index::ObstacleIndex;
use crate::scalar::{SimScalar, a3, a3f};
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
pub(crate) fn at<S: Scalar>(p: [f32; 3]) -> Vec3<S> {
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
pub(crate) fn axis<S: Copy>(v: Vec3<S>, k: usize) -> S {
    match k {
        0 => v.x,
        1 => v.y,
        _ => v.z,
    }
}

/// `v` with component `k` set to `x`.
pub(crate) fn with_axis<S>(mut v: Vec3<S>, k: usize, x: S) -> Vec3<S> {
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

    /// Whether the shape's interior meets the open axis-aligned box `(lo, hi)` (exact for
    /// every shape: the squared distance from the ball's centre, or the shaft's axis in x-z, to
    /// the box below the radius squared, and the intervals overlapping on the other axes).
    pub fn meets_box(&self, lo: [f32; 3], hi: [f32; 3]) -> bool {
        let gap = |c: f32, k: usize| (lo[k] - c).max(c - hi[k]).max(0.0);
        let overlap = |a: f32, b: f32, k: usize| a < hi[k] && b > lo[k];
        match *self {
            Shape3::Sphere { center, radius } => {
                let d2: f32 = (0..3).map(|k| gap(center[k], k).powi(2)).sum();
                d2 < radius * radius
            }
            Shape3::Box { min, max } => (0..3).all(|k| overlap(min[k], max[k], k)),
            Shape3::Shaft {
                center,
                radius,
                y_min,
                y_max,
            } => {
                let d2 = gap(center[0], 0).powi(2) + gap(center[1], 2).powi(2);
                d2 < radius * radius && overlap(y_min, y_max, 1)
            }
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

/// Keeps a point physical: out of every active obstacle of `obstacles` (put back on the
/// surface, [`SURFACE_OFFSET`] along the normal, the inward normal velocity removed) and inside
/// the bounds `[min, max]` (clamped, the outward velocity removed), in the point's scalar.
/// Returns what was corrected: bit 0 an obstacle, bit 1 the bounds. Shared by the 3D models
/// (the bee world's [`BeeWorld::confine`](crate::bees::BeeWorld::confine), the wang2014 engine).
/// `index` narrows the obstacles visited ([`ObstacleIndex::NONE`]: all of them); it changes no
/// result.
pub fn confine<S: SimScalar>(
    obstacles: &[BeeObstacle],
    index: &ObstacleIndex,
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
        // The index is asked again after each move: a push may carry p into another cell.
        let mut from = 0;
        while let Some(i) = index.next_near(obstacles, a3f(p), from) {
            from = i + 1;
            let o = &obstacles[i];
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
