// The ant tick of the GPU engine (host-sim/src/gpu/shaders.rs, ANT_TICK;
// host-sim/src/gpu/ant/engine.rs drives it): host-sim/src/ants/sim.rs's `AntGroup::plan`,
// `resolve` and `commit` and `AntSim::consume_food`, one thread per ant (or per object), over
// the scalar `S`. The ants' states stay on the GPU between ticks; a tick is
//
// 1. the grid of the sensed positions (`ant_sense_cells_main`, `GpuGrid`);
// 2. `ant_tick_plan_main`: sense the plan frame (`ant_plan_frame`; an ant that stays stopped
//    reads none, as on the CPU), run `ant_plan_checked`, write the plan and the prediction, and
//    raise the tick's largest shift between a prediction and its ant (which widens the resolve
//    frames' query);
// 3. `ant_tick_resolve_main`: sense the resolve frame (none for a stopped plan), run
//    `ant_resolve_checked`, write the next state;
// 4. `ant_tick_commit_main`: the events (a collecting or dropping stop that ended), a route's
//    way point passed with the probability of `ROUTE_ADVANCE` (an integer threshold on the
//    random word, computed on the host from the `f32` rule: the same draws), the counts per
//    place, the next state made current and sensed;
// 5. `ant_tick_end_main`: food taken (the collections of the tick, in any order: a saturating
//    subtraction of their count), and the first refusal kept for the host.
//
// Bindings (group 0), besides those of ant_sense.wgsl (0-5, 24-28) and the frames' output (6):
// 7 the tick's parameters, 8 the states, 9 the plans, 10 the predictions (written; binding 3
// reads them), 11 the next states, 12 the status words (two an ant: plan, resolve), 13 the
// groups' parameters, 14 each ant's group, 15 the tick's atomics, 16 the counts per place, 17
// and 29-33 the sensed ants' arrays (written; 2 and 24-28 read them), 18 the world (written;
// binding 1 reads it), 35 the chunk.
//
// The states, plans and next states (20 or 22 words an ant) are bound a chunk of ants at a time
// (AntChunk: a dispatch per chunk), so that no binding exceeds the adapter's largest (128 MiB
// on lavapipe: 1.5 million ants); thread `l` of a chunk serves ant `first + l`, its own words
// at `l` in those three, every other array by the ant's slot.

struct AntTickParams {
    seed: u32,
    step: u32,
    // A route's way point is passed when the random word's top 24 bits are below this
    // (rand::chance::<f32> of ROUTE_ADVANCE as an integer rule, engine.rs `route_threshold`).
    route_below: u32,
    // The places (object ids) counted: ids 0..places.
    places: u32,
}

// The ants `first..first + len` a dispatch serves.
struct AntChunk {
    first: u32,
    len: u32,
    pad0: u32,
    pad1: u32,
}

@group(0) @binding(7) var<uniform> ant_tick: AntTickParams;
@group(0) @binding(35) var<uniform> ant_chunk: AntChunk;
@group(0) @binding(8) var<storage, read_write> ant_tick_states: array<u32>;
@group(0) @binding(9) var<storage, read_write> ant_tick_plans: array<u32>;
@group(0) @binding(10) var<storage, read_write> ant_tick_predicted: array<u32>;
@group(0) @binding(11) var<storage, read_write> ant_tick_next: array<u32>;
@group(0) @binding(12) var<storage, read_write> ant_tick_status: array<u32>;
@group(0) @binding(13) var<storage, read> ant_tick_params: array<u32>;
@group(0) @binding(14) var<storage, read> ant_tick_group: array<u32>;
@group(0) @binding(15) var<storage, read_write> ant_tick_shared: array<atomic<u32>>;
@group(0) @binding(16) var<storage, read_write> ant_tick_counts: array<atomic<u32>>;
@group(0) @binding(17) var<storage, read_write> ant_tick_sensed_pos: array<u32>;
@group(0) @binding(29) var<storage, read_write> ant_tick_sensed_arrival: array<u32>;
@group(0) @binding(30) var<storage, read_write> ant_tick_sensed_ids: array<u32>;
@group(0) @binding(31) var<storage, read_write> ant_tick_sensed_labels: array<u32>;
@group(0) @binding(32) var<storage, read_write> ant_tick_sensed_nests: array<u32>;
@group(0) @binding(33) var<storage, read_write> ant_tick_sensed_origins: array<u32>;
@group(0) @binding(18) var<storage, read_write> ant_tick_world: array<u32>;

