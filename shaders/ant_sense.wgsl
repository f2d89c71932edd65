// What an ant senses of the world (host-sim/src/gpu/shaders.rs, ANT_SENSE): the sensor frames
// of host-sim/src/ants/sense.rs (`plan_frame`, `resolve_frame`) and the object geometry of
// host-sim/src/ants/world.rs (`AntObjectDef::closest`, `surface`, `pieces_within`), function by
// function, over the scalar `S`: in fixed point every key, distance, closest point and normal
// is the CPU's bit for bit, so the same neighbours, objects and surfaces enter the frames.
//
// The sensed ants are struct-of-arrays words (host-sim/src/gpu/ant/world.rs, `sensed_words`):
// positions, arrivals, ids, labels, nests, origins, each an array over the ants; the
// predictions of the plan phase an array of positions; the candidates come from the GPU grid
// (`GpuGrid`'s `starts` and `order` over the cells of ant_world.wgsl's `ant_world_cell` of the
// sensed positions). A query visits the rows of cells between the cells of `p - r` and
// `p + r` (`r` the range plus the grid margin): a superset of the ants in range, which the
// exact keys then select from, as the CPU's grid query is.
//
// Bindings (group 0): 0 the parameters, 1 the world (ant_world.wgsl), 2 the sensed ants, 3 the
// predictions, 4 and 5 the grid's `starts` and `order`; a kernel writes its results to binding
// 6. Loops per invocation (lavapipe stops an invocation's loop, its nested loops and the loops
// of the functions it calls counted with it, after 65,535 iterations): a neighbour query runs
// an iteration per candidate and at most eight more per candidate kept; the objects' loops
// about a hundred per polygon edge (a square root of 32 iterations, a few divisions, the pieces
// offered), so polygons of up to about 600 edges in all stay within it (measured: 600 pass, 700
// stop the resolve frame's; the heart of fig. 1c has 74). The edges' directions and lengths are
// precomputed on the host (AntWorldEdge) for that reason too.

// The parameters of a sensing dispatch: the number of ants, and the largest distance between
// an ant's prediction and its sensed position this tick (AntWorld::max_shift, widening the
// resolve frame's query over the sensed positions' grid).
struct AntSenseParams {
    n: u32,
    shift: S,
    pad0: u32,
    pad1: u32,
}

@group(0) @binding(0) var<uniform> ant_sense_params: AntSenseParams;
// The sensed ants, one array per field (world.rs, `SENSED_*`): ranges of one buffer, each bound
// on its own, so no binding holds more than two words an ant (10 million ants fit the 128 MiB
// bindings of lavapipe).
@group(0) @binding(2) var<storage, read> ant_sensed_pos_words: array<u32>;
@group(0) @binding(24) var<storage, read> ant_sensed_arrival_words: array<u32>;
@group(0) @binding(25) var<storage, read> ant_sensed_ids: array<u32>;
@group(0) @binding(26) var<storage, read> ant_sensed_labels: array<u32>;
@group(0) @binding(27) var<storage, read> ant_sensed_nests: array<u32>;
@group(0) @binding(28) var<storage, read> ant_sensed_origins: array<u32>;
@group(0) @binding(3) var<storage, read> ant_predicted: array<u32>;
@group(0) @binding(4) var<storage, read> ant_grid_starts: array<u32>;
@group(0) @binding(5) var<storage, read> ant_grid_order: array<u32>;

// The sensed ants' arrays: where each starts in the buffer, in multiples of the stride (the ant
// count rounded up to 64; world.rs, SENSED_*), and the field of ant_sensed_field.
const ANT_SENSED_POS: u32 = 0u;
const ANT_SENSED_ARRIVAL: u32 = 2u;
const ANT_SENSED_ID: u32 = 4u;
const ANT_SENSED_LABEL: u32 = 5u;
const ANT_SENSED_NEST: u32 = 6u;
const ANT_SENSED_ORIGIN: u32 = 7u;

// The pieces of obstacles fill_obstacles offers at most (4 × SURFACES).
const ANT_SENSE_PIECES: u32 = 24u;

// ---- the sensed ants ----

fn ant_sensed_pos(j: u32) -> vec2<S> {
    return vec2<S>(
        s_from_word(ant_sensed_pos_words[2u * j]),
        s_from_word(ant_sensed_pos_words[2u * j + 1u]),
    );
}

fn ant_sensed_arrival(j: u32) -> vec2<S> {
    return vec2<S>(
        s_from_word(ant_sensed_arrival_words[2u * j]),
        s_from_word(ant_sensed_arrival_words[2u * j + 1u]),
    );
}

