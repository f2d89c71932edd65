//! The scenario data model: what a scenario file says, checked and typed.
//!
//! Every type serializes to (and deserializes from) the TOML schema of the scenario files,
//! through the untyped serde shapes of `raw.rs` (the conversions: `build.rs`). Coordinates are `f32`: ant worlds are 2D `[x, y]` in
//! ant body lengths, bee worlds 3D `[x, y, z]` in the bee model's units with y up.

use std::path::PathBuf;

use std::borrow::Cow;
use std::fmt;

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

/// Largest number of agents in one group, and in a whole scenario.
pub const MAX_AGENTS: u32 = 10_000_000;

/// Largest magnitude of a world coordinate: the controllers' input range (±16000 for bees,
/// ±16384 for ants).
pub const MAX_COORD: f32 = swarm_core::bee::params::LIMIT;

/// Largest number of virtual particles sampled on one target.
pub const MAX_TARGET_PARTICLES: u32 = 100_000;

/// A whole scenario: the world, the agents, the objects, the timed events and what to record.
///
/// A `Scenario` obtained from [`Scenario::from_path`], [`Scenario::from_str`],
/// [`builtin`](super::builtin) or serde deserialization has been validated: names resolve,
/// regions lie inside the world, parameters pass the controllers' `validate()`.
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    /// Short name (`name` in the file; defaults to the file stem).
    pub name: String,
    /// What the scenario shows (free text, may cite a paper figure).
    pub description: String,
    /// Seed of the counter-based random numbers.
    pub seed: u32,
    /// Number of steps (ticks) to run.
    pub steps: u32,
    /// World bounds; their dimension must be the groups' models' (2D ants, 3D bees).
    pub world: World,
    /// Agent groups, at least one.
    pub groups: Vec<Group>,
    /// Objects; an object's id is its index here (see [`Scenario::object_id`]).
    pub objects: Vec<Object>,
    /// Timed events, in step order.
    pub events: Vec<Event>,
    /// What a run records.
    pub outputs: Outputs,
    /// Who computes the decisions (`backend = "gpu"`; default `cpu`).
    pub backend: Backend,
    /// The file the scenario was read from (not serialized).
    pub source: Option<PathBuf>,
}

impl Scenario {
    /// The id of the object called `name`: its index in [`Scenario::objects`].
    pub fn object_id(&self, name: &str) -> Option<u16> {
        self.objects
            .iter()
            .position(|o| o.name == name)
            .and_then(|i| u16::try_from(i).ok())
    }

    /// The object called `name`.
    pub fn object(&self, name: &str) -> Option<&Object> {
        self.objects.iter().find(|o| o.name == name)
    }

    /// The group called `name`.
    pub fn group(&self, name: &str) -> Option<&Group> {
        self.groups.iter().find(|g| g.name == name)
    }

    /// Agents in all groups.
    pub fn agents(&self) -> u64 {
        self.groups.iter().map(|g| u64::from(g.count)).sum()
    }

    /// This scenario over `steps` steps, every event at the same fraction of the run (step
    /// `s` of the `S`-step scenario at `s·steps/S`): a short run that still sees every event.
    #[must_use]
    pub fn squeezed(mut self, steps: u32) -> Scenario {
        for e in &mut self.events {
            e.step = (u64::from(e.step) * u64::from(steps) / u64::from(self.steps.max(1))) as u32;
        }
        self.steps = steps;
        self
    }

    /// This scenario with every group in `scalar`.
    #[must_use]
    pub fn in_scalar(mut self, scalar: ScalarType) -> Scenario {
        for g in &mut self.groups {
            g.scalar = scalar;
        }
        self
    }

    /// The world's corners, `D` numbers each, for `model`, a model of `D`-dimensional worlds.
    ///
    /// # Errors
    ///
    /// [`SimError::WrongWorld`](crate::SimError::WrongWorld) when the world has another
    /// dimension.
    pub fn bounds<const D: usize>(
        &self,
        model: &'static str,
    ) -> crate::Result<([f32; D], [f32; D])> {
        let wrong = || crate::SimError::WrongWorld {
            scenario: self.name.clone(),
            model,
            dim: D,
        };
        let min = <[f32; D]>::try_from(self.world.min()).map_err(|_| wrong())?;
        let max = <[f32; D]>::try_from(self.world.max()).map_err(|_| wrong())?;
        Ok((min, max))
    }

