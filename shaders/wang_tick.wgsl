// The wang2014 tick of the GPU engine (host-sim/src/gpu/shaders.rs, WANG_TICK;
// host-sim/src/gpu/wang/engine.rs drives it): host-sim/src/wang/sim.rs's phases, one thread per
// insect, over the scalar `S`, the states staying on the GPU between ticks. A tick is
//
// 1. `wang_tick_advect_main`: the advect frame (the navigation direction of the group's cost
//    field, `CostField::guide_at`; the nearest boundary, `WangWorld::boundary`; the lamp), then
//    `wang_advect_checked`; the reply kept (what the mirror compares), then the world's
//    corrections (`space_confine`) give x*, counted, and its cell in the MDE grid;
// 2. the grid of the x* (`GpuGrid`);
// 3. `wang_tick_separate_main`: the separate frame (the WANG_NEIGHBOURS nearest x* strictly
//    within the group's d_min, nearest first, ties by id: `WangGroup::separate_frame`), then
//    `wang_separate_checked`, the insects pushed counted;
// 4. `wang_tick_commit_main`: the world's corrections of x_{k+1}, counted, made current;
//    the refused insect's thread keeps the tick's first refusal.
//
// Bindings (group 0), besides the world (1, bee_world.wgsl), the grid's `starts` and `order`
// (4, 5, bee_sense.wgsl) and the confinement boxes (15, space.wgsl): 6 the cells of the x*,
// 7 the tick's parameters, 8 the states, 9 the advect replies, 10 the x* after the world's
// corrections, 11 the separate replies, 12 the groups' words, 13 each slot's group and id,
// 14 the tick's atomics, 16 the cost fields, 17 each slot's flags (corrections, pushes),
// 18 each slot's status words (advect, separate).

struct WangTickParams {
    n: u32,
    step: u32,
    seed: u32,
    // SURFACE_OFFSET (space.rs) in S, as `confine` converts it.
    offset: u32,
}

@group(0) @binding(6) var<storage, read_write> wang_cells: array<u32>;
@group(0) @binding(7) var<uniform> wang_tick: WangTickParams;
@group(0) @binding(8) var<storage, read_write> wang_states: array<u32>;
@group(0) @binding(9) var<storage, read_write> wang_moved: array<u32>;
@group(0) @binding(10) var<storage, read_write> wang_placed: array<u32>;
@group(0) @binding(11) var<storage, read_write> wang_next: array<u32>;
@group(0) @binding(12) var<storage, read> wang_groups: array<u32>;
@group(0) @binding(13) var<storage, read> wang_slots: array<u32>;
@group(0) @binding(14) var<storage, read_write> wang_shared: array<atomic<u32>>;
@group(0) @binding(16) var<storage, read> wang_fields: array<u32>;
@group(0) @binding(17) var<storage, read_write> wang_flags: array<u32>;
@group(0) @binding(18) var<storage, read_write> wang_status: array<u32>;

// Words of a state (position, velocity).
const WANG_STATE_WORDS: u32 = 6u;

// A group's words (host-sim/src/gpu/wang/layout.rs, GROUP_*): the parameters in S (scale, gain,
// s0, dt, d0, d_min, p_photo, u_photo), the noise source, the word where its goal's field
// starts (WANG_NO_FIELD: none), whether it has a lamp and where, d_min squared in S.
const WANG_GROUP_WORDS: u32 = 16u;
const WANG_GROUP_NOISE: u32 = 8u;
const WANG_GROUP_FIELD: u32 = 9u;
const WANG_GROUP_HAS_LAMP: u32 = 10u;
const WANG_GROUP_LAMP: u32 = 11u;
const WANG_GROUP_RANGE2: u32 = 14u;
const WANG_NO_FIELD: u32 = 0xffffffffu;

