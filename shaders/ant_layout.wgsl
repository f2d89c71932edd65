// The word layout of the ant kernels' buffers (host-sim/src/gpu/shaders.rs, ANT_LAYOUT): the
// values of the ant controller as u32 words, the same layout as
// host-sim/src/gpu/ant/layout.rs (which packs and unpacks them on the host; the word counts are
// checked against it by a test). An `S` is one word (`s_to_word`: the bits of an Fx or of an
// f32), an enum its discriminant, a u16 or a bool one word (0 or 1); an absent `Option` is a 0
// flag and zero words, and the entries of a frame past its length are zero words.

// AntState: pos, heading, label, nest, origin, arrival, goal (flag, x, y), follow (flag, turn,
// winding), motion, stop (flag, reason, remaining, place).
const ANT_STATE_WORDS: u32 = 20u;
// AntPlan: the state, then predicted.
const ANT_PLAN_WORDS: u32 = 22u;
// AntParams: speed, dt, theta, p_stop, casual_stop_ticks, collect_ticks, drop_ticks,
// contact_range, avoid_range, collision_range, w0, c, k.
const ANT_PARAMS_WORDS: u32 = 13u;
// AntNeighbor: id, pos, label, nest, origin, arrival.
const ANT_NEIGHBOR_WORDS: u32 = 8u;
// AntObject: kind, id, closest or center, normal, radius.
const ANT_OBJECT_WORDS: u32 = 7u;
// Surface: closest, normal.
const ANT_SURFACE_WORDS: u32 = 4u;
// PlanFrame: bounds (min, max), the neighbours' count and ANT_NEIGHBOURS of them, the objects'
// count and ANT_OBJECTS of them.
const ANT_PLAN_FRAME_WORDS: u32 = 98u;
// ResolveFrame: bounds, the neighbours' count and ANT_NEIGHBOURS predictions, the obstacles'
// count and ANT_SURFACES surfaces.
const ANT_RESOLVE_FRAME_WORDS: u32 = 46u;
// StepCtx: seed, agent, step.
const ANT_CTX_WORDS: u32 = 3u;

// Where the lists of the frames start.
const ANT_PLAN_FRAME_NEIGHBOURS: u32 = 5u;
const ANT_PLAN_FRAME_OBJECTS: u32 = 70u;
const ANT_RESOLVE_FRAME_NEIGHBOURS: u32 = 5u;
const ANT_RESOLVE_FRAME_OBSTACLES: u32 = 22u;

fn ant_vec2_from_words(x: u32, y: u32) -> vec2<S> {
    return vec2<S>(s_from_word(x), s_from_word(y));
}

// The words of an S, zero for an absent value.
fn ant_word_if(has: bool, v: S) -> u32 {
    return select(0u, s_to_word(v), has);
}

fn ant_state_from_words(w: array<u32, ANT_STATE_WORDS>) -> AntState {
    return AntState(
        ant_vec2_from_words(w[0], w[1]),
        ant_vec2_from_words(w[2], w[3]),
        w[4],
        w[5],
        w[6],
        ant_vec2_from_words(w[7], w[8]),
        w[9] != 0u,
        ant_vec2_from_words(w[10], w[11]),
        w[12] != 0u,
        AntFollow(w[13], s_from_word(w[14])),
        w[15],
        w[16] != 0u,
        AntStopTimer(w[17], w[18], w[19]),
    );
}

fn ant_state_to_words(s: AntState) -> array<u32, ANT_STATE_WORDS> {
    let g = s.has_goal;
    let f = s.has_follow;
    let t = s.has_stop;
    return array<u32, ANT_STATE_WORDS>(
        s_to_word(s.pos.x),
        s_to_word(s.pos.y),
        s_to_word(s.heading.x),
        s_to_word(s.heading.y),
        s.label,
        s.nest,
        s.origin,
        s_to_word(s.arrival.x),
        s_to_word(s.arrival.y),
        select(0u, 1u, g),
        ant_word_if(g, s.goal.x),
        ant_word_if(g, s.goal.y),
        select(0u, 1u, f),
        select(0u, s.follow.turn, f),
        ant_word_if(f, s.follow.winding),
        s.motion,
        select(0u, 1u, t),
        select(0u, s.stop.reason, t),
        select(0u, s.stop.remaining, t),
        select(0u, s.stop.place, t),
    );
}

