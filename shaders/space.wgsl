// The world's corrections of a new state (host-sim/src/gpu/shaders.rs, SPACE):
// host-sim/src/space.rs's `confine` over the scalar `S`, on the obstacles of bee_world.wgsl,
// shared by the 3D models' GPU engines (bees, wang2014).
//
// Binding (group 0): 15 the obstacles' confinement boxes (host-sim/src/gpu/space.rs,
// `confine_boxes`).

@group(0) @binding(15) var<storage, read> space_boxes: array<u32>;

// Words of an obstacle's confinement box (space.rs, BOX_WORDS): whether no point of S passes
// (`never`), then per axis the least value of S at or above the bounding box's low side less
// 1e-3 (in f64) and the greatest at or below its high side plus 1e-3.
const SPACE_BOX_WORDS: u32 = 7u;

// BeeObstacle::may_be_within(p, 0.0) (space.rs) of obstacle `k`: p within the bounding box
// widened by 1e-3 on every axis, compared in f64 on the CPU. A value of S converts to f64
// exactly, so `p ≥ lo - 1e-3` holds exactly when p ≥ the least S at or above `lo - 1e-3`
// (computed on the host in f64, gpu/space.rs `confine_boxes`), and likewise above: the same
// test, in S.
fn space_may_be_within(k: u32, p: vec3<S>) -> bool {
    let b = k * SPACE_BOX_WORDS;
    if (space_boxes[b] != 0u) {
        return false;
    }
    let lo = vec3<S>(s_from_word(space_boxes[b + 1u]), s_from_word(space_boxes[b + 2u]),
                     s_from_word(space_boxes[b + 3u]));
    let hi = vec3<S>(s_from_word(space_boxes[b + 4u]), s_from_word(space_boxes[b + 5u]),
                     s_from_word(space_boxes[b + 6u]));
    return all(p >= lo) && all(p <= hi);
}

// confine (space.rs): keeps a new position and velocity physical, in the agent's scalar: out of
// every active obstacle it is inside (put back on the surface, `offset` along the outward
// normal, the inward normal velocity removed) and inside the bounds (clamped, the outward
// velocity removed), at most four rounds, until a round moves nothing. Returns what was
// corrected: bit 0 an obstacle, bit 1 the bounds (`p` and `v` change only if something was).
fn space_confine(pos: ptr<function, vec3<S>>, vel: ptr<function, vec3<S>>, offset: S) -> u32 {
    var p = *pos;
    var v = *vel;
    let lo = bee_world_min();
    let hi = bee_world_max();
    var flags = 0u;
    for (var round = 0u; round < 4u; round = round + 1u) {
        var moved = false;
        for (var k = 0u; k < bee_world_obstacles(); k = k + 1u) {
            let o = bee_world_obstacle(k);
            if (!o.present || !space_may_be_within(k, p)) {
                continue;
            }
            let surf = bee_world_surface(o, p);
            if (!surf.inside) {
                continue;
            }
            let n = surf.normal;
            p = geom_vec3_add(surf.point, geom_vec3_mul(n, offset));
            let vn = geom_vec3_dot(v, n);
            if (vn < S_ZERO) {
                v = geom_vec3_sub(v, geom_vec3_mul(n, vn));
            }
            flags = flags | 1u;
            moved = true;
        }
        for (var k = 0u; k < 3u; k = k + 1u) {
            let x = p[k];
            if (x < lo[k]) {
                p[k] = lo[k];
                v[k] = s_max(v[k], S_ZERO);
                flags = flags | 2u;
                moved = true;
            } else if (x > hi[k]) {
                p[k] = hi[k];
                v[k] = s_min(v[k], S_ZERO);
                flags = flags | 2u;
                moved = true;
            }
        }
        if (!moved) {
            break;
        }
    }
    if (flags != 0u) {
        *pos = p;
        *vel = v;
    }
    return flags;
}
