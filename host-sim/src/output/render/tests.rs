use image::RgbImage;

use super::palette::INK;
use super::view::View;
use super::*;
use crate::output::frames::AgentSample;
use crate::output::scene::{Shape, ShapeKind};
use crate::output::testing::{sample_scene as scene, temp_path};

/// [`render_png`] into a temporary file, read back.
fn png(sc: &Scene, fr: &[Frame], opts: &RenderOptions) -> RgbImage {
    let (_dir, p) = temp_path("snapshot.png");
    render_png(sc, fr, &p, opts).unwrap();
    image::open(&p).unwrap().to_rgb8()
}

/// The colour of `img` at the world point `p` as `view` shows it.
fn color_at(img: &RgbImage, view: &View, sc: &Scene, p: [f32; 3]) -> [u8; 3] {
    let (x, y) = view.world(sc, p);
    img.get_pixel(x.round() as u32, y.round() as u32).0
}

/// The part of `img` below its first `top` rows (the side view of a 3D scene).
fn below(img: &RgbImage, top: usize) -> RgbImage {
    let h = img.height() - top as u32;
    image::imageops::crop_imm(img, 0, top as u32, img.width(), h).to_image()
}

/// `agents` agents walking around the middle of the [`scene`], never near the centre of its nest,
/// food sources or rock triangle, one frame every 6 steps (20 frames: the food has moved).
fn frames(agents: usize, nframes: usize) -> Vec<Frame> {
    (0..nframes)
        .map(|f| Frame {
            step: (f * 6) as u32,
            agents: (0..agents)
                .map(|i| {
                    let a = i as f32 * 0.7 + f as f32 * 0.05;
                    let r = 20.0 + (i % 7) as f32 * 3.0;
                    AgentSample {
                        id: i as u32,
                        group: (i % 2) as u16,
                        pos: [100.0 + r * a.cos() * 1.8, 50.0 + r * a.sin(), 0.0],
                        heading: [a.cos(), a.sin(), 0.0],
                        label: (i % 3) as u8,
                        motion: 1,
                        ..Default::default()
                    }
                })
                .collect(),
        })
        .collect()
}

#[test]
fn png_has_expected_size_and_nest_colour() {
    let (sc, fr) = (scene(), frames(50, 20));
    let img = png(&sc, &fr, &RenderOptions::default());
    assert_eq!(img.width(), 1024);
    let view = View::new(&sc, 1024);
    assert_eq!(img.height() as usize, view.h);
    // World is 2:1, so about 512 px tall.
    assert!((500..=530).contains(&img.height()), "{}", img.height());
    let at = |p| color_at(&img, &view, &sc, p);
    assert_eq!(at([20.0, 50.0, 0.0]), kind_color(ShapeKind::Nest));
    // The food source visible at the last step (moved at step 100) is drawn, the old one not.
    assert_eq!(at([150.0, 80.0, 0.0]), kind_color(ShapeKind::Food));
    assert_ne!(at([180.0, 50.0, 0.0]), kind_color(ShapeKind::Food));
    // Some agent of each label colour is drawn.
    for label in 0..3u16 {
        let c = agent_color(ColorBy::Label, label);
        assert!(img.pixels().any(|px| px.0 == c), "label {label}");
    }
    // Rock polygon centre.
    assert_eq!(at([100.0, 47.0, 0.0]), kind_color(ShapeKind::Rock));
}