// The words of `ant_tick_shared` (host-sim/src/gpu/ant/engine.rs, SHARED_*): the tick's
// largest shift (the word of a non-negative S: its order is the order of the values), the
// refusals of the plan and the resolve phase (0xffffffff − the lowest id refused, 0 for
// none), and the
// first refusal kept (a flag, its step, phase, slot and status word).
const ANT_TICK_SHIFT: u32 = 0u;
const ANT_TICK_PLAN_REFUSED: u32 = 1u;
const ANT_TICK_RESOLVE_REFUSED: u32 = 2u;
const ANT_TICK_KEPT: u32 = 3u;
const ANT_TICK_KEPT_STEP: u32 = 4u;
const ANT_TICK_KEPT_PHASE: u32 = 5u;
const ANT_TICK_KEPT_SLOT: u32 = 6u;
const ANT_TICK_KEPT_STATUS: u32 = 7u;

// The state of the chunk's ant `l`.
fn ant_tick_state(l: u32) -> AntState {
    var w: array<u32, ANT_STATE_WORDS>;
    for (var k = 0u; k < ANT_STATE_WORDS; k = k + 1u) {
        w[k] = ant_tick_states[l * ANT_STATE_WORDS + k];
    }
    return ant_state_from_words(w);
}

fn ant_tick_params_of(i: u32) -> AntParams {
    let b = ant_tick_group[i] * ANT_PARAMS_WORDS;
    var w: array<u32, ANT_PARAMS_WORDS>;
    for (var k = 0u; k < ANT_PARAMS_WORDS; k = k + 1u) {
        w[k] = ant_tick_params[b + k];
    }
    return ant_params_from_words(w);
}

// Notes a refusal of slot `i` in the phase's word: the lowest id wins (for_each_agent_by,
// par.rs: the CPU's slots move, these do not).
fn ant_tick_refused(word: u32, i: u32) {
    atomicMax(&ant_tick_shared[word], 0xffffffffu - ant_sensed_field(ANT_SENSED_ID, i));
}

// The slot of ant `id` (slots never move here; looked up only for a refusal, which ends the
// run).
fn ant_tick_slot_of(id: u32) -> u32 {
    for (var i = 0u; i < ant_sense_params.n; i = i + 1u) {
        if (ant_sensed_field(ANT_SENSED_ID, i) == id) {
            return i;
        }
    }
    return 0u;
}

@compute @workgroup_size(WORKGROUP)
fn ant_tick_plan_main(@builtin(global_invocation_id) id: vec3<u32>,
                      @builtin(num_workgroups) groups: vec3<u32>) {
    let l = thread_index(id, groups);
    if (l >= ant_chunk.len) {
        return;
    }
    let i = ant_chunk.first + l;
    let state = ant_tick_state(l);
    // An ant that stays stopped this tick reads nothing of its frame (xiang2018 §4.1).
    var frame: AntPlanFrame;
    if (state.has_stop && state.stop.remaining > 1u) {
        frame.bounds = ant_world_bounds();
    } else {
        frame = ant_plan_frame(i);
    }
    let ctx = StepCtx(ant_tick.seed, ant_sensed_field(ANT_SENSED_ID, i), ant_tick.step);
    let r = ant_plan_checked(state, &frame, ant_tick_params_of(i), ctx);
    ant_tick_status[2u * i] = r.status;
    if (r.status != ANT_OK) {
        ant_tick_refused(ANT_TICK_PLAN_REFUSED, i);
    }
    let w = ant_plan_to_words(r.plan);
    for (var k = 0u; k < ANT_PLAN_WORDS; k = k + 1u) {
        ant_tick_plans[l * ANT_PLAN_WORDS + k] = w[k];
    }
    ant_tick_predicted[2u * i] = w[ANT_STATE_WORDS];
    ant_tick_predicted[2u * i + 1u] = w[ANT_STATE_WORDS + 1u];
    // |dx| + |dy| bounds the distance (a larger query only narrows less).
    let d = geom_sub(r.plan.predicted, ant_sensed_pos(i));
    let shift = s_add(s_abs(d.x), s_abs(d.y));
    if (r.status == ANT_OK) {
        atomicMax(&ant_tick_shared[ANT_TICK_SHIFT], s_to_word(shift));
    }
}

