//! The ant bench world of `swarm bench`.

use swarm_core::ant::{AntParams, AntState};
use swarm_core::{Fx, Vec2};

use super::{AntGroup, AntObjectDef, AntObjectKind, AntSim, AntWorld, AnyAntGroup, Shape2};
use crate::scalar::SimScalar;
use crate::scenario::ScalarType;

/// Ants per unit² in the bench world (the density of xiang2018's 500-ant scenes).
const DENSITY: f32 = 0.02;

/// A square world holding `n` ants spread uniformly (density `DENSITY`), with a nest and
/// food sources and a rock, so every kind of interaction happens somewhere; the ants compute
/// in `scalar`.
pub fn bench_ant_world(n: usize, seed: u32, scalar: ScalarType) -> AntSim {
    match scalar {
        ScalarType::F32 => world::<f32>(n, seed),
        ScalarType::Fixed => world::<Fx>(n, seed),
    }
}

fn world<S: SimScalar>(n: usize, seed: u32) -> AntSim
where
    AnyAntGroup: From<AntGroup<S>>,
{
    let params = AntParams::<f32>::default();
    let side = ((n.max(1) as f32) / DENSITY).sqrt().clamp(50.0, 16_000.0);
    let mut w = AntWorld::new(
        [0.0, 0.0],
        [side, side],
        params.contact_range,
        params.collision_range,
    );
    let c = side / 2.0;
    let obj = |id, kind, center, radius| AntObjectDef {
        id,
        name: format!("object-{id}"),
        kind,
        shape: Shape2::Circle { center, radius },
        active: true,
    };
    w.objects = vec![
        obj(0, AntObjectKind::Nest, [c, c], 5.0),
        obj(
            1,
            AntObjectKind::Food { amount: None },
            [c + side / 4.0, c],
            5.0,
        ),
        obj(
            2,
            AntObjectKind::Food { amount: None },
            [c - side / 4.0, c],
            5.0,
        ),
        obj(3, AntObjectKind::Obstacle, [c, c + side / 4.0], 8.0),
    ];
    let states = (0..n as u32)
        .map(|i| {
            let r = |k| swarm_core::rand::rand(seed, i, u32::MAX, k) as f32 / u32::MAX as f32;
            let pos = Vec2::from_f32(r(0) * side, r(1) * side);
            let a = r(2) * std::f32::consts::TAU;
            AntState::exploring(0, pos, Vec2::from_f32(a.cos(), a.sin()))
        })
        .collect();
    let params = AntParams::<S>::default()
        .checked()
        .expect("default parameters are valid");
    AntSim::new(
        w,
        vec![AntGroup::new("bench".into(), 0, params, states).into()],
        seed,
    )
}
