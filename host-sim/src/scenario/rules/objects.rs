//! The rules of the objects: unique names, the kind fits the world, the geometry lies inside
//! the world (a polygon is simple), way point orders are unique.

use std::collections::HashMap;

use super::{Problem, finite_all, inside, positive, show};
use crate::scenario::types::{MAX_TARGET_PARTICLES, Object, ObjectKind, Scenario, World};

/// Checks the objects; returns the index of each name.
pub(super) fn validate_objects(s: &Scenario) -> Result<HashMap<&str, usize>, Problem> {
    if s.objects.len() > usize::from(u16::MAX) {
        return Err(Problem::new(
            "objects",
            format!(
                "at most {} objects (ids are 16-bit), found {}",
                u16::MAX,
                s.objects.len()
            ),
        ));
    }
    let mut names: HashMap<&str, usize> = HashMap::new();
    let mut orders: HashMap<u32, usize> = HashMap::new();
    for (i, o) in s.objects.iter().enumerate() {
        let path = format!("objects[{i}]");
        if o.name.is_empty() {
            return Err(Problem::new(
                format!("{path}.name"),
                "expected a non-empty name",
            ));
        }
        if let Some(j) = names.insert(&o.name, i) {
            return Err(Problem::new(
                format!("{path}.name"),
                format!(
                    "duplicate object name `{}` (also objects[{j}]); names must be unique",
                    o.name
                ),
            ));
        }
        if o.kind.dim() != s.world.dim() {
            return Err(Problem::new(
                format!("{path}.kind"),
                format!(
                    "a `{}` belongs in a {}D world ({}), but this world is {}D",
                    o.kind.tag(),
                    o.kind.dim(),
                    if o.kind.dim() == 2 { "ants" } else { "bees" },
                    s.world.dim()
                ),
            ));
        }
        validate_geometry(&s.world, o, &path)?;
        if let ObjectKind::Waypoint { order, .. } = o.kind
            && let Some(j) = orders.insert(order, i)
        {
            return Err(Problem::new(
                format!("{path}.order"),
                format!(
                    "way point order {order} is also used by objects[{j}]; orders must be unique"
                ),
            ));
        }
    }
    Ok(names)
}

pub(super) fn validate_geometry(world: &World, o: &Object, path: &str) -> Result<(), Problem> {
    let field = |f: &str| format!("{path}.{f}");
    // The round kinds with a centre point: the centre inside the world, a positive radius.
    if let (Some(center), Some(radius)) = (o.kind.point(), o.kind.radius()) {
        inside(world, center, &field("center"), "the centre")?;
        positive(radius, &field("radius"))?;
    }
    match &o.kind {
        ObjectKind::Nest { .. }
        | ObjectKind::Rock { .. }
        | ObjectKind::Disturbance { .. }
        | ObjectKind::Waypoint { .. }
        | ObjectKind::Sphere { .. }
        | ObjectKind::Zone { .. } => Ok(()),
        ObjectKind::Food { amount, .. } => {
            if *amount == Some(0) {
                return Err(Problem::new(
                    field("amount"),
                    "expected at least 1 unit of food (leave `amount` out for an endless source)",
                ));
            }
            Ok(())
        }
        ObjectKind::Target { particles, .. } => {
            if !(1..=MAX_TARGET_PARTICLES).contains(particles) {
                return Err(Problem::new(
                    field("particles"),
                    format!(
                        "expected 1 to {MAX_TARGET_PARTICLES} virtual particles, found {particles}"
                    ),
                ));
            }
            Ok(())
        }
        ObjectKind::Box { min, max }
        | ObjectKind::Region { min, max }
        | ObjectKind::Cave { min, max } => {
            inside(world, min, &field("min"), "the corner")?;
            inside(world, max, &field("max"), "the corner")?;
            if min.iter().zip(max).any(|(lo, hi)| lo >= hi) {
                return Err(Problem::new(
                    field("max"),
                    format!(
                        "expected `max` greater than `min` on every axis, found min {} max {}",
                        show(min),
                        show(max)
                    ),
                ));
            }
            Ok(())
        }
        ObjectKind::Shaft {
            center,
            radius,
            y_min,
            y_max,
        } => {
            finite_all(center, &field("center"))?;
            let (lo, hi) = (world.min(), world.max());
            if center[0] < lo[0] || center[0] > hi[0] || center[1] < lo[2] || center[1] > hi[2] {
                return Err(Problem::new(
                    field("center"),
                    format!(
                        "the axis [x, z] = {} lies outside the world's x range {}..{} or z \
                         range {}..{}",
                        show(center),
                        lo[0],
                        hi[0],
                        lo[2],
                        hi[2]
                    ),
                ));
            }
            positive(*radius, &field("radius"))?;
            for (v, f) in [(y_min, "y_min"), (y_max, "y_max")] {
                if !v.is_finite() || *v < lo[1] || *v > hi[1] {
                    return Err(Problem::new(
                        field(f),
                        format!(
                            "expected a height inside the world's y range {}..{}, found {v}",
                            lo[1], hi[1]
                        ),
                    ));
                }
            }
            if y_min >= y_max {
                return Err(Problem::new(
                    field("y_max"),
                    format!("expected `y_max` greater than `y_min` = {y_min}, found {y_max}"),
                ));
            }
            Ok(())
        }
        ObjectKind::Polygon { points } => {
            if points.len() < 3 {
                return Err(Problem::new(
                    field("points"),
                    format!(
                        "a polygon needs at least 3 points [x, y], found {}",
                        points.len()
                    ),
                ));
            }
            for (k, p) in points.iter().enumerate() {
                inside(world, p, &format!("{path}.points[{k}]"), "the point")?;
            }
            simple_polygon(points).map_err(|m| Problem::new(field("points"), m))
        }
    }
}

