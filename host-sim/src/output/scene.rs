//! `scene.json`: what to draw besides the agents, so `swarm render` can redraw a run later.
//!
//! ```json
//! {
//!   "dim": 2,
//!   "min": [0.0, 0.0, 0.0],
//!   "max": [200.0, 100.0, 0.0],
//!   "shapes": [
//!     { "type": "circle", "center": [20.0, 50.0, 0.0], "radius": 5.0, "kind": "nest", "name": "home" },
//!     { "type": "circle", "center": [180.0, 50.0, 0.0], "radius": 4.0, "kind": "food", "to_step": 1500 },
//!     { "type": "polygon", "points": [[90.0, 40.0], [110.0, 40.0], [100.0, 60.0]], "kind": "rock" },
//!     { "type": "box", "min": [0.0, 0.0, 0.0], "max": [1.0, 2.0, 1.0], "kind": "rock" }
//!   ]
//! }
//! ```
//!
//! Coordinates are world coordinates. 2D worlds (ants) draw the x–y plane; 3D worlds (bees, y up)
//! are drawn as a top view of the x–z plane. Polygon points are given in that drawing plane
//! (x, y in 2D; x, z in 3D). A shaft is a vertical cylinder: its circle's `center` y is ignored.
//! A shape is visible at step `s` when `from_step <= s < to_step` (each bound optional), which is
//! how objects added, removed or moved by timed events are recorded (a moved object is two
//! shapes with adjoining intervals).

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::json::{read_json, write_json};
use crate::{Result, SimError};

/// What an object is (decides its colour).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ShapeKind {
    /// An ant nest (dark brown disc).
    Nest,
    /// A food source (green disc).
    Food,
    /// A 2D obstacle (grey).
    Rock,
    /// A disturbance area (red ring).
    Disturbance,
    /// A way point (purple ring).
    Waypoint,
    /// A bee target (orange).
    Target,
    /// A vertical shaft obstacle (dark grey).
    Shaft,
    /// A spherical obstacle (slate grey).
    Sphere,
}

impl ShapeKind {
    /// Every kind, in legend order.
    pub const ALL: [ShapeKind; 8] = [
        ShapeKind::Nest,
        ShapeKind::Food,
        ShapeKind::Rock,
        ShapeKind::Disturbance,
        ShapeKind::Waypoint,
        ShapeKind::Target,
        ShapeKind::Shaft,
        ShapeKind::Sphere,
    ];
}

/// The geometry of a shape.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum Geometry {
    /// A disc (2D), a sphere or a vertical shaft (3D).
    Circle {
        /// Centre in world coordinates.
        center: [f32; 3],
        /// Radius.
        radius: f32,
    },
    /// A polygon in the drawing plane (x–y in 2D, x–z in 3D), at least 3 points.
    Polygon {
        /// The corners, in order.
        points: Vec<[f32; 2]>,
    },
    /// An axis-aligned box.
    Box {
        /// Smallest corner.
        min: [f32; 3],
        /// Largest corner.
        max: [f32; 3],
    },
}

/// One object to draw.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Shape {
    /// Its geometry (`"type"` plus fields, flattened into the shape's JSON object).
    #[serde(flatten)]
    pub geom: Geometry,
    /// What it is.
    pub kind: ShapeKind,
    /// Optional name (e.g. the nest name used in `deliveries_per_nest`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// First step it is visible at (inclusive); visible from the start when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub from_step: Option<u32>,
    /// Step it disappears at (exclusive); visible to the end when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub to_step: Option<u32>,
}

impl Shape {
    /// A circle visible all the time.
    pub fn circle(center: [f32; 3], radius: f32, kind: ShapeKind) -> Self {
        Self::new(Geometry::Circle { center, radius }, kind)
    }

    /// A polygon visible all the time.
    pub fn polygon(points: Vec<[f32; 2]>, kind: ShapeKind) -> Self {
        Self::new(Geometry::Polygon { points }, kind)
    }

    /// A box visible all the time.
    pub fn cuboid(min: [f32; 3], max: [f32; 3], kind: ShapeKind) -> Self {
        Self::new(Geometry::Box { min, max }, kind)
    }

    fn new(geom: Geometry, kind: ShapeKind) -> Self {
        Self {
            geom,
            kind,
            name: None,
            from_step: None,
            to_step: None,
        }
    }

    /// Sets the name.
    pub fn named(mut self, name: impl Into<String>) -> Self {
        self.name = Some(name.into());
        self
    }

    /// Sets the visible interval `[from, to)`.
    pub fn during(mut self, from: Option<u32>, to: Option<u32>) -> Self {
        self.from_step = from;
        self.to_step = to;
        self
    }

    /// Whether the shape is visible at `step`.
    pub fn visible_at(&self, step: u32) -> bool {
        self.from_step.is_none_or(|f| step >= f) && self.to_step.is_none_or(|t| step < t)
    }
}

/// Everything to draw besides the agents.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Scene {
    /// 2 (ants: x–y plane) or 3 (bees: y up, drawn as a top view of x–z).
    pub dim: u8,
    /// World bounds, smallest corner (z = 0 in 2D).
    pub min: [f32; 3],
    /// World bounds, largest corner (z = 0 in 2D).
    pub max: [f32; 3],
    /// The objects.
    #[serde(default)]
    pub shapes: Vec<Shape>,
}

