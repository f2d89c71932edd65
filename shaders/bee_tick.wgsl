// The bee tick of the GPU engine (host-sim/src/gpu/shaders.rs, BEE_TICK;
// host-sim/src/gpu/bee/engine.rs drives it): host-sim/src/bees/sim.rs's `BeeGroup::decide`,
// `confine` and `commit` and `BeeWorld::confine` (host-sim/src/bees/world.rs), one thread per
// bee, over the scalar `S`. The bees' states stay on the GPU between ticks; a tick is
//
// 1. the grid of the sensed positions (`bee_sense_cells_main` of the sensing kernel,
//    `GpuGrid`);
// 2. `bee_tick_step_main`: sense the frame (`bee_sense_frame`, with the bee's frame time and
//    its group's goal from the inputs, binding 3), run `bee_step_checked`, write the status,
//    the decision and the next state as the controller gave them, and note a refusal (the
//    lowest slot);
// 3. `bee_tick_commit_main`: the world's corrections (`BeeWorld::confine`: out of every active
//    obstacle, inside the bounds), counted per kind with atomics (sums: any order gives the
//    same counts), the corrected state made current and sensed; thread 0 keeps the first
//    refusal for the host.
//
// The frame times are not computed here: the CPU computes each bee's clock in f64 (`bee_time`,
// `wrap_time`), which WGSL does not have, and the host uploads them every tick (binding 3,
// docs/gpu.md says why).
//
// Bindings (group 0), besides those of bee_sense.wgsl (0-5) and the sensing kernels' output
// (6): 7 the tick's parameters, 8 the states, 9 the decisions, 10 the next states (before the
// world's corrections: what the mirror compares), 11 the status words, 12 the groups'
// parameters, 13 each bee's group, 14 the tick's atomics, 15 the obstacles' confinement boxes,
// 16 the sensed bees (written; binding 2 reads them), 17 what the world corrected of each bee.

struct BeeTickParams {
    step: u32,
    // SURFACE_OFFSET (world.rs) in S: how far outside the surface `confine` puts a bee (converted
    // on the host, `S::from_f32`, as `confine` converts it).
    offset: u32,
    pad0: u32,
    pad1: u32,
}

@group(0) @binding(7) var<uniform> bee_tick: BeeTickParams;
@group(0) @binding(8) var<storage, read_write> bee_tick_states: array<u32>;
@group(0) @binding(9) var<storage, read_write> bee_tick_decisions: array<u32>;
@group(0) @binding(10) var<storage, read_write> bee_tick_next: array<u32>;
@group(0) @binding(11) var<storage, read_write> bee_tick_status: array<u32>;
@group(0) @binding(12) var<storage, read> bee_tick_params: array<u32>;
@group(0) @binding(13) var<storage, read> bee_tick_group: array<u32>;
@group(0) @binding(14) var<storage, read_write> bee_tick_shared: array<atomic<u32>>;
@group(0) @binding(15) var<storage, read> bee_tick_boxes: array<u32>;
@group(0) @binding(16) var<storage, read_write> bee_tick_sensed: array<u32>;
@group(0) @binding(17) var<storage, read_write> bee_tick_corrected: array<u32>;

// The words of `bee_tick_shared` (host-sim/src/gpu/bee/engine.rs, SHARED_*): this tick's
// refusal (n - the lowest slot refused, 0 for none) and corrections (obstacle, bounds), cleared
// by the host every tick; the first refusal kept (a flag, its step, slot and status word); the
// corrections since the start, each a u64 as two words (low, high).
const BEE_TICK_REFUSED: u32 = 0u;
const BEE_TICK_OBSTACLE: u32 = 1u;
const BEE_TICK_BOUNDS: u32 = 2u;
const BEE_TICK_KEPT: u32 = 3u;
const BEE_TICK_KEPT_STEP: u32 = 4u;
const BEE_TICK_KEPT_SLOT: u32 = 5u;
const BEE_TICK_KEPT_STATUS: u32 = 6u;
const BEE_TICK_TOTAL_OBSTACLE: u32 = 7u;
const BEE_TICK_TOTAL_BOUNDS: u32 = 9u;

