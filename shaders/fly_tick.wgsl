// The ren2016 tick of the GPU engine (host-sim/src/gpu/shaders.rs, FLY_TICK;
// host-sim/src/gpu/fly/engine.rs drives it): host-sim/src/fly/sim.rs's step, one thread per
// insect, over the scalar `S`, the states staying on the GPU between ticks. A tick is
//
// 1. `fly_tick_cells_main`: the cell of every insect's position (bee_world.wgsl's grid);
// 2. the grid's sort (`GpuGrid`);
// 3. `fly_tick_step_main`: the frame of host-sim/src/fly/sense.rs (`fly_frame`: the
//    FLY_NEIGHBOURS nearest insects within r_att by exact key, nearest first, ties by id, and
//    whether more were in range; the stimulus, a threat before a goal, within r_res; the
//    surfaces within ORCA's reach, `FlyWorld::surfaces`), then `fly_step_checked`; the status,
//    the next state as the controller gave it and the decision written, the infeasible programs
//    and truncated frames counted;
// 4. `fly_tick_commit_main`: the world's corrections (`space_confine`, `FlyWorld::confine`),
//    counted, the state made current; the refused insect's thread keeps the tick's first refusal.
//
// Bindings (group 0), besides the world (1, bee_world.wgsl: the container, the obstacles, the
// stimulus sources as targets, the grid), the grid's `starts` and `order` (4, 5, bee_sense.wgsl)
// and the confinement boxes (15, space.wgsl): 6 the cells, 7 the tick's parameters, 8 the states,
// 9 the next states, 10 the decisions, 11 the groups' words, 12 each slot's group and id, 13 the
// tick's atomics, 14 each slot's flags, 16 each slot's status word.

struct FlyTickParams {
    n: u32,
    step: u32,
    seed: u32,
    // SURFACE_OFFSET (space.rs) in S, as `confine` converts it.
    offset: u32,
}

@group(0) @binding(6) var<storage, read_write> fly_cells: array<u32>;
@group(0) @binding(7) var<uniform> fly_tick: FlyTickParams;
@group(0) @binding(8) var<storage, read_write> fly_states: array<u32>;
@group(0) @binding(9) var<storage, read_write> fly_next: array<u32>;
@group(0) @binding(10) var<storage, read_write> fly_decisions: array<u32>;
@group(0) @binding(11) var<storage, read> fly_groups: array<u32>;
@group(0) @binding(12) var<storage, read> fly_slots: array<u32>;
@group(0) @binding(13) var<storage, read_write> fly_shared: array<atomic<u32>>;
@group(0) @binding(14) var<storage, read_write> fly_flags: array<u32>;
@group(0) @binding(16) var<storage, read_write> fly_status: array<u32>;

// Words of a state (position, velocity, escape_theta, escaping) and of a decision (pref,
// infeasible) (host-sim/src/gpu/fly/layout.rs).
const FLY_STATE_WORDS: u32 = 8u;
const FLY_DECISION_WORDS: u32 = 4u;

// A group's words (layout.rs, GROUP_*): the sixteen parameters in S in FlyParams' order, then
// orca_neighbours, noise, fallback, escape_sides, the goal's and the threat's object ids
// (FLY_NO_SOURCE: none), r_att, r_rep and r_ali squared in S (the selection's bands), and the
// goal's and the threat's regions (FLY_REGION_WORDS each: FLY_REGION_BOX or FLY_REGION_CAVE, 0
// for a source with a centre only, then its lower and upper corners in S).
const FLY_GROUP_WORDS: u32 = 40u;
const FLY_GROUP_ORCA_NEIGHBOURS: u32 = 16u;
const FLY_GROUP_GOAL: u32 = 20u;
const FLY_GROUP_THREAT: u32 = 21u;
const FLY_GROUP_RANGE2: u32 = 22u;
const FLY_GROUP_REP2: u32 = 23u;
const FLY_GROUP_ALI2: u32 = 24u;
const FLY_GROUP_REGIONS: u32 = 26u;
const FLY_REGION_WORDS: u32 = 7u;
const FLY_REGION_BOX: u32 = 1u;
const FLY_REGION_CAVE: u32 = 2u;
// Entries a truncated frame keeps for each farther zone with members (sense.rs, ZONE_QUOTA).
const FLY_ZONE_QUOTA: u32 = 3u;
const FLY_NO_SOURCE: u32 = 0xffffffffu;

// A slot's flags (layout.rs, FLAG_*): what the world corrected (bit 0 an obstacle, bit 1 the
// container), whether the frame was truncated.
const FLY_FLAG_TRUNCATED: u32 = 4u;

