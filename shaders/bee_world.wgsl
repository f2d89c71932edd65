// The bee world (host-sim/src/gpu/shaders.rs, BEE_WORLD): the volume, the ranges, the grids,
// the obstacles, the targets and their particles, as u32 words in the layout of
// host-sim/src/gpu/bee/world.rs (which packs them on the host, every value converted there as
// host-sim/src/bees/sense.rs and world.rs convert it), over the scalar `S`; and the obstacles'
// geometry of host-sim/src/bees/world.rs (`sphere_surface`, `box_surface_open`,
// `shaft_surface_open`, `Shape3::surface`), function by function: in fixed point every closest
// point, normal, distance and inside test is the CPU's bit for bit. The buffer is binding 1 of
// group 0 of every kernel that composes this module.
//
// The grids are the GPU's own: the cell of a point is `floor((x - origin) · (1 / cell))` per
// axis, clamped to the grid, computed in `S`; its key `(z · ny + y) · nx + x`. It is monotonic
// in each coordinate, so the cells between the keys of `p - r` and `p + r` hold every point
// within `r` of `p` on each axis (world.rs says why).

@group(0) @binding(1) var<storage, read> bee_world: array<u32>;

// Words of the header, a grid's shape (in the header), an obstacle, a target, a particle.
const BEE_WORLD_HEADER_WORDS: u32 = 32u;
const BEE_WORLD_GRID_WORDS: u32 = 8u;
const BEE_WORLD_OBSTACLE_WORDS: u32 = 16u;
const BEE_WORLD_TARGET_WORDS: u32 = 6u;
const BEE_WORLD_PARTICLE_WORDS: u32 = 4u;

// The header's words.
const BEE_WORLD_H_OBSTACLES: u32 = 0u;
const BEE_WORLD_H_OBSTACLES_AT: u32 = 1u;
const BEE_WORLD_H_TARGETS: u32 = 2u;
const BEE_WORLD_H_TARGETS_AT: u32 = 3u;
const BEE_WORLD_H_PARTICLES: u32 = 4u;
const BEE_WORLD_H_PARTICLES_AT: u32 = 5u;
const BEE_WORLD_H_PARTICLE_STARTS_AT: u32 = 6u;
const BEE_WORLD_H_BOUNDS: u32 = 7u;
const BEE_WORLD_H_RANGE: u32 = 13u;
const BEE_WORLD_H_RANGE2: u32 = 14u;
const BEE_WORLD_H_SENSE: u32 = 15u;
const BEE_WORLD_H_GRID: u32 = 16u;
const BEE_WORLD_H_PARTICLE_GRID: u32 = 24u;

// A grid's words, from its first.
const BEE_WORLD_G_ORIGIN: u32 = 0u;
const BEE_WORLD_G_INV_CELL: u32 = 3u;
const BEE_WORLD_G_SIZE: u32 = 4u;
const BEE_WORLD_G_MARGIN: u32 = 7u;

// Shape3, the `shape` of a BeeWorldObstacle.
const BEE_WORLD_SPHERE: u32 = 0u;
const BEE_WORLD_BOX: u32 = 1u;
const BEE_WORLD_SHAFT: u32 = 2u;

// A bee's goal when its group has none (target ids are u16).
const BEE_WORLD_NO_GOAL: u32 = 0xffffffffu;

// BeeObstacle: its shape, id, whether it is present, its open faces (a box's -x, +x, -y, +y,
// -z, +z as bits 0 to 5; a shaft's bottom and top caps as bits 0 and 1: decided on the host as
// Shape3::surface decides them), its bounding box (`lo`, `hi`, for a cheap rejection), and the
// shape's numbers: a sphere's centre `a` and radius `b.x`; a box's corners `a` and `b`; a
// shaft's axis (`a.x`, `a.y` = x, z), radius `a.z`, bottom `b.x` and top `b.y`.
struct BeeWorldObstacle {
    shape: u32,
    id: u32,
    present: bool,
    open: u32,
    lo: vec3<S>,
    hi: vec3<S>,
    a: vec3<S>,
    b: vec3<S>,
}

// A uniform grid: the lower corner of cell 0, 1 / the cells' edge, the cells along each axis,
// and what a query adds to its radius.
struct BeeWorldGrid {
    origin: vec3<S>,
    inv_cell: S,
    size: vec3<u32>,
    margin: S,
}

// Surface<S> (world.rs): the closest point of an obstacle's surface to a query point, the
// outward unit normal there, the distance, and whether the point is inside the solid.
struct BeeWorldSurface {
    point: vec3<S>,
    normal: vec3<S>,
    distance: S,
    inside: bool,
}