// A field's header (layout.rs, FIELD_*): cells along x, y, z; the grid's lower corner and cell
// (f32 bits, converted here as `guide_at` converts them); where its cell records start (a word
// a cell, `GuideCell`: the guide's x, y, z as i8 in bits 0-23, the goal flag in bit 24); the
// guides' scale (f32 bits: a component q stands for f32(q)·scale).
const WANG_FIELD_DIMS: u32 = 0u;
const WANG_FIELD_MIN: u32 = 3u;
const WANG_FIELD_CELL: u32 = 6u;
const WANG_FIELD_CELLS: u32 = 7u;
const WANG_FIELD_SCALE: u32 = 8u;

// The words of `wang_shared` (engine.rs, SHARED_*): this tick's refusals (0xffffffff − the lowest
// id refused, 0 for none; advect, separate), corrections (obstacle, bounds) and insects pushed,
// cleared by the host every tick; the first refusal kept (a flag, its step, the insect's id, phase and
// status word); the corrections and pushes since the start, each a u64 as two words.
const WANG_SHARED_REFUSED: u32 = 0u;
const WANG_SHARED_OBSTACLE: u32 = 2u;
const WANG_SHARED_BOUNDS: u32 = 3u;
const WANG_SHARED_PUSHED: u32 = 4u;
const WANG_SHARED_KEPT: u32 = 5u;
const WANG_SHARED_KEPT_STEP: u32 = 6u;
const WANG_SHARED_KEPT_ID: u32 = 7u;
const WANG_SHARED_KEPT_PHASE: u32 = 8u;
const WANG_SHARED_KEPT_STATUS: u32 = 9u;
const WANG_SHARED_TOTAL_OBSTACLE: u32 = 10u;
const WANG_SHARED_TOTAL_BOUNDS: u32 = 12u;
const WANG_SHARED_TOTAL_PUSHED: u32 = 14u;

// ---- the buffers' values ----

fn wang_state_at(w: array<u32, 6>) -> WangState {
    return WangState(
        vec3<S>(s_from_word(w[0]), s_from_word(w[1]), s_from_word(w[2])),
        vec3<S>(s_from_word(w[3]), s_from_word(w[4]), s_from_word(w[5])),
    );
}

fn wang_state_words(s: WangState) -> array<u32, 6> {
    return array<u32, 6>(
        s_to_word(s.pos.x), s_to_word(s.pos.y), s_to_word(s.pos.z),
        s_to_word(s.vel.x), s_to_word(s.vel.y), s_to_word(s.vel.z),
    );
}

fn wang_tick_state(i: u32) -> WangState {
    var w: array<u32, 6>;
    for (var k = 0u; k < WANG_STATE_WORDS; k = k + 1u) {
        w[k] = wang_states[i * WANG_STATE_WORDS + k];
    }
    return wang_state_at(w);
}

fn wang_tick_placed(i: u32) -> WangState {
    var w: array<u32, 6>;
    for (var k = 0u; k < WANG_STATE_WORDS; k = k + 1u) {
        w[k] = wang_placed[i * WANG_STATE_WORDS + k];
    }
    return wang_state_at(w);
}

fn wang_tick_placed_pos(i: u32) -> vec3<S> {
    let b = i * WANG_STATE_WORDS;
    return vec3<S>(s_from_word(wang_placed[b]), s_from_word(wang_placed[b + 1u]),
                   s_from_word(wang_placed[b + 2u]));
}

fn wang_tick_next(i: u32) -> WangState {
    var w: array<u32, 6>;
    for (var k = 0u; k < WANG_STATE_WORDS; k = k + 1u) {
        w[k] = wang_next[i * WANG_STATE_WORDS + k];
    }
    return wang_state_at(w);
}

fn wang_group_s(g: u32, k: u32) -> S {
    return s_from_word(wang_groups[g * WANG_GROUP_WORDS + k]);
}

// The parameters of group g (validated on the host: `Checked`).
fn wang_group_params(g: u32) -> WangParams {
    return WangParams(
        wang_group_s(g, 0u), wang_group_s(g, 1u), wang_group_s(g, 2u), wang_group_s(g, 3u),
        wang_group_s(g, 4u), wang_group_s(g, 5u), wang_group_s(g, 6u), wang_group_s(g, 7u),
        wang_groups[g * WANG_GROUP_WORDS + WANG_GROUP_NOISE],
    );
}