// The words of `fly_shared` (engine.rs, SHARED_*): this tick's lowest refused id (0xffffffff −
// id, 0 for none), infeasible programs, truncated frames, corrections (obstacle, bounds), cleared
// by the host every tick; the first refusal kept (a flag, its step, the insect's id and status word); the
// counts since the start, each a u64 as two words.
const FLY_SHARED_REFUSED: u32 = 0u;
const FLY_SHARED_INFEASIBLE: u32 = 1u;
const FLY_SHARED_TRUNCATED: u32 = 2u;
const FLY_SHARED_OBSTACLE: u32 = 3u;
const FLY_SHARED_BOUNDS: u32 = 4u;
const FLY_SHARED_KEPT: u32 = 5u;
const FLY_SHARED_KEPT_STEP: u32 = 6u;
const FLY_SHARED_KEPT_ID: u32 = 7u;
const FLY_SHARED_KEPT_STATUS: u32 = 8u;
const FLY_SHARED_TOTAL_INFEASIBLE: u32 = 10u;
const FLY_SHARED_TOTAL_TRUNCATED: u32 = 12u;
const FLY_SHARED_TOTAL_OBSTACLE: u32 = 14u;
const FLY_SHARED_TOTAL_BOUNDS: u32 = 16u;

// ---- the buffers' values ----

fn fly_s(w: u32) -> S {
    return s_from_word(w);
}

fn fly_state_at(b: u32, from_next: bool) -> FlyState {
    var w: array<u32, 8>;
    for (var k = 0u; k < FLY_STATE_WORDS; k = k + 1u) {
        w[k] = select(fly_states[b + k], fly_next[b + k], from_next);
    }
    return FlyState(vec3<S>(fly_s(w[0]), fly_s(w[1]), fly_s(w[2])),
                     vec3<S>(fly_s(w[3]), fly_s(w[4]), fly_s(w[5])), fly_s(w[6]), w[7] != 0u);
}

// The current state of slot i.
fn fly_tick_state(i: u32) -> FlyState {
    return fly_state_at(i * FLY_STATE_WORDS, false);
}

fn fly_tick_pos(j: u32) -> vec3<S> {
    let b = j * FLY_STATE_WORDS;
    return vec3<S>(fly_s(fly_states[b]), fly_s(fly_states[b + 1u]), fly_s(fly_states[b + 2u]));
}

fn fly_tick_vel(j: u32) -> vec3<S> {
    let b = j * FLY_STATE_WORDS + 3u;
    return vec3<S>(fly_s(fly_states[b]), fly_s(fly_states[b + 1u]), fly_s(fly_states[b + 2u]));
}

fn fly_state_words(s: FlyState) -> array<u32, 8> {
    return array<u32, 8>(
        s_to_word(s.pos.x), s_to_word(s.pos.y), s_to_word(s.pos.z),
        s_to_word(s.vel.x), s_to_word(s.vel.y), s_to_word(s.vel.z),
        s_to_word(s.escape_theta), select(0u, 1u, s.escaping),
    );
}

fn fly_group_s(g: u32, k: u32) -> S {
    return fly_s(fly_groups[g * FLY_GROUP_WORDS + k]);
}

fn fly_group_u(g: u32, k: u32) -> u32 {
    return fly_groups[g * FLY_GROUP_WORDS + k];
}

// The parameters of group g (validated on the host: `Checked`).
fn fly_group_params(g: u32) -> FlyParams {
    var s: array<S, 16>;
    for (var k = 0u; k < 16u; k = k + 1u) {
        s[k] = fly_group_s(g, k);
    }
    let o = FLY_GROUP_ORCA_NEIGHBOURS;
    return FlyParams(s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7], s[8], s[9], s[10], s[11],
                     s[12], s[13], s[14], s[15], fly_group_u(g, o), fly_group_u(g, o + 1u),
                     fly_group_u(g, o + 2u), fly_group_u(g, o + 3u));
}

// The id of the insect in slot i.
fn fly_tick_id(i: u32) -> u32 {
    return fly_slots[fly_tick.n + i];
}

// ---- the frame (host-sim/src/fly/sense.rs, world.rs) ----

// The selection of the frame's neighbours and how many insects were within range.
struct FlyNear {
    near: BeeSenseSelected,
    within: u32,
}