fn ant_plan_from_words(w: array<u32, ANT_PLAN_WORDS>) -> AntPlan {
    var state: array<u32, ANT_STATE_WORDS>;
    for (var k = 0u; k < ANT_STATE_WORDS; k = k + 1u) {
        state[k] = w[k];
    }
    return AntPlan(ant_state_from_words(state), ant_vec2_from_words(w[20], w[21]));
}

fn ant_plan_to_words(p: AntPlan) -> array<u32, ANT_PLAN_WORDS> {
    let state = ant_state_to_words(p.state);
    var w: array<u32, ANT_PLAN_WORDS>;
    for (var k = 0u; k < ANT_STATE_WORDS; k = k + 1u) {
        w[k] = state[k];
    }
    w[20] = s_to_word(p.predicted.x);
    w[21] = s_to_word(p.predicted.y);
    return w;
}

fn ant_params_from_words(w: array<u32, ANT_PARAMS_WORDS>) -> AntParams {
    return AntParams(
        s_from_word(w[0]),
        s_from_word(w[1]),
        s_from_word(w[2]),
        s_from_word(w[3]),
        w[4],
        w[5],
        w[6],
        s_from_word(w[7]),
        s_from_word(w[8]),
        s_from_word(w[9]),
        s_from_word(w[10]),
        s_from_word(w[11]),
        w[12],
    );
}

fn ant_ctx_from_words(w: array<u32, ANT_CTX_WORDS>) -> StepCtx {
    return StepCtx(w[0], w[1], w[2]);
}

fn ant_rect_from_words(a: u32, b: u32, c: u32, d: u32) -> GeomRect {
    return GeomRect(ant_vec2_from_words(a, b), ant_vec2_from_words(c, d));
}

// (A list's length is taken at most its capacity.)
fn ant_plan_frame_from_words(w: array<u32, ANT_PLAN_FRAME_WORDS>) -> AntPlanFrame {
    var f: AntPlanFrame;
    f.bounds = ant_rect_from_words(w[0], w[1], w[2], w[3]);
    f.neighbours_len = min(w[4], ANT_NEIGHBOURS);
    for (var i = 0u; i < ANT_NEIGHBOURS; i = i + 1u) {
        let b = ANT_PLAN_FRAME_NEIGHBOURS + i * ANT_NEIGHBOR_WORDS;
        f.neighbours[i] = AntNeighbor(
            w[b],
            ant_vec2_from_words(w[b + 1u], w[b + 2u]),
            w[b + 3u],
            w[b + 4u],
            w[b + 5u],
            ant_vec2_from_words(w[b + 6u], w[b + 7u]),
        );
    }
    f.objects_len = min(w[ANT_PLAN_FRAME_OBJECTS - 1u], ANT_OBJECTS);
    for (var i = 0u; i < ANT_OBJECTS; i = i + 1u) {
        let b = ANT_PLAN_FRAME_OBJECTS + i * ANT_OBJECT_WORDS;
        let a = ant_vec2_from_words(w[b + 2u], w[b + 3u]);
        let n = ant_vec2_from_words(w[b + 4u], w[b + 5u]);
        f.objects[i] = AntObject(w[b], w[b + 1u], AntSurface(a, n), a, s_from_word(w[b + 6u]));
    }
    return f;
}