@compute @workgroup_size(WORKGROUP)
fn ant_tick_resolve_main(@builtin(global_invocation_id) id: vec3<u32>,
                         @builtin(num_workgroups) groups: vec3<u32>) {
    let l = thread_index(id, groups);
    if (l >= ant_chunk.len) {
        return;
    }
    let i = ant_chunk.first + l;
    var pw: array<u32, ANT_PLAN_WORDS>;
    for (var k = 0u; k < ANT_PLAN_WORDS; k = k + 1u) {
        pw[k] = ant_tick_plans[l * ANT_PLAN_WORDS + k];
    }
    let plan = ant_plan_from_words(pw);
    // A stopped ant does not move: its resolve frame is never read.
    var frame: AntResolveFrame;
    if (ant_state_is_stopped(plan.state)) {
        frame.bounds = ant_world_bounds();
    } else {
        frame = ant_resolve_frame(i);
    }
    let r = ant_resolve_checked(plan, &frame, ant_tick_params_of(i));
    ant_tick_status[2u * i + 1u] = r.status;
    if (r.status != ANT_OK) {
        ant_tick_refused(ANT_TICK_RESOLVE_REFUSED, i);
    }
    let w = ant_state_to_words(r.state);
    for (var k = 0u; k < ANT_STATE_WORDS; k = k + 1u) {
        ant_tick_next[l * ANT_STATE_WORDS + k] = w[k];
    }
}

// Whether way point `place` is on the route.
fn ant_tick_on_route(place: u32) -> bool {
    let at = ant_world[ANT_WORLD_H_ROUTE_AT];
    for (var k = 0u; k < ant_world[ANT_WORLD_H_ROUTE]; k = k + 1u) {
        if (ant_world[at + k] == place) {
            return true;
        }
    }
    return false;
}

// Counts one event at `place` in the counts' array `which` (0 collections, 1 deliveries).
fn ant_tick_count(which: u32, place: u32) {
    if (place < ant_tick.places) {
        atomicAdd(&ant_tick_counts[which * ant_tick.places + place], 1u);
    }
}

