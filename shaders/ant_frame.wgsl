// What an ant senses (host-sim/src/gpu/shaders.rs, ANT_FRAME): `swarm_core::ant::frame`
// (core-nostd/src/ant/frame.rs, xiang2018 §3-4), the sensor frames of the two phases of a tick
// with the simulator's capacities (host_sim::ants::{N, O}, the wire's; SURFACES), over the
// scalar `S`. A heapless `Vec` is a fixed array and its length (`neighbours_len`, ...); the
// entries past the length mean nothing.

// WIRE_ANT_NEIGHBOURS (host_sim::ants::N): neighbours in a plan or resolve frame.
const ANT_NEIGHBOURS: u32 = 8u;
// WIRE_ANT_OBJECTS (host_sim::ants::O): objects in a plan frame.
const ANT_OBJECTS: u32 = 4u;
// SURFACES: obstacle surfaces in a resolve frame.
const ANT_SURFACES: u32 = 6u;

// AntObject's variants, the `kind` of an AntObject.
const ANT_OBJECT_OBSTACLE: u32 = 0u;
const ANT_OBJECT_DISTURBANCE: u32 = 1u;
const ANT_OBJECT_FOOD: u32 = 2u;
const ANT_OBJECT_NEST: u32 = 3u;

// AntNeighbor<S>: a neighbour as sensed in the plan phase (§4.2.1, Fig. 6).
struct AntNeighbor {
    id: u32,
    pos: vec2<S>,
    label: u32,
    nest: u32,
    origin: u32,
    arrival: vec2<S>,
}

// Surface<S>: a point of an obstacle's surface and the outward unit normal there.
struct AntSurface {
    closest: vec2<S>,
    normal: vec2<S>,
}

// AntObject<S>: an object in sensing range (§4.2.2, Fig. 4b). `kind` is the variant; an
// Obstacle has `surface`, a Disturbance `center` and `radius`, a Food or Nest also `id`.
struct AntObject {
    kind: u32,
    id: u32,
    surface: AntSurface,
    center: vec2<S>,
    radius: S,
}

// PlanFrame<S, N, O>: the sensor frame of `plan`.
struct AntPlanFrame {
    bounds: GeomRect,
    neighbours_len: u32,
    neighbours: array<AntNeighbor, ANT_NEIGHBOURS>,
    objects_len: u32,
    objects: array<AntObject, ANT_OBJECTS>,
}

// ResolveFrame<S, N>: the sensor frame of `resolve` (the neighbours' predictions, the obstacle
// surfaces within one step).
struct AntResolveFrame {
    bounds: GeomRect,
    neighbours_len: u32,
    neighbours: array<vec2<S>, ANT_NEIGHBOURS>,
    obstacles_len: u32,
    obstacles: array<AntSurface, ANT_SURFACES>,
}

// Surface::check: the point (finite, inside the coordinate limit) and a unit normal (±2 %),
// the errors naming the fields `closest` and `normal` (Surface::validate: the frame's names).
fn ant_surface_check(s: AntSurface, closest: u32, normal: u32) -> u32 {
    let e = ant_check_point(s.closest, closest);
    if (e != ANT_OK) {
        return e;
    }
    let l2 = geom_length_sq(s.normal);
    if (!(l2 > s_from_f32(0.96f) && l2 < s_from_f32(1.04f))) {
        if (!geom_check(s.normal)) {
            return ant_error(ANT_ERROR_NON_FINITE, normal);
        }
        return ant_error(ANT_ERROR_OUT_OF_RANGE, normal);
    }
    return ANT_OK;
}

// check_object (frame.rs): an object of a plan frame: a finite point and, for a disc, a
// positive radius.
fn ant_check_object(o: AntObject) -> u32 {
    if (o.kind == ANT_OBJECT_OBSTACLE) {
        return ant_surface_check(o.surface, ANT_FIELD_OBJECTS_CLOSEST, ANT_FIELD_OBJECTS_NORMAL);
    }
    let e = ant_check_point(o.center, ANT_FIELD_OBJECTS_CENTER);
    if (e != ANT_OK) {
        return e;
    }
    let big = s_from_f32(ANT_COORD_LIMIT);
    return ant_check_range(o.radius, S_EPS, big, ANT_FIELD_OBJECTS_RADIUS);
}

