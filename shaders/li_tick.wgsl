// The li2015 tick of the GPU engine (host-sim/src/gpu/shaders.rs, LI_TICK;
// host-sim/src/gpu/swarm3d.rs drives it): host-sim/src/li/sim.rs's step, one thread per insect,
// over the scalar `S`, the states staying on the GPU between ticks. A tick is
//
// 1. `li_tick_cells_main`: the cell of every insect's position (bee_world.wgsl's grid);
// 2. the grid's sort (`GpuGrid`);
// 3. `li_tick_step_main`: the frame of `li_frame` (sim.rs: the LI_NEIGHBOURS nearest insects
//    strictly within the neighbour distance by exact key, nearest first, ties by id, and whether
//    more were in range; the surfaces within ORCA's reach, fly_surfaces.wgsl), then
//    `li_step_checked`; the status, the next state as the controller gave it and the decision
//    written, the arrivals, proposals, holds, infeasible programs and truncated frames counted;
// 4. `li_tick_commit_main`: the world's corrections (`space_confine`), counted, the state made
//    current; the refused insect's thread keeps the tick's first refusal.
//
// Bindings (group 0), besides the world (1, bee_world.wgsl), the grid's `starts` and `order`
// (4, 5, bee_sense.wgsl), the groups' words (11, li_step.wgsl) and the confinement boxes (15,
// space.wgsl): 6 the cells, 7 the tick's parameters, 8 the states, 9 the next states, 10 the
// decisions, 12 each slot's group and id, 13 the tick's atomics, 14 each slot's flags, 16 each
// slot's status word.

struct LiTickParams {
    n: u32,
    step: u32,
    seed: u32,
    // SURFACE_OFFSET (space.rs) in S, as `confine` converts it.
    offset: u32,
}

@group(0) @binding(6) var<storage, read_write> li_cells: array<u32>;
@group(0) @binding(7) var<uniform> li_tick: LiTickParams;
@group(0) @binding(8) var<storage, read_write> li_states: array<u32>;
@group(0) @binding(9) var<storage, read_write> li_next: array<u32>;
@group(0) @binding(10) var<storage, read_write> li_decisions: array<u32>;
@group(0) @binding(12) var<storage, read> li_slots: array<u32>;
@group(0) @binding(13) var<storage, read_write> li_shared: array<atomic<u32>>;
@group(0) @binding(14) var<storage, read_write> li_flags: array<u32>;
@group(0) @binding(16) var<storage, read_write> li_status: array<u32>;

// Words of a state (position, velocity, waypoint, segment start, age) and of a decision (pref,
// proposals, accepted, infeasible) (host-sim/src/gpu/li/layout.rs).
const LI_STATE_WORDS: u32 = 13u;
const LI_DECISION_WORDS: u32 = 6u;

// A slot's flags (swarm3d.rs, FLAG_TRUNCATED): what the world corrected (bit 0 an obstacle,
// bit 1 the container), whether the frame was truncated.
const LI_FLAG_TRUNCATED: u32 = 4u;

// The words of `li_shared` (swarm3d.rs, SharedLayout): this tick's lowest refused id (0xffffffff −
// id, 0 for none) and counts, cleared by the host every tick; the first refusal kept (a flag, its
// step, the insect's id and status word); the counts since the start, each a u64 as two words.
const LI_SHARED_REFUSED: u32 = 0u;
const LI_SHARED_ARRIVALS: u32 = 1u;
const LI_SHARED_PROPOSALS: u32 = 2u;
const LI_SHARED_HELD: u32 = 3u;
const LI_SHARED_INFEASIBLE: u32 = 4u;
const LI_SHARED_TRUNCATED: u32 = 5u;
const LI_SHARED_CORRECTED: u32 = 6u;
const LI_SHARED_KEPT: u32 = 7u;
const LI_SHARED_KEPT_STEP: u32 = 8u;
const LI_SHARED_KEPT_ID: u32 = 9u;
const LI_SHARED_KEPT_STATUS: u32 = 10u;
const LI_SHARED_TOTAL_ARRIVALS: u32 = 12u;
const LI_SHARED_TOTAL_PROPOSALS: u32 = 14u;
const LI_SHARED_TOTAL_HELD: u32 = 16u;
const LI_SHARED_TOTAL_INFEASIBLE: u32 = 18u;
const LI_SHARED_TOTAL_TRUNCATED: u32 = 20u;
const LI_SHARED_TOTAL_CORRECTED: u32 = 22u;

// ---- the buffers' values ----