    /// Every group's parameters, as `read` (the model's reader) gives them, in group order.
    ///
    /// # Errors
    ///
    /// The first error of `read`.
    pub fn group_params<P>(
        &self,
        read: impl Fn(&Group) -> crate::Result<P>,
    ) -> crate::Result<Vec<P>> {
        self.groups.iter().map(read).collect()
    }

    /// Total number of agents over all groups.
    pub fn agent_count(&self) -> u64 {
        self.groups.iter().map(|g| u64::from(g.count)).sum()
    }

    /// Shortens (or lengthens) the run to `steps` and drops the events that would fall at or
    /// after the new end, so the scenario stays valid (what `--steps` does).
    pub fn set_steps(&mut self, steps: u32) {
        self.steps = steps;
        self.events.retain(|e| e.step < steps);
    }

    /// The scenario as TOML text in the scenario-file schema (loading it again gives the same
    /// scenario, apart from `source`).
    pub fn to_toml(&self) -> Result<String, toml::ser::Error> {
        toml::to_string(self)
    }
}

/// World bounds, tagged by `dim` in the file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum World {
    /// `{ dim = 2, min = [x, y], max = [x, y] }`: a plane (the ants' arena, in ant body
    /// lengths).
    Plane {
        /// Lower corner.
        min: [f32; 2],
        /// Upper corner.
        max: [f32; 2],
    },
    /// `{ dim = 3, min = [x, y, z], max = [x, y, z] }`: a volume, y up (the bees' meadow).
    Space {
        /// Lower corner.
        min: [f32; 3],
        /// Upper corner.
        max: [f32; 3],
    },
}

impl World {
    /// 2 or 3.
    pub fn dim(&self) -> usize {
        match self {
            World::Plane { .. } => 2,
            World::Space { .. } => 3,
        }
    }

    /// Lower corner (`dim` numbers).
    pub fn min(&self) -> &[f32] {
        match self {
            World::Plane { min, .. } => min,
            World::Space { min, .. } => min,
        }
    }

    /// Upper corner (`dim` numbers).
    pub fn max(&self) -> &[f32] {
        match self {
            World::Plane { max, .. } => max,
            World::Space { max, .. } => max,
        }
    }

    /// Whether `p` (with `dim` numbers) lies inside the bounds (borders included).
    pub fn contains(&self, p: &[f32]) -> bool {
        p.len() == self.dim()
            && p.iter()
                .zip(self.min().iter().zip(self.max()))
                .all(|(v, (lo, hi))| v >= lo && v <= hi)
    }
}

/// The name of the model that drives a group (`model = "ant"` in the file): a built-in model
/// (`ant`, `bee`) or one registered with [`models::register`](crate::models::register). The
/// scenario's rules find it in the model table ([`models::find`](crate::models::find)).
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(transparent)]
pub struct Model(Cow<'static, str>);

impl Model {
    /// The model called `name`.
    pub const fn new(name: &'static str) -> Model {
        Model(Cow::Borrowed(name))
    }

    /// The name, as the file writes it.
    pub fn as_str(&self) -> &str {
        &self.0
    }
}

impl From<String> for Model {
    fn from(name: String) -> Model {
        Model(Cow::Owned(name))
    }
}

impl fmt::Display for Model {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

/// Who computes the agents' decisions: `backend = "cpu"` (the default; rayon over the cores)
/// or `"gpu"` (wgpu compute kernels; `--backend` on `swarm run` overrides the file). In fixed
/// point both decide the same bits.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize, clap::ValueEnum,
)]
#[serde(rename_all = "snake_case")]
pub enum Backend {
    /// The CPU engine (the default).
    #[default]
    Cpu,
    /// The GPU engine of the model (wgpu; lavapipe where there is no GPU).
    Gpu,
}

impl Backend {
    /// `cpu` or `gpu`.
    pub fn name(self) -> &'static str {
        match self {
            Backend::Cpu => "cpu",
            Backend::Gpu => "gpu",
        }
    }

    /// Whether it is the default (`cpu`): not written in a scenario file.
    pub fn is_default(&self) -> bool {
        *self == Backend::Cpu
    }
}