// zone_shares (sense.rs): how many of each zone's nearest members (repulsion, alignment,
// attraction) a frame holds, from the zones' member counts `n`.
fn fly_zone_shares(n: vec3<u32>) -> vec3<u32> {
    let q_ali = min(n.y, FLY_ZONE_QUOTA);
    let q_att = min(n.z, FLY_ZONE_QUOTA);
    let rep = min(n.x, FLY_NEIGHBOURS - q_ali - q_att);
    let ali = min(n.y, FLY_NEIGHBOURS - rep - q_att);
    let att = min(n.z, FLY_NEIGHBOURS - rep - ali);
    return vec3<u32>(rep, ali, att);
}

// Appends the first `k` of `band` to `out`.
fn fly_near_append(out: ptr<function, BeeSenseSelected>, band: BeeSenseSelected, k: u32) {
    for (var m = 0u; m < k; m = m + 1u) {
        let at = (*out).len;
        (*out).keys[at] = band.keys[m];
        (*out).ties[at] = band.ties[m];
        (*out).slots[at] = band.slots[m];
        (*out).len = at + 1u;
    }
}

// select_bands::<S, 16, 3> (nearest.rs) and the shares of fly_frame (sense.rs): the insects
// strictly within r_att of slot i (at `me`), banded by squared distance in S into the zones
// (below r_rep², r_ali², r_att²: `g`'s words), each band's FLY_NEIGHBOURS nearest kept (ties
// by id), then each band's share of the frame, nearest first; and how many were within r_att
// (more than FLY_NEIGHBOURS: the frame is truncated).
fn fly_tick_near(i: u32, me: vec3<S>, r_att: S, g: u32) -> FlyNear {
    let grid = bee_world_grid(BEE_WORLD_H_GRID);
    let q = bee_sense_query(grid, me, s_add(r_att, grid.margin));
    let rep2 = fly_group_s(g, FLY_GROUP_REP2);
    let ali2 = fly_group_s(g, FLY_GROUP_ALI2);
    let att2 = fly_group_s(g, FLY_GROUP_RANGE2);
    var rep: BeeSenseSelected;
    var ali: BeeSenseSelected;
    var att: BeeSenseSelected;
    var n = vec3<u32>(0u, 0u, 0u);
    for (var z = q.lo.z; z <= q.hi.z; z = z + 1u) {
        for (var y = q.lo.y; y <= q.hi.y; y = y + 1u) {
            let row = bee_world_cell_key(grid, vec3<u32>(q.lo.x, y, z));
            let end = bee_grid_starts[row + q.hi.x - q.lo.x + 1u];
            for (var s = bee_grid_starts[row]; s < end; s = s + 1u) {
                let j = bee_grid_order[s];
                if (j == i) {
                    continue;
                }
                let d = geom_vec3_length_sq(geom_vec3_sub(fly_tick_pos(j), me));
                if (d < rep2) {
                    n.x = n.x + 1u;
                    bee_sense_offer(&rep, FLY_NEIGHBOURS, d, fly_tick_id(j), j);
                } else if (d < ali2) {
                    n.y = n.y + 1u;
                    bee_sense_offer(&ali, FLY_NEIGHBOURS, d, fly_tick_id(j), j);
                } else if (d < att2) {
                    n.z = n.z + 1u;
                    bee_sense_offer(&att, FLY_NEIGHBOURS, d, fly_tick_id(j), j);
                }
            }
        }
    }
    let share = fly_zone_shares(n);
    var near: BeeSenseSelected;
    fly_near_append(&near, rep, share.x);
    fly_near_append(&near, ali, share.y);
    fly_near_append(&near, att, share.z);
    return FlyNear(near, n.x + n.y + n.z);
}

// echo_point (sense.rs): where a ray from p along vel leaves the box [lo, hi] (the nearest exit
// ahead, clamped to p from outside); none for an insect at rest.
fn fly_echo_point(p: vec3<S>, vel: vec3<S>, lo: vec3<S>, hi: vec3<S>) -> GeomOptionVec3 {
    let dir = geom_vec3_normalized(vel);
    if (!dir.is_some) {
        return dir;
    }
    let d = dir.value;
    var found = false;
    var t = S_ZERO;
    for (var k = 0u; k < 3u; k = k + 1u) {
        var exit = S_ZERO;
        if (d[k] > S_ZERO) {
            exit = s_div(s_sub(hi[k], p[k]), d[k]);
        } else if (d[k] < S_ZERO) {
            exit = s_div(s_sub(lo[k], p[k]), d[k]);
        } else {
            continue;
        }
        t = select(exit, s_min(t, exit), found);
        found = true;
    }
    if (!found) {
        return GeomOptionVec3(false, vec3<S>());
    }
    return GeomOptionVec3(true, geom_vec3_add(p, geom_vec3_mul(d, s_max(t, S_ZERO))));
}