// The field `field` (ANT_SENSED_ID, _LABEL, _NEST or _ORIGIN) of ant `j`.
fn ant_sensed_field(field: u32, j: u32) -> u32 {
    switch field {
        case ANT_SENSED_ID: {
            return ant_sensed_ids[j];
        }
        case ANT_SENSED_LABEL: {
            return ant_sensed_labels[j];
        }
        case ANT_SENSED_NEST: {
            return ant_sensed_nests[j];
        }
        default: {
            return ant_sensed_origins[j];
        }
    }
}

fn ant_predicted_pos(j: u32) -> vec2<S> {
    return vec2<S>(s_from_word(ant_predicted[2u * j]), s_from_word(ant_predicted[2u * j + 1u]));
}

// ---- Nearest (sense.rs) ----

// The `cap` (at most 8) smallest (key, tie) pairs offered, in increasing order, each with its
// slot: sense.rs's `Nearest<S, K>` for K = cap.
struct AntNearest {
    keys: array<S, 8>,
    ties: array<u32, 8>,
    slots: array<u32, 8>,
    len: u32,
}

// Whether (ka, ta) comes before (kb, tb): by key, then by tie.
fn ant_nearest_less(ka: S, ta: u32, kb: S, tb: u32) -> bool {
    return ka < kb || (ka == kb && ta < tb);
}

// Nearest::offer: an insertion, the last one dropped when full.
fn ant_nearest_offer(near: ptr<function, AntNearest>, cap: u32, key: S, tie: u32, slot: u32) {
    if ((*near).len == cap) {
        let last = cap - 1u;
        if (cap == 0u || !ant_nearest_less(key, tie, (*near).keys[last], (*near).ties[last])) {
            return;
        }
        (*near).len = (*near).len - 1u;
    }
    var k = (*near).len;
    while (k > 0u && ant_nearest_less(key, tie, (*near).keys[k - 1u], (*near).ties[k - 1u])) {
        (*near).keys[k] = (*near).keys[k - 1u];
        (*near).ties[k] = (*near).ties[k - 1u];
        (*near).slots[k] = (*near).slots[k - 1u];
        k = k - 1u;
    }
    (*near).keys[k] = key;
    (*near).ties[k] = tie;
    (*near).slots[k] = slot;
    (*near).len = (*near).len + 1u;
}

// ---- object geometry (world.rs) ----

// closest_on_segment: the point of edge `e` closest to p, and whether it lies strictly between
// its ends (else it is one of them): the projection on the unit direction, clamped to the
// length (both precomputed, ant_world.wgsl's AntWorldEdge).
struct AntSenseSegment {
    closest: vec2<S>,
    on_edge: bool,
}

fn ant_sense_closest_on_segment(e: AntWorldEdge, p: vec2<S>) -> AntSenseSegment {
    if (!e.has_unit) {
        return AntSenseSegment(e.a, false);
    }
    let t = geom_dot(geom_sub(p, e.a), e.unit);
    if (t <= S_ZERO) {
        return AntSenseSegment(e.a, false);
    } else if (t >= e.len) {
        return AntSenseSegment(e.b, false);
    }
    return AntSenseSegment(geom_add(e.a, geom_mul(e.unit, t)), true);
}

// Whether edge `e` crosses the horizontal through p to the right of p (closest_on_polygon_edge's
// even-odd rule).
fn ant_sense_crosses(e: AntWorldEdge, p: vec2<S>) -> bool {
    if ((e.a.y > p.y) == (e.b.y > p.y)) {
        return false;
    }
    let f = s_div(s_sub(p.y, e.a.y), s_sub(e.b.y, e.a.y));
    return p.x < s_add(e.a.x, s_mul(f, s_sub(e.b.x, e.a.x)));
}

// closest_on_polygon_edge: the closest boundary point of polygon `o` to p, whether p is inside
// (even-odd rule), the edge the point is on (the first of equally near ones) and whether it
// lies strictly between the edge's ends.
struct AntSensePolygon {
    closest: vec2<S>,
    inside: bool,
    edge: u32,
    on_edge: bool,
}