/// The scalar type a group's controllers compute in.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize, clap::ValueEnum,
)]
#[serde(rename_all = "snake_case")]
pub enum ScalarType {
    /// `"f32"` (the default).
    #[default]
    F32,
    /// `"fixed"`: I16F16 fixed point, bit-identical everywhere.
    Fixed,
}

impl ScalarType {
    /// The matching `swarm_core` kind.
    pub fn kind(&self) -> swarm_core::ScalarKind {
        match self {
            ScalarType::F32 => swarm_core::ScalarKind::F32,
            ScalarType::Fixed => swarm_core::ScalarKind::I16F16,
        }
    }
}

/// A group of agents of one model, sharing spawn region, parameters and scalar type.
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    /// Name, unique in the scenario.
    pub name: String,
    /// The model that drives it (`ant`, `bee`, or a registered model).
    pub model: Model,
    /// Number of agents, 1 to [`MAX_AGENTS`].
    pub count: u32,
    /// Scalar type of the controllers (default `f32`).
    pub scalar: ScalarType,
    /// Where the agents start.
    pub spawn: Spawn,
    /// The object the group calls home, for models that have one (ants: their nest, required).
    pub nest: Option<String>,
    /// The object the group heads for, for models that have one (bees: a `target`, optional).
    pub goal: Option<String>,
    /// The object the group flees, for models that have one (ren2016: a predator, optional).
    pub threat: Option<String>,
    /// The model's parameter table, under the model's name in the file (`ant = { w0 = 0.6 }`,
    /// `[groups.bee]`), as written; the model reads it ([`Group::params_as`]) and its rules
    /// check it.
    pub params: Option<toml::Table>,
}

impl Group {
    /// The parameter table read as `T` (the model's override type); `T::default()` when the
    /// group has none.
    ///
    /// # Errors
    ///
    /// [`SimError::ParamsTable`](crate::SimError::ParamsTable) when the table does not read as
    /// `T` (a loaded scenario's tables have been read by their model's rules already).
    pub fn params_as<T: DeserializeOwned + Default>(&self) -> crate::Result<T> {
        match &self.params {
            None => Ok(T::default()),
            Some(table) => toml::Value::Table(table.clone())
                .try_into()
                .map_err(|source| crate::SimError::ParamsTable {
                    group: self.name.clone(),
                    model: self.model.to_string(),
                    source: Box::new(source),
                }),
        }
    }

    /// Sets the parameter table to `params` (the model's override type) written out.
    ///
    /// # Errors
    ///
    /// [`SimError::ParamsWrite`](crate::SimError::ParamsWrite) when `params` is not a table.
    pub fn set_params<T: Serialize>(&mut self, params: &T) -> crate::Result<()> {
        let table =
            toml::Table::try_from(params).map_err(|source| crate::SimError::ParamsWrite {
                group: self.name.clone(),
                source: Box::new(source),
            })?;
        self.params = Some(table);
        Ok(())
    }
}

/// Where a group's agents start, and their initial heading.
#[derive(Clone, Debug, PartialEq)]
pub struct Spawn {
    /// The region sampled uniformly.
    pub region: SpawnRegion,
    /// Initial heading (a direction, `dim` numbers, not necessarily unit length); `None`: a
    /// random heading per agent.
    pub heading: Option<Vec<f32>>,
}

/// A spawn region.
#[derive(Clone, Debug, PartialEq)]
pub enum SpawnRegion {
    /// `{ at = "object", radius = r }`: uniform in the disc (2D) or ball (3D) of radius `r`
    /// around the object's centre.
    Around {
        /// The object's name.
        at: String,
        /// Radius of the disc / ball.
        radius: f32,
    },
    /// `{ min = [...], max = [...] }`: uniform in the box (`dim` numbers each).
    Box {
        /// Lower corner.
        min: Vec<f32>,
        /// Upper corner.
        max: Vec<f32>,
    },
}

/// A named object of the world; its id is its index in [`Scenario::objects`].
#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    /// Name, unique in the scenario.
    pub name: String,
    /// Present at the start (default `true`); events add, remove, start and stop it later.
    pub active: bool,
    /// What it is, with its geometry (`kind` in the file).
    pub kind: ObjectKind,
}