fn li_vec3_at(w: ptr<function, array<u32, 13>>, k: u32) -> vec3<S> {
    return vec3<S>(s_from_word((*w)[k]), s_from_word((*w)[k + 1u]), s_from_word((*w)[k + 2u]));
}

fn li_state_at(b: u32, from_next: bool) -> LiState {
    var w: array<u32, 13>;
    for (var k = 0u; k < LI_STATE_WORDS; k = k + 1u) {
        w[k] = select(li_states[b + k], li_next[b + k], from_next);
    }
    return LiState(li_vec3_at(&w, 0u), li_vec3_at(&w, 3u), li_vec3_at(&w, 6u),
                   li_vec3_at(&w, 9u), w[12]);
}

fn li_tick_pos(j: u32) -> vec3<S> {
    let b = j * LI_STATE_WORDS;
    return vec3<S>(s_from_word(li_states[b]), s_from_word(li_states[b + 1u]),
                   s_from_word(li_states[b + 2u]));
}

fn li_tick_vel(j: u32) -> vec3<S> {
    let b = j * LI_STATE_WORDS + 3u;
    return vec3<S>(s_from_word(li_states[b]), s_from_word(li_states[b + 1u]),
                   s_from_word(li_states[b + 2u]));
}

// Writes state s as the words of slot i of `li_next` (`to_next`) or `li_states`.
fn li_write_state(i: u32, s: LiState, to_next: bool) {
    let w = array<u32, 13>(
        s_to_word(s.pos.x), s_to_word(s.pos.y), s_to_word(s.pos.z),
        s_to_word(s.vel.x), s_to_word(s.vel.y), s_to_word(s.vel.z),
        s_to_word(s.waypoint.x), s_to_word(s.waypoint.y), s_to_word(s.waypoint.z),
        s_to_word(s.seg_start.x), s_to_word(s.seg_start.y), s_to_word(s.seg_start.z),
        s.age,
    );
    for (var k = 0u; k < LI_STATE_WORDS; k = k + 1u) {
        if (to_next) {
            li_next[i * LI_STATE_WORDS + k] = w[k];
        } else {
            li_states[i * LI_STATE_WORDS + k] = w[k];
        }
    }
}

// The id of the insect in slot i.
fn li_tick_id(i: u32) -> u32 {
    return li_slots[li_tick.n + i];
}

// ---- the frame (sim.rs, li_frame) ----

// li_frame of the insect in slot i of group g at `me`: the nearest insects strictly within the
// range (squared in S: the group's words), nearest first, ties by id, the surfaces within
// ORCA's reach; returns whether more than FLY_NEIGHBOURS were in range (truncated).
fn li_tick_frame(f: ptr<function, FlyFrame>, i: u32, g: u32, p: LiParams, me: vec3<S>) -> bool {
    let grid = bee_world_grid(BEE_WORLD_H_GRID);
    let q = bee_sense_query(grid, me, s_add(p.range, grid.margin));
    let r2 = li_group_s(g, LI_GROUP_RANGE2);
    var near: BeeSenseSelected;
    var within = 0u;
    for (var z = q.lo.z; z <= q.hi.z; z = z + 1u) {
        for (var y = q.lo.y; y <= q.hi.y; y = y + 1u) {
            let row = bee_world_cell_key(grid, vec3<u32>(q.lo.x, y, z));
            let end = bee_grid_starts[row + q.hi.x - q.lo.x + 1u];
            for (var s = bee_grid_starts[row]; s < end; s = s + 1u) {
                let j = bee_grid_order[s];
                if (j == i) {
                    continue;
                }
                let d = geom_vec3_length_sq(geom_vec3_sub(li_tick_pos(j), me));
                if (d < r2) {
                    within = within + 1u;
                    bee_sense_offer(&near, FLY_NEIGHBOURS, d, li_tick_id(j), j);
                }
            }
        }
    }
    (*f).neighbours_len = near.len;
    for (var k = 0u; k < near.len; k = k + 1u) {
        let j = near.slots[k];
        (*f).neighbours[k] = FlyNeighbour(near.ties[k], li_tick_pos(j), li_tick_vel(j));
    }
    // reach (swarm3d/world.rs): ORCA's radius + τ·v0.
    fly_surfaces_sense(f, me, s_add(li_orca_radius(p), s_mul(p.tau, p.speed)));
    return within > FLY_NEIGHBOURS;
}

// ---- counts ----

// Adds `v` to the u64 of words `at` (low) and `at + 1` (high).
fn li_count64(at: u32, v: u32) {
    let before = atomicAdd(&li_shared[at], v);
    if (before + v < before) {
        atomicAdd(&li_shared[at + 1u], 1u);
    }
}

