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
//    lowest id);
// 3. `bee_tick_commit_main`: the world's corrections (`BeeWorld::confine`: out of every active
//    obstacle, inside the bounds), counted per kind with atomics (sums: any order gives the
//    same counts), the corrected state made current and sensed; the refused bee's thread keeps the first
//    refusal for the host.
//
// The frame times are not computed here: the CPU computes each bee's clock in f64 (`bee_time`,
// `wrap_time`), which WGSL does not have, and the host uploads them every tick (binding 3,
// docs/gpu.md says why).
//
// Bindings (group 0), besides those of bee_sense.wgsl (0-5) and the sensing kernels' output
// (6): 7 the tick's parameters, 8 the states, 9 the decisions, 10 the next states (before the
// world's corrections: what the mirror compares), 11 the status words, 12 the groups'
// parameters, 13 each bee's group, 14 the tick's atomics, 15 the obstacles' confinement boxes (space.wgsl),
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
@group(0) @binding(16) var<storage, read_write> bee_tick_sensed: array<u32>;
@group(0) @binding(17) var<storage, read_write> bee_tick_corrected: array<u32>;

// The words of `bee_tick_shared` (host-sim/src/gpu/bee/engine.rs, SHARED_*): this tick's
// refusal (0xffffffff − the lowest id refused, 0 for none) and corrections (obstacle, bounds), cleared
// by the host every tick; the first refusal kept (a flag, its step, the bee's id and status word); the
// corrections since the start, each a u64 as two words (low, high).
const BEE_TICK_REFUSED: u32 = 0u;
const BEE_TICK_OBSTACLE: u32 = 1u;
const BEE_TICK_BOUNDS: u32 = 2u;
const BEE_TICK_KEPT: u32 = 3u;
const BEE_TICK_KEPT_STEP: u32 = 4u;
const BEE_TICK_KEPT_ID: u32 = 5u;
const BEE_TICK_KEPT_STATUS: u32 = 6u;
const BEE_TICK_TOTAL_OBSTACLE: u32 = 7u;
const BEE_TICK_TOTAL_BOUNDS: u32 = 9u;

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
        // for_each_agent_by (par.rs): the lowest id refused is the error reported.
        atomicMax(&bee_tick_shared[BEE_TICK_REFUSED], 0xffffffffu - bee_sensed_id(i));
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

// BeeWorld::confine (world.rs): the state's position and velocity kept physical by
// `space_confine` (space.wgsl). Returns what was corrected: bit 0 an obstacle, bit 1 the bounds.
fn bee_tick_confine(s: ptr<function, BeeState>) -> u32 {
    var p = (*s).pos;
    var v = (*s).vel;
    let flags = space_confine(&p, &v, s_from_word(bee_tick.offset));
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
// converting back exactly); the thread of the refused bee keeps the tick's refusal if none is
// kept yet.
@compute @workgroup_size(WORKGROUP)
fn bee_tick_commit_main(@builtin(global_invocation_id) id: vec3<u32>,
                        @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    let n = bee_sense_params.n;
    if (i >= n) {
        return;
    }
    // The thread of the lowest id refused keeps the tick's refusal (ids are unique: one
    // thread at most), if none is kept yet.
    let refused = atomicLoad(&bee_tick_shared[BEE_TICK_REFUSED]);
    let me = bee_tick_sensed[BEE_SENSED_ID * n + i];
    if (refused != 0u && me == 0xffffffffu - refused
        && atomicLoad(&bee_tick_shared[BEE_TICK_KEPT]) == 0u) {
        atomicStore(&bee_tick_shared[BEE_TICK_KEPT], 1u);
        atomicStore(&bee_tick_shared[BEE_TICK_KEPT_STEP], bee_tick.step);
        atomicStore(&bee_tick_shared[BEE_TICK_KEPT_ID], me);
        atomicStore(&bee_tick_shared[BEE_TICK_KEPT_STATUS], bee_tick_status[i]);
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
