//! The world of the 3D flying models: a container (the world's box, whose walls the insects
//! sense like the midges' glass box of ren2016's Fig. 1), the obstacles in it, the stimulus
//! sources (objects whose centre is a target to pursue or a predator to escape, moved by
//! scenario events), and the *sensed* state of every insect: what it broadcast at its last
//! step (position and actual velocity), read by every neighbour's next step.

use rayon::prelude::*;
use swarm_core::orca3d::Surface;
use swarm_core::{Scalar, Vec3};

use crate::grid::Grid;
use crate::obstacle_index::ObstacleIndex;
use crate::scalar::{SimScalar, a3};
use crate::scenario::Action;
use crate::space::{BeeObstacle, at, axis, confine, with_axis};

/// An object whose centre is a stimulus (ren2016 §2.3): a group's `goal` (pursued) or `threat`
/// (escaped).
#[derive(Clone, Debug, PartialEq)]
pub struct Source {
    /// Object id (its index in the scenario).
    pub id: u16,
    /// Name.
    pub name: String,
    /// Centre `[x, y, z]`.
    pub center: [f32; 3],
    /// Present now.
    pub active: bool,
    /// For a `region` `[min, max]`: as a threat, the walls the insects sense ahead of them
    /// (the bats' echolocation of Fig. 9, spec §2.3 and R13: the stimulus is where an
    /// insect's heading meets them); as a goal, an area pursued toward its nearest point (the
    /// locusts' crop field of Fig. 4: nothing to pursue once inside).
    pub region: Option<[[f32; 3]; 2]>,
    /// The region is a `cave` the insects fly inside (Fig. 9): as a goal, each insect pursues
    /// the echo ahead of it ([`ahead_point`](crate::fly::ahead_point)); as a threat, it
    /// is a `region`.
    pub cave: bool,
}

/// A state with a position and a velocity (what the world senses, keeps physical and
/// broadcasts): every model living in a [`World3d`].
pub trait Kinematic<S>: Send + Sync {
    /// Its position and velocity.
    fn kinematics(&self) -> (Vec3<S>, Vec3<S>);
    /// Its position and velocity, to correct.
    fn kinematics_mut(&mut self) -> (&mut Vec3<S>, &mut Vec3<S>);
}

/// What every insect broadcast at its last step, by slot (`f64` holds `f32` and `Fx` values
/// exactly).
#[derive(Clone, Debug, Default)]
pub struct Sensed {
    /// Positions.
    pub pos: Vec<[f64; 3]>,
    /// Actual velocities.
    pub vel: Vec<[f64; 3]>,
    /// Stable insect ids.
    pub id: Vec<u32>,
}

impl Sensed {
    /// Writes slots `first..first + states.len()` (insects `ids`), in parallel.
    pub fn write<S: SimScalar, K: Kinematic<S>>(
        &mut self,
        first: usize,
        ids: &[u32],
        states: &[K],
    ) {
        let r = first..first + states.len();
        self.pos[r.clone()]
            .par_iter_mut()
            .zip(self.vel[r.clone()].par_iter_mut())
            .zip(self.id[r].par_iter_mut())
            .zip(states.par_iter().zip(ids.par_iter()))
            .with_min_len(4096)
            .for_each(|(((p, v), i), (s, &id))| {
                let (pos, vel) = s.kinematics();
                *p = a3(pos);
                *v = a3(vel);
                *i = id;
            });
    }

    /// Room for `n` insects.
    pub fn resize(&mut self, n: usize) {
        self.pos.resize(n, [0.0; 3]);
        self.vel.resize(n, [0.0; 3]);
        self.id.resize(n, 0);
    }
}

/// The container, its obstacles and stimulus sources, and the sensed insects.
#[derive(Clone, Debug, Default)]
pub struct World3d {
    /// Lower corner of the container.
    pub min: [f32; 3],
    /// Upper corner.
    pub max: [f32; 3],
    /// Obstacles (inactive ones included; frames and physics skip them).
    pub obstacles: Vec<BeeObstacle>,
    /// Stimulus sources (inactive ones included).
    pub sources: Vec<Source>,
    /// Neighbour range: the groups' largest r_att.
    pub range: f32,
    /// Surface range: the groups' largest ORCA reach ([`reach`]).
    pub reach: f32,
    /// The sensed insects.
    pub sensed: Sensed,
    pub(crate) grid: Grid,
}