// The id of the insect in slot i.
fn wang_tick_id(i: u32) -> u32 {
    return wang_slots[wang_tick.n + i];
}

// ---- the navigation direction (host-sim/src/fields/guide.rs) ----

// Per axis: the lower and upper cell of the interpolation and the weight of the upper one.
struct WangAxis {
    lower: u32,
    upper: u32,
    t: S,
}

// axis: u = (p − min)/cell − ½, i = ⌊u⌋, t = u − i, clamped to the border cells.
fn wang_axis(p: S, min_bits: u32, cell_bits: u32, n: u32) -> WangAxis {
    let half = s_from_f32(0.5f);
    let u = s_sub(s_div(s_sub(p, s_from_f32(bitcast<f32>(min_bits))),
                        s_from_f32(bitcast<f32>(cell_bits))), half);
    let i = s_floor_i32(u);
    let last = i32(n) - 1;
    if (i < 0) {
        return WangAxis(0u, 0u, S_ZERO);
    }
    if (i >= last) {
        return WangAxis(u32(last), u32(last), S_ZERO);
    }
    return WangAxis(u32(i), u32(i) + 1u, s_clamp_to(s_sub(u, s_from_i32(i)), S_ZERO, S_ONE));
}

// The record of cell c of the field at `f`.
fn wang_cell_record(f: u32, c: vec3<u32>) -> u32 {
    return wang_fields[wang_fields[f + WANG_FIELD_CELLS] + wang_cell_index(f, c)];
}

// One component of a record: the sign-extended byte at `shift` times the scale, in S.
fn wang_record_component(record: u32, shift: u32, scale: f32) -> S {
    let v = f32(extractBits(bitcast<i32>(record), shift, 8u)) * scale;
    return s_from_f32(v);
}

// GuideCell::guide of a record of the field at `f`, in S.
fn wang_record_guide(f: u32, record: u32) -> vec3<S> {
    let scale = bitcast<f32>(wang_fields[f + WANG_FIELD_SCALE]);
    return vec3<S>(wang_record_component(record, 0u, scale),
                   wang_record_component(record, 8u, scale),
                   wang_record_component(record, 16u, scale));
}

// CellGrid::index: x + nx·(y + ny·z).
fn wang_cell_index(f: u32, c: vec3<u32>) -> u32 {
    let nx = wang_fields[f + WANG_FIELD_DIMS];
    let ny = wang_fields[f + WANG_FIELD_DIMS + 1u];
    return c.x + nx * (c.y + ny * c.z);
}


// CostField::guide_at for the field at word `f`: the trilinear interpolation of the 8
// surrounding cell guides (weights multiplied x, y, z; corners in the order of bit k = axis k),
// renormalised and faded by the weight of the corners outside the goal; the nearest cell's
// guide where the sum is shorter than 1e-3; zero for a non-finite point.
fn wang_guide_at(f: u32, p: vec3<S>) -> vec3<S> {
    if (!(s_is_finite(p.x) && s_is_finite(p.y) && s_is_finite(p.z))) {
        return vec3<S>();
    }
    var ax: array<WangAxis, 3>;
    for (var k = 0u; k < 3u; k = k + 1u) {
        ax[k] = wang_axis(p[k], wang_fields[f + WANG_FIELD_MIN + k],
                          wang_fields[f + WANG_FIELD_CELL], wang_fields[f + WANG_FIELD_DIMS + k]);
    }
    var sum = vec3<S>();
    var reach = S_ZERO;
    for (var c = 0u; c < 8u; c = c + 1u) {
        var w = S_ONE;
        var cell = vec3<u32>();
        for (var k = 0u; k < 3u; k = k + 1u) {
            if (((c >> k) & 1u) == 1u) {
                w = s_mul(w, ax[k].t);
                cell[k] = ax[k].upper;
            } else {
                w = s_mul(w, s_sub(S_ONE, ax[k].t));
                cell[k] = ax[k].lower;
            }
        }
        let record = wang_cell_record(f, cell);
        sum = geom_vec3_add(sum, geom_vec3_mul(wang_record_guide(f, record), w));
        if (((record >> 24u) & 1u) == 0u) {
            reach = s_add(reach, w);
        }
    }
    if (geom_vec3_length(sum) >= s_from_f32(1e-3f)) {
        let unit = geom_vec3_normalized(sum);
        if (unit.is_some) {
            if (reach < S_ONE) {
                return geom_vec3_mul(unit.value, reach);
            }
            return unit.value;
        }
    }
    let half = s_from_f32(0.5f);
    var nearest = vec3<u32>();
    for (var k = 0u; k < 3u; k = k + 1u) {
        nearest[k] = select(ax[k].lower, ax[k].upper, ax[k].t >= half);
    }
    return wang_record_guide(f, wang_cell_record(f, nearest));
}