@compute @workgroup_size(WORKGROUP)
fn ant_tick_commit_main(@builtin(global_invocation_id) id: vec3<u32>,
                        @builtin(num_workgroups) groups: vec3<u32>) {
    let l = thread_index(id, groups);
    if (l >= ant_chunk.len) {
        return;
    }
    let i = ant_chunk.first + l;
    let old = ant_tick_state(l);
    var w: array<u32, ANT_STATE_WORDS>;
    for (var k = 0u; k < ANT_STATE_WORDS; k = k + 1u) {
        w[k] = ant_tick_next[l * ANT_STATE_WORDS + k];
    }
    var s = ant_state_from_words(w);
    let agent = ant_tick_sensed_ids[i];
    // sim.rs `event`: the end of a collecting or dropping stop that changed the label.
    if (old.has_stop && !s.has_stop) {
        let place = old.stop.place;
        if (old.stop.reason == ANT_STOP_COLLECTING_FOOD && s.label == ANT_LABEL_FOOD) {
            ant_tick_count(0u, place);
            let r = rand_rand(ant_tick.seed, agent, ant_tick.step, ANT_TICK_ROUTE_STREAM);
            if (ant_tick_on_route(place) && (r >> 8u) < ant_tick.route_below) {
                // sim.rs `advance`: the next leg starts here.
                s.nest = place;
                s.origin = place;
                s.label = ANT_LABEL_NEST;
                s.arrival = s.pos;
                s.heading = geom_neg(s.heading);
            }
        } else if (old.stop.reason == ANT_STOP_DROPPING_FOOD && s.label == ANT_LABEL_NEST) {
            ant_tick_count(1u, place);
        }
    }
    w = ant_state_to_words(s);
    for (var k = 0u; k < ANT_STATE_WORDS; k = k + 1u) {
        ant_tick_states[l * ANT_STATE_WORDS + k] = w[k];
    }
    // The sensed ant (world.rs, SensedAnts::write).
    ant_tick_sensed_pos[2u * i] = w[0];
    ant_tick_sensed_pos[2u * i + 1u] = w[1];
    ant_tick_sensed_arrival[2u * i] = w[7];
    ant_tick_sensed_arrival[2u * i + 1u] = w[8];
    ant_tick_sensed_labels[i] = s.label;
    ant_tick_sensed_nests[i] = s.nest;
    ant_tick_sensed_origins[i] = s.origin;
}

// The random stream of the route decisions (sim.rs, ROUTE_STREAM).
const ANT_TICK_ROUTE_STREAM: u32 = 0x5200u;

// One thread per object (at least one): food sources with an amount lose what was collected
// this tick and disappear when empty (AntSim::consume_food); thread 0 keeps the tick's first
// refusal if none is kept yet (the plan's before the resolve's, the lowest id).
@compute @workgroup_size(WORKGROUP)
fn ant_tick_end_main(@builtin(global_invocation_id) id: vec3<u32>,
                     @builtin(num_workgroups) groups: vec3<u32>) {
    let k = thread_index(id, groups);
    let objects = ant_tick_world[ANT_WORLD_H_OBJECTS];
    if (k < objects) {
        let b = ant_tick_world[ANT_WORLD_H_OBJECTS_AT] + k * ANT_WORLD_OBJECT_WORDS;
        let oid = ant_tick_world[b + 1u];
        let amount = ant_tick_world[b + 3u];
        if (ant_tick_world[b] == ANT_WORLD_FOOD && amount != ANT_WORLD_AMOUNT_ENDLESS
            && oid < ant_tick.places) {
            let taken = atomicLoad(&ant_tick_counts[oid]);
            if (taken > 0u) {
                let left = select(0u, amount - taken, amount > taken);
                ant_tick_world[b + 3u] = left;
                if (left == 0u) {
                    ant_tick_world[b + 2u] = 0u;
                }
            }
        }
    }
    if (k != 0u || atomicLoad(&ant_tick_shared[ANT_TICK_KEPT]) != 0u) {
        return;
    }
    let n = ant_sense_params.n;
    let plan = atomicLoad(&ant_tick_shared[ANT_TICK_PLAN_REFUSED]);
    let resolve = atomicLoad(&ant_tick_shared[ANT_TICK_RESOLVE_REFUSED]);
    var phase = 0u;
    var refused = plan;
    if (plan == 0u) {
        phase = 1u;
        refused = resolve;
    }
    if (refused != 0u) {
        let slot = ant_tick_slot_of(0xffffffffu - refused);
        atomicStore(&ant_tick_shared[ANT_TICK_KEPT], 1u);
        atomicStore(&ant_tick_shared[ANT_TICK_KEPT_STEP], ant_tick.step);
        atomicStore(&ant_tick_shared[ANT_TICK_KEPT_PHASE], phase);
        atomicStore(&ant_tick_shared[ANT_TICK_KEPT_SLOT], slot);
        atomicStore(&ant_tick_shared[ANT_TICK_KEPT_STATUS], ant_tick_status[2u * slot + phase]);
    }
}