/// How far from a surface ORCA's obstacle plane can bind: radius + τ·max_speed. Farther, the
/// plane `n·v ≥ −(d − radius)/τ` (spec §2.5) admits every velocity up to the speed limit, so a
/// frame leaves those surfaces out without changing any decision.
pub fn reach<S: Scalar>(radius: S, tau: S, max_speed: S) -> S {
    radius + tau * max_speed
}

impl World3d {
    /// An empty container `[min, max]` with neighbour range `range` and surface range `reach`.
    pub fn new(min: [f32; 3], max: [f32; 3], range: f32, reach: f32) -> Self {
        World3d {
            min,
            max,
            range,
            reach,
            ..World3d::default()
        }
    }

    /// Room for `n` insects and a neighbour grid sized for them: cells of the neighbour range,
    /// or larger when the insects are sparse (no more cells than insects).
    pub fn resize(&mut self, n: usize) {
        self.sensed.resize(n);
        let volume: f32 = (0..3)
            .map(|k| (self.max[k] - self.min[k]).max(1e-3))
            .product();
        let cell = (self.range * 1.001).max((volume / n.max(1) as f32).cbrt());
        self.grid = Grid::new(self.min, self.max, cell);
    }

    /// The number of insects.
    pub fn len(&self) -> usize {
        self.sensed.pos.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Rebuilds the neighbour grid from the sensed positions.
    pub fn index_positions(&mut self) {
        self.grid.rebuild(&self.sensed.pos, |p| {
            [p[0] as f32, p[1] as f32, p[2] as f32]
        });
    }

    /// Source `id` while it is active.
    pub fn source(&self, id: u16) -> Option<&Source> {
        self.sources.iter().find(|s| s.id == id && s.active)
    }

    /// The surfaces ORCA must respect at `p` (spec §2.5, ours): the closest point and outward
    /// normal of every active obstacle and every container wall (inward normal) nearer than
    /// `reach`, nearest first (ties: obstacles in scenario order, then the walls −x, +x, −y,
    /// +y, −z, +z), at most `O`; in the insect's scalar. An insect inside an obstacle is at
    /// distance 0 and gets the outward normal.
    pub fn surfaces<S: SimScalar, const O: usize>(
        &self,
        p: Vec3<S>,
        reach: S,
    ) -> heapless::Vec<Surface<S>, O> {
        let mut near = Nearest::<S, O>::default();
        let pf = a3(p);
        for o in self.obstacles.iter().filter(|o| o.active) {
            if !o.may_be_within(pf, f64::from(self.reach)) {
                continue;
            }
            let s = o.shape.surface(p, self.min, self.max);
            let d = if s.inside { S::ZERO } else { s.distance };
            if d < reach {
                near.offer(d, s.point, s.normal);
            }
        }
        let (lo, hi) = (at::<S>(self.min), at::<S>(self.max));
        for k in 0..3 {
            for (wall, sign) in [(lo, S::ONE), (hi, -S::ONE)] {
                let w = axis(wall, k);
                let d = ((axis(p, k) - w) * sign).max(S::ZERO);
                if d < reach {
                    near.offer(d, with_axis(p, k, w), with_axis(Vec3::zero(), k, sign));
                }
            }
        }
        near.items.into_iter().map(|(_, s)| s).collect()
    }

    /// Keeps a state physical: out of every active obstacle and inside the container
    /// ([`confine`]); returns what was corrected (bit 0 an obstacle, bit 1 a wall). ORCA's
    /// obstacle planes keep insects out by themselves; this is the backstop, and every
    /// correction is counted.
    pub fn confine<S: SimScalar>(&self, s: &mut impl Kinematic<S>) -> u8 {
        let (pos, vel) = s.kinematics_mut();
        confine(
            &self.obstacles,
            &ObstacleIndex::NONE,
            self.min,
            self.max,
            pos,
            vel,
        )
    }

    /// Applies a timed event of the scenario (`Action` on the object with id `object`): an
    /// obstacle or a stimulus source added, removed or moved (a sphere is both).
    pub fn apply(&mut self, object: u16, action: &Action) {
        let on = match action {
            Action::Add(_) | Action::Start(_) => Some(true),
            Action::Remove(_) | Action::Stop(_) => Some(false),
            Action::Move { .. } => None,
        };
        if let Some(o) = self.obstacles.iter_mut().find(|o| o.id == object) {
            match (on, action) {
                (Some(active), _) => o.active = active,
                (None, Action::Move { to, .. }) => {
                    o.set_center(to);
                }
                _ => {}
            }
        }
        if let Some(s) = self.sources.iter_mut().find(|s| s.id == object) {
            match (on, action) {
                (Some(active), _) => s.active = active,
                (None, Action::Move { to, .. }) => {
                    if let &[x, y, z] = to.as_slice() {
                        let shift = [x - s.center[0], y - s.center[1], z - s.center[2]];
                        s.center = [x, y, z];
                        if let Some(b) = &mut s.region {
                            b.iter_mut()
                                .for_each(|c| (0..3).for_each(|k| c[k] += shift[k]));
                        }
                    }
                }
                _ => {}
            }
        }
    }
}

/// Whether a body of radius `r` may start at `q` in the container `[min, max]`: one radius off
/// every active obstacle (a spawn region may hold one: the lamp of Fig. 7 among its moths).
pub fn clear_of(
    obstacles: &[BeeObstacle],
    min: [f32; 3],
    max: [f32; 3],
    r: f32,
    q: [f32; 3],
) -> bool {
    obstacles.iter().filter(|o| o.active).all(|o| {
        let s = o.shape.surface(Vec3::new(q[0], q[1], q[2]), min, max);
        !s.inside && s.distance >= r
    })
}

/// The `O` nearest surfaces offered, nearest first, the earlier offer first on ties.
struct Nearest<S, const O: usize> {
    items: heapless::Vec<(S, Surface<S>), O>,
}

impl<S, const O: usize> Default for Nearest<S, O> {
    fn default() -> Self {
        Nearest {
            items: heapless::Vec::new(),
        }
    }
}

impl<S: Scalar, const O: usize> Nearest<S, O> {
    fn offer(&mut self, d: S, point: Vec3<S>, normal: Vec3<S>) {
        let len = self.items.len();
        let i: usize = self.items.iter().position(|e| d < e.0).unwrap_or(len);
        if i >= O {
            return;
        }
        if self.items.is_full() {
            self.items.pop();
        }
        // Room was made: the insert cannot fail.
        let _ = self.items.insert(i, (d, Surface { point, normal }));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::space::Shape3;

    #[test]
    fn surfaces_are_the_nearest_walls_and_obstacles_within_reach() {
        let mut w = World3d::new([0.0; 3], [10.0; 3], 2.0, 3.0);
        w.obstacles.push(BeeObstacle::new(
            0,
            "ball",
            Shape3::Sphere {
                center: [2.5, 2.5, 5.0],
                radius: 1.0,
            },
            true,
        ));
        // 0.5 from −x, 1.0 from the ball, 2.5 from −y; +x, +y, the z walls out of reach.
        let p = Vec3::<f32>::new(0.5, 2.5, 5.0);
        let s = w.surfaces::<f32, 4>(p, 3.0);
        assert_eq!(s.len(), 3);
        assert_eq!(s[0].normal, Vec3::new(1.0, 0.0, 0.0));
        assert_eq!(s[0].point, Vec3::new(0.0, 2.5, 5.0));
        assert_eq!(s[2].normal, Vec3::new(0.0, 1.0, 0.0));
        assert_eq!(s[1].point, Vec3::new(1.5, 2.5, 5.0));
        assert_eq!(s[1].normal, Vec3::new(-1.0, 0.0, 0.0));
        // Capacity 2 keeps the two nearest; a short reach keeps the wall only.
        assert_eq!(w.surfaces::<f32, 2>(p, 3.0).as_slice(), &s[..2]);
        assert_eq!(w.surfaces::<f32, 4>(p, 0.6).len(), 1);
        // An inactive obstacle is not sensed.
        w.obstacles[0].active = false;
        assert_eq!(w.surfaces::<f32, 4>(p, 3.0).len(), 2);
    }

    #[test]
    fn the_reach_is_where_an_obstacle_plane_stops_binding() {
        assert_eq!(reach(0.5f32, 0.5, 10.0), 5.5);
    }
}
