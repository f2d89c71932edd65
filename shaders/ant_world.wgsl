// The ant world (host-sim/src/gpu/shaders.rs, ANT_WORLD): the arena, the ranges, the route,
// the grid and the objects, as u32 words in the layout of host-sim/src/gpu/ant/world.rs (which
// packs them on the host, every value converted there as host-sim/src/ants/sense.rs and
// world.rs convert it), over the scalar `S`. The buffer is binding 1 of group 0 of every kernel
// that composes this module.
//
// The grid is the GPU's own: the cell of a point is `floor((x - origin) · (1 / cell))` per
// axis, clamped to the grid, computed in `S`. It is monotonic in each coordinate, so the cells
// between the keys of `p - r` and `p + r` hold every point within `r` of `p` on each axis
// (world.rs says why).

@group(0) @binding(1) var<storage, read> ant_world: array<u32>;

// Words of the header, an object, a polygon vertex (with the normal of its edge).
const ANT_WORLD_HEADER_WORDS: u32 = 24u;
const ANT_WORLD_OBJECT_WORDS: u32 = 8u;
const ANT_WORLD_VERTEX_WORDS: u32 = 8u;

// The header's words.
const ANT_WORLD_H_OBJECTS: u32 = 0u;
const ANT_WORLD_H_OBJECTS_AT: u32 = 1u;
const ANT_WORLD_H_VERTICES: u32 = 2u;
const ANT_WORLD_H_VERTICES_AT: u32 = 3u;
const ANT_WORLD_H_ROUTE: u32 = 4u;
const ANT_WORLD_H_ROUTE_AT: u32 = 5u;
const ANT_WORLD_H_BOUNDS: u32 = 6u;
const ANT_WORLD_H_CONTACT: u32 = 10u;
const ANT_WORLD_H_CONTACT2: u32 = 11u;
const ANT_WORLD_H_COLLISION: u32 = 12u;
const ANT_WORLD_H_COLLISION2: u32 = 13u;
const ANT_WORLD_H_SENSE: u32 = 14u;
const ANT_WORLD_H_STEP_REACH: u32 = 15u;
const ANT_WORLD_H_GRID_ORIGIN: u32 = 16u;
const ANT_WORLD_H_GRID_INV_CELL: u32 = 18u;
const ANT_WORLD_H_GRID_NX: u32 = 19u;
const ANT_WORLD_H_GRID_NY: u32 = 20u;
const ANT_WORLD_H_GRID_MARGIN: u32 = 21u;

// AntObjectKind (world.rs), the `kind` of an AntWorldObject.
const ANT_WORLD_NEST: u32 = 0u;
const ANT_WORLD_FOOD: u32 = 1u;
const ANT_WORLD_OBSTACLE: u32 = 2u;
const ANT_WORLD_DISTURBANCE: u32 = 3u;
const ANT_WORLD_WAYPOINT: u32 = 4u;
// Shape2, the `shape` of an AntWorldObject.
const ANT_WORLD_CIRCLE: u32 = 0u;
const ANT_WORLD_POLYGON: u32 = 1u;
// A food source's `extra` when it is endless (else the food left; a way point's is its order).
const ANT_WORLD_AMOUNT_ENDLESS: u32 = 0xffffffffu;

// AntObjectDef: what it is, its id, whether it is present, and its shape: a circle's `center`
// and `radius`, or a polygon's vertices `first..first + count` (of ant_world_vertex).
struct AntWorldObject {
    kind: u32,
    id: u32,
    present: bool,
    extra: u32,
    shape: u32,
    center: vec2<S>,
    radius: S,
    first: u32,
    count: u32,
}

// `Option<u16>` of a way point's id.
struct AntWorldTarget {
    is_some: bool,
    id: u32,
}

// Header word `k` as an S.
fn ant_world_s(k: u32) -> S {
    return s_from_word(ant_world[k]);
}

fn ant_world_objects() -> u32 {
    return ant_world[ANT_WORLD_H_OBJECTS];
}

// Object `k` (0 ≤ k < ant_world_objects()).
fn ant_world_object(k: u32) -> AntWorldObject {
    let b = ant_world[ANT_WORLD_H_OBJECTS_AT] + k * ANT_WORLD_OBJECT_WORDS;
    var o: AntWorldObject;
    o.kind = ant_world[b];
    o.id = ant_world[b + 1u];
    o.present = ant_world[b + 2u] != 0u;
    o.extra = ant_world[b + 3u];
    o.shape = ant_world[b + 4u];
    if (o.shape == ANT_WORLD_CIRCLE) {
        o.center = vec2<S>(s_from_word(ant_world[b + 5u]), s_from_word(ant_world[b + 6u]));
        o.radius = s_from_word(ant_world[b + 7u]);
    } else {
        o.first = ant_world[b + 5u];
        o.count = ant_world[b + 6u];
    }
    return o;
}