#[test]
fn gif_decodes_with_expected_frames() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("run.gif");
    let (sc, fr) = (scene(), frames(50, 20));
    render_gif(&sc, &fr, &p, &RenderOptions::default()).unwrap();
    let file = std::fs::File::open(&p).unwrap();
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::Indexed);
    let mut dec = opts.read_info(file).unwrap();
    assert_eq!(dec.width(), 480);
    assert_eq!(dec.height() as usize, View::new(&sc, 480).h);
    let mut count = 0;
    while let Some(f) = dec.read_next_frame().unwrap() {
        assert_eq!((f.width, f.height), (dec.width(), dec.height()));
        count += 1;
    }
    assert_eq!(count, 20);
    assert_eq!(dec.repeat(), gif::Repeat::Infinite);

    // Subsampled to at most gif_max_frames.
    let opts = RenderOptions {
        gif_max_frames: 7,
        ..RenderOptions::default()
    };
    render_gif(&sc, &fr, &p, &opts).unwrap();
    let mut dec = gif::DecodeOptions::new()
        .read_info(std::fs::File::open(&p).unwrap())
        .unwrap();
    let mut count = 0;
    while dec.read_next_frame().unwrap().is_some() {
        count += 1;
    }
    assert_eq!(count, 7);
}

#[test]
fn rendering_is_deterministic() {
    let dir = tempfile::tempdir().unwrap();
    let (sc, fr) = (scene(), frames(50, 20));
    let o = RenderOptions::default();
    let read = |n: &str| std::fs::read(dir.path().join(n)).unwrap();
    render_png(&sc, &fr, dir.path().join("a.png"), &o).unwrap();
    render_png(&sc, &fr, dir.path().join("b.png"), &o).unwrap();
    assert_eq!(read("a.png"), read("b.png"));
    render_gif(&sc, &fr, dir.path().join("a.gif"), &o).unwrap();
    render_gif(&sc, &fr, dir.path().join("b.gif"), &o).unwrap();
    assert_eq!(read("a.gif"), read("b.gif"));
}

#[test]
fn three_d_top_view() {
    let mut sc = Scene::new_3d([0.0, 0.0, 0.0], [100.0, 30.0, 50.0]);
    sc.shapes = vec![
        Shape::circle([50.0, 0.0, 25.0], 4.0, ShapeKind::Shaft),
        Shape::circle([20.0, 10.0, 10.0], 3.0, ShapeKind::Target),
        Shape::cuboid([80.0, 0.0, 5.0], [90.0, 10.0, 15.0], ShapeKind::Sphere),
    ];
    let fr: Vec<Frame> = (0..10)
        .map(|f| Frame {
            step: f,
            agents: (0..30)
                .map(|i| AgentSample {
                    id: i,
                    group: (i % 3) as u16,
                    pos: [5.0 + f as f32 * 3.0, 15.0, 2.0 + i as f32 * 1.5],
                    ..Default::default()
                })
                .collect(),
        })
        .collect();
    let img = png(&sc, &fr, &RenderOptions::default());
    let view = View::new(&sc, 1024);
    let side = View::side(&sc, &view);
    // The top view, then the side view below it.
    assert_eq!(
        (img.width(), img.height() as usize),
        (1024, view.h + side.h)
    );
    // The shaft stands full height in the side view.
    let side_img = below(&img, view.h);
    for y in [2.0, 15.0, 28.0] {
        assert_eq!(
            color_at(&side_img, &side, &sc, [50.0, y, 0.0]),
            kind_color(ShapeKind::Shaft)
        );
    }
    assert_eq!(
        color_at(&img, &view, &sc, [50.0, 99.0, 25.0]),
        kind_color(ShapeKind::Shaft)
    );
    // z grows downwards in the top view.
    assert!(view.world(&sc, [0.0, 0.0, 40.0]).1 > view.world(&sc, [0.0, 0.0, 10.0]).1);
    // Bees are coloured by group in 3D.
    assert!(
        img.pixels()
            .any(|px| px.0 == agent_color(ColorBy::Group, 1))
    );
}