/// The kinds of object, with their geometry. Ant kinds are 2D; bee and field-model kinds
/// (spheres, boxes, shafts, targets, zones, regions) 3D.
#[derive(Clone, Debug, PartialEq)]
pub enum ObjectKind {
    /// Ants: a nest (circle).
    Nest {
        /// Centre `[x, y]`.
        center: [f32; 2],
        /// Radius.
        radius: f32,
    },
    /// Ants: a food source (circle).
    Food {
        /// Centre `[x, y]`.
        center: [f32; 2],
        /// Radius.
        radius: f32,
        /// Units of food; `None`: endless.
        amount: Option<u32>,
    },
    /// Ants: a circular obstacle.
    Rock {
        /// Centre `[x, y]`.
        center: [f32; 2],
        /// Radius.
        radius: f32,
    },
    /// Ants: a polygonal obstacle (simple polygon, at least 3 points, either orientation).
    Polygon {
        /// Vertices `[x, y]`.
        points: Vec<[f32; 2]>,
    },
    /// Ants: an external disturbance, a dangerous circle ants flee (xiang §4.2.2).
    Disturbance {
        /// Centre `[x, y]`.
        center: [f32; 2],
        /// Radius.
        radius: f32,
    },
    /// Ants: an intermediate destination (xiang Fig. 14): the way points, in increasing `order`,
    /// make the route nest → way points → food that the colony travels leg by leg (see
    /// `ants::AntWorld::target_of`).
    Waypoint {
        /// Centre `[x, y]`.
        center: [f32; 2],
        /// Radius.
        radius: f32,
        /// Visiting order (unique among way points).
        order: u32,
    },
    /// Bees: a spherical obstacle.
    Sphere {
        /// Centre `[x, y, z]`.
        center: [f32; 3],
        /// Radius.
        radius: f32,
    },
    /// Bees: an axis-aligned box obstacle (e.g. the ground).
    Box {
        /// Lower corner `[x, y, z]`.
        min: [f32; 3],
        /// Upper corner `[x, y, z]`.
        max: [f32; 3],
    },
    /// Bees: a vertical cylinder obstacle (chen Fig. 13-14).
    Shaft {
        /// Axis position `[x, z]`.
        center: [f32; 2],
        /// Radius.
        radius: f32,
        /// Bottom of the shaft.
        y_min: f32,
        /// Top of the shaft.
        y_max: f32,
    },
    /// Bees: a nest or flower, sampled into `particles` static virtual particles on its
    /// surface that repel bees like neighbours (chen §V-B, the zig-zag approach).
    Target {
        /// Centre `[x, y, z]`.
        center: [f32; 3],
        /// Radius.
        radius: f32,
        /// Number of virtual particles.
        particles: u32,
    },
    /// 3D field models: a ball-shaped area agents head for (a goal area of wang2014 §5, where
    /// the navigation field is zero); not an obstacle.
    Zone {
        /// Centre `[x, y, z]`.
        center: [f32; 3],
        /// Radius.
        radius: f32,
    },
    /// 3D field models: a box-shaped area agents head for (a goal area of wang2014 §5); not an
    /// obstacle.
    Region {
        /// Lower corner `[x, y, z]`.
        min: [f32; 3],
        /// Upper corner `[x, y, z]`.
        max: [f32; 3],
    },
    /// 3D fly models: a box-shaped enclosure the insects fly inside and sense by echo (the
    /// bats' cave of ren2016 Fig. 9); not an obstacle (the world's walls keep them in). As a
    /// goal, each insect pursues the echo ahead of it: the point where its heading meets the
    /// walls, or half its visual range ahead when they are farther; as a threat, it escapes
    /// the wall ahead (as a `region` threat).
    Cave {
        /// Lower corner `[x, y, z]`.
        min: [f32; 3],
        /// Upper corner `[x, y, z]`.
        max: [f32; 3],
    },
}

