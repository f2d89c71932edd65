// The word layout of the bee kernels' buffers (host-sim/src/gpu/shaders.rs, BEE_LAYOUT): the
// values of the bee controller as u32 words, the same layout as host-sim/src/gpu/bee/layout.rs
// (which packs and unpacks them on the host; the word counts are checked against it by a
// test). An `S` is one word (`s_to_word`: the bits of an Fx or of an f32), a bool one word (0 or
// 1); an absent `Option` is a 0 flag and zero words, and the entries of a frame past its length
// are zero words.

// BeeState: pos, vel, forward, density, avoiding, u0, roll, pitch.
const BEE_STATE_WORDS: u32 = 16u;
// BeeDecision: accel, velocity, roll, pitch, avoiding, density.
const BEE_DECISION_WORDS: u32 = 10u;
// BeeParams: its 17 scalars in the Rust order.
const BEE_PARAMS_WORDS: u32 = 17u;
// BeeNeighbor: pos, vel, density.
const BEE_NEIGHBOR_WORDS: u32 = 7u;
// BeeFrame: t, the neighbours' count and BEE_NEIGHBOURS of them, the targets' count and
// BEE_TARGETS of them, the goal (flag, x, y, z), the obstacle (flag, point, normal).
const BEE_FRAME_WORDS: u32 = 174u;

// Where the parts of a frame start.
const BEE_FRAME_NEIGHBOURS: u32 = 2u;
const BEE_FRAME_TARGETS: u32 = 115u;
const BEE_FRAME_GOAL: u32 = 163u;
const BEE_FRAME_OBSTACLE: u32 = 167u;

fn bee_vec3_from_words(x: u32, y: u32, z: u32) -> vec3<S> {
    return vec3<S>(s_from_word(x), s_from_word(y), s_from_word(z));
}

fn bee_bool_word(b: bool) -> u32 {
    return select(0u, 1u, b);
}

fn bee_state_from_words(w: array<u32, BEE_STATE_WORDS>) -> BeeState {
    return BeeState(
        bee_vec3_from_words(w[0], w[1], w[2]),
        bee_vec3_from_words(w[3], w[4], w[5]),
        bee_vec3_from_words(w[6], w[7], w[8]),
        s_from_word(w[9]),
        w[10] != 0u,
        bee_vec3_from_words(w[11], w[12], w[13]),
        s_from_word(w[14]),
        s_from_word(w[15]),
    );
}

fn bee_state_to_words(s: BeeState) -> array<u32, BEE_STATE_WORDS> {
    return array<u32, BEE_STATE_WORDS>(
        s_to_word(s.pos.x),
        s_to_word(s.pos.y),
        s_to_word(s.pos.z),
        s_to_word(s.vel.x),
        s_to_word(s.vel.y),
        s_to_word(s.vel.z),
        s_to_word(s.forward.x),
        s_to_word(s.forward.y),
        s_to_word(s.forward.z),
        s_to_word(s.density),
        bee_bool_word(s.avoiding),
        s_to_word(s.u0.x),
        s_to_word(s.u0.y),
        s_to_word(s.u0.z),
        s_to_word(s.roll),
        s_to_word(s.pitch),
    );
}

fn bee_decision_to_words(d: BeeDecision) -> array<u32, BEE_DECISION_WORDS> {
    return array<u32, BEE_DECISION_WORDS>(
        s_to_word(d.accel.x),
        s_to_word(d.accel.y),
        s_to_word(d.accel.z),
        s_to_word(d.velocity.x),
        s_to_word(d.velocity.y),
        s_to_word(d.velocity.z),
        s_to_word(d.roll),
        s_to_word(d.pitch),
        bee_bool_word(d.avoiding),
        s_to_word(d.density),
    );
}

fn bee_params_from_words(w: array<u32, BEE_PARAMS_WORDS>) -> BeeParams {
    return BeeParams(
        s_from_word(w[0]),
        s_from_word(w[1]),
        s_from_word(w[2]),
        s_from_word(w[3]),
        s_from_word(w[4]),
        s_from_word(w[5]),
        s_from_word(w[6]),
        s_from_word(w[7]),
        s_from_word(w[8]),
        s_from_word(w[9]),
        s_from_word(w[10]),
        s_from_word(w[11]),
        s_from_word(w[12]),
        s_from_word(w[13]),
        s_from_word(w[14]),
        s_from_word(w[15]),
        s_from_word(w[16]),
    );
}