// nearest_outside (sense.rs): the point of the box [lo, hi] nearest to p; none inside it.
fn fly_nearest_outside(p: vec3<S>, lo: vec3<S>, hi: vec3<S>) -> GeomOptionVec3 {
    let q = vec3<S>(s_min(s_max(p.x, lo.x), hi.x), s_min(s_max(p.y, lo.y), hi.y),
                    s_min(s_max(p.z, lo.z), hi.z));
    return GeomOptionVec3(any(q != p), q);
}

// ahead_point (sense.rs): the echo ahead in the cave [lo, hi], or the point r_res/2 ahead when
// the walls are farther; none for an insect at rest.
fn fly_ahead_point(p: vec3<S>, vel: vec3<S>, lo: vec3<S>, hi: vec3<S>, r_res: S) -> GeomOptionVec3 {
    let wall = fly_echo_point(p, vel, lo, hi);
    if (!wall.is_some) {
        return wall;
    }
    let half = s_mul(r_res, s_from_f32(0.5f));
    let dir = geom_vec3_normalized(vel);
    if (!dir.is_some) {
        return dir;
    }
    if (geom_vec3_length_sq(geom_vec3_sub(wall.value, p)) > s_mul(half, half)) {
        return GeomOptionVec3(true, geom_vec3_add(p, geom_vec3_mul(dir.value, half)));
    }
    return wall;
}

// Three S words of group g from word k on.
fn fly_group_vec3(g: u32, k: u32) -> vec3<S> {
    return vec3<S>(fly_group_s(g, k), fly_group_s(g, k + 1u), fly_group_s(g, k + 2u));
}

// stimulus (sense.rs): the group's threat (kind FLY_STIMULUS_PREDATOR) or goal if it is active
// and within r_res (squared in S, H(0) = 1): its centre, or for a region the echo ahead (a
// threat), the echo ahead or the point r_res/2 ahead (a cave's goal) or its nearest point (a
// goal).
fn fly_tick_source(f: ptr<function, FlyFrame>, g: u32, kind: u32, me: vec3<S>, vel: vec3<S>,
                   r_res: S, r2: S) -> bool {
    let threat = kind == FLY_STIMULUS_PREDATOR;
    let id = fly_group_u(g, select(FLY_GROUP_GOAL, FLY_GROUP_THREAT, threat));
    if (id == FLY_NO_SOURCE) {
        return false;
    }
    var c = bee_world_target_center(id);
    let r = FLY_GROUP_REGIONS + select(0u, FLY_REGION_WORDS, threat);
    let region = fly_group_u(g, r);
    if (c.is_some && region != 0u) {
        let lo = fly_group_vec3(g, r + 1u);
        let hi = fly_group_vec3(g, r + 4u);
        if (threat) {
            c = fly_echo_point(me, vel, lo, hi);
        } else if (region == FLY_REGION_CAVE) {
            c = fly_ahead_point(me, vel, lo, hi, r_res);
        } else {
            c = fly_nearest_outside(me, lo, hi);
        }
    }
    if (!c.is_some || !(geom_vec3_length_sq(geom_vec3_sub(c.value, me)) <= r2)) {
        return false;
    }
    (*f).has_stimulus = true;
    (*f).stimulus_pos = c.value;
    (*f).stimulus_kind = kind;
    return true;
}

// fly_frame (sense.rs) of the insect in slot i of group g; returns whether it was truncated.
fn fly_tick_frame(f: ptr<function, FlyFrame>, i: u32, g: u32, p: FlyParams, me: vec3<S>) -> bool {
    let near = fly_tick_near(i, me, p.r_att, g);
    (*f).neighbours_len = near.near.len;
    for (var k = 0u; k < near.near.len; k = k + 1u) {
        let j = near.near.slots[k];
        (*f).neighbours[k] = FlyNeighbour(near.near.ties[k], fly_tick_pos(j), fly_tick_vel(j));
    }
    let r2 = s_mul(p.r_res, p.r_res);
    let vel = fly_tick_vel(i);
    if (!fly_tick_source(f, g, FLY_STIMULUS_PREDATOR, me, vel, p.r_res, r2)) {
        fly_tick_source(f, g, FLY_STIMULUS_TARGET, me, vel, p.r_res, r2);
    }
    fly_surfaces_sense(f, me, fly_reach(p));
    return near.within > FLY_NEIGHBOURS;
}

// ---- counts ----

// Adds one to the u64 of words `at` (low) and `at + 1` (high).
fn fly_count64(at: u32) {
    if (atomicAdd(&fly_shared[at], 1u) == 0xffffffffu) {
        atomicAdd(&fly_shared[at + 1u], 1u);
    }
}