// PlanFrame::check_neighbour: neighbour `i`'s points, an id other than the ant's and the
// earlier neighbours', a consistent origin.
fn ant_plan_frame_check_neighbour(frame: ptr<function, AntPlanFrame>, i: u32, agent: u32) -> u32 {
    let n = (*frame).neighbours[i];
    var e = ant_check_point(n.pos, ANT_FIELD_NEIGHBOURS_POS);
    if (e != ANT_OK) {
        return e;
    }
    e = ant_check_point(n.arrival, ANT_FIELD_NEIGHBOURS_ARRIVAL);
    if (e != ANT_OK) {
        return e;
    }
    var seen = n.id == agent;
    for (var k = 0u; k < i; k = k + 1u) {
        seen = seen || (*frame).neighbours[k].id == n.id;
    }
    if (seen) {
        return ant_error(ANT_ERROR_INCONSISTENT, ANT_FIELD_NEIGHBOURS_ID);
    }
    if (n.label == ANT_LABEL_NEST && n.origin != n.nest) {
        return ant_error(ANT_ERROR_INCONSISTENT, ANT_FIELD_NEIGHBOURS_ORIGIN);
    }
    return ANT_OK;
}

// PlanFrame::validate: every field; `agent` is the sensing ant's own id.
fn ant_plan_frame_validate(frame: ptr<function, AntPlanFrame>, agent: u32) -> u32 {
    var e = ant_check_bounds((*frame).bounds);
    if (e != ANT_OK) {
        return e;
    }
    for (var i = 0u; i < (*frame).neighbours_len; i = i + 1u) {
        e = ant_error_at(ant_plan_frame_check_neighbour(frame, i, agent), i);
        if (e != ANT_OK) {
            return e;
        }
    }
    for (var i = 0u; i < (*frame).objects_len; i = i + 1u) {
        e = ant_error_at(ant_check_object((*frame).objects[i]), i);
        if (e != ANT_OK) {
            return e;
        }
    }
    return ANT_OK;
}

// ResolveFrame::validate: every field.
fn ant_resolve_frame_validate(frame: ptr<function, AntResolveFrame>) -> u32 {
    var e = ant_check_bounds((*frame).bounds);
    if (e != ANT_OK) {
        return e;
    }
    for (var i = 0u; i < (*frame).neighbours_len; i = i + 1u) {
        e = ant_error_at(ant_check_point((*frame).neighbours[i], ANT_FIELD_NEIGHBOURS), i);
        if (e != ANT_OK) {
            return e;
        }
    }
    for (var i = 0u; i < (*frame).obstacles_len; i = i + 1u) {
        let s = (*frame).obstacles[i];
        e = ant_error_at(
            ant_surface_check(s, ANT_FIELD_OBSTACLES_CLOSEST, ANT_FIELD_OBSTACLES_NORMAL),
            i,
        );
        if (e != ANT_OK) {
            return e;
        }
    }
    return ANT_OK;
}

// check_bounds (frame.rs): finite corners inside the coordinate limit, min < max on both axes.
fn ant_check_bounds(b: GeomRect) -> u32 {
    var e = ant_check_point(b.min, ANT_FIELD_BOUNDS);
    if (e != ANT_OK) {
        return e;
    }
    e = ant_check_point(b.max, ANT_FIELD_BOUNDS);
    if (e != ANT_OK) {
        return e;
    }
    if (b.min.x < b.max.x && b.min.y < b.max.y) {
        return ANT_OK;
    }
    return ant_error(ANT_ERROR_OUT_OF_RANGE, ANT_FIELD_BOUNDS);
}