impl ObjectKind {
    /// The `kind` string of the file (`"nest"`, `"food"`, ...).
    pub fn tag(&self) -> &'static str {
        match self {
            ObjectKind::Nest { .. } => "nest",
            ObjectKind::Food { .. } => "food",
            ObjectKind::Rock { .. } => "rock",
            ObjectKind::Polygon { .. } => "polygon",
            ObjectKind::Disturbance { .. } => "disturbance",
            ObjectKind::Waypoint { .. } => "waypoint",
            ObjectKind::Sphere { .. } => "sphere",
            ObjectKind::Box { .. } => "box",
            ObjectKind::Shaft { .. } => "shaft",
            ObjectKind::Target { .. } => "target",
            ObjectKind::Zone { .. } => "zone",
            ObjectKind::Region { .. } => "region",
            ObjectKind::Cave { .. } => "cave",
        }
    }

    /// The world dimension the kind belongs to: 2 (ants) or 3 (bees).
    pub fn dim(&self) -> usize {
        match self {
            ObjectKind::Nest { .. }
            | ObjectKind::Food { .. }
            | ObjectKind::Rock { .. }
            | ObjectKind::Polygon { .. }
            | ObjectKind::Disturbance { .. }
            | ObjectKind::Waypoint { .. } => 2,
            ObjectKind::Sphere { .. }
            | ObjectKind::Box { .. }
            | ObjectKind::Shaft { .. }
            | ObjectKind::Target { .. }
            | ObjectKind::Zone { .. }
            | ObjectKind::Region { .. }
            | ObjectKind::Cave { .. } => 3,
        }
    }

    /// Whether agents must not enter it (rock, polygon, sphere, box, shaft).
    pub fn is_obstacle(&self) -> bool {
        matches!(
            self,
            ObjectKind::Rock { .. }
                | ObjectKind::Polygon { .. }
                | ObjectKind::Sphere { .. }
                | ObjectKind::Box { .. }
                | ObjectKind::Shaft { .. }
        )
    }

    /// The centre of the kinds that have one (`[x, y]`, `[x, y, z]`, or `[x, z]` for a
    /// shaft); `None` for polygons and boxes.
    pub fn center(&self) -> Option<&[f32]> {
        match self {
            ObjectKind::Nest { center, .. }
            | ObjectKind::Food { center, .. }
            | ObjectKind::Rock { center, .. }
            | ObjectKind::Disturbance { center, .. }
            | ObjectKind::Waypoint { center, .. }
            | ObjectKind::Shaft { center, .. } => Some(center),
            ObjectKind::Sphere { center, .. }
            | ObjectKind::Target { center, .. }
            | ObjectKind::Zone { center, .. } => Some(center),
            ObjectKind::Polygon { .. }
            | ObjectKind::Box { .. }
            | ObjectKind::Region { .. }
            | ObjectKind::Cave { .. } => None,
        }
    }

    /// The centre as a point of the world (`dim` numbers): `None` for polygons, boxes and
    /// shafts (whose centre is an axis).
    pub fn point(&self) -> Option<&[f32]> {
        match self {
            ObjectKind::Shaft { .. } => None,
            _ => self.center(),
        }
    }

    /// The radius of the round kinds.
    pub fn radius(&self) -> Option<f32> {
        match self {
            ObjectKind::Nest { radius, .. }
            | ObjectKind::Food { radius, .. }
            | ObjectKind::Rock { radius, .. }
            | ObjectKind::Disturbance { radius, .. }
            | ObjectKind::Waypoint { radius, .. }
            | ObjectKind::Sphere { radius, .. }
            | ObjectKind::Shaft { radius, .. }
            | ObjectKind::Target { radius, .. }
            | ObjectKind::Zone { radius, .. } => Some(*radius),
            ObjectKind::Polygon { .. }
            | ObjectKind::Box { .. }
            | ObjectKind::Region { .. }
            | ObjectKind::Cave { .. } => None,
        }
    }

    /// Moves the centre to `to` (what a `move` event does). Returns `false`, changing
    /// nothing, when the kind has no centre or `to` has the wrong number of coordinates.
    pub fn set_center(&mut self, to: &[f32]) -> bool {
        match self {
            ObjectKind::Nest { center, .. }
            | ObjectKind::Food { center, .. }
            | ObjectKind::Rock { center, .. }
            | ObjectKind::Disturbance { center, .. }
            | ObjectKind::Waypoint { center, .. }
            | ObjectKind::Shaft { center, .. } => set_array(center, to),
            ObjectKind::Sphere { center, .. }
            | ObjectKind::Target { center, .. }
            | ObjectKind::Zone { center, .. } => set_array(center, to),
            ObjectKind::Polygon { .. }
            | ObjectKind::Box { .. }
            | ObjectKind::Region { .. }
            | ObjectKind::Cave { .. } => false,
        }
    }

    /// The virtual particles of a `target`: `particles` points spread evenly over its sphere
    /// (a Fibonacci sphere: deterministic, same bits on every machine). Empty for other kinds.
    pub fn sample_particles(&self) -> Vec<[f32; 3]> {
        match self {
            ObjectKind::Target {
                center,
                radius,
                particles,
            } => fibonacci_sphere(*center, *radius, *particles),
            _ => Vec::new(),
        }
    }
}