// (A list's length is taken at most its capacity. The words come by pointer: naga copies an
// array passed by value for every access at an index known only at run time.)
fn bee_frame_from_words(w: ptr<function, array<u32, BEE_FRAME_WORDS>>) -> BeeFrame {
    var f: BeeFrame;
    f.t = s_from_word((*w)[0]);
    f.neighbours_len = min((*w)[1], BEE_NEIGHBOURS);
    for (var i = 0u; i < BEE_NEIGHBOURS; i = i + 1u) {
        let b = BEE_FRAME_NEIGHBOURS + i * BEE_NEIGHBOR_WORDS;
        f.neighbours[i] = BeeNeighbor(
            bee_vec3_from_words((*w)[b], (*w)[b + 1u], (*w)[b + 2u]),
            bee_vec3_from_words((*w)[b + 3u], (*w)[b + 4u], (*w)[b + 5u]),
            s_from_word((*w)[b + 6u]),
        );
    }
    f.targets_len = min((*w)[BEE_FRAME_TARGETS - 1u], BEE_TARGETS);
    for (var i = 0u; i < BEE_TARGETS; i = i + 1u) {
        let b = BEE_FRAME_TARGETS + 3u * i;
        f.targets[i] = bee_vec3_from_words((*w)[b], (*w)[b + 1u], (*w)[b + 2u]);
    }
    let g = BEE_FRAME_GOAL;
    f.has_goal = (*w)[g] != 0u;
    f.goal = bee_vec3_from_words((*w)[g + 1u], (*w)[g + 2u], (*w)[g + 3u]);
    let o = BEE_FRAME_OBSTACLE;
    f.has_obstacle = (*w)[o] != 0u;
    f.obstacle = BeeObstacleSense(
        bee_vec3_from_words((*w)[o + 1u], (*w)[o + 2u], (*w)[o + 3u]),
        bee_vec3_from_words((*w)[o + 4u], (*w)[o + 5u], (*w)[o + 6u]),
    );
    return f;
}

// The words of an S, zero for an absent value.
fn bee_word_if(has: bool, v: S) -> u32 {
    return select(0u, s_to_word(v), has);
}

// (By pointer, as bee_frame_from_words; every entry is written, zero words past a list's
// length.)
fn bee_frame_to_words(f: ptr<function, BeeFrame>) -> array<u32, BEE_FRAME_WORDS> {
    var w: array<u32, BEE_FRAME_WORDS>;
    w[0] = s_to_word((*f).t);
    w[1] = (*f).neighbours_len;
    for (var i = 0u; i < BEE_NEIGHBOURS; i = i + 1u) {
        let b = BEE_FRAME_NEIGHBOURS + i * BEE_NEIGHBOR_WORDS;
        let n = (*f).neighbours[i];
        let has = i < (*f).neighbours_len;
        w[b] = bee_word_if(has, n.pos.x);
        w[b + 1u] = bee_word_if(has, n.pos.y);
        w[b + 2u] = bee_word_if(has, n.pos.z);
        w[b + 3u] = bee_word_if(has, n.vel.x);
        w[b + 4u] = bee_word_if(has, n.vel.y);
        w[b + 5u] = bee_word_if(has, n.vel.z);
        w[b + 6u] = bee_word_if(has, n.density);
    }
    w[BEE_FRAME_TARGETS - 1u] = (*f).targets_len;
    for (var i = 0u; i < BEE_TARGETS; i = i + 1u) {
        let b = BEE_FRAME_TARGETS + 3u * i;
        let has = i < (*f).targets_len;
        w[b] = bee_word_if(has, (*f).targets[i].x);
        w[b + 1u] = bee_word_if(has, (*f).targets[i].y);
        w[b + 2u] = bee_word_if(has, (*f).targets[i].z);
    }
    let g = BEE_FRAME_GOAL;
    w[g] = bee_bool_word((*f).has_goal);
    w[g + 1u] = bee_word_if((*f).has_goal, (*f).goal.x);
    w[g + 2u] = bee_word_if((*f).has_goal, (*f).goal.y);
    w[g + 3u] = bee_word_if((*f).has_goal, (*f).goal.z);
    let o = BEE_FRAME_OBSTACLE;
    let h = (*f).has_obstacle;
    w[o] = bee_bool_word(h);
    w[o + 1u] = bee_word_if(h, (*f).obstacle.point.x);
    w[o + 2u] = bee_word_if(h, (*f).obstacle.point.y);
    w[o + 3u] = bee_word_if(h, (*f).obstacle.point.z);
    w[o + 4u] = bee_word_if(h, (*f).obstacle.normal.x);
    w[o + 5u] = bee_word_if(h, (*f).obstacle.normal.y);
    w[o + 6u] = bee_word_if(h, (*f).obstacle.normal.z);
    return w;
}
