// The obstacle surfaces of a 3D insect's frame (host-sim/src/gpu/shaders.rs, FLY_SURFACES):
// `World3d::surfaces` (host-sim/src/swarm3d/world.rs) over the scalar `S`, on the bee world's
// words (bee_world.wgsl), into a FlyFrame (fly_step.wgsl). The ren2016 tick (fly_tick.wgsl) and
// the li2015 tick (li_tick.wgsl) sense the same surfaces.

// Nearest::offer (world.rs): keeps the FLY_SURFACES nearest surfaces offered, nearest first, the
// earlier offer first on ties.
fn fly_offer(f: ptr<function, FlyFrame>, keys: ptr<function, array<S, 4>>, d: S, s: FlySurface) {
    let len = (*f).surfaces_len;
    var at = len;
    for (var k = 0u; k < len; k = k + 1u) {
        if (d < (*keys)[k]) {
            at = k;
            break;
        }
    }
    if (at >= FLY_SURFACES) {
        return;
    }
    var last = len;
    if (len == FLY_SURFACES) {
        last = len - 1u;
    }
    for (var k = last; k > at; k = k - 1u) {
        (*keys)[k] = (*keys)[k - 1u];
        (*f).surfaces[k] = (*f).surfaces[k - 1u];
    }
    (*keys)[at] = d;
    (*f).surfaces[at] = s;
    (*f).surfaces_len = last + 1u;
}

// FlyWorld::surfaces: the closest point and outward normal of every active obstacle (distance 0
// inside) and every container wall (inward normal; walls −x, +x, −y, +y, −z, +z) nearer than
// `reach`, nearest first, at most FLY_SURFACES. (The CPU skips obstacles whose bounding box is
// beyond the world's reach in f64: none of them could be nearer than `reach`.)
fn fly_surfaces_sense(f: ptr<function, FlyFrame>, p: vec3<S>, reach: S) {
    var keys: array<S, 4>;
    for (var k = 0u; k < bee_world_obstacles(); k = k + 1u) {
        let o = bee_world_obstacle(k);
        if (!o.present) {
            continue;
        }
        let s = bee_world_surface(o, p);
        let d = select(s.distance, S_ZERO, s.inside);
        if (d < reach) {
            fly_offer(f, &keys, d, FlySurface(s.point, s.normal));
        }
    }
    let lo = bee_world_min();
    let hi = bee_world_max();
    for (var k = 0u; k < 3u; k = k + 1u) {
        for (var side = 0u; side < 2u; side = side + 1u) {
            let w = select(lo[k], hi[k], side == 1u);
            let sign = select(S_ONE, s_neg(S_ONE), side == 1u);
            let d = s_max(s_mul(s_sub(p[k], w), sign), S_ZERO);
            if (d < reach) {
                var point = p;
                point[k] = w;
                // `with_axis(Vec3::zero(), k, sign)`, each component chosen (bee_world.wgsl).
                let normal = vec3<S>(select(S_ZERO, sign, k == 0u), select(S_ZERO, sign, k == 1u),
                                     select(S_ZERO, sign, k == 2u));
                fly_offer(f, &keys, d, FlySurface(point, normal));
            }
        }
    }
}
