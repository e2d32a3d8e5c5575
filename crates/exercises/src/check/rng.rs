//! The checks' random numbers: seeded generators (so a run is repeatable), scripted ones that hand
//! out chosen values such as 0 and [`U_MAX`](super::U_MAX) first, and the record of a generator's state that lets a
//! failure message say how to rebuild it.

use super::call::{Arg, note_draw};
use super::format::num;
use glam::DVec3;
use rand::{RngCore, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use std::f64::consts::PI;
use std::fmt;

/// The seeded generator every check uses, so that a run is repeatable. The environment variable
/// `RTL_EXERCISES_SEED_OFFSET` (unset: 0) shifts every seed, to measure the checks' false-failure
/// rate over many runs (e.g. `RTL_EXERCISES_SEED_OFFSET=7 cargo test -p rtl-exercises --features
/// solutions`).
pub fn seeded(seed: u64) -> Xoshiro256PlusPlus {
    let offset = std::env::var("RTL_EXERCISES_SEED_OFFSET")
        .ok()
        .and_then(|s| s.parse::<u64>().ok())
        .unwrap_or(0);
    Xoshiro256PlusPlus::seed_from_u64(seed.wrapping_add(offset.wrapping_mul(1_000_003)))
}

/// Uniformly distributed unit vectors, for the checks' own integrations (not the learner's).
pub fn uniform_direction(rng: &mut dyn RngCore) -> DVec3 {
    use rand::Rng;
    let z = 1.0 - 2.0 * rng.random::<f64>();
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * rng.random::<f64>();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// A generator that first replays a script of uniform values (each a multiple of 2^-53 in [0, 1),
/// e.g. 0 or [`U_MAX`](super::U_MAX)) as `rng.random::<f64>()` would draw them, then continues with a seeded stream.
pub struct ScriptedRng {
    script: Vec<u64>,
    next: usize,
    rest: Xoshiro256PlusPlus,
}

impl ScriptedRng {
    /// Replay `uniforms` first. rand 0.9 draws an `f64` as `(next_u64() >> 11) * 2^-53`.
    pub fn new(uniforms: &[f64], seed: u64) -> Self {
        let script = uniforms
            .iter()
            .map(|&u| {
                assert!((0.0..1.0).contains(&u), "a scripted uniform lies in [0, 1)");
                let k = (u * (1u64 << 53) as f64) as u64;
                assert_eq!(
                    k as f64,
                    u * (1u64 << 53) as f64,
                    "a scripted uniform is a multiple of 2^-53"
                );
                k << 11
            })
            .collect();
        Self {
            script,
            next: 0,
            rest: seeded(seed),
        }
    }
}

impl RngCore for ScriptedRng {
    fn next_u32(&mut self) -> u32 {
        (self.next_u64() >> 32) as u32
    }
    fn next_u64(&mut self) -> u64 {
        match self.script.get(self.next) {
            Some(&x) => {
                self.next += 1;
                x
            }
            None => self.rest.next_u64(),
        }
    }
    fn fill_bytes(&mut self, dst: &mut [u8]) {
        self.rest.fill_bytes(dst);
    }
}

/// The random-number source a check hands to the learner's code: [`seeded`]'s generator, after a
/// script of uniforms if [`Generator::scripted`], which counts what it has drawn. [`Generator::arg`]
/// names it for a panic report as a call that rebuilds it where it is (`check::replay(101, 8434)`),
/// and the uniforms that the call in progress drew are kept for the report too.
pub struct Generator {
    rng: ScriptedRng,
    seed: u64,
    script: [f64; SCRIPT_MAX],
    script_len: usize,
    drawn: u64,
}

/// The most uniforms a [`Generator`] replays before its seeded stream.
pub const SCRIPT_MAX: usize = 4;

impl Generator {
    /// The generator of [`seeded`]`(seed)`.
    pub fn new(seed: u64) -> Self {
        Self::scripted(&[], seed)
    }

    /// Replays `uniforms` (at most [`SCRIPT_MAX`], as [`ScriptedRng`] does), then [`seeded`]`(seed)`.
    pub fn scripted(uniforms: &[f64], seed: u64) -> Self {
        assert!(
            uniforms.len() <= SCRIPT_MAX,
            "a script of at most {SCRIPT_MAX} uniforms"
        );
        let mut script = [0.0; SCRIPT_MAX];
        script[..uniforms.len()].copy_from_slice(uniforms);
        Self {
            rng: ScriptedRng::new(uniforms, seed),
            seed,
            script,
            script_len: uniforms.len(),
            drawn: 0,
        }
    }

    /// This generator as it is now, as an argument of a recorded call: see [`calling`](super::calling).
    pub fn arg(&self) -> Arg {
        let replayed = (self.drawn as usize).min(self.script_len);
        let mut script = [0.0; SCRIPT_MAX];
        let left = self.script_len - replayed;
        script[..left].copy_from_slice(&self.script[replayed..self.script_len]);
        Arg::Rng(RngState {
            seed: self.seed,
            script,
            script_len: left,
            skip: self.drawn - replayed as u64,
        })
    }
}

impl RngCore for Generator {
    fn next_u32(&mut self) -> u32 {
        // As Xoshiro256PlusPlus does, so that `replay` gives the same values.
        (self.next_u64() >> 32) as u32
    }
    fn next_u64(&mut self) -> u64 {
        let x = self.rng.next_u64();
        self.drawn += 1;
        note_draw(x);
        x
    }
    fn fill_bytes(&mut self, dst: &mut [u8]) {
        rand::rand_core::impls::fill_bytes_via_next(self, dst);
    }
}

/// [`seeded`]`(seed)` after `skip` draws of 64 bits: a generator of a check where a panic report
/// found it (`replay(101, 8434)`), so that the call can be repeated in a test of one's own.
pub fn replay(seed: u64, skip: u64) -> Xoshiro256PlusPlus {
    let mut rng = seeded(seed);
    for _ in 0..skip {
        rng.next_u64();
    }
    rng
}

/// A [`Generator`] as a recorded call received it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RngState {
    seed: u64,
    /// The scripted uniforms still to come.
    script: [f64; SCRIPT_MAX],
    script_len: usize,
    /// Draws of the seeded stream already made.
    skip: u64,
}

impl fmt::Display for RngState {
    /// The expression that builds the same generator: `rtl_exercises::check::replay(101, 8434)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.script_len > 0 {
            let script: Vec<String> = self.script[..self.script_len]
                .iter()
                .map(|&u| num(u))
                .collect();
            write!(
                f,
                "rtl_exercises::check::ScriptedRng::new(&[{}], {})",
                script.join(", "),
                self.seed
            )
        } else if self.skip == 0 {
            write!(f, "rtl_exercises::check::seeded({})", self.seed)
        } else {
            write!(
                f,
                "rtl_exercises::check::replay({}, {})",
                self.seed, self.skip
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::*;
    use rand::Rng;

    #[test]
    fn scripted_rng_replays_zero_and_the_largest_uniform() {
        let mut rng = ScriptedRng::new(&[0.0, U_MAX, 0.5], 1);
        assert_eq!(rng.random::<f64>(), 0.0);
        assert_eq!(rng.random::<f64>(), U_MAX);
        assert_eq!(rng.random::<f64>(), 0.5);
        assert!(rng.random::<f64>() < 1.0);
    }

    #[test]
    fn a_generator_is_named_as_the_expression_that_rebuilds_it() {
        let mut g = Generator::new(9);
        assert_eq!(g.arg().to_string(), "rtl_exercises::check::seeded(9)");
        for _ in 0..5 {
            g.next_u64();
        }
        g.next_u32();
        assert_eq!(g.arg().to_string(), "rtl_exercises::check::replay(9, 6)");
        // replay(9, 6) goes on as the generator does, whichever width is drawn.
        let mut r = replay(9, 6);
        assert_eq!((g.next_u64(), g.next_u32()), (r.next_u64(), r.next_u32()));
        // A script is named by what is left of it, then by the seeded stream after it.
        let mut s = Generator::scripted(&[0.0, 0.25, 0.5], 3);
        assert_eq!(
            s.arg().to_string(),
            "rtl_exercises::check::ScriptedRng::new(&[0, 0.25, 0.5], 3)"
        );
        s.next_u64();
        assert_eq!(
            s.arg().to_string(),
            "rtl_exercises::check::ScriptedRng::new(&[0.25, 0.5], 3)"
        );
        s.next_u64();
        s.next_u64();
        assert_eq!(s.arg().to_string(), "rtl_exercises::check::seeded(3)");
        s.next_u64();
        assert_eq!(s.arg().to_string(), "rtl_exercises::check::replay(3, 1)");
    }
}
