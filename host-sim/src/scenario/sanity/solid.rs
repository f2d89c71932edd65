//! The solids of the obstacles, with exact tests of a point, a disc or a ball against them.

use crate::ants::{AntObjectDef, AntObjectKind, Shape2};
use crate::scenario::types::ObjectKind;

/// An obstacle's solid.
pub(super) enum Solid {
    Disc([f32; 2], f32),
    /// A polygon, as the engine's object (for its inside test).
    Polygon(AntObjectDef),
    Ball([f32; 3], f32),
    Cuboid([f32; 3], [f32; 3]),
    /// A vertical cylinder: axis `[x, z]`, radius, y range.
    Cylinder([f32; 2], f32, f32, f32),
}

pub(super) fn dist(a: &[f32], b: &[f32]) -> f32 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f32>()
        .sqrt()
}

impl Solid {
    pub(super) fn of(kind: &ObjectKind) -> Option<Solid> {
        Some(match kind {
            ObjectKind::Rock { center, radius } => Solid::Disc(*center, *radius),
            ObjectKind::Polygon { points } => Solid::Polygon(AntObjectDef {
                id: 0,
                name: String::new(),
                kind: AntObjectKind::Obstacle,
                shape: Shape2::Polygon {
                    points: points.clone(),
                },
                active: true,
            }),
            ObjectKind::Sphere { center, radius } => Solid::Ball(*center, *radius),
            ObjectKind::Box { min, max } => Solid::Cuboid(*min, *max),
            ObjectKind::Shaft {
                center,
                radius,
                y_min,
                y_max,
            } => Solid::Cylinder(*center, *radius, *y_min, *y_max),
            _ => return None,
        })
    }

    /// (inside, distance from `p` to the boundary) for the 2D solids.
    fn polygon_probe(def: &AntObjectDef, p: &[f32]) -> (bool, f32) {
        let p = [p[0], p.get(1).copied().unwrap_or(0.0)];
        let (q, inside) = def.closest(swarm_core::Vec2::new(p[0], p[1]));
        (inside, dist(&p, &[q.x, q.y]))
    }

    /// Whether the point `p` (`dim` numbers) lies inside (borders included).
    pub(super) fn contains_point(&self, p: &[f32]) -> bool {
        self.contains_round(p, 0.0)
    }

    /// Whether the disc or ball (`c`, `r`) lies wholly inside (borders included).
    pub(super) fn contains_round(&self, c: &[f32], r: f32) -> bool {
        match self {
            Solid::Disc(center, radius) => dist(c, center) + r <= *radius,
            Solid::Ball(center, radius) => dist(c, center) + r <= *radius,
            Solid::Polygon(def) => {
                let (inside, d) = Self::polygon_probe(def, c);
                inside && d >= r
            }
            Solid::Cuboid(lo, hi) => (0..3).all(|k| c[k] - r >= lo[k] && c[k] + r <= hi[k]),
            Solid::Cylinder(axis, radius, y0, y1) => {
                dist(&[c[0], c[2]], axis) + r <= *radius && c[1] - r >= *y0 && c[1] + r <= *y1
            }
        }
    }

    /// Whether the disc or ball (`c`, `r`) and the solid share more than a boundary point.
    pub(super) fn overlaps_round(&self, c: &[f32], r: f32) -> bool {
        match self {
            Solid::Disc(center, radius) => dist(c, center) < r + radius,
            Solid::Ball(center, radius) => dist(c, center) < r + radius,
            Solid::Polygon(def) => {
                let (inside, d) = Self::polygon_probe(def, c);
                inside || d < r
            }
            Solid::Cuboid(lo, hi) => {
                let q: Vec<f32> = (0..3).map(|k| c[k].clamp(lo[k], hi[k])).collect();
                dist(c, &q) < r
            }
            Solid::Cylinder(axis, radius, y0, y1) => {
                let out_h = (dist(&[c[0], c[2]], axis) - radius).max(0.0);
                let out_y = (y0 - c[1]).max(c[1] - y1).max(0.0);
                out_h.hypot(out_y) < r
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes_contain_and_overlap_exactly() {
        let disc = Solid::Disc([0.0, 0.0], 10.0);
        assert!(disc.contains_round(&[5.0, 0.0], 5.0));
        assert!(!disc.contains_round(&[5.0, 0.0], 5.5));
        assert!(disc.overlaps_round(&[14.0, 0.0], 5.0));
        assert!(
            !disc.overlaps_round(&[15.0, 0.0], 5.0),
            "touching is not overlapping"
        );
        // A concave polygon (a U): the notch is outside.
        let u = Solid::of(&ObjectKind::Polygon {
            points: vec![
                [0.0, 0.0],
                [30.0, 0.0],
                [30.0, 30.0],
                [20.0, 30.0],
                [20.0, 10.0],
                [10.0, 10.0],
                [10.0, 30.0],
                [0.0, 30.0],
            ],
        })
        .unwrap();
        assert!(u.contains_round(&[5.0, 15.0], 4.0));
        assert!(!u.contains_round(&[5.0, 15.0], 6.0));
        assert!(!u.contains_point(&[15.0, 20.0]), "the notch");
        assert!(!u.overlaps_round(&[15.0, 20.0], 4.0));
        assert!(u.overlaps_round(&[15.0, 20.0], 6.0));
        let cube = Solid::Cuboid([0.0; 3], [10.0; 3]);
        assert!(cube.contains_round(&[5.0; 3], 5.0));
        assert!(!cube.contains_round(&[5.0, 5.0, 6.0], 5.0));
        assert!(cube.overlaps_round(&[5.0, 12.0, 5.0], 2.5));
        assert!(
            !cube.overlaps_round(&[12.0, 12.0, 5.0], 2.5),
            "corner distance is 2.83"
        );
        let shaft = Solid::Cylinder([0.0, 0.0], 3.0, 0.0, 20.0);
        assert!(shaft.contains_round(&[1.0, 10.0, 0.0], 2.0));
        assert!(!shaft.contains_round(&[1.0, 19.0, 0.0], 2.0));
        assert!(shaft.overlaps_round(&[0.0, 21.0, 0.0], 2.0));
        assert!(!shaft.overlaps_round(&[5.0, 10.0, 0.0], 1.5));
        let ball = Solid::Ball([0.0; 3], 4.0);
        assert!(ball.contains_point(&[0.0, 4.0, 0.0]));
        assert!(!ball.contains_point(&[0.0, 4.1, 0.0]));
    }
}