// Header word `k` as an S.
fn bee_world_s(k: u32) -> S {
    return s_from_word(bee_world[k]);
}

fn bee_world_v3(at: u32) -> vec3<S> {
    return vec3<S>(
        s_from_word(bee_world[at]),
        s_from_word(bee_world[at + 1u]),
        s_from_word(bee_world[at + 2u]),
    );
}

// The volume's corners (BeeWorld::min, max in S: `at` of world.rs).
fn bee_world_min() -> vec3<S> {
    return bee_world_v3(BEE_WORLD_H_BOUNDS);
}

fn bee_world_max() -> vec3<S> {
    return bee_world_v3(BEE_WORLD_H_BOUNDS + 3u);
}

fn bee_world_obstacles() -> u32 {
    return bee_world[BEE_WORLD_H_OBSTACLES];
}

// Obstacle `k` (0 ≤ k < bee_world_obstacles()).
fn bee_world_obstacle(k: u32) -> BeeWorldObstacle {
    let b = bee_world[BEE_WORLD_H_OBSTACLES_AT] + k * BEE_WORLD_OBSTACLE_WORDS;
    return BeeWorldObstacle(
        bee_world[b],
        bee_world[b + 1u],
        bee_world[b + 2u] != 0u,
        bee_world[b + 3u],
        bee_world_v3(b + 4u),
        bee_world_v3(b + 7u),
        bee_world_v3(b + 10u),
        bee_world_v3(b + 13u),
    );
}

// Whether p lies within `r` of obstacle `o`'s bounding box on every axis (a cheap rejection
// with a margin in `r`: every point whose surface distance is within the range passes).
fn bee_world_near(o: BeeWorldObstacle, p: vec3<S>, r: S) -> bool {
    let lo = geom_vec3_sub(o.lo, vec3<S>(r, r, r));
    let hi = geom_vec3_add(o.hi, vec3<S>(r, r, r));
    return all(p >= lo) && all(p <= hi);
}

// BeeWorld::target_center: the centre of the first active target with object id `id`.
fn bee_world_target_center(id: u32) -> GeomOptionVec3 {
    let n = bee_world[BEE_WORLD_H_TARGETS];
    let at = bee_world[BEE_WORLD_H_TARGETS_AT];
    for (var k = 0u; k < n; k = k + 1u) {
        let b = at + k * BEE_WORLD_TARGET_WORDS;
        if (bee_world[b] == id && bee_world[b + 1u] != 0u) {
            return GeomOptionVec3(true, bee_world_v3(b + 2u));
        }
    }
    return GeomOptionVec3(false, vec3<S>());
}

// The target particles: `count` of them, in the order of the particles' grid.
fn bee_world_particles() -> u32 {
    return bee_world[BEE_WORLD_H_PARTICLES];
}

// The particle in place `s` of the particles' grid: its point.
fn bee_world_particle(s: u32) -> vec3<S> {
    return bee_world_v3(bee_world[BEE_WORLD_H_PARTICLES_AT] + s * BEE_WORLD_PARTICLE_WORDS);
}

// Its index among the particles (BeeWorld::particles; the tie key of the selection).
fn bee_world_particle_index(s: u32) -> u32 {
    return bee_world[bee_world[BEE_WORLD_H_PARTICLES_AT] + s * BEE_WORLD_PARTICLE_WORDS + 3u];
}

// The particles' grid's `starts`: the particles of cell `c` are in places
// starts(c)..starts(c + 1).
fn bee_world_particle_start(c: u32) -> u32 {
    return bee_world[bee_world[BEE_WORLD_H_PARTICLE_STARTS_AT] + c];
}

// ---- the grids ----

// The grid whose words start at header word `at` (BEE_WORLD_H_GRID: the bees';
// BEE_WORLD_H_PARTICLE_GRID: the particles').
fn bee_world_grid(at: u32) -> BeeWorldGrid {
    return BeeWorldGrid(
        bee_world_v3(at + BEE_WORLD_G_ORIGIN),
        bee_world_s(at + BEE_WORLD_G_INV_CELL),
        vec3<u32>(
            bee_world[at + BEE_WORLD_G_SIZE],
            bee_world[at + BEE_WORLD_G_SIZE + 1u],
            bee_world[at + BEE_WORLD_G_SIZE + 2u],
        ),
        bee_world_s(at + BEE_WORLD_G_MARGIN),
    );
}