/// `Ok` when the closed polygon has no repeated consecutive points, no two non-adjacent edges
/// touching or crossing, and a non-zero area.
fn simple_polygon(points: &[[f32; 2]]) -> Result<(), String> {
    let n = points.len();
    let p = |i: usize| {
        let [x, y] = points[i % n];
        [f64::from(x), f64::from(y)]
    };
    for i in 0..n {
        if p(i) == p(i + 1) {
            return Err(format!(
                "points {i} and {} are the same point; a polygon's points must differ",
                (i + 1) % n
            ));
        }
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let on_segment = |a: [f64; 2], b: [f64; 2], q: [f64; 2]| {
        q[0] >= a[0].min(b[0])
            && q[0] <= a[0].max(b[0])
            && q[1] >= a[1].min(b[1])
            && q[1] <= a[1].max(b[1])
    };
    let intersects = |a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]| {
        let (d1, d2) = (cross(c, d, a), cross(c, d, b));
        let (d3, d4) = (cross(a, b, c), cross(a, b, d));
        if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
            && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
        {
            return true;
        }
        (d1 == 0.0 && on_segment(c, d, a))
            || (d2 == 0.0 && on_segment(c, d, b))
            || (d3 == 0.0 && on_segment(a, b, c))
            || (d4 == 0.0 && on_segment(a, b, d))
    };
    for i in 0..n {
        for j in i + 1..n {
            let adjacent = j == i + 1 || (i == 0 && j == n - 1);
            if adjacent {
                continue;
            }
            if intersects(p(i), p(i + 1), p(j), p(j + 1)) {
                return Err(format!(
                    "the polygon is not simple: edge {i} (points {i}-{}) touches or crosses \
                     edge {j} (points {j}-{})",
                    (i + 1) % n,
                    (j + 1) % n
                ));
            }
        }
    }
    let area2: f64 = (0..n)
        .map(|i| p(i)[0] * p(i + 1)[1] - p(i + 1)[0] * p(i)[1])
        .sum();
    if area2 == 0.0 {
        return Err("the polygon has zero area (its points are collinear)".to_owned());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simple_polygons() {
        assert!(simple_polygon(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]).is_ok());
        // A bow tie crosses itself.
        assert!(simple_polygon(&[[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]]).is_err());
        assert!(simple_polygon(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]).is_err());
        assert!(simple_polygon(&[[0.0, 0.0], [0.0, 0.0], [2.0, 2.0]]).is_err());
    }
}
