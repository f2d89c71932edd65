// What a bee senses of the world (host-sim/src/gpu/shaders.rs, BEE_SENSE): the sensor frame of
// host-sim/src/bees/sense.rs (`bee_frame`, `fill_with`, the selection `select` / `Selected`),
// function by function, over the scalar `S`, with the obstacle geometry of bee_world.wgsl: in
// fixed point every key, distance, closest point and normal is the CPU's bit for bit, so the
// same neighbours, target particles and obstacle enter the frame.
//
// The sensed bees are struct-of-arrays words (host-sim/src/gpu/bee/world.rs, `sensed_words`):
// positions, velocities, densities, ids, each an array over the bees; what each frame takes
// besides the world (its time and its group's goal) two more arrays (`input_words`). The
// neighbour candidates come from the GPU grid (`GpuGrid`'s `starts` and `order` over the cells
// of bee_world.wgsl's `bee_world_cell` of the sensed positions), the particles from the
// particles' grid in the world's words: a query visits the rows of cells between the cells of
// `p - r` and `p + r` (`r` the range plus the grid's margin), a superset of the points in range,
// which the exact keys then select from, as the CPU's grid query is.
//
// Bindings (group 0): 0 the parameters, 1 the world (bee_world.wgsl), 2 the sensed bees, 3 the
// frames' inputs, 4 and 5 the grid's `starts` and `order`; a kernel writes its results to
// binding 6. Loops per invocation (lavapipe stops an invocation's loop, its nested loops and the
// loops of the functions it calls counted with it, after 65,535 iterations): a query runs an
// iteration per candidate and at most sixteen more per candidate kept.