// ---- the nearest boundary (host-sim/src/wang/world.rs) ----

struct WangNearest {
    found: bool,
    d: S,
    boundary: WangBoundary,
}

// offer: keeps `b` at distance `d` if it is within d0 and strictly nearer than the best so far.
fn wang_offer(best: ptr<function, WangNearest>, d: S, d0: S, b: WangBoundary) {
    if (d < d0 && (!(*best).found || d < (*best).d)) {
        *best = WangNearest(true, d, b);
    }
}

// curvature: 1/|p − c| beside a sphere, 1/ρ about the vertical axis beside a shaft's side
// (a horizontal normal at a height between the caps), 0 elsewhere.
fn wang_curvature(o: BeeWorldObstacle, p: vec3<S>, n: vec3<S>) -> WangBoundary {
    var b: WangBoundary;
    if (o.shape == BEE_WORLD_SPHERE) {
        let rho = geom_vec3_length(geom_vec3_sub(p, o.a));
        if (rho > S_ZERO) {
            b.curvature = s_div(S_ONE, rho);
        }
    } else if (o.shape == BEE_WORLD_SHAFT) {
        // o.a = (centre x, centre z, radius), o.b = (bottom, top).
        let side = n.y == S_ZERO && p.y >= o.b.x && p.y <= o.b.y;
        let rho = geom_length(vec2<S>(s_sub(p.x, o.a.x), s_sub(p.z, o.a.y)));
        if (side && rho > S_ZERO) {
            b.curvature = s_div(S_ONE, rho);
            b.axis = vec3<S>(S_ZERO, S_ONE, S_ZERO);
        }
    }
    return b;
}

// WangWorld::boundary: the nearest boundary of eq. 2 within d0 of p (strictly closer): the
// closest surface point of an active obstacle (distance 0 inside one), then the walls −x, +x,
// −y, +y, −z, +z (inward normals); ties keep the first. (The CPU skips the obstacles whose
// bounding box is beyond its range in f64: none of them could be nearer than d0.)
fn wang_tick_boundary(p: vec3<S>, d0: S) -> WangNearest {
    var best = WangNearest(false, S_ZERO, WangBoundary(vec3<S>(), vec3<S>(), S_ZERO, vec3<S>()));
    for (var k = 0u; k < bee_world_obstacles(); k = k + 1u) {
        let o = bee_world_obstacle(k);
        if (!o.present) {
            continue;
        }
        let s = bee_world_surface(o, p);
        let d = select(s.distance, S_ZERO, s.inside);
        var b = wang_curvature(o, p, s.normal);
        b.point = s.point;
        b.normal = s.normal;
        wang_offer(&best, d, d0, b);
    }
    let lo = bee_world_min();
    let hi = bee_world_max();
    for (var k = 0u; k < 3u; k = k + 1u) {
        for (var side = 0u; side < 2u; side = side + 1u) {
            let f = select(lo[k], hi[k], side == 1u);
            let sign = select(S_ONE, s_neg(S_ONE), side == 1u);
            let d = s_max(s_mul(s_sub(p[k], f), sign), S_ZERO);
            var point = p;
            point[k] = f;
            var normal = vec3<S>();
            normal[k] = sign;
            wang_offer(&best, d, d0, WangBoundary(point, normal, S_ZERO, vec3<S>()));
        }
    }
    return best;
}

