//! The PNG snapshot: the last frame with fading trails, a legend and, for a 3D scene, the side
//! view below the top view.

use std::io;
use std::path::Path;

use image::ImageEncoder;
use image::codecs::png::{CompressionType, FilterType, PngEncoder};

use super::RenderOptions;
use super::canvas::{Canvas, stack};
use super::draw::{AgentStyle, auto_radius, frame_canvas};
use super::legend::draw_legend;
use super::palette::palette;
use super::view::View;
use crate::Result;
use crate::output::atomic::write_atomic;
use crate::output::frames::Frame;
use crate::output::scene::Scene;

/// Draws the last frame with trails, the legend and, for a 3D scene, the side view below.
fn snapshot_canvas(scene: &Scene, frames: &[Frame], opts: &RenderOptions) -> Canvas {
    let view = View::new(scene, opts.width);
    let last = frames.len() - 1;
    let frame = &frames[last];
    let n = frame.agents.len();
    let r = opts
        .agent_radius_px
        .unwrap_or_else(|| auto_radius(n, view.w));
    let style = AgentStyle::new(opts, scene, n, r);
    let idx: Vec<usize> = (last.saturating_sub(opts.trail)..=last).collect();
    let mut canvas = frame_canvas(&view, scene, frames, &idx, frame, style);
    if opts.legend {
        let scale = (view.w as i64 / 400).max(1);
        draw_legend(&mut canvas, scene, frame, style.by, scale);
    }
    if scene.dim == 3 {
        let side = View::side(scene, &view);
        canvas = stack(
            canvas,
            &frame_canvas(&side, scene, frames, &idx, frame, style),
        );
    }
    canvas
}

/// The RGB image of the last frame (see [`snapshot_canvas`]).
pub(super) fn snapshot_rgb(
    scene: &Scene,
    frames: &[Frame],
    opts: &RenderOptions,
) -> image::RgbImage {
    to_rgb(&snapshot_canvas(scene, frames, opts))
}

fn to_rgb(canvas: &Canvas) -> image::RgbImage {
    let pal = palette();
    let mut rgb = Vec::with_capacity(canvas.px.len() * 3);
    for &i in &canvas.px {
        rgb.extend_from_slice(&pal[i as usize]);
    }
    image::RgbImage::from_raw(canvas.w as u32, canvas.h as u32, rgb).expect("buffer size matches")
}

/// Writes `img` as a PNG file, whole or not at all.
pub(super) fn write_png(img: &image::RgbImage, path: &Path) -> Result<()> {
    write_atomic(path, |w| {
        PngEncoder::new_with_quality(w, CompressionType::Default, FilterType::Adaptive)
            .write_image(
                img.as_raw(),
                img.width(),
                img.height(),
                image::ExtendedColorType::Rgb8,
            )
            .map_err(io::Error::other)
    })
}