// The parameters of a sensing dispatch: the number of bees.
struct BeeSenseParams {
    n: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

@group(0) @binding(0) var<uniform> bee_sense_params: BeeSenseParams;
@group(0) @binding(2) var<storage, read> bee_sensed: array<u32>;
@group(0) @binding(3) var<storage, read> bee_sense_inputs: array<u32>;
@group(0) @binding(4) var<storage, read> bee_grid_starts: array<u32>;
@group(0) @binding(5) var<storage, read> bee_grid_order: array<u32>;

// Where the sensed bees' arrays start, in multiples of the bee count (world.rs, SENSED_*).
const BEE_SENSED_POS: u32 = 0u;
const BEE_SENSED_VEL: u32 = 3u;
const BEE_SENSED_DENSITY: u32 = 6u;
const BEE_SENSED_ID: u32 = 7u;
// Where the inputs' arrays start, in multiples of the bee count (world.rs, INPUT_*).
const BEE_INPUT_T: u32 = 0u;
const BEE_INPUT_GOAL: u32 = 1u;

// ---- the sensed bees and the inputs ----

fn bee_sensed_v3(at: u32) -> vec3<S> {
    return vec3<S>(
        s_from_word(bee_sensed[at]),
        s_from_word(bee_sensed[at + 1u]),
        s_from_word(bee_sensed[at + 2u]),
    );
}

// The sensed position of the bee in slot j (`v3` of sense.rs).
fn bee_sensed_pos(j: u32) -> vec3<S> {
    return bee_sensed_v3(BEE_SENSED_POS * bee_sense_params.n + 3u * j);
}

fn bee_sensed_vel(j: u32) -> vec3<S> {
    return bee_sensed_v3(BEE_SENSED_VEL * bee_sense_params.n + 3u * j);
}

fn bee_sensed_density(j: u32) -> S {
    return s_from_word(bee_sensed[BEE_SENSED_DENSITY * bee_sense_params.n + j]);
}

// The stable id of the bee in slot j.
fn bee_sensed_id(j: u32) -> u32 {
    return bee_sensed[BEE_SENSED_ID * bee_sense_params.n + j];
}

// The frame time of bee i.
fn bee_input_t(i: u32) -> S {
    return s_from_word(bee_sense_inputs[BEE_INPUT_T * bee_sense_params.n + i]);
}

// The object id of the target of bee i's group (BEE_WORLD_NO_GOAL for none).
fn bee_input_goal(i: u32) -> u32 {
    return bee_sense_inputs[BEE_INPUT_GOAL * bee_sense_params.n + i];
}

// ---- Selected (sense.rs) ----

// The `cap` (at most 16) smallest (key, tie) pairs offered, in increasing order, each with its
// slot: sense.rs's `Selected<K>` for K = cap (its keys are the squared distance's order bits,
// then the tie: the order of the values, for squared distances are never negative).
struct BeeSenseSelected {
    keys: array<S, 16>,
    ties: array<u32, 16>,
    slots: array<u32, 16>,
    len: u32,
}

// Whether (ka, ta) comes before (kb, tb): by key, then by tie.
fn bee_sense_less(ka: S, ta: u32, kb: S, tb: u32) -> bool {
    return ka < kb || (ka == kb && ta < tb);
}

// Offers a candidate: an insertion, the last one dropped when full (Selected::merge keeps the
// `K` smallest keys whatever the order the candidates come in; so does this).
fn bee_sense_offer(near: ptr<function, BeeSenseSelected>, cap: u32, key: S, tie: u32, slot: u32) {
    if ((*near).len == cap) {
        let last = cap - 1u;
        if (!bee_sense_less(key, tie, (*near).keys[last], (*near).ties[last])) {
            return;
        }
        (*near).len = (*near).len - 1u;
    }
    var k = (*near).len;
    while (k > 0u && bee_sense_less(key, tie, (*near).keys[k - 1u], (*near).ties[k - 1u])) {
        (*near).keys[k] = (*near).keys[k - 1u];
        (*near).ties[k] = (*near).ties[k - 1u];
        (*near).slots[k] = (*near).slots[k - 1u];
        k = k - 1u;
    }
    (*near).keys[k] = key;
    (*near).ties[k] = tie;
    (*near).slots[k] = slot;
    (*near).len = (*near).len + 1u;
}

// The cells a query of radius `r` around p visits in grid `g`: x, y and z from `lo` to `hi`.
struct BeeSenseQuery {
    lo: vec3<u32>,
    hi: vec3<u32>,
}

fn bee_sense_query(g: BeeWorldGrid, p: vec3<S>, r: S) -> BeeSenseQuery {
    let rr = vec3<S>(r, r, r);
    return BeeSenseQuery(
        bee_world_cell_xyz(g, geom_vec3_sub(p, rr)),
        bee_world_cell_xyz(g, geom_vec3_add(p, rr)),
    );
}

// neighbours (sense.rs): the BEE_NEIGHBOURS bees nearest to slot i (at `me`) strictly within
// the neighbour range (squared distance in S below the range squared), nearest first, ties by
// stable id: the same bees whatever the slot order.
fn bee_sense_neighbours(i: u32, me: vec3<S>) -> BeeSenseSelected {
    let g = bee_world_grid(BEE_WORLD_H_GRID);
    let r2 = bee_world_s(BEE_WORLD_H_RANGE2);
    let q = bee_sense_query(g, me, s_add(bee_world_s(BEE_WORLD_H_RANGE), g.margin));
    var near: BeeSenseSelected;
    for (var z = q.lo.z; z <= q.hi.z; z = z + 1u) {
        for (var y = q.lo.y; y <= q.hi.y; y = y + 1u) {
            let row = bee_world_cell_key(g, vec3<u32>(q.lo.x, y, z));
            let end = bee_grid_starts[row + q.hi.x - q.lo.x + 1u];
            for (var s = bee_grid_starts[row]; s < end; s = s + 1u) {
                let j = bee_grid_order[s];
                if (j == i) {
                    continue;
                }
                let d = geom_vec3_length_sq(geom_vec3_sub(bee_sensed_pos(j), me));
                if (d < r2) {
                    bee_sense_offer(&near, BEE_NEIGHBOURS, d, bee_sensed_id(j), j);
                }
            }
        }
    }
    return near;
}

// fill_with's target particles: the BEE_TARGETS particles of the active targets nearest to
// `me` strictly within the neighbour range, nearest first, ties by particle index; their
// places in the particles' grid. (The CPU queries only near a target's sphere, on which the
// particles lie: a test in f32 that only narrows, not made here.)
fn bee_sense_particles(me: vec3<S>) -> BeeSenseSelected {
    let g = bee_world_grid(BEE_WORLD_H_PARTICLE_GRID);
    let r2 = bee_world_s(BEE_WORLD_H_RANGE2);
    var near: BeeSenseSelected;
    if (bee_world_particles() == 0u) {
        return near;
    }
    let q = bee_sense_query(g, me, s_add(bee_world_s(BEE_WORLD_H_RANGE), g.margin));
    for (var z = q.lo.z; z <= q.hi.z; z = z + 1u) {
        for (var y = q.lo.y; y <= q.hi.y; y = y + 1u) {
            let row = bee_world_cell_key(g, vec3<u32>(q.lo.x, y, z));
            let end = bee_world_particle_start(row + q.hi.x - q.lo.x + 1u);
            for (var s = bee_world_particle_start(row); s < end; s = s + 1u) {
                let d = geom_vec3_length_sq(geom_vec3_sub(bee_world_particle(s), me));
                if (d < r2) {
                    bee_sense_offer(&near, BEE_TARGETS, d, bee_world_particle_index(s), s);
                }
            }
        }
    }
    return near;
}

// The nearest obstacle sensed, if any.
struct BeeSenseObstacle {
    found: bool,
    sense: BeeObstacleSense,
}

// fill_with's obstacle: the nearest active obstacle within the sensing range 2·d0 (a bee inside
// an obstacle is at distance 0; ties by obstacle order): its closest surface point and outward
// unit normal. (The CPU skips an obstacle whose bounding box is beyond the range and a margin,
// in f64; bee_world_near does the same in S with the grid's margin: neither can skip one
// within the range.)
fn bee_sense_obstacle(me: vec3<S>) -> BeeSenseObstacle {
    let range = bee_world_s(BEE_WORLD_H_SENSE);
    let reach = s_add(range, bee_world_s(BEE_WORLD_H_GRID + BEE_WORLD_G_MARGIN));
    var best = BeeSenseObstacle(false, BeeObstacleSense(vec3<S>(), vec3<S>()));
    var best_dist = S_ZERO;
    for (var k = 0u; k < bee_world_obstacles(); k = k + 1u) {
        let o = bee_world_obstacle(k);
        if (!o.present || !bee_world_near(o, me, reach)) {
            continue;
        }
        let surf = bee_world_surface(o, me);
        var dist = surf.distance;
        if (surf.inside) {
            dist = S_ZERO;
        }
        if (dist <= range && (!best.found || dist < best_dist)) {
            best_dist = dist;
            best = BeeSenseObstacle(true, BeeObstacleSense(surf.point, surf.normal));
        }
    }
    return best;
}

// bee_frame: the sensor frame of the bee in slot i at time `t`, its group flying to the target
// of object id `goal` (BEE_WORLD_NO_GOAL for none):
//
// * `neighbours`: the BEE_NEIGHBOURS nearest bees within h + 2r (strictly), by distance then
//   stable id, with the position, velocity and density they broadcast;
// * `targets`: the BEE_TARGETS nearest virtual particles of the active targets within the same
//   range (by distance, then particle index);
// * `goal`: the centre of the group's target while it is active;
// * `obstacle`: the nearest active obstacle within the sensing range 2·d0.
//
// The entries past a list's length are zero, as is an absent goal's or obstacle's value.
fn bee_sense_frame(i: u32, goal: u32, t: S) -> BeeFrame {
    var f: BeeFrame;
    f.t = t;
    let me = bee_sensed_pos(i);
    let near = bee_sense_neighbours(i, me);
    f.neighbours_len = near.len;
    for (var k = 0u; k < near.len; k = k + 1u) {
        let j = near.slots[k];
        f.neighbours[k] = BeeNeighbor(bee_sensed_pos(j), bee_sensed_vel(j), bee_sensed_density(j));
    }
    let particles = bee_sense_particles(me);
    f.targets_len = particles.len;
    for (var k = 0u; k < particles.len; k = k + 1u) {
        f.targets[k] = bee_world_particle(particles.slots[k]);
    }
    let g = bee_world_target_center(goal);
    f.has_goal = g.is_some;
    f.goal = g.value;
    let o = bee_sense_obstacle(me);
    f.has_obstacle = o.found;
    f.obstacle = o.sense;
    return f;
}