// WangGroup::advect_frame for an insect of group g at p.
fn wang_tick_advect_frame(g: u32, p: WangParams, pos: vec3<S>) -> WangAdvectFrame {
    var f: WangAdvectFrame;
    let gw = g * WANG_GROUP_WORDS;
    let field = wang_groups[gw + WANG_GROUP_FIELD];
    if (field != WANG_NO_FIELD) {
        f.guide = wang_guide_at(field, pos);
    }
    let b = wang_tick_boundary(pos, p.d0);
    f.has_boundary = b.found;
    f.boundary = b.boundary;
    f.has_lamp = wang_groups[gw + WANG_GROUP_HAS_LAMP] != 0u;
    f.lamp = vec3<S>(wang_group_s(g, WANG_GROUP_LAMP), wang_group_s(g, WANG_GROUP_LAMP + 1u),
                     wang_group_s(g, WANG_GROUP_LAMP + 2u));
    return f;
}

// ---- counts ----

// Adds one to the u64 of words `at` (low) and `at + 1` (high).
fn wang_count64(at: u32) {
    if (atomicAdd(&wang_shared[at], 1u) == 0xffffffffu) {
        atomicAdd(&wang_shared[at + 1u], 1u);
    }
}

// Counts the world's corrections `fix` (bit 0 an obstacle, bit 1 the bounds): this tick's and
// since the start.
fn wang_count_fix(fix: u32) {
    if ((fix & 1u) != 0u) {
        atomicAdd(&wang_shared[WANG_SHARED_OBSTACLE], 1u);
        wang_count64(WANG_SHARED_TOTAL_OBSTACLE);
    }
    if ((fix & 2u) != 0u) {
        atomicAdd(&wang_shared[WANG_SHARED_BOUNDS], 1u);
        wang_count64(WANG_SHARED_TOTAL_BOUNDS);
    }
}

// Notes a refusal of slot i in `phase`: the lowest id refused is the one reported
// (for_each_agent_by, par.rs).
fn wang_refuse(i: u32, phase: u32) {
    atomicMax(&wang_shared[WANG_SHARED_REFUSED + phase], 0xffffffffu - wang_tick_id(i));
}

// ---- the kernels ----

// Phase 1 (WangGroup::advect, WangGroup::place): the advect reply, x* after the world's
// corrections, its cell.
@compute @workgroup_size(WORKGROUP)
fn wang_tick_advect_main(@builtin(global_invocation_id) id: vec3<u32>,
                         @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= wang_tick.n) {
        return;
    }
    let g = wang_slots[i];
    let p = wang_group_params(g);
    let s = wang_tick_state(i);
    let c = StepCtx(wang_tick.seed, wang_tick_id(i), wang_tick.step);
    let r = wang_advect_checked(s, wang_tick_advect_frame(g, p, s.pos), p, c);
    wang_status[2u * i] = r.status;
    if (r.status != BEE_OK) {
        wang_refuse(i, 0u);
    }
    let moved = wang_state_words(r.state);
    var pos = r.state.pos;
    var vel = r.state.vel;
    let fix = space_confine(&pos, &vel, s_from_word(wang_tick.offset));
    let placed = wang_state_words(WangState(pos, vel));
    for (var k = 0u; k < WANG_STATE_WORDS; k = k + 1u) {
        wang_moved[i * WANG_STATE_WORDS + k] = moved[k];
        wang_placed[i * WANG_STATE_WORDS + k] = placed[k];
    }
    wang_flags[i] = fix;
    wang_count_fix(fix);
    wang_cells[i] = bee_world_cell(pos);
}

