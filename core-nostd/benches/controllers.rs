//! Criterion benches of the inner kernels: one ant `plan` + `resolve` with 8 neighbours and
//! one bee `step` with 16 neighbours, in f32 and I16F16.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use swarm_core::ant::{
    self, AntNeighbor, AntObject, AntParams, AntState, Label, PlanFrame, ResolveFrame,
};
use swarm_core::bee::{self, BeeFrame, BeeNeighbor, BeeParams, BeeState, ObstacleSense};
use swarm_core::{Fx, Rect, Scalar, StepCtx, Vec2, Vec3};

fn ant_inputs<S: Scalar>() -> (AntState<S>, PlanFrame<S, 8, 4>, ResolveFrame<S, 8>) {
    let v = Vec2::<S>::from_f32;
    let bounds = Rect::new(v(0.0, 0.0), v(100.0, 100.0));
    let state = AntState::at_nest(0, v(50.0, 50.0), v(0.6, 0.8));
    let mut plan = PlanFrame::new(bounds);
    let mut resolve = ResolveFrame::new(bounds);
    for i in 0..8u32 {
        let a = i as f32 * std::f32::consts::FRAC_PI_4;
        let p = v(50.0 + 1.5 * a.cos(), 50.0 + 1.5 * a.sin());
        let _ = plan.neighbours.push(AntNeighbor {
            id: 10 + i,
            pos: p,
            label: if i % 3 == 0 { Label::Food } else { Label::Nest },
            nest: 0,
            origin: if i % 3 == 0 { 1 } else { 0 },
            arrival: v(80.0, 20.0),
        });
        let _ = resolve
            .neighbours
            .push(v(50.6 + 1.2 * a.cos(), 50.8 + 1.2 * a.sin()));
    }
    let _ = plan.objects.push(AntObject::Food {
        id: 1,
        center: v(80.0, 20.0),
        radius: S::from_f32(3.0),
    });
    (state, plan, resolve)
}

fn bench_ant<S: Scalar>(c: &mut Criterion, name: &str) {
    let params = AntParams::<S>::default();
    let (state, pf, rf) = ant_inputs::<S>();
    let mut step = 0u32;
    c.bench_function(name, |b| {
        b.iter(|| {
            step = step.wrapping_add(1);
            let ctx = StepCtx {
                seed: 1,
                agent: 0,
                step,
            };
            let plan = ant::plan(black_box(&state), black_box(&pf), &params, ctx).unwrap();
            ant::resolve(&plan, black_box(&rf), &params).unwrap()
        })
    });
}

fn bee_inputs<S: Scalar>() -> (BeeState<S>, BeeFrame<S, 16, 8>) {
    let v = Vec3::<S>::from_f32;
    let state = BeeState::new(v(0.0, 2.0, 0.0), v(1.0, 0.0, 0.2));
    let mut frame = BeeFrame::new(S::from_f32(3.5));
    for i in 0..16u32 {
        let a = i as f32 * std::f32::consts::FRAC_PI_8;
        let _ = frame.neighbours.push(BeeNeighbor {
            pos: v(
                1.2 * a.cos(),
                2.0 + 0.3 * (i as f32 - 8.0) / 8.0,
                1.2 * a.sin(),
            ),
            vel: v(0.5, 0.0, 0.1),
            density: S::from_f32(0.05),
        });
    }
    frame.obstacle = Some(ObstacleSense {
        point: v(1.5, 2.0, 0.3),
        normal: v(-1.0, 0.0, 0.0),
    });
    (state, frame)
}

fn bench_bee<S: Scalar>(c: &mut Criterion, name: &str) {
    let params = BeeParams::<S>::default();
    let (state, frame) = bee_inputs::<S>();
    c.bench_function(name, |b| {
        b.iter(|| bee::step(black_box(&state), black_box(&frame), &params).unwrap())
    });
}

fn benches(c: &mut Criterion) {
    bench_ant::<f32>(c, "ant plan+resolve, 8 neighbours, f32");
    bench_ant::<Fx>(c, "ant plan+resolve, 8 neighbours, I16F16");
    bench_bee::<f32>(c, "bee step, 16 neighbours, f32");
    bench_bee::<Fx>(c, "bee step, 16 neighbours, I16F16");
}

criterion_group!(controllers, benches);
criterion_main!(controllers);