fn ant_sense_closest_on_polygon_edge(o: AntWorldObject, p: vec2<S>) -> AntSensePolygon {
    var best = AntSensePolygon(p, false, 0u, false);
    var best_d = S_ZERO;
    var found = false;
    var inside = false;
    for (var k = 0u; k < o.count; k = k + 1u) {
        let e = ant_world_edge(o.first, o.count, k);
        let q = ant_sense_closest_on_segment(e, p);
        let d = geom_length(geom_sub(p, q.closest));
        if (!found || d < best_d) {
            found = true;
            best_d = d;
            best = AntSensePolygon(q.closest, false, k, q.on_edge);
        }
        if (ant_sense_crosses(e, p)) {
            inside = !inside;
        }
    }
    best.inside = inside;
    return best;
}

// Whether p is inside polygon `o` (the even-odd rule of closest_on_polygon_edge alone).
fn ant_sense_polygon_inside(o: AntWorldObject, p: vec2<S>) -> bool {
    var inside = false;
    for (var k = 0u; k < o.count; k = k + 1u) {
        if (ant_sense_crosses(ant_world_edge(o.first, o.count, k), p)) {
            inside = !inside;
        }
    }
    return inside;
}

// facing: the unit normal of a sensed piece of an edge of outward normal `out`, pointing along
// `d`: the edge's own normal turned toward `d` for a point between the edge's ends, `d` itself
// for a vertex; the edge's outward normal when `d` is zero.
fn ant_sense_facing(d: vec2<S>, on_edge: bool, out: vec2<S>) -> vec2<S> {
    if (on_edge) {
        if (geom_dot(d, out) < S_ZERO) {
            return geom_neg(out);
        }
        return out;
    }
    return geom_normalized_or(d, out);
}

// AntObjectDef::closest: the point of the object's boundary closest to p, and whether p is
// inside it.
struct AntSenseClosest {
    closest: vec2<S>,
    inside: bool,
}

fn ant_sense_closest(o: AntWorldObject, p: vec2<S>) -> AntSenseClosest {
    if (o.shape == ANT_WORLD_CIRCLE) {
        let d = geom_sub(p, o.center);
        let u = geom_normalized(d);
        if (u.is_some) {
            return AntSenseClosest(
                geom_add(o.center, geom_mul(u.value, o.radius)),
                geom_length(d) <= o.radius,
            );
        }
        return AntSenseClosest(geom_add(o.center, vec2<S>(o.radius, S_ZERO)), true);
    }
    let q = ant_sense_closest_on_polygon_edge(o, p);
    return AntSenseClosest(q.closest, q.inside);
}

// AntObjectDef::surface: the closest boundary point, the unit outward normal there (for p
// inside, from p through the closest point: the way out), and whether p is inside.
struct AntSenseSurface {
    closest: vec2<S>,
    normal: vec2<S>,
    inside: bool,
}

fn ant_sense_surface(o: AntWorldObject, p: vec2<S>) -> AntSenseSurface {
    if (o.shape == ANT_WORLD_CIRCLE) {
        let c = ant_sense_closest(o, p);
        let n = geom_normalized_or(geom_sub(c.closest, o.center), vec2<S>(S_ONE, S_ZERO));
        return AntSenseSurface(c.closest, n, c.inside);
    }
    let q = ant_sense_closest_on_polygon_edge(o, p);
    var d = geom_sub(p, q.closest);
    if (q.inside) {
        d = geom_sub(q.closest, p);
    }
    let out = ant_world_edge(o.first, o.count, q.edge).normal;
    return AntSenseSurface(q.closest, ant_sense_facing(d, q.on_edge, out), q.inside);
}

// fill_obstacles' pieces: the first ANT_SENSE_PIECES distinct points offered; `near` keeps the
// ANT_SURFACES nearest of them (by distance, then offer order). (Two pointers rather than one
// struct holding both: naga's SPIR-V writer cannot pass a pointer to a member of a pointed-to
// struct on to a function.)
struct AntSensePieces {
    found: array<AntSurface, 24>,
    len: u32,
}

fn ant_sense_offer_piece(
    acc: ptr<function, AntSensePieces>,
    near: ptr<function, AntNearest>,
    q: vec2<S>,
    n: vec2<S>,
    d: S,
) {
    let len = (*acc).len;
    if (len >= ANT_SENSE_PIECES) {
        return;
    }
    for (var k = 0u; k < len; k = k + 1u) {
        if (all((*acc).found[k].closest == q)) {
            return;
        }
    }
    (*acc).found[len] = AntSurface(q, n);
    ant_nearest_offer(near, ANT_SURFACES, d, len, len);
    (*acc).len = len + 1u;
}

