//! Pictures of a run: a PNG snapshot of the last frame with fading trails, and an animated GIF.
//!
//! Everything is drawn by hand with simple raster operations (filled discs, rings, Bresenham
//! lines, scanline polygon fill, a 3×5 pixel font) onto an indexed canvas whose colours come
//! from one fixed palette. The PNG is that canvas expanded to RGB (an [`image::RgbImage`]); the
//! GIF uses the palette directly as its global colour table, so no quantisation is needed and
//! the output is deterministic: the same inputs give the same bytes.
//!
//! 2D worlds are drawn with x to the right and y up; 3D worlds as a top view (looking down the
//! y axis) with x to the right and z down, and below it a side view (looking along +z: x to the
//! right, y up) in which every bee is drawn as its body along its heading (a line from the dot
//! toward where it flies) and its wings as a dark bar through the dot along the rolled wing axis
//! cos(roll)·s − sin(roll)·up (s = heading × up, the bee's right), projected: a bee flying
//! across the view shows its roll as the tilt of the bar (positive roll: right wing down).
//! Shafts are drawn full height in the side view.
//!
//! The pieces: `canvas` (the indexed raster and its primitives), `font` (the 3×5 pixel font),
//! `palette` (the fixed colours and their indices), `view` (world to pixels: plan, top and side
//! views), `draw` (a frame of a scene: world, objects, trails, agents, the 3D side panel),
//! `legend` (legend and step), `snapshot` (the PNG) and `animation` (the GIF).

mod animation;
mod canvas;
mod draw;
mod font;
mod legend;
mod palette;
mod snapshot;
mod view;

#[cfg(test)]
mod tests;

use std::path::Path;

use super::frames::{Frame, check_frames};
use super::scene::Scene;
use crate::{Result, SimError};

pub use animation::gif_frame_indices;
pub use palette::{agent_color, kind_color};

/// How agents are coloured.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ColorBy {
    /// By label in 2D worlds (ants), by group in 3D worlds (bees).
    #[default]
    Auto,
    /// By state label (ants: nothing grey, food green, nest blue).
    Label,
    /// By agent group.
    Group,
}

/// Rendering settings.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    /// PNG width in pixels (height follows the world's aspect ratio, at most 4× the width).
    pub width: u32,
    /// PNG: trail length in recorded frames.
    pub trail: usize,
    /// Trails are drawn for at most this many agents (an evenly spaced subset by id).
    pub max_trail_agents: usize,
    /// Agent dot radius in PNG pixels; `None` picks one from the agent count.
    pub agent_radius_px: Option<f32>,
    /// PNG: draw a legend (colour swatches with names) and the step.
    pub legend: bool,
    /// Agent colours.
    pub color_by: ColorBy,
    /// GIF width in pixels.
    pub gif_width: u32,
    /// GIF: at most this many frames (evenly subsampled, first and last kept).
    pub gif_max_frames: usize,
    /// GIF: trail length, in shown GIF frames.
    pub gif_trail: usize,
    /// GIF: delay between frames in hundredths of a second.
    pub gif_delay_cs: u16,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            width: 1024,
            trail: 60,
            max_trail_agents: 2000,
            agent_radius_px: None,
            legend: true,
            color_by: ColorBy::Auto,
            gif_width: 480,
            gif_max_frames: 150,
            gif_trail: 6,
            gif_delay_cs: 6,
        }
    }
}

/// Refuses what cannot be drawn: an invalid scene, no frames, or frames that do not match.
fn check_inputs(scene: &Scene, frames: &[Frame], path: &Path) -> Result<()> {
    scene.validate(path)?;
    if frames.is_empty() {
        return Err(SimError::NoFrames {
            path: path.to_path_buf(),
        });
    }
    check_frames(frames, path)?;
    Ok(())
}

/// Renders the PNG image (RGB) of the last frame in memory, without writing it.
pub fn snapshot_image(
    scene: &Scene,
    frames: &[Frame],
    opts: &RenderOptions,
) -> Result<image::RgbImage> {
    check_inputs(scene, frames, Path::new("<snapshot>"))?;
    Ok(snapshot::snapshot_rgb(scene, frames, opts))
}

/// Writes a PNG snapshot of the last frame: objects visible at its step, fading trails of the last
/// `opts.trail` frames (for at most `opts.max_trail_agents` agents), every agent as a dot
/// coloured by label or group, and a legend. Whole or not at all.
pub fn render_png(
    scene: &Scene,
    frames: &[Frame],
    path: impl AsRef<Path>,
    opts: &RenderOptions,
) -> Result<()> {
    let path = path.as_ref();
    check_inputs(scene, frames, path)?;
    snapshot::write_png(&snapshot::snapshot_rgb(scene, frames, opts), path)
}

/// Writes an animated, looping GIF of the run: at most `opts.gif_max_frames` frames, each with
/// the objects visible at its step, short fading trails, the agents and the step number. Uses
/// the renderer's fixed palette (no quantisation). Whole or not at all.
pub fn render_gif(
    scene: &Scene,
    frames: &[Frame],
    path: impl AsRef<Path>,
    opts: &RenderOptions,
) -> Result<()> {
    let path = path.as_ref();
    check_inputs(scene, frames, path)?;
    animation::write_gif(scene, frames, path, opts)
}
