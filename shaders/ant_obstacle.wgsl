// Obstacles (host-sim/src/gpu/shaders.rs, ANT_OBSTACLE): `swarm_core::ant::obstacle`
// (core-nostd/src/ant/obstacle.rs; xiang2018 §4.2.2, "obstacles > external disturbance >
// food = nest"), over the scalar `S`: the avoiding turn of Fig. 5b, going round an obstacle
// that blocks the way to the goal, and the hard constraint that keeps the move of eq. 5 out of
// every obstacle the ant senses.

// SURFACE_MARGIN: how far in front of an obstacle surface a move ends at the least (1/64).
const ANT_SURFACE_MARGIN: f32 = 0.015625f;

// The result of nearest_surface: Option<(distance, Surface, rim)>.
struct AntNearestSurface {
    is_some: bool,
    dist: S,
    surface: AntSurface,
    rim: bool,
}

// The result of obstacle_heading: Option<(heading, Option<Follow>)>.
struct AntObstacleHeading {
    is_some: bool,
    heading: vec2<S>,
    has_follow: bool,
    follow: AntFollow,
}

// nearest_surface (obstacle.rs): the nearest surface to go round, an obstacle, or with
// `disturbances` also the rim of a disturbance's dangerous circle the ant is outside of; the
// flag tells a rim. The first of equally near ones.
fn ant_nearest_surface(
    pos: vec2<S>,
    frame: ptr<function, AntPlanFrame>,
    disturbances: bool,
) -> AntNearestSurface {
    var best = AntNearestSurface(false, S_ZERO, AntSurface(), false);
    for (var i = 0u; i < (*frame).objects_len; i = i + 1u) {
        let o = (*frame).objects[i];
        var found = false;
        var dist = S_ZERO;
        var surface = o.surface;
        var rim = false;
        if (o.kind == ANT_OBJECT_OBSTACLE) {
            // Inside (the normal points from the ant to the surface): distance 0.
            let away = geom_sub(pos, o.surface.closest);
            if (geom_dot(away, o.surface.normal) < S_ZERO) {
                dist = S_ZERO;
            } else {
                dist = geom_length(away);
            }
            found = true;
        } else if (o.kind == ANT_OBJECT_DISTURBANCE && disturbances) {
            let away = geom_sub(pos, o.center);
            let len = geom_length(away);
            let u = geom_normalized(away);
            if (u.is_some && len >= o.radius) {
                surface = AntSurface(geom_add(o.center, geom_mul(u.value, o.radius)), u.value);
                dist = s_sub(len, o.radius);
                rim = true;
                found = true;
            }
        }
        if (found && (!best.is_some || dist < best.dist)) {
            best = AntNearestSurface(true, dist, surface, rim);
        }
    }
    return best;
}

// tangent: the direction along the surface with normal `n`, the way `turn` goes round.
fn ant_tangent(n: vec2<S>, turn: u32) -> vec2<S> {
    if (turn == ANT_TURN_CCW) {
        return geom_perp(n);
    }
    return geom_neg(geom_perp(n));
}

// obstacle_heading: what the nearest obstacle makes an ant heading `heading` do this tick
// (§4.2.2), if anything: the new heading, and the Follow the ant keeps (ours) when it has a
// goal. Avoiding (Fig. 5b): an obstacle ahead within `avoid_range` turns the ant along its
// surface on the side of its heading (a random side when exactly head-on); going round (ours):
// an ant with a goal turns along the surface on the shorter side and keeps to it until the way
// toward the goal is free (Pledge's winding counter).
fn ant_obstacle_heading(
    s: AntState,
    heading: vec2<S>,
    frame: ptr<function, AntPlanFrame>,
    params: AntParams,
    ctx: StepCtx,
) -> AntObstacleHeading {
    let none = AntObstacleHeading(false, vec2<S>(), false, AntFollow());
    var goal = GeomOptionVec2(false, vec2<S>());
    if (s.has_goal) {
        goal = geom_normalized(geom_sub(s.goal, s.pos));
    }
    let found = ant_nearest_surface(s.pos, frame, goal.is_some);
    if (!found.is_some) {
        return none;
    }
    let dist = found.dist;
    let n = found.surface.normal;
    let g = goal.value;
    // Round a danger the ants keep farther off (ours).
    var near = s_div(params.avoid_range, s_from_i32(2));
    if (found.rim) {
        near = params.avoid_range;
    }
    if (s.has_follow && goal.is_some && dist <= s_add(s_add(params.avoid_range, near), near)) {
        let f = s.follow;
        let winding = ant_unwrap(ant_turn_angle(g, ant_tangent(n, f.turn)), f.winding);
        // A quarter turn, and a little for the rounding.
        let free = geom_dot(g, n) > S_ZERO && s_abs(winding) <= s_from_f32(1.03f);
        if (!free) {
            let h = ant_follow_heading(n, dist, f.turn, near, s_add(near, near));
            return AntObstacleHeading(true, h, true, AntFollow(f.turn, winding));
        }
    }
    // Fig. 5b: only an obstacle ahead, within the avoiding range; an ant with a goal starts
    // going round from twice that (ours).
    var range = params.avoid_range;
    if (goal.is_some) {
        range = s_add(s_add(params.avoid_range, near), near);
    }
    if (!(geom_dot(heading, n) < S_ZERO && dist <= range)) {
        return none;
    }
    var turn = ANT_TURN_CW;
    if (goal.is_some) {
        // The shorter way, judged from the goal's direction; nearly head-on, the ant's own
        // preferred side (drawn at step 0).
        let side = geom_dot(geom_perp(n), g);
        if (s_abs(side) >= s_from_f32(0.25f)) {
            turn = ant_side_of(side);
        } else if ((rand_rand(ctx.seed, ctx.agent, 0u, RAND_ANT_SIDE) & 1u) == 1u) {
            turn = ANT_TURN_CCW;
        }
    } else {
        // Fig. 5b: the smaller turn; exactly head-on, a random side.
        let side = geom_dot(geom_perp(n), heading);
        if (side != S_ZERO) {
            turn = ant_side_of(side);
        } else if ((rand_rand(ctx.seed, ctx.agent, ctx.step, RAND_ANT_FALLBACK) & 1u) == 1u) {
            turn = ANT_TURN_CCW;
        }
    }
    let h = ant_tangent(n, turn);
    if (goal.is_some) {
        return AntObstacleHeading(true, h, true, AntFollow(turn, ant_turn_angle(g, h)));
    }
    return AntObstacleHeading(true, h, false, AntFollow());
}