// AntObjectDef::pieces_within: the convex pieces of obstacle `o` within `reach` of p, as
// sensed surfaces with their distance, offered to `acc` and `near`: a disc is one piece, a
// polygon one per edge; from inside, the one way out. (The Rust computes the surface first and
// uses only its `inside` when p is outside a polygon; here the even-odd rule alone decides
// that, the same bit, and the surface is computed only for the way out: one pass over the
// edges instead of two.)
fn ant_sense_pieces_within(
    o: AntWorldObject,
    p: vec2<S>,
    reach: S,
    acc: ptr<function, AntSensePieces>,
    near: ptr<function, AntNearest>,
) {
    if (o.shape == ANT_WORLD_POLYGON && !ant_sense_polygon_inside(o, p)) {
        for (var k = 0u; k < o.count; k = k + 1u) {
            let e = ant_world_edge(o.first, o.count, k);
            let q = ant_sense_closest_on_segment(e, p);
            let away = geom_sub(p, q.closest);
            let d = geom_length(away);
            if (d <= reach) {
                let n = ant_sense_facing(away, q.on_edge, e.normal);
                ant_sense_offer_piece(acc, near, q.closest, n, d);
            }
        }
        return;
    }
    let s = ant_sense_surface(o, p);
    var d = S_ZERO;
    if (!s.inside) {
        d = geom_length(geom_sub(p, s.closest));
    }
    if (d <= reach) {
        ant_sense_offer_piece(acc, near, s.closest, s.normal, d);
    }
}

// ---- the frames (sense.rs) ----

// The grid cells a query of radius `r` around p visits: columns x..z, rows y..w.
fn ant_sense_query(p: vec2<S>, r: S) -> vec4<u32> {
    let lo = ant_world_cell_xy(geom_sub(p, vec2<S>(r, r)));
    let hi = ant_world_cell_xy(geom_add(p, vec2<S>(r, r)));
    return vec4<u32>(lo, hi);
}

// Whether an ant whose nest is `home` (destination `dest`) senses object `o` (plan_frame's
// `on_leg`): on a route only its leg's two way points, and the food only on the last leg.
fn ant_sense_on_leg(o: AntWorldObject, home: u32, dest: AntWorldTarget) -> bool {
    if (o.kind == ANT_WORLD_WAYPOINT) {
        return o.id == home || (dest.is_some && o.id == dest.id);
    }
    if (o.kind == ANT_WORLD_FOOD) {
        return !dest.is_some;
    }
    return true;
}

// plan_frame: the plan-phase sensor frame of ant `i`: its ANT_NEIGHBOURS nearest neighbours
// within the contact range (by squared distance, then id; on a route only those of its leg) and
// its ANT_OBJECTS nearest active objects within the sensing range (by distance to the boundary,
// 0 inside, then object index; on a route its leg's ends and the food only on the last leg).
fn ant_plan_frame(i: u32) -> AntPlanFrame {
    var f: AntPlanFrame;
    f.bounds = ant_world_bounds();
    let me = ant_sensed_pos(i);
    let home = ant_sensed_field(ANT_SENSED_NEST, i);
    let routed = ant_world_routed();
    let r2 = ant_world_s(ANT_WORLD_H_CONTACT2);
    let nx = ant_world[ANT_WORLD_H_GRID_NX];
    var near: AntNearest;
    let q = ant_sense_query(
        me,
        s_add(ant_world_s(ANT_WORLD_H_CONTACT), ant_world_s(ANT_WORLD_H_GRID_MARGIN)),
    );
    for (var row = q.y; row <= q.w; row = row + 1u) {
        let end = ant_grid_starts[row * nx + q.z + 1u];
        for (var s = ant_grid_starts[row * nx + q.x]; s < end; s = s + 1u) {
            let j = ant_grid_order[s];
            if (j == i || (routed && ant_sensed_field(ANT_SENSED_NEST, j) != home)) {
                continue;
            }
            let k = geom_length_sq(geom_sub(ant_sensed_pos(j), me));
            if (k <= r2) {
                ant_nearest_offer(&near, ANT_NEIGHBOURS, k, ant_sensed_field(ANT_SENSED_ID, j), j);
            }
        }
    }
    f.neighbours_len = near.len;
    for (var k = 0u; k < near.len; k = k + 1u) {
        let j = near.slots[k];
        f.neighbours[k] = AntNeighbor(
            ant_sensed_field(ANT_SENSED_ID, j),
            ant_sensed_pos(j),
            ant_sensed_field(ANT_SENSED_LABEL, j),
            ant_sensed_field(ANT_SENSED_NEST, j),
            ant_sensed_field(ANT_SENSED_ORIGIN, j),
            ant_sensed_arrival(j),
        );
    }

    let sense = ant_world_s(ANT_WORLD_H_SENSE);
    let dest = ant_world_target_of(home);
    var objects: AntNearest;
    for (var k = 0u; k < ant_world_objects(); k = k + 1u) {
        let o = ant_world_object(k);
        if (!o.present || !ant_sense_on_leg(o, home, dest)) {
            continue;
        }
        let c = ant_sense_closest(o, me);
        var dist = S_ZERO;
        if (!c.inside) {
            dist = geom_length(geom_sub(c.closest, me));
        }
        if (dist <= sense) {
            ant_nearest_offer(&objects, ANT_OBJECTS, dist, k, k);
        }
    }
    var len = 0u;
    for (var m = 0u; m < objects.len; m = m + 1u) {
        let o = ant_world_object(objects.slots[m]);
        var sensed: AntObject;
        if (o.kind == ANT_WORLD_OBSTACLE) {
            let s = ant_sense_surface(o, me);
            sensed.kind = ANT_OBJECT_OBSTACLE;
            sensed.surface = AntSurface(s.closest, s.normal);
        } else if (o.shape != ANT_WORLD_CIRCLE) {
            // Nests, food and disturbances are circles (checked when the world is built).
            continue;
        } else {
            sensed.center = o.center;
            sensed.radius = o.radius;
            if (o.kind == ANT_WORLD_DISTURBANCE) {
                sensed.kind = ANT_OBJECT_DISTURBANCE;
            } else {
                sensed.id = o.id;
                // A way point is the nest of the ants whose leg starts there, else food.
                let start = o.kind == ANT_WORLD_WAYPOINT && o.id == home;
                let nest = o.kind == ANT_WORLD_NEST || start;
                sensed.kind = select(ANT_OBJECT_FOOD, ANT_OBJECT_NEST, nest);
            }
        }
        f.objects[len] = sensed;
        len = len + 1u;
    }
    f.objects_len = len;
    return f;
}

