//! The PNG snapshot: the last frame with fading trails, a legend and, for a 3D scene, the side
//! view below the top view.

use std::io;
use std::path::Path;

use image::ImageEncoder;
use image::codecs::png::{CompressionType, FilterType, PngEncoder};

use super::canvas::{CLEAR, Canvas, compose, stack};
use super::draw::{
    auto_radius, draw_agents, draw_base, draw_objects, draw_trails, side_canvas, trail_stride,
};
use super::legend::draw_legend;
use super::palette::{I_BG, palette, resolve_color_by};
use super::view::View;
use super::{RenderOptions, check_inputs};
use crate::output::atomic::write_atomic;
use crate::output::error::Result;
use crate::output::frames::Frame;
use crate::output::scene::Scene;

/// Draws the last frame with trails; returns the canvas.
fn snapshot_canvas(scene: &Scene, frames: &[Frame], opts: &RenderOptions) -> (Canvas, View) {
    let view = View::new(scene, opts.width);
    let mut canvas = Canvas::new(view.w, view.h, I_BG);
    let last = frames.len() - 1;
    let frame = &frames[last];
    let by = resolve_color_by(opts.color_by, scene);
    draw_base(&mut canvas, &view, scene);
    let first = last.saturating_sub(opts.trail);
    let idx: Vec<usize> = (first..=last).collect();
    let n = frame.agents.len();
    draw_trails(
        &mut canvas,
        &view,
        scene,
        frames,
        &idx,
        trail_stride(n, opts.max_trail_agents),
        by,
    );
    let mut objects = Canvas::new(view.w, view.h, CLEAR);
    draw_objects(&mut objects, &view, scene, frame.step);
    compose(&mut canvas, &objects);
    let r = opts
        .agent_radius_px
        .unwrap_or_else(|| auto_radius(n, view.w));
    draw_agents(&mut canvas, &view, scene, frame, r, by);
    if opts.legend {
        let scale = (view.w as i64 / 400).max(1);
        draw_legend(&mut canvas, scene, frame, by, scale);
    }
    if scene.dim == 3 {
        let side = View::side(scene, &view);
        let panel = side_canvas(
            &side,
            scene,
            frames,
            &idx,
            trail_stride(n, opts.max_trail_agents),
            frame,
            r,
            by,
        );
        canvas = stack(canvas, &panel);
    }
    (canvas, view)
}

/// Renders the PNG image (RGB) of the last frame in memory, without writing it.
pub fn snapshot_image(
    scene: &Scene,
    frames: &[Frame],
    opts: &RenderOptions,
) -> Result<image::RgbImage> {
    check_inputs(scene, frames, Path::new("<snapshot>"))?;
    let (canvas, _) = snapshot_canvas(scene, frames, opts);
    Ok(to_rgb(&canvas))
}

fn to_rgb(canvas: &Canvas) -> image::RgbImage {
    let pal = palette();
    let mut rgb = Vec::with_capacity(canvas.px.len() * 3);
    for &i in &canvas.px {
        rgb.extend_from_slice(&pal[i as usize]);
    }
    image::RgbImage::from_raw(canvas.w as u32, canvas.h as u32, rgb).expect("buffer size matches")
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
    let (canvas, _) = snapshot_canvas(scene, frames, opts);
    let img = to_rgb(&canvas);
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