// side_of: the way round whose direction along the surface has the positive component `side`
// of a heading on `normal.perp()`.
fn ant_side_of(side: S) -> u32 {
    if (side > S_ZERO) {
        return ANT_TURN_CCW;
    }
    return ANT_TURN_CW;
}

// follow_heading: along the surface on the `turn` side; turned toward it when farther than
// `far`, away from it when nearer than `near`.
fn ant_follow_heading(n: vec2<S>, dist: S, turn: u32, near: S, far: S) -> vec2<S> {
    var pull = S_ZERO;
    if (dist > far) {
        pull = s_div(s_sub(far, dist), far);
    } else if (dist < near) {
        pull = s_div(s_sub(near, dist), near);
    }
    let t = ant_tangent(n, turn);
    return geom_normalized_or(geom_add(t, geom_mul(n, s_clamp_to(pull, s_neg(S_ONE), S_ONE))), t);
}

// turn_angle: the signed turn from `a` to `b` (counter-clockwise positive) as a diamond angle
// in quarter turns, in (-2, 2].
fn ant_turn_angle(a: vec2<S>, b: vec2<S>) -> S {
    let x = geom_dot(a, b);
    let y = geom_cross(a, b);
    let d = s_add(s_abs(x), s_abs(y));
    if (d == S_ZERO) {
        return S_ZERO;
    }
    let t = s_div(y, d);
    let two = s_from_i32(2);
    if (x >= S_ZERO) {
        return t;
    } else if (y >= S_ZERO) {
        return s_sub(two, t);
    }
    return s_sub(s_neg(two), t);
}

// unwrap (obstacle.rs): the turn equal to `angle` modulo a full turn (4 quarter turns)
// nearest to `previous`, limited to ±WINDING_LIMIT.
fn ant_unwrap(angle: S, previous: S) -> S {
    let full = s_from_i32(4);
    let turns = s_floor_i32(s_add(s_div(s_sub(previous, angle), full), s_from_f32(0.5f)));
    let lim = s_from_f32(ANT_WINDING_LIMIT);
    return s_clamp_to(s_add(angle, s_mul(full, s_from_i32(turns))), s_neg(lim), lim);
}

// The worst surface of constrain's closure `worst`: Option<(clearance, start, normal)>.
struct AntWorst {
    is_some: bool,
    c: S,
    start: S,
    normal: vec2<S>,
}

// constrain's closure `worst`: of the surfaces the move `m` from `pos` ends behind (clearance
// below 0), the one it ends farthest behind (the first of equals), with its clearance and how
// far in front of it the ant starts (`clearance`: both less the margin).
fn ant_constrain_worst(
    pos: vec2<S>,
    m: vec2<S>,
    frame: ptr<function, AntResolveFrame>,
    margin: S,
) -> AntWorst {
    var w = AntWorst(false, S_ZERO, S_ZERO, vec2<S>());
    for (var i = 0u; i < (*frame).obstacles_len; i = i + 1u) {
        let s = (*frame).obstacles[i];
        let start = s_sub(geom_dot(geom_sub(pos, s.closest), s.normal), margin);
        let c = s_add(start, geom_dot(m, s.normal));
        if (c < S_ZERO && (!w.is_some || c < w.c)) {
            w = AntWorst(true, c, start, s.normal);
        }
    }
    return w;
}

// constrain: the hard constraint on the move of eq. 5 (ours). `step` is the move
// p(t+1) - p(t) and the frame's obstacles the surfaces; the result ends at least
// SURFACE_MARGIN in front of every surface: a move that would end behind a surface slides
// along it (up to three times), a move that still crosses one is dropped, an ant that starts
// behind a surface moves out along its normal, at most `step`'s length.
fn ant_constrain(pos: vec2<S>, step: vec2<S>, frame: ptr<function, AntResolveFrame>) -> vec2<S> {
    let margin = s_from_f32(ANT_SURFACE_MARGIN);
    var m = step;
    for (var k = 0u; k < 3u; k = k + 1u) {
        let w = ant_constrain_worst(pos, m, frame, margin);
        if (!w.is_some) {
            return m;
        }
        if (w.start < S_ZERO) {
            return geom_mul(w.normal, s_min(s_neg(w.start), geom_length(step)));
        }
        // Slide: remove the part of the move that goes into the surface.
        m = geom_sub(m, geom_mul(w.normal, w.c));
    }
    if (!ant_constrain_worst(pos, m, frame, margin).is_some) {
        return m;
    }
    return vec2<S>();
}