// resolve_frame: the resolve-phase sensor frame of ant `i`: the predictions of its
// ANT_NEIGHBOURS nearest neighbours within the collision range (strictly) of its own (by
// squared distance, then id), and fill_obstacles' surfaces: every piece of an active obstacle
// within the step reach of its sensed position, each point once (the first 24 offered, in
// object then edge order), the ANT_SURFACES nearest (by distance, then offer order).
fn ant_resolve_frame(i: u32) -> AntResolveFrame {
    var f: AntResolveFrame;
    f.bounds = ant_world_bounds();

    let me = ant_sensed_pos(i);
    let reach = ant_world_s(ANT_WORLD_H_STEP_REACH);
    var acc: AntSensePieces;
    var pieces: AntNearest;
    for (var k = 0u; k < ant_world_objects(); k = k + 1u) {
        let o = ant_world_object(k);
        if (o.present && o.kind == ANT_WORLD_OBSTACLE) {
            ant_sense_pieces_within(o, me, reach, &acc, &pieces);
        }
    }
    f.obstacles_len = pieces.len;
    for (var m = 0u; m < pieces.len; m = m + 1u) {
        f.obstacles[m] = acc.found[pieces.slots[m]];
    }

    // Every prediction lies within `shift` of its ant's sensed position: the ants sensed
    // within the collision range plus `shift` of p* include every ant predicted within the
    // collision range of it.
    let p = ant_predicted_pos(i);
    let r2 = ant_world_s(ANT_WORLD_H_COLLISION2);
    let nx = ant_world[ANT_WORLD_H_GRID_NX];
    var near: AntNearest;
    let r = s_add(
        s_add(ant_world_s(ANT_WORLD_H_COLLISION), ant_sense_params.shift),
        ant_world_s(ANT_WORLD_H_GRID_MARGIN),
    );
    let q = ant_sense_query(p, r);
    for (var row = q.y; row <= q.w; row = row + 1u) {
        let end = ant_grid_starts[row * nx + q.z + 1u];
        for (var s = ant_grid_starts[row * nx + q.x]; s < end; s = s + 1u) {
            let j = ant_grid_order[s];
            if (j == i) {
                continue;
            }
            let k = geom_length_sq(geom_sub(ant_predicted_pos(j), p));
            if (k < r2) {
                ant_nearest_offer(&near, ANT_NEIGHBOURS, k, ant_sensed_field(ANT_SENSED_ID, j), j);
            }
        }
    }
    f.neighbours_len = near.len;
    for (var k = 0u; k < near.len; k = k + 1u) {
        f.neighbours[k] = ant_predicted_pos(near.slots[k]);
    }
    return f;
}