// The cell of coordinate `x` on an axis of `n` cells from `origin` (GridShape3::cell_xyz).
fn bee_world_cell_axis(x: S, origin: S, inv_cell: S, n: u32) -> u32 {
    let c = s_floor_i32(s_mul(s_sub(x, origin), inv_cell));
    return u32(clamp(c, 0, i32(n) - 1));
}

// The cell of `p` in grid `g`, as (x, y, z).
fn bee_world_cell_xyz(g: BeeWorldGrid, p: vec3<S>) -> vec3<u32> {
    return vec3<u32>(
        bee_world_cell_axis(p.x, g.origin.x, g.inv_cell, g.size.x),
        bee_world_cell_axis(p.y, g.origin.y, g.inv_cell, g.size.y),
        bee_world_cell_axis(p.z, g.origin.z, g.inv_cell, g.size.z),
    );
}

// The key of cell `c` of grid `g` in its sort: (z · ny + y) · nx + x (GridShape3::cell_of).
fn bee_world_cell_key(g: BeeWorldGrid, c: vec3<u32>) -> u32 {
    return (c.z * g.size.y + c.y) * g.size.x + c.x;
}

// The key of the cell of `p` in the bees' grid.
fn bee_world_cell(p: vec3<S>) -> u32 {
    let g = bee_world_grid(BEE_WORLD_H_GRID);
    return bee_world_cell_key(g, bee_world_cell_xyz(g, p));
}

// ---- obstacle geometry (world.rs) ----

// `d.normalized().unwrap_or_else(up)`: straight up is the normal of last resort.
fn bee_world_normalized_or_up(d: vec3<S>) -> vec3<S> {
    let n = geom_vec3_normalized(d);
    return select(geom_vec3_up(), n.value, n.is_some);
}

// from_outside: a surface point seen from outside: `p` is off the solid, `q` the closest solid
// point.
fn bee_world_from_outside(p: vec3<S>, q: vec3<S>) -> BeeWorldSurface {
    let d = geom_vec3_sub(p, q);
    return BeeWorldSurface(q, bee_world_normalized_or_up(d), geom_vec3_length(d), false);
}

// sphere_surface: the radial projection of p and the radial normal (the centre itself: the top
// point, normal up).
fn bee_world_sphere_surface(center: vec3<S>, radius: S, p: vec3<S>) -> BeeWorldSurface {
    let d = geom_vec3_sub(p, center);
    let len = geom_vec3_length(d);
    let normal = bee_world_normalized_or_up(d);
    return BeeWorldSurface(
        geom_vec3_add(center, geom_vec3_mul(normal, radius)),
        normal,
        s_abs(s_sub(len, radius)),
        len < radius,
    );
}

// Whether coordinate `x` lies inside [lo, hi] as box_surface_open's `inside` decides on one
// axis: strictly past an open face, on or past a closed one.
fn bee_world_box_within(x: S, lo: S, hi: S, open_lo: bool, open_hi: bool) -> bool {
    let above = select(x >= lo, x > lo, open_lo);
    let below = select(x <= hi, x < hi, open_hi);
    return above && below;
}

// box_surface_open: the axis-aligned box [lo, hi]. Outside: the clamped point, the normal from
// it to p (face, edge or corner). Inside: the nearest open face (bit f of `open_faces`, faces
// -x, +x, -y, +y, -z, +z; ties in that order), its normal; a point on a closed face counts as
// inside. With no face open, all are. (`box_surface` is this with every face open.)
fn bee_world_box_surface_open(lo: vec3<S>, hi: vec3<S>, p: vec3<S>, open_faces: u32)
    -> BeeWorldSurface {
    let q = vec3<S>(
        s_clamp_to(p.x, lo.x, hi.x),
        s_clamp_to(p.y, lo.y, hi.y),
        s_clamp_to(p.z, lo.z, hi.z),
    );
    if (any(q != p)) {
        return bee_world_from_outside(p, q);
    }
    var open = open_faces & 0x3fu;
    if (open == 0u) {
        open = 0x3fu;
    }
    var found = false;
    var distance = S_ZERO;
    var face = 0u;
    for (var f = 0u; f < 6u; f = f + 1u) {
        let k = f / 2u;
        var dist = s_sub(hi[k], p[k]);
        if (f % 2u == 0u) {
            dist = s_sub(p[k], lo[k]);
        }
        if ((open & (1u << f)) != 0u && (!found || dist < distance)) {
            found = true;
            distance = dist;
            face = f;
        }
    }
    let k = face / 2u;
    var point = p;
    var one = S_ONE;
    if (face % 2u == 0u) {
        point[k] = lo[k];
        one = s_neg(S_ONE);
    } else {
        point[k] = hi[k];
    }
    // `with_axis(Vec3::zero(), k, ±1)`, each component chosen rather than written, so that no
    // compiler folds the sign into the whole vector (-0 for the zero components, in f32).
    let normal = vec3<S>(
        select(S_ZERO, one, k == 0u),
        select(S_ZERO, one, k == 1u),
        select(S_ZERO, one, k == 2u),
    );
    let inside = bee_world_box_within(p.x, lo.x, hi.x, (open & 1u) != 0u, (open & 2u) != 0u)
        && bee_world_box_within(p.y, lo.y, hi.y, (open & 4u) != 0u, (open & 8u) != 0u)
        && bee_world_box_within(p.z, lo.z, hi.z, (open & 16u) != 0u, (open & 32u) != 0u);
    return BeeWorldSurface(point, normal, distance, inside);
}

