//! The animated GIF of a run.

use std::io;
use std::path::Path;

use super::RenderOptions;
use super::canvas::{CLEAR, Canvas, compose, stack};
use super::draw::{
    AgentStyle, auto_radius, draw_agents, draw_base, draw_objects, draw_trails, frame_canvas,
};
use super::legend::draw_step;
use super::palette::{I_BG, palette};
use super::view::View;
use crate::output::atomic::write_atomic;
use crate::output::frames::Frame;
use crate::output::scene::Scene;
use crate::{Result, SimError};

/// The indices of the frames shown in the GIF: at most `max` (≥ 2), evenly spaced, first and
/// last included.
pub fn gif_frame_indices(n: usize, max: usize) -> Vec<usize> {
    let m = n.min(max.max(2));
    match m {
        0 => Vec::new(),
        1 => vec![0],
        _ => (0..m).map(|i| i * (n - 1) / (m - 1)).collect(),
    }
}

/// Writes the GIF of [`render_gif`](super::render_gif) (inputs checked), whole or not at all.
pub(super) fn write_gif(
    scene: &Scene,
    frames: &[Frame],
    path: &Path,
    opts: &RenderOptions,
) -> Result<()> {
    let view = View::new(scene, opts.gif_width);
    let side = (scene.dim == 3).then(|| View::side(scene, &view));
    let total_h = view.h + side.as_ref().map_or(0, |s| s.h);
    if view.w > u16::MAX as usize || total_h > u16::MAX as usize {
        return Err(SimError::GifTooLarge {
            path: path.to_path_buf(),
            width: view.w,
            height: total_h,
        });
    }
    let shown = gif_frame_indices(frames.len(), opts.gif_max_frames);
    let n = frames[0].agents.len();
    let r = opts
        .agent_radius_px
        .map(|r| r * view.w as f32 / opts.width.max(1) as f32)
        .unwrap_or_else(|| auto_radius(n, view.w))
        .max(0.5);
    let style = AgentStyle::new(opts, scene, n, r);
    let text_scale = (view.w as i64 / 320).max(1);
    let flat_palette: Vec<u8> = palette().into_iter().flatten().collect();

    write_atomic(path, |w| {
        let mut enc = gif::Encoder::new(w, view.w as u16, total_h as u16, &flat_palette)
            .map_err(io::Error::other)?;
        enc.set_repeat(gif::Repeat::Infinite)
            .map_err(io::Error::other)?;
        let mut canvas = Canvas::new(view.w, view.h, I_BG);
        let mut base = Canvas::new(view.w, view.h, I_BG);
        draw_base(&mut base, &view, scene);
        // Object overlay, redrawn only when the set of visible shapes changes.
        let mut objects_key: Option<Vec<bool>> = None;
        let mut objects = Canvas::new(view.w, view.h, CLEAR);
        for (k, &fi) in shown.iter().enumerate() {
            let frame = &frames[fi];
            let key: Vec<bool> = scene
                .shapes
                .iter()
                .map(|s| s.visible_at(frame.step))
                .collect();
            if objects_key.as_ref() != Some(&key) {
                draw_objects(&mut objects, &view, scene, frame.step);
                objects_key = Some(key);
            }
            canvas.px.copy_from_slice(&base.px);
            // Trail: the original frames spanning the last `gif_trail` shown frames, at most 32
            // segments per agent.
            let from = shown[k.saturating_sub(opts.gif_trail)];
            let step = (fi - from).div_ceil(32).max(1);
            let mut idx: Vec<usize> = (from..=fi).rev().step_by(step).collect();
            if idx.last() != Some(&from) {
                idx.push(from);
            }
            idx.reverse();
            draw_trails(&mut canvas, &view, scene, frames, &idx, style);
            compose(&mut canvas, &objects);
            draw_agents(&mut canvas, &view, scene, frame, style);
            draw_step(&mut canvas, frame.step, text_scale);
            let both;
            let pixels = match &side {
                Some(sv) => {
                    let panel = frame_canvas(sv, scene, frames, &idx, frame, style);
                    let top = Canvas {
                        w: canvas.w,
                        h: canvas.h,
                        px: canvas.px.clone(),
                    };
                    both = stack(top, &panel);
                    both.px.as_slice()
                }
                None => canvas.px.as_slice(),
            };
            let mut gf =
                gif::Frame::from_indexed_pixels(view.w as u16, total_h as u16, pixels, None);
            gf.delay = if k + 1 == shown.len() {
                opts.gif_delay_cs.saturating_mul(20).max(100)
            } else {
                opts.gif_delay_cs
            };
            enc.write_frame(&gf).map_err(io::Error::other)?;
        }
        enc.into_inner().map_err(io::Error::other)?.flush()
    })
}
