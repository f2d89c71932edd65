// Interactions (host-sim/src/gpu/shaders.rs, ANT_INTERACT): `swarm_core::ant::interact`
// (core-nostd/src/ant/interact.rs; xiang2018 §4.2), over the scalar `S`: information transfer
// with neighbours (Table 1) and the environment with priority obstacles > disturbance >
// food = nest (Fig. 4b).

// EnvAction's variants, the `kind` of an AntEnvAction.
const ANT_ENV_NONE: u32 = 0u;
const ANT_ENV_AVOID: u32 = 1u;
const ANT_ENV_ESCAPE: u32 = 2u;
const ANT_ENV_COLLECT: u32 = 3u;
const ANT_ENV_DROP: u32 = 4u;
const ANT_ENV_AT_NEST: u32 = 5u;

// EnvAction<S>: what the environment makes the ant do this tick. Avoid has `heading` and
// `has_follow`/`follow`, Escape `heading`, Collect (a food source) and Drop (a nest) `place`.
struct AntEnvAction {
    kind: u32,
    heading: vec2<S>,
    has_follow: bool,
    follow: AntFollow,
    place: u32,
}

// transfers: whether neighbour `j` can tell ant `i` about `i`'s destination (Table 1,
// §4.2.1): situations 1 and 2 (an S_nothing or S_nest ant meets an S_food one), situation 3
// (an S_food ant meets an S_nest one of its own nest).
fn ant_transfers(i: AntState, j: AntNeighbor) -> bool {
    if ((i.label == ANT_LABEL_NOTHING || i.label == ANT_LABEL_NEST) && j.label == ANT_LABEL_FOOD) {
        return true;
    }
    if (i.label == ANT_LABEL_FOOD && j.label == ANT_LABEL_NEST) {
        return j.nest == i.nest;
    }
    return false;
}

// informer: Algorithm 2: among the neighbours in contact range that transfer information, the
// nearest (ties: the lower id); its latest arrival position, the point ant `i` turns toward
// (Fig. 6). Distances, not squared distances: squares saturate in fixed point beyond ~181.
fn ant_informer(
    i: AntState,
    frame: ptr<function, AntPlanFrame>,
    params: AntParams,
) -> GeomOptionVec2 {
    var found = false;
    var bd = S_ZERO;
    var bid = 0u;
    var arrival = vec2<S>();
    for (var k = 0u; k < (*frame).neighbours_len; k = k + 1u) {
        let j = (*frame).neighbours[k];
        if (!ant_transfers(i, j)) {
            continue;
        }
        let d = geom_length(geom_sub(j.pos, i.pos));
        if (d > params.contact_range) {
            continue;
        }
        if (!found || d < bd || (d == bd && j.id < bid)) {
            found = true;
            bd = d;
            bid = j.id;
            arrival = j.arrival;
        }
    }
    return GeomOptionVec2(found, arrival);
}

// environment: the environment interaction of §4.2.2 for an ant at `s.pos` heading
// `s.heading`, by priority: food or its own nest where the ant stops (ours: before obstacles);
// an obstacle (ant_obstacle_heading); a disturbance it is inside of (escape); its own nest,
// unladen (relabels as S_nest).
fn ant_environment(
    s: AntState,
    frame: ptr<function, AntPlanFrame>,
    params: AntParams,
    ctx: StepCtx,
) -> AntEnvAction {
    var at_nest = false;
    for (var i = 0u; i < (*frame).objects_len; i = i + 1u) {
        let o = (*frame).objects[i];
        if (o.kind == ANT_OBJECT_FOOD) {
            if (s.label != ANT_LABEL_FOOD && ant_inside(s.pos, o.center, o.radius)) {
                return AntEnvAction(ANT_ENV_COLLECT, vec2<S>(), false, AntFollow(), o.id);
            }
        } else if (o.kind == ANT_OBJECT_NEST) {
            if (o.id == s.nest && ant_inside(s.pos, o.center, o.radius)) {
                if (s.label == ANT_LABEL_FOOD) {
                    return AntEnvAction(ANT_ENV_DROP, vec2<S>(), false, AntFollow(), o.id);
                }
                at_nest = true;
            }
        }
    }
    let avoid = ant_obstacle_heading(s, s.heading, frame, params, ctx);
    if (avoid.is_some) {
        return AntEnvAction(ANT_ENV_AVOID, avoid.heading, avoid.has_follow, avoid.follow, 0u);
    }
    let escape = ant_escape_disturbance(s, frame, ctx);
    if (escape.is_some) {
        return AntEnvAction(ANT_ENV_ESCAPE, escape.value, false, AntFollow(), 0u);
    }
    if (at_nest) {
        return AntEnvAction(ANT_ENV_AT_NEST, vec2<S>(), false, AntFollow(), 0u);
    }
    return AntEnvAction(ANT_ENV_NONE, vec2<S>(), false, AntFollow(), 0u);
}

// inside (interact.rs): whether `p` is in the circle (border included).
fn ant_inside(p: vec2<S>, center: vec2<S>, radius: S) -> bool {
    return geom_length(geom_sub(p, center)) <= radius;
}

// escape_disturbance: the way away from the centre of the nearest disturbance whose dangerous
// circle holds the ant (`nearest` of interact.rs: the first of equally near ones; Fig. 5c); a
// random direction when exactly on the centre.
fn ant_escape_disturbance(
    s: AntState,
    frame: ptr<function, AntPlanFrame>,
    ctx: StepCtx,
) -> GeomOptionVec2 {
    var found = false;
    var bd = S_ZERO;
    var away = vec2<S>();
    for (var i = 0u; i < (*frame).objects_len; i = i + 1u) {
        let o = (*frame).objects[i];
        if (o.kind != ANT_OBJECT_DISTURBANCE) {
            continue;
        }
        let a = geom_sub(s.pos, o.center);
        let dist = geom_length(a);
        if (dist < o.radius && (!found || dist < bd)) {
            found = true;
            bd = dist;
            away = a;
        }
    }
    if (!found) {
        return GeomOptionVec2(false, vec2<S>());
    }
    let n = geom_normalized(away);
    if (n.is_some) {
        return n;
    }
    let a = rand_angle(ctx.seed, ctx.agent, ctx.step, RAND_ANT_FALLBACK, S_PI);
    return GeomOptionVec2(true, geom_from_angle(a));
}