fn set_array<const N: usize>(dst: &mut [f32; N], src: &[f32]) -> bool {
    match <[f32; N]>::try_from(src) {
        Ok(a) => {
            *dst = a;
            true
        }
        Err(_) => false,
    }
}

/// `n` points on the sphere (`center`, `radius`): point i at height y = 1 − (2i + 1)/n and
/// longitude i·golden angle. Computed in `f64` and rounded once, so the result does not depend
/// on the platform's `f32` math.
fn fibonacci_sphere(center: [f32; 3], radius: f32, n: u32) -> Vec<[f32; 3]> {
    let golden_angle = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let (r, nf) = (f64::from(radius), f64::from(n));
    (0..n)
        .map(|i| {
            let fi = f64::from(i);
            let y = 1.0 - (2.0 * fi + 1.0) / nf;
            let ring = (1.0 - y * y).max(0.0).sqrt();
            let phi = fi * golden_angle;
            [
                (f64::from(center[0]) + r * ring * phi.cos()) as f32,
                (f64::from(center[1]) + r * y) as f32,
                (f64::from(center[2]) + r * ring * phi.sin()) as f32,
            ]
        })
        .collect()
}

impl Object {
    /// The virtual particles of a `target` (see [`ObjectKind::sample_particles`]).
    pub fn sample_particles(&self) -> Vec<[f32; 3]> {
        self.kind.sample_particles()
    }
}

/// A timed change of the world, applied before step `step` runs.
#[derive(Clone, Debug, PartialEq)]
pub struct Event {
    /// The step at which it happens (`< steps`).
    pub step: u32,
    /// What happens.
    pub action: Action,
}

/// What an event does.
#[derive(Clone, Debug, PartialEq)]
pub enum Action {
    /// `add = "name"`: the object appears.
    Add(String),
    /// `remove = "name"`: the object disappears.
    Remove(String),
    /// `move = { object = "name", to = [...] }`: the object's centre moves to `to`.
    Move {
        /// The object's name.
        object: String,
        /// The new centre (as many numbers as the object's `center`).
        to: Vec<f32>,
    },
    /// `start = "name"`: a disturbance starts acting.
    Start(String),
    /// `stop = "name"`: a disturbance stops acting.
    Stop(String),
}

impl Action {
    /// The object the action applies to.
    pub fn object(&self) -> &str {
        match self {
            Action::Add(o) | Action::Remove(o) | Action::Start(o) | Action::Stop(o) => o,
            Action::Move { object, .. } => object,
        }
    }

    /// The key of the action in the file: `add`, `remove`, `move`, `start` or `stop`.
    pub fn verb(&self) -> &'static str {
        match self {
            Action::Add(_) => "add",
            Action::Remove(_) => "remove",
            Action::Move { .. } => "move",
            Action::Start(_) => "start",
            Action::Stop(_) => "stop",
        }
    }
}

/// What a run records.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Outputs {
    /// Record every `every` steps (default 10, at least 1).
    pub every: u32,
    /// Trajectories as CSV (default true).
    pub trajectories: bool,
    /// Trajectories as `.npy`: `positions.npy`, and for 3D (bee) worlds `attitude.npy`, the
    /// roll and pitch in degrees (default true).
    pub npy: bool,
    /// PNG snapshot (default true).
    pub render: bool,
    /// Animated GIF (default true).
    pub gif: bool,
}

impl Default for Outputs {
    fn default() -> Self {
        Outputs {
            every: 10,
            trajectories: true,
            npy: true,
            render: true,
            gif: true,
        }
    }
}
