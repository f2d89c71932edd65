//! Builds an [`AntSim`] from a 2D [`Scenario`], and applies its timed events.

use swarm_core::ant::{AntParams, AntState};
use swarm_core::{Fx, Vec2};

use super::sim::{AntGroup, AntSim, AnyAntGroup};
use super::world::{AntObjectDef, AntObjectKind, AntWorld, Shape2};
use crate::scalar::SimScalar;
use crate::scenario::{Action, Group, ObjectKind, ScalarType, Scenario, SpawnRegion};
use crate::spawn::{around_center, draw};
use crate::{Result, SimError};

impl AntSim {
    /// The ant simulation of `scenario` (a 2D world), with seed `seed`.
    pub fn from_scenario(scenario: &Scenario, seed: u32) -> Result<AntSim> {
        let (min, max) = scenario.bounds::<2>("ant")?;
        let params = scenario.group_params(super::ant_params)?;
        let contact = params.iter().map(|p| p.contact_range).fold(0.0, f32::max);
        let collision = params.iter().map(|p| p.collision_range).fold(0.0, f32::max);
        let mut world = AntWorld::new(min, max, contact, collision);
        world.objects = scenario
            .objects
            .iter()
            .enumerate()
            .filter_map(|(id, o)| object_def(id as u16, &o.name, &o.kind, o.active))
            .collect();
        world.set_route();

        let groups = crate::spawn::groups(scenario, params, |g, p, first| {
            let nest = g
                .nest
                .as_deref()
                .and_then(|n| scenario.object_id(n))
                .ok_or_else(|| SimError::NoObject {
                    group: g.name.clone(),
                    what: "nest",
                    name: g.nest.clone().unwrap_or_default(),
                })?;
            Ok::<AnyAntGroup, SimError>(match g.scalar {
                ScalarType::F32 => spawn::<f32>(scenario, g, p, nest, first, seed)?.into(),
                ScalarType::Fixed => spawn::<Fx>(scenario, g, p, nest, first, seed)?.into(),
            })
        })?;
        Ok(AntSim::new(world, groups, seed))
    }

    /// Applies a timed event of the scenario (`Action` on the object with id `object`).
    pub fn apply(&mut self, object: u16, action: &Action) {
        let Some(o) = self.world.objects.iter_mut().find(|o| o.id == object) else {
            return;
        };
        match action {
            Action::Add(_) | Action::Start(_) => o.active = true,
            Action::Remove(_) | Action::Stop(_) => o.active = false,
            Action::Move { to, .. } => {
                if let (Shape2::Circle { center, .. }, [x, y]) = (&mut o.shape, to.as_slice()) {
                    *center = [*x, *y];
                }
            }
        }
        // An obstacle put on top of ants pushes them out (counted in `moved_out`).
        if o.kind == AntObjectKind::Obstacle && o.active {
            self.move_out_of_obstacles();
        }
    }
}

/// The engine's view of a scenario object (`None` for 3D kinds).
fn object_def(id: u16, name: &str, kind: &ObjectKind, active: bool) -> Option<AntObjectDef> {
    let circle = |center: [f32; 2], radius: f32| Shape2::Circle { center, radius };
    let (kind, shape) = match kind {
        ObjectKind::Nest { center, radius } => (AntObjectKind::Nest, circle(*center, *radius)),
        ObjectKind::Food {
            center,
            radius,
            amount,
        } => (
            AntObjectKind::Food { amount: *amount },
            circle(*center, *radius),
        ),
        // Way points (xiang Fig. 14): legs of the route, see `AntWorld::target_of`.
        ObjectKind::Waypoint {
            center,
            radius,
            order,
        } => (
            AntObjectKind::Waypoint { order: *order },
            circle(*center, *radius),
        ),
        ObjectKind::Rock { center, radius } => (AntObjectKind::Obstacle, circle(*center, *radius)),
        ObjectKind::Polygon { points } => (
            AntObjectKind::Obstacle,
            Shape2::Polygon {
                points: points.clone(),
            },
        ),
        ObjectKind::Disturbance { center, radius } => {
            (AntObjectKind::Disturbance, circle(*center, *radius))
        }
        _ => return None,
    };
    Some(AntObjectDef {
        id,
        name: name.to_string(),
        kind,
        shape,
        active,
    })
}

