//! The bee world: the volume, its obstacles and targets, and the *sensed* state of every bee
//! (struct of arrays, `f64`, as of the previous step) from which sensor frames are built.
//!
//! Obstacle geometry is computed in the scalar of the bee that senses it (`f32`, or `Fx`
//! arithmetic only in fixed point, so the GPU backend reproduces every bit; `docs/gpu.md`):
//! the closest point of a surface and its outward unit normal, for points outside and inside
//! the solid ([`Surface`]).

use rayon::prelude::*;
use swarm_core::bee::BeeState;
use swarm_core::{Scalar, Vec3};

use crate::grid::Grid;
use crate::obstacle_index::ObstacleIndex;
use crate::scalar::{SimScalar, a3};
use crate::scenario::ObjectKind;
pub use crate::space::{
    BeeObstacle, SURFACE_OFFSET, Shape3, Surface, box_surface, box_surface_open, confine,
    shaft_surface, shaft_surface_open, sphere_surface,
};

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
        confine(
            &self.obstacles,
            &ObstacleIndex::NONE,
            self.min,
            self.max,
            &mut s.pos,
            &mut s.vel,
        )
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

#[cfg(test)]
mod tests {
    use super::*;
    use swarm_core::Vec2;

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
