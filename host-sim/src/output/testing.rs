//! Fixtures shared by the output module's tests.

use std::fmt::Debug;
use std::path::{Path, PathBuf};

use tempfile::TempDir;

use super::scene::{Scene, Shape, ShapeKind};
use crate::Result;

/// A fresh temporary folder and the path `name` in it; the folder goes with the guard.
pub(crate) fn temp_path(name: &str) -> (TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    (dir, path)
}

/// The names in `dir`, sorted.
pub(crate) fn entries(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Writes `contents` to `path` and returns the message of the error `read` gives for it.
pub(crate) fn read_error<'a, T: Debug>(
    path: &'a Path,
    contents: impl AsRef<[u8]>,
    read: impl FnOnce(&'a Path) -> Result<T>,
) -> String {
    std::fs::write(path, contents).unwrap();
    read(path).unwrap_err().to_string()
}

/// Writes `value` to `path` with `write`, checks that `read` gives it back, and returns the
/// file's text.
pub(crate) fn round_trip<'a, T: PartialEq + Debug>(
    path: &'a Path,
    value: &T,
    write: impl FnOnce(&T, &'a Path) -> Result<()>,
    read: impl FnOnce(&'a Path) -> Result<T>,
) -> String {
    write(value, path).unwrap();
    assert_eq!(&read(path).unwrap(), value);
    std::fs::read_to_string(path).unwrap()
}

/// A 2D scene 200 × 100: a nest, a food source moved at step 100, a rock triangle and a rock
/// box, and a disturbance during steps 10 to 50.
pub(crate) fn sample_scene() -> Scene {
    let mut s = Scene::new_2d([0.0, 0.0], [200.0, 100.0]);
    s.shapes = vec![
        Shape::circle([20.0, 50.0, 0.0], 6.0, ShapeKind::Nest).named("home"),
        Shape::circle([180.0, 50.0, 0.0], 5.0, ShapeKind::Food).during(None, Some(100)),
        Shape::circle([150.0, 80.0, 0.0], 5.0, ShapeKind::Food).during(Some(100), None),
        Shape::polygon(
            vec![[90.0, 40.0], [110.0, 40.0], [100.0, 60.0]],
            ShapeKind::Rock,
        ),
        Shape::circle([100.0, 20.0, 0.0], 8.0, ShapeKind::Disturbance).during(Some(10), Some(50)),
        Shape::cuboid([60.0, 70.0, 0.0], [70.0, 90.0, 0.0], ShapeKind::Rock),
    ];
    s
}
