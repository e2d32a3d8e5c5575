//! Write a scene file with many emitting spheres over a floor, for measuring next-event estimation
//! under many lights (the hierarchy over the light density's targets, the choice of an emitter by
//! power; `book/src/figures/render-speed.md`, twenty-fifth and twenty-sixth rounds):
//!
//! ```sh
//! # ten thousand equal small lamps
//! cargo run --release -p rtl-render --example many_lamps -- 10000 0.02 0.02 > many.toml
//! # forty lamps of radii 0.05 to 0.5 (radiance the same: power grows with the area)
//! cargo run --release -p rtl-render --example many_lamps -- 40 0.05 0.5 > forty.toml
//! # the same forty, and each again under the floor; or with a wall among them
//! cargo run --release -p rtl-render --example many_lamps -- 40 0.05 0.5 1 mirror > both.toml
//! cargo run --release -p rtl-render --example many_lamps -- 40 0.05 0.5 1 wall > wall.toml
//! rtl render many.toml --strategy mis
//! ```
//!
//! Arguments: the number of lamps, the least and the largest radius (drawn uniformly between
//! them), optionally a seed (default 1), and optionally `mirror` (each lamp also mirrored under
//! the floor, below the horizon of every point on its top: the light tree's cosine at the shading
//! point, `render-speed.md`'s twenty-seventh round) or `wall` (a white wall seven units high across
//! the floor at `x = 1.5`). The lamps lie on a jittered square grid three to five
//! units above a white floor,
//! seen by a camera below them that looks down at the floor (the lamps are out of its view: the
//! image's noise is next-event estimation's). The file is the same for the same arguments on every machine.

use std::fmt::Write;

/// SplitMix64 (Steele, Lea and Flood 2014): a fixed, portable stream of `u64`s.
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform on [0, 1), 53 bits.
    fn uniform(&mut self) -> f64 {
        (self.next() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

fn arg<T: std::str::FromStr>(args: &[String], i: usize, name: &str, default: T) -> Result<T, String>
where
    T::Err: std::fmt::Display,
{
    args.get(i)
        .map_or(Ok(default), |s| s.parse())
        .map_err(|e| format!("{name} (argument {}): {e}", i + 1))
}

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let n: usize = arg(&args, 0, "number of lamps", 10_000)?;
    let r_min: f64 = arg(&args, 1, "least radius", 0.02)?;
    let r_max: f64 = arg(&args, 2, "largest radius", r_min)?;
    let seed: u64 = arg(&args, 3, "seed", 1)?;
    let extra: String = arg(&args, 4, "extra", String::new())?;
    if !["", "mirror", "wall"].contains(&extra.as_str()) {
        return Err(format!(
            "extra (argument 5): {extra:?}, expected mirror or wall"
        ));
    }
    if n == 0 || n > 1_000_000 {
        return Err(format!("number of lamps: {n}, expected 1 to 1000000"));
    }
    if !(r_min > 0.0 && r_min <= r_max && r_max.is_finite()) {
        return Err(format!(
            "radii: {r_min} to {r_max}, expected 0 < least <= largest"
        ));
    }
    // a square grid of side `k` cells over [-10, 10]^2; each lamp jittered inside its cell
    let k = (n as f64).sqrt().ceil() as usize;
    let cell = 20.0 / k as f64;
    let mut rng = SplitMix(seed);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# {n} emitting spheres of radii {r_min} to {r_max} over a floor (seed {seed}), written by\n\
         # `cargo run --release -p rtl-render --example many_lamps -- {n} {r_min} {r_max} {seed}{}`.\n\
         description = \"{n} lamps over a floor\"\n\n\
         [render]\nwidth = 96\naspect = \"1:1\"\nspp = 16\nmax_depth = 8\nbackground = [0, 0, 0]\n\n\
         [camera]\nvfov = 40\nlookfrom = [0, 2.5, 5]\nlookat = [0, 0, -1]\n\n\
         [materials]\nwhite = {{ type = \"lambertian\", albedo = [0.7, 0.7, 0.7] }}\n\
         lamp = {{ type = \"light\", emit = [4, 4, 4] }}\n\n\
         [[objects]]\ntype = \"quad\"\nq = [-12, 0, 12]\nu = [24, 0, 0]\nv = [0, 0, -24]\n\
         material = \"white\"",
        if extra.is_empty() {
            String::new()
        } else {
            format!(" {extra}")
        }
    );
    if extra == "wall" {
        let _ = write!(
            s,
            "\n\n[[objects]]\ntype = \"quad\"\nq = [1.5, 0, 12]\nu = [0, 0, -24]\nv = [0, 7, 0]\n\
             material = \"white\""
        );
    }
    for i in 0..n {
        let (gx, gz) = ((i % k) as f64, (i / k) as f64);
        let radius = r_min + (r_max - r_min) * rng.uniform();
        // jitter inside the cell, keeping the sphere off its neighbours where the cell allows
        let slack = (cell - 2.0 * radius).max(0.0);
        let x = -10.0 + gx * cell + 0.5 * cell + (rng.uniform() - 0.5) * slack;
        let z = -10.0 + gz * cell + 0.5 * cell + (rng.uniform() - 0.5) * slack;
        let y = 3.0 + radius + 2.0 * rng.uniform();
        let _ = write!(
            s,
            "\n\n[[objects]]\ntype = \"sphere\"\ncenter = [{x:.6}, {y:.6}, {z:.6}]\n\
             radius = {radius:.6}\nmaterial = \"lamp\""
        );
        if extra == "mirror" {
            let _ = write!(
                s,
                "\n\n[[objects]]\ntype = \"sphere\"\ncenter = [{x:.6}, {:.6}, {z:.6}]\n\
                 radius = {radius:.6}\nmaterial = \"lamp\"",
                -y
            );
        }
    }
    println!("{s}");
    Ok(())
}