impl Scene {
    /// An empty 2D world.
    pub fn new_2d(min: [f32; 2], max: [f32; 2]) -> Self {
        Self {
            dim: 2,
            min: [min[0], min[1], 0.0],
            max: [max[0], max[1], 0.0],
            shapes: Vec::new(),
        }
    }

    /// An empty 3D world.
    pub fn new_3d(min: [f32; 3], max: [f32; 3]) -> Self {
        Self {
            dim: 3,
            min,
            max,
            shapes: Vec::new(),
        }
    }

    /// The drawing-plane coordinates of a world point: (x, y) in 2D, (x, z) in 3D.
    pub fn plan(&self, p: [f32; 3]) -> [f32; 2] {
        if self.dim == 3 {
            [p[0], p[2]]
        } else {
            [p[0], p[1]]
        }
    }

    /// Checks the scene makes sense; `path` names the file in the error.
    pub fn validate(&self, path: &Path) -> Result<()> {
        let path = || path.to_path_buf();
        if self.dim != 2 && self.dim != 3 {
            return Err(SimError::SceneDim {
                path: path(),
                dim: self.dim,
            });
        }
        let lo = self.plan(self.min);
        let hi = self.plan(self.max);
        for k in 0..2 {
            if !(lo[k].is_finite() && hi[k].is_finite() && lo[k] < hi[k]) {
                return Err(SimError::SceneBounds {
                    path: path(),
                    min: self.min,
                    max: self.max,
                });
            }
        }
        for (i, s) in self.shapes.iter().enumerate() {
            let finite = |v: &[f32]| v.iter().all(|c| c.is_finite());
            let ok = match &s.geom {
                Geometry::Circle { center, radius } => {
                    finite(center) && radius.is_finite() && *radius >= 0.0
                }
                Geometry::Polygon { points } => {
                    points.len() >= 3 && points.iter().all(|p| finite(p))
                }
                Geometry::Box { min, max } => {
                    finite(min) && finite(max) && (0..3).all(|k| min[k] <= max[k])
                }
            };
            if !ok {
                return Err(SimError::SceneShape {
                    path: path(),
                    index: i,
                    shape: format!("{:?} {:?}", s.kind, s.geom),
                });
            }
            if let (Some(f), Some(t)) = (s.from_step, s.to_step)
                && f > t
            {
                return Err(SimError::SceneShapeSteps {
                    path: path(),
                    index: i,
                    from: f,
                    to: t,
                });
            }
        }
        Ok(())
    }

    /// Writes pretty `scene.json`, whole or not at all.
    pub fn write(&self, path: impl AsRef<Path>) -> Result<()> {
        let path = path.as_ref();
        self.validate(path)?;
        write_json(path, self)
    }

    /// Reads and validates a `scene.json`.
    pub fn read(path: impl AsRef<Path>) -> Result<Self> {
        let path = path.as_ref();
        let s: Scene = read_json(path)?;
        s.validate(path)?;
        Ok(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::testing::{read_error, round_trip, sample_scene, temp_path};

    #[test]
    fn json_round_trip_and_format() {
        let (_dir, p) = temp_path("scene.json");
        let text = round_trip(&p, &sample_scene(), Scene::write, Scene::read);
        assert!(text.contains("\"type\": \"circle\""), "{text}");
        assert!(text.contains("\"kind\": \"nest\""), "{text}");
        assert!(text.contains("\"to_step\": 100"), "{text}");
    }

    #[test]
    fn reads_hand_written_json() {
        let (_dir, p) = temp_path("scene.json");
        std::fs::write(
            &p,
            r#"{"dim": 3, "min": [0,0,0], "max": [10,5,10], "shapes": [
                {"type": "circle", "center": [5, 0, 5], "radius": 1, "kind": "shaft"},
                {"type": "box", "min": [1,1,1], "max": [2,2,2], "kind": "sphere", "from_step": 3}]}"#,
        )
        .unwrap();
        let s = Scene::read(&p).unwrap();
        assert_eq!(s.shapes.len(), 2);
        assert!(!s.shapes[1].visible_at(2) && s.shapes[1].visible_at(3));
        assert_eq!(s.plan([1.0, 2.0, 3.0]), [1.0, 3.0]);
    }

    #[test]
    fn visibility_interval() {
        let s = Shape::circle([0.0; 3], 1.0, ShapeKind::Food).during(Some(10), Some(20));
        assert!(!s.visible_at(9));
        assert!(s.visible_at(10));
        assert!(s.visible_at(19));
        assert!(!s.visible_at(20));
    }

    #[test]
    fn invalid_scenes_are_refused() {
        let (_dir, p) = temp_path("scene.json");
        let mut s = sample_scene();
        s.dim = 4;
        assert!(s.write(&p).unwrap_err().to_string().contains("dim"));
        let mut s = sample_scene();
        s.shapes
            .push(Shape::polygon(vec![[0.0, 0.0]], ShapeKind::Rock));
        assert!(s.write(&p).unwrap_err().to_string().contains("shape 6"));
        assert!(!p.exists());
        let bad = r#"{"dim": 2, "min": [0,0,0], "max": [0,1,0]}"#;
        let msg = read_error(&p, bad, Scene::read);
        assert!(
            msg.contains("scene.json") && msg.contains("bounds"),
            "{msg}"
        );
        let bad = r#"{"dim": 2, "min": [0,0,0], "max": [1,1,0], "shapes": [{"type": "blob"}]}"#;
        let msg = read_error(&p, bad, Scene::read);
        assert!(
            msg.contains("scene.json") && msg.contains("parsing"),
            "{msg}"
        );
    }
}