// Counts `v` of this tick's `at` and of the totals' `total`.
fn li_count(at: u32, total: u32, v: u32) {
    atomicAdd(&li_shared[at], v);
    li_count64(total, v);
}

// ---- the kernels ----

// The cell of every insect's position in the grid.
@compute @workgroup_size(WORKGROUP)
fn li_tick_cells_main(@builtin(global_invocation_id) id: vec3<u32>,
                      @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= li_tick.n) {
        return;
    }
    li_cells[i] = bee_world_cell(li_tick_pos(i));
}

// LiGroup::decide: the frame, the step; the next state and decision as the controller gave
// them (what the mirror compares), the counts (Step3d::count of sim.rs).
@compute @workgroup_size(WORKGROUP)
fn li_tick_step_main(@builtin(global_invocation_id) id: vec3<u32>,
                     @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= li_tick.n) {
        return;
    }
    let g = li_slots[i];
    let p = li_group_params(g);
    let s = li_state_at(i * LI_STATE_WORDS, false);
    var f: FlyFrame;
    let truncated = li_tick_frame(&f, i, g, p, s.pos);
    let c = StepCtx(li_tick.seed, li_tick_id(i), li_tick.step);
    let r = li_step_checked(g, s, &f, p, c);
    li_status[i] = r.status;
    if (r.status != BEE_OK) {
        // The lowest id refused is the one reported (for_each_agent_by, par.rs).
        atomicMax(&li_shared[LI_SHARED_REFUSED], 0xffffffffu - li_tick_id(i));
    }
    li_write_state(i, r.next, true);
    let d = i * LI_DECISION_WORDS;
    li_decisions[d] = s_to_word(r.pref.x);
    li_decisions[d + 1u] = s_to_word(r.pref.y);
    li_decisions[d + 2u] = s_to_word(r.pref.z);
    li_decisions[d + 3u] = r.proposals;
    li_decisions[d + 4u] = select(0u, 1u, r.accepted);
    li_decisions[d + 5u] = select(0u, 1u, r.infeasible);
    li_flags[i] = select(0u, LI_FLAG_TRUNCATED, truncated);
    if (r.proposals > 0u) {
        li_count(LI_SHARED_ARRIVALS, LI_SHARED_TOTAL_ARRIVALS, 1u);
        li_count(LI_SHARED_PROPOSALS, LI_SHARED_TOTAL_PROPOSALS, r.proposals);
        if (!r.accepted) {
            li_count(LI_SHARED_HELD, LI_SHARED_TOTAL_HELD, 1u);
        }
    }
    if (r.infeasible) {
        li_count(LI_SHARED_INFEASIBLE, LI_SHARED_TOTAL_INFEASIBLE, 1u);
    }
    if (truncated) {
        li_count(LI_SHARED_TRUNCATED, LI_SHARED_TOTAL_TRUNCATED, 1u);
    }
}

// LiGroup::commit: the world's corrections of the next state, counted, made current; the
// thread of the refused insect keeps the tick's refusal if none is kept yet.
@compute @workgroup_size(WORKGROUP)
fn li_tick_commit_main(@builtin(global_invocation_id) id: vec3<u32>,
                       @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    let n = li_tick.n;
    if (i >= n) {
        return;
    }
    // The thread of the lowest id refused keeps the tick's refusal (ids are unique: one
    // thread at most), if none is kept yet.
    let refused = atomicLoad(&li_shared[LI_SHARED_REFUSED]);
    let me = li_tick_id(i);
    if (refused != 0u && me == 0xffffffffu - refused
        && atomicLoad(&li_shared[LI_SHARED_KEPT]) == 0u) {
        atomicStore(&li_shared[LI_SHARED_KEPT], 1u);
        atomicStore(&li_shared[LI_SHARED_KEPT_STEP], li_tick.step);
        atomicStore(&li_shared[LI_SHARED_KEPT_ID], me);
        atomicStore(&li_shared[LI_SHARED_KEPT_STATUS], li_status[i]);
    }
    let s = li_state_at(i * LI_STATE_WORDS, true);
    var pos = s.pos;
    var vel = s.vel;
    let fix = space_confine(&pos, &vel, s_from_word(li_tick.offset));
    li_flags[i] = li_flags[i] | fix;
    if (fix != 0u) {
        li_count(LI_SHARED_CORRECTED, LI_SHARED_TOTAL_CORRECTED, 1u);
    }
    li_write_state(i, LiState(pos, vel, s.waypoint, s.seg_start, s.age), false);
}