// Words of an obstacle's confinement box (engine.rs, BOX_WORDS): whether no point of S passes
// (`never`), then per axis the least value of S at or above the bounding box's low side less
// 1e-3 (in f64) and the greatest at or below its high side plus 1e-3.
const BEE_TICK_BOX_WORDS: u32 = 7u;

// The current state of the bee in slot i.
fn bee_tick_state(i: u32) -> BeeState {
    var w: array<u32, BEE_STATE_WORDS>;
    for (var k = 0u; k < BEE_STATE_WORDS; k = k + 1u) {
        w[k] = bee_tick_states[i * BEE_STATE_WORDS + k];
    }
    return bee_state_from_words(w);
}

// The next state of the bee in slot i, as its controller gave it.
fn bee_tick_next_state(i: u32) -> BeeState {
    var w: array<u32, BEE_STATE_WORDS>;
    for (var k = 0u; k < BEE_STATE_WORDS; k = k + 1u) {
        w[k] = bee_tick_next[i * BEE_STATE_WORDS + k];
    }
    return bee_state_from_words(w);
}

// The parameters of the group of the bee in slot `i` (validated on the host: `Checked`).
fn bee_tick_params_of(i: u32) -> BeeParams {
    let b = bee_tick_group[i] * BEE_PARAMS_WORDS;
    var w: array<u32, BEE_PARAMS_WORDS>;
    for (var k = 0u; k < BEE_PARAMS_WORDS; k = k + 1u) {
        w[k] = bee_tick_params[b + k];
    }
    return bee_params_from_words(w);
}

// BeeGroup::decide (sim.rs) for the bee in slot i: its frame (`fill_frame`: the sensed world of
// the last tick, its own clock, its group's goal), then `step_with` (`bee_step_checked`: the
// same bits, the constants of the step computed from the frame's time).
@compute @workgroup_size(WORKGROUP)
fn bee_tick_step_main(@builtin(global_invocation_id) id: vec3<u32>,
                      @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    let n = bee_sense_params.n;
    if (i >= n) {
        return;
    }
    var frame = bee_sense_frame(i, bee_input_goal(i), bee_input_t(i));
    let r = bee_step_checked(bee_tick_state(i), &frame, bee_tick_params_of(i));
    bee_tick_status[i] = r.status;
    if (r.status != BEE_OK) {
        // for_each_agent (par.rs): the lowest slot refused is the error reported.
        atomicMax(&bee_tick_shared[BEE_TICK_REFUSED], n - i);
    }
    let d = bee_decision_to_words(r.decision);
    for (var k = 0u; k < BEE_DECISION_WORDS; k = k + 1u) {
        bee_tick_decisions[i * BEE_DECISION_WORDS + k] = d[k];
    }
    let s = bee_state_to_words(r.state);
    for (var k = 0u; k < BEE_STATE_WORDS; k = k + 1u) {
        bee_tick_next[i * BEE_STATE_WORDS + k] = s[k];
    }
}

// BeeObstacle::may_be_within(p, 0.0) (world.rs) of obstacle `k`: p within the bounding box
// widened by 1e-3 on every axis, compared in f64 on the CPU. A value of S converts to f64
// exactly, so `p ≥ lo - 1e-3` holds exactly when p ≥ the least S at or above `lo - 1e-3`
// (computed on the host in f64, engine.rs `confine_boxes`), and likewise above: the same test,
// in S.
fn bee_tick_may_be_within(k: u32, p: vec3<S>) -> bool {
    let b = k * BEE_TICK_BOX_WORDS;
    if (bee_tick_boxes[b] != 0u) {
        return false;
    }
    let lo = bee_vec3_from_words(bee_tick_boxes[b + 1u], bee_tick_boxes[b + 2u],
                                 bee_tick_boxes[b + 3u]);
    let hi = bee_vec3_from_words(bee_tick_boxes[b + 4u], bee_tick_boxes[b + 5u],
                                 bee_tick_boxes[b + 6u]);
    return all(p >= lo) && all(p <= hi);
}