// Counts one of this tick's `at` and of the totals' `total`.
fn fly_count(at: u32, total: u32) {
    atomicAdd(&fly_shared[at], 1u);
    fly_count64(total);
}

// ---- the kernels ----

// The cell of every insect's position in the grid.
@compute @workgroup_size(WORKGROUP)
fn fly_tick_cells_main(@builtin(global_invocation_id) id: vec3<u32>,
                       @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= fly_tick.n) {
        return;
    }
    fly_cells[i] = bee_world_cell(fly_tick_pos(i));
}

// FlyGroup::decide: the frame, the step; the next state and decision as the controller gave
// them (what the mirror compares), the counts.
@compute @workgroup_size(WORKGROUP)
fn fly_tick_step_main(@builtin(global_invocation_id) id: vec3<u32>,
                      @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= fly_tick.n) {
        return;
    }
    let g = fly_slots[i];
    let p = fly_group_params(g);
    let s = fly_tick_state(i);
    var f: FlyFrame;
    let truncated = fly_tick_frame(&f, i, g, p, s.pos);
    let c = StepCtx(fly_tick.seed, fly_tick_id(i), fly_tick.step);
    let r = fly_step_checked(s, &f, p, c);
    fly_status[i] = r.status;
    if (r.status != BEE_OK) {
        // The lowest id refused is the one reported (for_each_agent_by, par.rs).
        atomicMax(&fly_shared[FLY_SHARED_REFUSED], 0xffffffffu - fly_tick_id(i));
    }
    let w = fly_state_words(r.next);
    for (var k = 0u; k < FLY_STATE_WORDS; k = k + 1u) {
        fly_next[i * FLY_STATE_WORDS + k] = w[k];
    }
    let d = i * FLY_DECISION_WORDS;
    fly_decisions[d] = s_to_word(r.pref.x);
    fly_decisions[d + 1u] = s_to_word(r.pref.y);
    fly_decisions[d + 2u] = s_to_word(r.pref.z);
    fly_decisions[d + 3u] = select(0u, 1u, r.infeasible);
    fly_flags[i] = select(0u, FLY_FLAG_TRUNCATED, truncated);
    if (r.infeasible) {
        fly_count(FLY_SHARED_INFEASIBLE, FLY_SHARED_TOTAL_INFEASIBLE);
    }
    if (truncated) {
        fly_count(FLY_SHARED_TRUNCATED, FLY_SHARED_TOTAL_TRUNCATED);
    }
}

// FlyGroup::commit: the world's corrections of the next state, counted, made current; the
// thread of the refused insect keeps the tick's refusal if none is kept yet.
@compute @workgroup_size(WORKGROUP)
fn fly_tick_commit_main(@builtin(global_invocation_id) id: vec3<u32>,
                        @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    let n = fly_tick.n;
    if (i >= n) {
        return;
    }
    // The thread of the lowest id refused keeps the tick's refusal (ids are unique: one
    // thread at most), if none is kept yet.
    let refused = atomicLoad(&fly_shared[FLY_SHARED_REFUSED]);
    let me = fly_tick_id(i);
    if (refused != 0u && me == 0xffffffffu - refused
        && atomicLoad(&fly_shared[FLY_SHARED_KEPT]) == 0u) {
        atomicStore(&fly_shared[FLY_SHARED_KEPT], 1u);
        atomicStore(&fly_shared[FLY_SHARED_KEPT_STEP], fly_tick.step);
        atomicStore(&fly_shared[FLY_SHARED_KEPT_ID], me);
        atomicStore(&fly_shared[FLY_SHARED_KEPT_STATUS], fly_status[i]);
    }
    let s = fly_state_at(i * FLY_STATE_WORDS, true);
    var pos = s.pos;
    var vel = s.vel;
    let fix = space_confine(&pos, &vel, s_from_word(fly_tick.offset));
    fly_flags[i] = fly_flags[i] | fix;
    if ((fix & 1u) != 0u) {
        fly_count(FLY_SHARED_OBSTACLE, FLY_SHARED_TOTAL_OBSTACLE);
    }
    if ((fix & 2u) != 0u) {
        fly_count(FLY_SHARED_BOUNDS, FLY_SHARED_TOTAL_BOUNDS);
    }
    let w = fly_state_words(FlyState(pos, vel, s.escape_theta, s.escaping));
    for (var k = 0u; k < FLY_STATE_WORDS; k = k + 1u) {
        fly_states[i * FLY_STATE_WORDS + k] = w[k];
    }
}
