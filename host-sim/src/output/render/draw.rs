//! Drawing a frame of a scene: the world, its objects, the agents' trails and dots, and the
//! side panel of a 3D scene.

use super::canvas::{CLEAR, Canvas, compose};
use super::palette::{
    I_BG, I_BORDER, I_INK, I_OUTSIDE, SHADES, agent_index, kind_index, resolve_color_by,
};
use super::view::View;
use super::{ColorBy, RenderOptions};
use crate::output::frames::{AgentSample, Frame};
use crate::output::scene::{Geometry, Scene, Shape, ShapeKind};

/// The world area and its border on the outside colour.
pub(super) fn draw_base(canvas: &mut Canvas, view: &View, scene: &Scene) {
    canvas.px.fill(I_OUTSIDE);
    let (x0, y0) = view.world(scene, scene.min);
    let (x1, y1) = view.world(scene, scene.max);
    let (xa, xb) = (x0.min(x1).round() as i64, x0.max(x1).round() as i64);
    let (ya, yb) = (y0.min(y1).round() as i64, y0.max(y1).round() as i64);
    canvas.rect(xa, ya, xb, yb, I_BG);
    canvas.rect_outline(xa - 1, ya - 1, xb + 1, yb + 1, I_BORDER);
}

/// The objects visible at `step` on a clear canvas: obstacles first, then nests, food and
/// targets (a nest on the ground box of a bee scene stays visible from above), then rings.
/// Drawn over the trails and under the agents.
pub(super) fn draw_objects(canvas: &mut Canvas, view: &View, scene: &Scene, step: u32) {
    canvas.px.fill(CLEAR);
    let layer = |k: ShapeKind| match k {
        ShapeKind::Rock | ShapeKind::Shaft | ShapeKind::Sphere => 0,
        ShapeKind::Nest | ShapeKind::Food | ShapeKind::Target => 1,
        ShapeKind::Disturbance | ShapeKind::Waypoint => 2,
    };
    for l in 0..3 {
        for s in scene
            .shapes
            .iter()
            .filter(|s| layer(s.kind) == l && s.visible_at(step))
        {
            draw_shape(canvas, view, scene, s);
        }
    }
}

fn draw_shape(canvas: &mut Canvas, view: &View, scene: &Scene, s: &Shape) {
    let c = kind_index(s.kind);
    let ring_px = (view.w as f32 / 400.0).max(1.5);
    match &s.geom {
        Geometry::Circle { center, radius } if view.side && s.kind == ShapeKind::Shaft => {
            // A vertical shaft, full height.
            let (x0, y0) = view.world(scene, [center[0] - radius, scene.min[1], 0.0]);
            let (x1, y1) = view.world(scene, [center[0] + radius, scene.max[1], 0.0]);
            canvas.rect(
                x0.round() as i64,
                y1.min(y0).round() as i64,
                x1.round().max(x0.round() + 1.0) as i64,
                y0.max(y1).round() as i64,
                c,
            );
        }
        Geometry::Polygon { .. } if view.side => {}
        Geometry::Circle { center, radius } => {
            let (x, y) = view.world(scene, *center);
            let r = radius * view.scale;
            match s.kind {
                ShapeKind::Disturbance | ShapeKind::Waypoint => {
                    canvas.ring(x, y, r.max(2.0), ring_px, c)
                }
                ShapeKind::Nest | ShapeKind::Food | ShapeKind::Target => {
                    canvas.disc(x, y, r.max(2.0), c)
                }
                _ => canvas.disc(x, y, r.max(0.5), c),
            }
        }
        Geometry::Polygon { points } => {
            let pts: Vec<[f32; 2]> = points
                .iter()
                .map(|p| {
                    let (x, y) = view.px(*p);
                    [x, y]
                })
                .collect();
            canvas.polygon(&pts, c);
        }
        Geometry::Box { min, max } => {
            let (x0, y0) = view.world(scene, *min);
            let (x1, y1) = view.world(scene, *max);
            let (xa, ya) = (x0.min(x1).round() as i64, y0.min(y1).round() as i64);
            let (xb, yb) = (x0.max(x1).round() as i64, y0.max(y1).round() as i64);
            if s.kind == ShapeKind::Target {
                // A goal area (a `region`): its outline, so that what lies in it stays visible.
                for k in 0..ring_px.round().max(1.0) as i64 {
                    canvas.rect_outline(xa + k, ya + k, xb - k, yb - k, c);
                }
            } else {
                canvas.rect(xa, ya, xb, yb, c);
            }
        }
    }
}

/// How agents are drawn: their colours, their dot radius in pixels, and which of them get trails
/// (every `stride`-th by id).
#[derive(Clone, Copy, Debug)]
pub(super) struct AgentStyle {
    pub(super) by: ColorBy,
    pub(super) r: f32,
    pub(super) stride: usize,
}

impl AgentStyle {
    /// The style for `agents` agents drawn as dots of radius `r` with `opts`' colours and trails.
    pub(super) fn new(opts: &RenderOptions, scene: &Scene, agents: usize, r: f32) -> Self {
        Self {
            by: resolve_color_by(opts.color_by, scene),
            r,
            stride: trail_stride(agents, opts.max_trail_agents),
        }
    }
}