// BeeWorld::confine (world.rs): keeps a bee's new state physical, in the bee's scalar: out of
// every active obstacle it is inside (put back on the surface, SURFACE_OFFSET along the
// outward normal, the inward normal velocity removed) and inside the bounds (clamped, the
// outward velocity removed), at most four rounds, until a round moves nothing. Returns what was
// corrected: bit 0 an obstacle, bit 1 the bounds (the state changes only if something was).
fn bee_tick_confine(s: ptr<function, BeeState>) -> u32 {
    var p = (*s).pos;
    var v = (*s).vel;
    let offset = s_from_word(bee_tick.offset);
    let lo = bee_world_min();
    let hi = bee_world_max();
    var flags = 0u;
    for (var round = 0u; round < 4u; round = round + 1u) {
        var moved = false;
        for (var k = 0u; k < bee_world_obstacles(); k = k + 1u) {
            let o = bee_world_obstacle(k);
            if (!o.present || !bee_tick_may_be_within(k, p)) {
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
        (*s).pos = p;
        (*s).vel = v;
    }
    return flags;
}

// Adds one to the u64 of words `at` (low) and `at + 1` (high): the add that wraps the low word
// carries.
fn bee_tick_count64(at: u32) {
    if (atomicAdd(&bee_tick_shared[at], 1u) == 0xffffffffu) {
        atomicAdd(&bee_tick_shared[at + 1u], 1u);
    }
}

// BeeGroup::confine and BeeGroup::commit (sim.rs), and BeeSim::publish's counts: the world's
// corrections of the next state of the bee in slot i (`BeeWorld::confine`), noted
// (`corrected`) and counted per kind (`Contacts`: this tick's and since the start), the state
// made current and sensed (`Sensed::write`: the sensed words are the state's, the sensed `f64`
// converting back exactly); thread 0 keeps the tick's refusal if none is kept yet.
@compute @workgroup_size(WORKGROUP)
fn bee_tick_commit_main(@builtin(global_invocation_id) id: vec3<u32>,
                        @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    let n = bee_sense_params.n;
    if (i == 0u && atomicLoad(&bee_tick_shared[BEE_TICK_KEPT]) == 0u) {
        let refused = atomicLoad(&bee_tick_shared[BEE_TICK_REFUSED]);
        if (refused != 0u) {
            let slot = n - refused;
            atomicStore(&bee_tick_shared[BEE_TICK_KEPT], 1u);
            atomicStore(&bee_tick_shared[BEE_TICK_KEPT_STEP], bee_tick.step);
            atomicStore(&bee_tick_shared[BEE_TICK_KEPT_SLOT], slot);
            atomicStore(&bee_tick_shared[BEE_TICK_KEPT_STATUS], bee_tick_status[slot]);
        }
    }
    if (i >= n) {
        return;
    }
    var s = bee_tick_next_state(i);
    let fix = bee_tick_confine(&s);
    bee_tick_corrected[i] = fix;
    if ((fix & 1u) != 0u) {
        atomicAdd(&bee_tick_shared[BEE_TICK_OBSTACLE], 1u);
        bee_tick_count64(BEE_TICK_TOTAL_OBSTACLE);
    }
    if ((fix & 2u) != 0u) {
        atomicAdd(&bee_tick_shared[BEE_TICK_BOUNDS], 1u);
        bee_tick_count64(BEE_TICK_TOTAL_BOUNDS);
    }
    let w = bee_state_to_words(s);
    for (var k = 0u; k < BEE_STATE_WORDS; k = k + 1u) {
        bee_tick_states[i * BEE_STATE_WORDS + k] = w[k];
    }
    // The sensed bee (world.rs, Sensed::write): position, velocity, density (the id stays).
    for (var k = 0u; k < 3u; k = k + 1u) {
        bee_tick_sensed[BEE_SENSED_POS * n + 3u * i + k] = w[k];
        bee_tick_sensed[BEE_SENSED_VEL * n + 3u * i + k] = w[3u + k];
    }
    bee_tick_sensed[BEE_SENSED_DENSITY * n + i] = w[9];
}