// An edge of a polygon, from vertex `a` to the next vertex `b`: its outward unit normal
// (edge_normal in world.rs: computed on the host in f32 and converted), and what
// closest_on_segment computes of `b - a` for every ant, computed once on the host with the
// same functions (the same bits): `(b - a).normalized()` (`has_unit`, `unit`) and
// `(b - a).length()`.
struct AntWorldEdge {
    a: vec2<S>,
    b: vec2<S>,
    normal: vec2<S>,
    unit: vec2<S>,
    len: S,
    has_unit: bool,
}

// Polygon vertex `v` (an index over every polygon's vertices).
fn ant_world_vertex(v: u32) -> vec2<S> {
    let b = ant_world[ANT_WORLD_H_VERTICES_AT] + v * ANT_WORLD_VERTEX_WORDS;
    return vec2<S>(s_from_word(ant_world[b]), s_from_word(ant_world[b + 1u]));
}

// Edge `k` of the polygon of vertices `first..first + count`: from vertex k to vertex k + 1
// (vertex 0 after the last).
fn ant_world_edge(first: u32, count: u32, k: u32) -> AntWorldEdge {
    let b = ant_world[ANT_WORLD_H_VERTICES_AT] + (first + k) * ANT_WORLD_VERTEX_WORDS;
    let v = vec2<S>(s_from_word(ant_world[b]), s_from_word(ant_world[b + 1u]));
    return AntWorldEdge(
        v,
        ant_world_vertex(first + (k + 1u) % count),
        vec2<S>(s_from_word(ant_world[b + 2u]), s_from_word(ant_world[b + 3u])),
        vec2<S>(s_from_word(ant_world[b + 4u]), s_from_word(ant_world[b + 5u])),
        s_from_word(ant_world[b + 6u]),
        ant_world[b + 7u] != 0u,
    );
}

// bounds (sense.rs): the arena as a robot senses it.
fn ant_world_bounds() -> GeomRect {
    let b = ANT_WORLD_H_BOUNDS;
    return GeomRect(
        vec2<S>(ant_world_s(b), ant_world_s(b + 1u)),
        vec2<S>(ant_world_s(b + 2u), ant_world_s(b + 3u)),
    );
}

// Whether there is a route of way points.
fn ant_world_routed() -> bool {
    return ant_world[ANT_WORLD_H_ROUTE] != 0u;
}

// AntWorld::target_of: the destination of an ant whose nest is `home`, the way point after
// `home` on the route (the first one for a nest that is not on it), none past the last one or
// without a route.
fn ant_world_target_of(home: u32) -> AntWorldTarget {
    let n = ant_world[ANT_WORLD_H_ROUTE];
    let at = ant_world[ANT_WORLD_H_ROUTE_AT];
    var next = 0u;
    for (var k = 0u; k < n; k = k + 1u) {
        if (ant_world[at + k] == home) {
            next = k + 1u;
            break;
        }
    }
    if (next < n) {
        return AntWorldTarget(true, ant_world[at + next]);
    }
    return AntWorldTarget(false, 0u);
}

// The grid's cells across and up.
fn ant_world_grid_size() -> vec2<u32> {
    return vec2<u32>(ant_world[ANT_WORLD_H_GRID_NX], ant_world[ANT_WORLD_H_GRID_NY]);
}

// The grid cell of coordinate `x` on an axis of `n` cells from `origin`.
fn ant_world_cell_axis(x: S, origin: S, n: u32) -> u32 {
    let c = s_floor_i32(s_mul(s_sub(x, origin), ant_world_s(ANT_WORLD_H_GRID_INV_CELL)));
    return u32(clamp(c, 0, i32(n) - 1));
}

// The grid cell of `p`, as (column, row).
fn ant_world_cell_xy(p: vec2<S>) -> vec2<u32> {
    let size = ant_world_grid_size();
    let o = ANT_WORLD_H_GRID_ORIGIN;
    return vec2<u32>(
        ant_world_cell_axis(p.x, ant_world_s(o), size.x),
        ant_world_cell_axis(p.y, ant_world_s(o + 1u), size.y),
    );
}

// The grid cell of `p`: its key in the grid's sort, row by row.
fn ant_world_cell(p: vec2<S>) -> u32 {
    let c = ant_world_cell_xy(p);
    return c.y * ant_world[ANT_WORLD_H_GRID_NX] + c.x;
}