/// The side view draws a bee's wings as a bar along the rolled wing axis: a bee flying +x
/// (across the view, wings along z, edge-on) with a roll of 40° shows a dark bar above and
/// below its dot; a level one shows none.
#[test]
fn the_side_view_shows_the_roll_as_a_tilted_wing_bar() {
    let sc = Scene::new_3d([0.0, 0.0, 0.0], [100.0, 30.0, 50.0]);
    let ink = |roll: f32| {
        let fr = vec![Frame {
            step: 0,
            agents: vec![AgentSample {
                pos: [50.0, 15.0, 25.0],
                heading: [1.0, 0.0, 0.0],
                roll,
                ..Default::default()
            }],
        }];
        let opts = RenderOptions {
            agent_radius_px: Some(4.0),
            legend: false,
            ..RenderOptions::default()
        };
        let img = snapshot_image(&sc, &fr, &opts).unwrap();
        let view = View::new(&sc, opts.width);
        let side = View::side(&sc, &view);
        let img = below(&img, view.h);
        let (x, y) = side.world(&sc, [50.0, 15.0, 25.0]);
        let (x, y) = (x.round() as u32, y.round() as u32);
        // Pixels straight above and below the dot, past its disc.
        (5..8)
            .filter(|d| img.get_pixel(x, y - d).0 == INK && img.get_pixel(x, y + d).0 == INK)
            .count()
    };
    assert!(ink(40.0) > 0, "no wing bar for a rolled bee");
    assert_eq!(
        ink(0.0),
        0,
        "a level bee flying across the view shows no bar"
    );
}

#[test]
fn a_nest_on_the_ground_box_stays_visible_from_above() {
    let mut sc = Scene::new_3d([0.0, 0.0, 0.0], [100.0, 30.0, 50.0]);
    // The ground box comes after the nest in the scene, as in bees-fig15-nest.
    sc.shapes = vec![
        Shape::circle([50.0, 2.0, 25.0], 5.0, ShapeKind::Target),
        Shape::cuboid([0.0, 0.0, 0.0], [100.0, 1.0, 50.0], ShapeKind::Rock),
    ];
    let fr = vec![Frame {
        step: 0,
        agents: vec![AgentSample {
            pos: [5.0, 15.0, 5.0],
            ..Default::default()
        }],
    }];
    let img = png(&sc, &fr, &RenderOptions::default());
    let at = |p| color_at(&img, &View::new(&sc, 1024), &sc, p);
    assert_eq!(at([50.0, 2.0, 25.0]), kind_color(ShapeKind::Target));
    assert_eq!(at([90.0, 0.5, 45.0]), kind_color(ShapeKind::Rock));
}

#[test]
fn refuses_empty_frames_and_leaves_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("x.png");
    let msg = render_png(&scene(), &[], &p, &RenderOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("x.png") && msg.contains("no recorded frames"),
        "{msg}"
    );
    assert!(!p.exists());
}

#[test]
fn frame_index_subsampling() {
    assert_eq!(gif_frame_indices(0, 150), Vec::<usize>::new());
    assert_eq!(gif_frame_indices(1, 150), vec![0]);
    assert_eq!(gif_frame_indices(5, 150), vec![0, 1, 2, 3, 4]);
    let v = gif_frame_indices(1000, 150);
    assert_eq!(v.len(), 150);
    assert_eq!((v[0], v[149]), (0, 999));
    assert!(v.windows(2).all(|w| w[0] < w[1]));
}

/// 500 agents × 300 frames: both pictures well under a few seconds in release (this test
/// only checks it finishes; time it with `cargo test --release -- --nocapture perf`).
#[test]
fn perf_500_agents_300_frames() {
    let dir = tempfile::tempdir().unwrap();
    let (sc, fr, o) = (scene(), frames(500, 300), RenderOptions::default());
    let t = std::time::Instant::now();
    render_png(&sc, &fr, dir.path().join("p.png"), &o).unwrap();
    let t_png = t.elapsed();
    let t = std::time::Instant::now();
    render_gif(&sc, &fr, dir.path().join("p.gif"), &o).unwrap();
    eprintln!(
        "perf: 500 agents x 300 frames: png {t_png:?}, gif {:?}",
        t.elapsed()
    );
}