// shaft_surface_open: the vertical cylinder of axis `center` = (x, z), `radius`, from `y_min`
// to `y_max`. Outside: the closest point on the side, a cap or the rim edge between them, the
// normal from it to p. Inside: the nearest of the side (radial normal; on the axis, +x) and the
// open caps (bit 0 of `open_caps` the bottom, bit 1 the top; ties: side, bottom, top); a point
// on a closed cap counts as inside. (`shaft_surface` is this with both caps open.)
fn bee_world_shaft_surface_open(
    center: vec2<S>,
    radius: S,
    y_min: S,
    y_max: S,
    p: vec3<S>,
    open_caps: u32,
) -> BeeWorldSurface {
    let d = vec2<S>(s_sub(p.x, center.x), s_sub(p.z, center.y));
    let rho = geom_length(d);
    let radial = geom_normalized_or(d, vec2<S>(S_ONE, S_ZERO));
    if (rho > radius || p.y < y_min || p.y > y_max) {
        let r = s_min(rho, radius);
        let q = vec3<S>(
            s_add(center.x, s_mul(radial.x, r)),
            s_clamp_to(p.y, y_min, y_max),
            s_add(center.y, s_mul(radial.y, r)),
        );
        return bee_world_from_outside(p, q);
    }
    let open_bottom = (open_caps & 1u) != 0u;
    let open_top = (open_caps & 2u) != 0u;
    // The side, then the caps if open and strictly nearer: `cap` 0 for the side, 1 the
    // bottom, 2 the top.
    var cap = 0u;
    var distance = s_sub(radius, rho);
    let bottom = s_sub(p.y, y_min);
    if (open_bottom && bottom < distance) {
        cap = 1u;
        distance = bottom;
    }
    let top = s_sub(y_max, p.y);
    if (open_top && top < distance) {
        cap = 2u;
        distance = top;
    }
    // The side's point and normal (radial.x, 0, radial.y), a cap's (p.x, y, p.z) and ∓up
    // (-up = (-0, -1, -0)), each component chosen rather than written, so that no compiler
    // folds a cap's sign into the side's zero (-0, in f32).
    let on_cap = cap != 0u;
    let is_bottom = cap == 1u;
    let down = geom_vec3_neg(geom_vec3_up());
    let cap_normal = select(geom_vec3_up(), down, is_bottom);
    var best = BeeWorldSurface(
        vec3<S>(
            select(s_add(center.x, s_mul(radial.x, radius)), p.x, on_cap),
            select(p.y, select(y_max, y_min, is_bottom), on_cap),
            select(s_add(center.y, s_mul(radial.y, radius)), p.z, on_cap),
        ),
        vec3<S>(
            select(radial.x, cap_normal.x, on_cap),
            select(S_ZERO, cap_normal.y, on_cap),
            select(radial.y, cap_normal.z, on_cap),
        ),
        distance,
        false,
    );
    let lo = select(p.y >= y_min, p.y > y_min, open_bottom);
    let hi = select(p.y <= y_max, p.y < y_max, open_top);
    best.inside = rho < radius && lo && hi;
    return best;
}

// Shape3::surface (BeeWorld::surface): the closest surface point of obstacle `o` to p, the
// faces lying on or beyond the world's bounds closed (`o.open`).
fn bee_world_surface(o: BeeWorldObstacle, p: vec3<S>) -> BeeWorldSurface {
    if (o.shape == BEE_WORLD_SPHERE) {
        return bee_world_sphere_surface(o.a, o.b.x, p);
    } else if (o.shape == BEE_WORLD_BOX) {
        return bee_world_box_surface_open(o.a, o.b, p, o.open);
    }
    return bee_world_shaft_surface_open(o.a.xy, o.a.z, o.b.x, o.b.y, p, o.open);
}