/// Draws the trails through `frames[idx]` for the agents `0, stride, 2·stride, ...`, oldest
/// segments first and most faded.
pub(super) fn draw_trails(
    canvas: &mut Canvas,
    view: &View,
    scene: &Scene,
    frames: &[Frame],
    idx: &[usize],
    style: AgentStyle,
) {
    if idx.len() < 2 {
        return;
    }
    let segs = idx.len() - 1;
    let max_jump = (view.w.max(view.h) as f32) / 4.0;
    let n = frames[idx[0]].agents.len();
    for s in 0..segs {
        // Age: segs-1 (oldest) ... 0 (newest); shade 1 (newest) ... SHADES-1 (oldest).
        let age = segs - 1 - s;
        let shade = 1 + age * (SHADES - 1) / segs;
        let (fa, fb) = (&frames[idx[s]], &frames[idx[s + 1]]);
        for a in (0..n).step_by(style.stride) {
            let (p, q) = (&fa.agents[a], &fb.agents[a]);
            let (x0, y0) = view.world(scene, p.pos);
            let (x1, y1) = view.world(scene, q.pos);
            if !(x0.is_finite() && y0.is_finite() && x1.is_finite() && y1.is_finite()) {
                continue;
            }
            if (x1 - x0).abs() > max_jump || (y1 - y0).abs() > max_jump {
                continue;
            }
            canvas.line(
                x0,
                y0,
                x1,
                y1,
                agent_index(style.by, q.label, q.group, shade),
            );
        }
    }
}

/// The agents of `frame` as `view` shows them: dots in a plan or top view; in the side view of a
/// 3D scene, bees with heading and wings ([`draw_bee_side`]).
pub(super) fn draw_agents(
    canvas: &mut Canvas,
    view: &View,
    scene: &Scene,
    frame: &Frame,
    style: AgentStyle,
) {
    for a in &frame.agents {
        let (x, y) = view.world(scene, a.pos);
        if !(x.is_finite() && y.is_finite()) {
            continue;
        }
        let c = agent_index(style.by, a.label, a.group, 0);
        if view.side {
            draw_bee_side(canvas, a, (x, y), style.r, c);
        } else {
            canvas.disc(x, y, style.r, c);
        }
    }
}

/// A bee in the side view at pixel `(x, y)`: a dot of colour `c`, its body as a line along its
/// heading and its wings as a dark bar along the rolled wing axis, projected on (x, y) (see the
/// module docs).
fn draw_bee_side(canvas: &mut Canvas, a: &AgentSample, (x, y): (f32, f32), r: f32, c: u8) {
    let body = (3.0 * r).max(5.0);
    let wing = 0.7 * body;
    let h = a.heading;
    // Screen y grows downward: a world direction (u, v) is (u, −v) on screen.
    canvas.line(x, y, x + body * h[0], y - body * h[1], c);
    // s = heading × up = (−h.z, 0, h.x), normalized; wing axis cos·s − sin·up.
    let len = h[0].hypot(h[2]);
    let (sx, _sz) = if len > 1e-6 {
        (-h[2] / len, h[0] / len)
    } else {
        (0.0, 1.0)
    };
    let (sin, cos) = a.roll.to_radians().sin_cos();
    let (wx, wy) = (cos * sx, -sin);
    canvas.line(
        x - wing * wx,
        y + wing * wy,
        x + wing * wx,
        y - wing * wy,
        I_INK,
    );
    canvas.disc(x, y, (0.6 * r).max(0.5), c);
}

/// `frame` as `view` shows it: the world, the trails through `frames[idx]`, the objects visible
/// at its step and the agents; the side view of a 3D scene (shafts full height, bees with heading
/// and wings) with its title.
pub(super) fn frame_canvas(
    view: &View,
    scene: &Scene,
    frames: &[Frame],
    idx: &[usize],
    frame: &Frame,
    style: AgentStyle,
) -> Canvas {
    let mut canvas = Canvas::new(view.w, view.h, I_BG);
    draw_base(&mut canvas, view, scene);
    draw_trails(&mut canvas, view, scene, frames, idx, style);
    let mut objects = Canvas::new(view.w, view.h, CLEAR);
    draw_objects(&mut objects, view, scene, frame.step);
    compose(&mut canvas, &objects);
    draw_agents(&mut canvas, view, scene, frame, style);
    if view.side {
        let scale = (view.w as i64 / 400).max(1);
        canvas.text(
            view.ox as i64,
            2 * scale,
            "side view - x right / y up - line: heading - bar: wings at the roll",
            scale,
            I_INK,
        );
    }
    canvas
}

pub(super) fn auto_radius(agents: usize, width: usize) -> f32 {
    let base = match agents {
        0..=1000 => 3.0,
        1001..=5000 => 2.2,
        5001..=50_000 => 1.4,
        _ => 0.5,
    };
    (base * width as f32 / 1024.0).max(0.5)
}

fn trail_stride(agents: usize, max: usize) -> usize {
    agents.div_ceil(max.max(1)).max(1)
}