// WangGroup::separate_frame's selection: the WANG_NEIGHBOURS x* nearest to slot i (at `me`)
// strictly within d_min (squared distance in S below `r2`), nearest first, ties by id.
fn wang_tick_close(i: u32, me: vec3<S>, d_min: S, r2: S) -> BeeSenseSelected {
    let g = bee_world_grid(BEE_WORLD_H_GRID);
    let q = bee_sense_query(g, me, s_add(d_min, g.margin));
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
                let d = geom_vec3_length_sq(geom_vec3_sub(wang_tick_placed_pos(j), me));
                if (d < r2) {
                    bee_sense_offer(&near, WANG_NEIGHBOURS, d, wang_tick_id(j), j);
                }
            }
        }
    }
    return near;
}

// Phase 2 (WangGroup::separate): the separate frame, then minimum distance enforcement.
@compute @workgroup_size(WORKGROUP)
fn wang_tick_separate_main(@builtin(global_invocation_id) id: vec3<u32>,
                           @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= wang_tick.n) {
        return;
    }
    let g = wang_slots[i];
    let p = wang_group_params(g);
    let me = wang_tick_placed(i);
    var f: WangSeparateFrame;
    if (p.d_min > S_ZERO) {
        let near = wang_tick_close(i, me.pos, p.d_min, wang_group_s(g, WANG_GROUP_RANGE2));
        f.len = near.len;
        for (var k = 0u; k < near.len; k = k + 1u) {
            f.ids[k] = near.ties[k];
            f.pos[k] = wang_tick_placed_pos(near.slots[k]);
        }
    }
    let c = StepCtx(wang_tick.seed, wang_tick_id(i), wang_tick.step);
    let r = wang_separate_checked(me, &f, p, c);
    wang_status[2u * i + 1u] = r.status;
    if (r.status != BEE_OK) {
        wang_refuse(i, 1u);
    }
    let w = wang_state_words(r.state);
    for (var k = 0u; k < WANG_STATE_WORDS; k = k + 1u) {
        wang_next[i * WANG_STATE_WORDS + k] = w[k];
    }
    wang_flags[i] = wang_flags[i] | (min(r.pushes, 255u) << 8u);
    if (r.pushes > 0u) {
        atomicAdd(&wang_shared[WANG_SHARED_PUSHED], 1u);
        wang_count64(WANG_SHARED_TOTAL_PUSHED);
    }
}

// WangGroup::commit: the world's corrections of x_{k+1}, counted, made current; the thread of
// the refused insect keeps the tick's refusal (advect's before separate's) if none is kept yet.
@compute @workgroup_size(WORKGROUP)
fn wang_tick_commit_main(@builtin(global_invocation_id) id: vec3<u32>,
                         @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    let n = wang_tick.n;
    if (i >= n) {
        return;
    }
    // The thread of the lowest id refused in the first phase with a refusal keeps it (ids are
    // unique: one thread at most), if none is kept yet.
    let advect = atomicLoad(&wang_shared[WANG_SHARED_REFUSED]);
    let phase = select(0u, 1u, advect == 0u);
    let refused = atomicLoad(&wang_shared[WANG_SHARED_REFUSED + phase]);
    let me = wang_tick_id(i);
    if (refused != 0u && me == 0xffffffffu - refused
        && atomicLoad(&wang_shared[WANG_SHARED_KEPT]) == 0u) {
        atomicStore(&wang_shared[WANG_SHARED_KEPT], 1u);
        atomicStore(&wang_shared[WANG_SHARED_KEPT_STEP], wang_tick.step);
        atomicStore(&wang_shared[WANG_SHARED_KEPT_ID], me);
        atomicStore(&wang_shared[WANG_SHARED_KEPT_PHASE], phase);
        atomicStore(&wang_shared[WANG_SHARED_KEPT_STATUS], wang_status[2u * i + phase]);
    }
    let s = wang_tick_next(i);
    var pos = s.pos;
    var vel = s.vel;
    let fix = space_confine(&pos, &vel, s_from_word(wang_tick.offset));
    wang_flags[i] = wang_flags[i] | fix;
    wang_count_fix(fix);
    let w = wang_state_words(WangState(pos, vel));
    for (var k = 0u; k < WANG_STATE_WORDS; k = k + 1u) {
        wang_states[i * WANG_STATE_WORDS + k] = w[k];
    }
}
