//! A small ant colony driven through `swarm-core`'s controller, printed as it forages.
//!
//! ```text
//! cargo run --release -p swarm-core --example ant_colony -- [ANTS] [STEPS] [f32|fixed]
//! ```
//!
//! 300 ants leave their nest at (20, 50) of a 100 × 100 arena; food lies at (80, 50), a rock
//! in between. Every tick each ant runs `ant::plan` then `ant::resolve` (xiang2018 §4), exactly
//! as a robot would. Watch the labels change as information spreads (Table 1) and the
//! deliveries climb once a trail forms. The last lines draw the arena as text.

#[path = "../tests/common/world.rs"]
mod world;

use swarm_core::ant::Label;
use swarm_core::{Fx, Scalar};
use world::World;

fn run<S: Scalar>(ants: usize, steps: u32) {
    let mut w = World::<S>::demo(ants, 2018);
    println!(
        "{ants} ants, {steps} ticks, scalar {:?}; nest (20,50), food (80,50), rock (50,40) r 6",
        S::KIND
    );
    println!(
        "{:>6} {:>8} {:>6} {:>6} {:>10}",
        "tick", "nothing", "food", "nest", "delivered"
    );
    for _ in 0..steps {
        w.step();
        if w.step.is_multiple_of((steps / 10).max(1)) {
            let [nothing, food, nest] = w.label_counts();
            println!(
                "{:>6} {:>8} {:>6} {:>6} {:>10}",
                w.step, nothing, food, nest, w.deliveries
            );
        }
    }
    draw(&w);
    println!("trajectory hash {:016x}", w.hash());
}

/// The arena as 50 × 25 characters: `F` laden ants, `n` ants heading for food, `#` the rock.
fn draw<S: Scalar>(w: &World<S>) {
    let (cols, rows) = (50usize, 25usize);
    let mut grid = vec![vec![' '; cols]; rows];
    for (r, row) in grid.iter_mut().enumerate() {
        for (c, cell) in row.iter_mut().enumerate() {
            let (x, y) = ((c as f32 + 0.5) * 2.0, 100.0 - (r as f32 + 0.5) * 4.0);
            for rock in &w.rocks {
                let (cx, cy) = (rock.center.x.to_f32(), rock.center.y.to_f32());
                if (x - cx).hypot(y - cy) <= rock.radius.to_f32() {
                    *cell = '#';
                }
            }
        }
    }
    for a in &w.ants {
        let (x, y) = (a.pos.x.to_f32(), a.pos.y.to_f32());
        let (c, r) = ((x / 2.0) as usize, ((100.0 - y) / 4.0) as usize);
        if let Some(cell) = grid
            .get_mut(r.min(rows - 1))
            .and_then(|row| row.get_mut(c.min(cols - 1)))
        {
            *cell = match a.label {
                Label::Food => 'F',
                Label::Nest => 'n',
                Label::Nothing => '.',
            };
        }
    }
    let put = |g: &mut Vec<Vec<char>>, x: f32, y: f32, ch| {
        g[((100.0 - y) / 4.0) as usize][(x / 2.0) as usize] = ch
    };
    put(&mut grid, 20.0, 50.0, 'N');
    put(&mut grid, 80.0, 50.0, '*');
    println!("+{}+", "-".repeat(cols));
    for row in grid {
        println!("|{}|", row.into_iter().collect::<String>());
    }
    println!(
        "+{}+  N nest, * food, # rock, F laden ant, n ant seeking food",
        "-".repeat(cols)
    );
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: ant_colony [ANTS (default 300)] [STEPS (default 3000)] [f32|fixed]";
    let num = |i: usize, default: u64| -> u64 {
        args.get(i).map_or(default, |s| {
            s.parse().unwrap_or_else(|_| {
                eprintln!("error: `{s}` is not a number\n{usage}");
                std::process::exit(2)
            })
        })
    };
    let (ants, steps) = (num(0, 300) as usize, num(1, 3000) as u32);
    match args.get(2).map(String::as_str) {
        None | Some("f32") => run::<f32>(ants, steps),
        Some("fixed") => run::<Fx>(ants, steps),
        Some(other) => {
            eprintln!("error: unknown scalar `{other}` (f32 or fixed)\n{usage}");
            std::process::exit(2)
        }
    }
}