fn ant_plan_frame_to_words(f: AntPlanFrame) -> array<u32, ANT_PLAN_FRAME_WORDS> {
    var w: array<u32, ANT_PLAN_FRAME_WORDS>;
    w[0] = s_to_word(f.bounds.min.x);
    w[1] = s_to_word(f.bounds.min.y);
    w[2] = s_to_word(f.bounds.max.x);
    w[3] = s_to_word(f.bounds.max.y);
    w[4] = f.neighbours_len;
    for (var i = 0u; i < f.neighbours_len; i = i + 1u) {
        let b = ANT_PLAN_FRAME_NEIGHBOURS + i * ANT_NEIGHBOR_WORDS;
        let n = f.neighbours[i];
        w[b] = n.id;
        w[b + 1u] = s_to_word(n.pos.x);
        w[b + 2u] = s_to_word(n.pos.y);
        w[b + 3u] = n.label;
        w[b + 4u] = n.nest;
        w[b + 5u] = n.origin;
        w[b + 6u] = s_to_word(n.arrival.x);
        w[b + 7u] = s_to_word(n.arrival.y);
    }
    w[ANT_PLAN_FRAME_OBJECTS - 1u] = f.objects_len;
    for (var i = 0u; i < f.objects_len; i = i + 1u) {
        let b = ANT_PLAN_FRAME_OBJECTS + i * ANT_OBJECT_WORDS;
        let o = f.objects[i];
        w[b] = o.kind;
        if (o.kind == ANT_OBJECT_OBSTACLE) {
            w[b + 2u] = s_to_word(o.surface.closest.x);
            w[b + 3u] = s_to_word(o.surface.closest.y);
            w[b + 4u] = s_to_word(o.surface.normal.x);
            w[b + 5u] = s_to_word(o.surface.normal.y);
        } else {
            w[b + 1u] = select(o.id, 0u, o.kind == ANT_OBJECT_DISTURBANCE);
            w[b + 2u] = s_to_word(o.center.x);
            w[b + 3u] = s_to_word(o.center.y);
            w[b + 6u] = s_to_word(o.radius);
        }
    }
    return w;
}

fn ant_resolve_frame_from_words(w: array<u32, ANT_RESOLVE_FRAME_WORDS>) -> AntResolveFrame {
    var f: AntResolveFrame;
    f.bounds = ant_rect_from_words(w[0], w[1], w[2], w[3]);
    f.neighbours_len = min(w[4], ANT_NEIGHBOURS);
    for (var i = 0u; i < ANT_NEIGHBOURS; i = i + 1u) {
        let b = ANT_RESOLVE_FRAME_NEIGHBOURS + 2u * i;
        f.neighbours[i] = ant_vec2_from_words(w[b], w[b + 1u]);
    }
    f.obstacles_len = min(w[ANT_RESOLVE_FRAME_OBSTACLES - 1u], ANT_SURFACES);
    for (var i = 0u; i < ANT_SURFACES; i = i + 1u) {
        let b = ANT_RESOLVE_FRAME_OBSTACLES + i * ANT_SURFACE_WORDS;
        f.obstacles[i] = AntSurface(
            ant_vec2_from_words(w[b], w[b + 1u]),
            ant_vec2_from_words(w[b + 2u], w[b + 3u]),
        );
    }
    return f;
}

fn ant_resolve_frame_to_words(f: AntResolveFrame) -> array<u32, ANT_RESOLVE_FRAME_WORDS> {
    var w: array<u32, ANT_RESOLVE_FRAME_WORDS>;
    w[0] = s_to_word(f.bounds.min.x);
    w[1] = s_to_word(f.bounds.min.y);
    w[2] = s_to_word(f.bounds.max.x);
    w[3] = s_to_word(f.bounds.max.y);
    w[4] = f.neighbours_len;
    for (var i = 0u; i < f.neighbours_len; i = i + 1u) {
        let b = ANT_RESOLVE_FRAME_NEIGHBOURS + 2u * i;
        w[b] = s_to_word(f.neighbours[i].x);
        w[b + 1u] = s_to_word(f.neighbours[i].y);
    }
    w[ANT_RESOLVE_FRAME_OBSTACLES - 1u] = f.obstacles_len;
    for (var i = 0u; i < f.obstacles_len; i = i + 1u) {
        let b = ANT_RESOLVE_FRAME_OBSTACLES + i * ANT_SURFACE_WORDS;
        let s = f.obstacles[i];
        w[b] = s_to_word(s.closest.x);
        w[b + 1u] = s_to_word(s.closest.y);
        w[b + 2u] = s_to_word(s.normal.x);
        w[b + 3u] = s_to_word(s.normal.y);
    }
    return w;
}