/// The ants of group `g`, ids `first..`, spawned uniformly in its region with the scenario's
/// counter-based random numbers. Ants spawned around their own nest start labelled S_nest (they
/// leave the nest, xiang §4); elsewhere S_nothing.
fn spawn<S: SimScalar>(
    scenario: &Scenario,
    g: &Group,
    params: AntParams<f32>,
    nest: u16,
    first: usize,
    seed: u32,
) -> Result<AntGroup<S>> {
    let params = params
        .cast::<S>()
        .checked()
        .map_err(|source| SimError::GroupParams {
            group: g.name.clone(),
            source,
        })?;
    let at_nest = matches!(&g.spawn.region, SpawnRegion::Around { at, .. }
        if g.nest.as_deref() == Some(at.as_str()));
    let states = (0..g.count)
        .map(|k| {
            let id = (first + k as usize) as u32;
            let u = |k| draw(seed, id, k);
            let pos = match &g.spawn.region {
                SpawnRegion::Around { at, radius } => {
                    let c: [f32; 2] = around_center(scenario, at);
                    let (r, a) = (radius * u(0).sqrt(), u(1) * std::f32::consts::TAU);
                    [c[0] + r * a.cos(), c[1] + r * a.sin()]
                }
                SpawnRegion::Box { min, max } => [
                    min[0] + (max[0] - min[0]) * u(0),
                    min[1] + (max[1] - min[1]) * u(1),
                ],
            };
            let heading = match g.spawn.heading.as_deref() {
                Some([x, y]) => [*x, *y],
                _ => {
                    let a = u(2) * std::f32::consts::TAU;
                    [a.cos(), a.sin()]
                }
            };
            let (p, h) = (
                Vec2::<S>::from_f32(pos[0], pos[1]),
                Vec2::from_f32(heading[0], heading[1]),
            );
            if at_nest {
                // Spawned around its nest, it has just left it: its latest arrival at the nest
                // (where it heads when laden) is the nest's centre, inside the nest even when
                // the spawn area is wider than the nest.
                let c: [f32; 2] = around_center(scenario, g.nest.as_deref().unwrap_or_default());
                AntState {
                    arrival: Vec2::from_f32(c[0], c[1]),
                    ..AntState::at_nest(nest, p, h)
                }
            } else {
                AntState::exploring(nest, p, h)
            }
        })
        .collect();
    Ok(AntGroup::new(g.name.clone(), first, params, states))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ants::AntEvent;

    #[test]
    fn every_builtin_ant_scenario_builds_and_runs() {
        for name in crate::scenario::builtin_names()
            .iter()
            .filter(|n| n.starts_with("ants"))
        {
            let sc = crate::scenario::builtin(name).unwrap();
            let mut sim = AntSim::from_scenario(&sc, sc.seed).unwrap();
            assert_eq!(sim.agents() as u64, sc.agent_count(), "{name}");
            for _ in 0..20 {
                sim.step().unwrap_or_else(|e| panic!("{name}: {e}"));
            }
        }
    }

    #[test]
    fn fig7a_colony_delivers_food() {
        let sc = crate::scenario::builtin("ants-fig7a-single-colony").unwrap();
        let mut sim = AntSim::from_scenario(&sc, sc.seed).unwrap();
        let mut delivered = 0;
        for _ in 0..2000 {
            delivered += sim
                .step()
                .unwrap()
                .iter()
                .filter(|e| matches!(e, AntEvent::Delivered { .. }))
                .count();
        }
        assert!(delivered > 0, "no food delivered in 2000 ticks");
    }
}
