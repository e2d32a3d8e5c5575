//! The intersection tier chosen by timing it, where a processor runs two and which one is faster is
//! not known in advance: an Intel processor with AVX-512, whose 512-bit instructions take the vector
//! units of two ports (and on some models lower the clock while they run), so that eight `f64` lanes
//! to a register may or may not beat two registers of four. On AMD's Zen 4 and Zen 5 AVX-512 was
//! faster in every measurement, so it runs there without a race ([`HitTier::preferred`]).
//!
//! Every tier finds the same hits bit for bit, so a render may change tiers between its passes and
//! its image stays what either tier alone makes. The race costs no extra work: it times passes the
//! render needs anyway.
//!
//! The first pass also pays for the thread pool's start and the first touch of the buffers, so it
//! runs tier `a` and is not counted. The next four run `a, b, b, a` (where passes grow, each tier
//! gets one shorter and one longer pass). The tier with less time per sample per pixel over its two
//! passes runs the rest. The renderer keeps the race's passes short, a thirty-second of the render
//! at most, so that a short render does not spend most of its time on the slower tier.

use crate::traversal::HitTier;

/// Which of the race's two tiers runs each pass: pass `i` runs `tiers[ORDER[i]]` (pass 0 not
/// counted).
const ORDER: [usize; 5] = [0, 0, 1, 1, 0];

/// A race of two tiers over a render's first passes: ask [`TierRace::tier`] before each pass, tell
/// [`TierRace::record`] how long it took.
#[derive(Clone, Debug, PartialEq)]
pub struct TierRace {
    tiers: [HitTier; 2],
    /// Passes recorded so far.
    passes: usize,
    /// Each tier's counted seconds and samples per pixel.
    secs: [f64; 2],
    spp: [u64; 2],
}

/// How a race ended: the tier that won, the one that lost, and how many times the loser's time per
/// sample the winner's is (at most 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RaceOutcome {
    pub winner: HitTier,
    pub loser: HitTier,
    pub time_ratio: f64,
}

impl TierRace {
    /// A race of `a` (which runs the uncounted first pass, and wins a tie) against `b`.
    pub fn new(a: HitTier, b: HitTier) -> TierRace {
        TierRace {
            tiers: [a, b],
            passes: 0,
            secs: [0.0; 2],
            spp: [0; 2],
        }
    }

    /// The race the renderer runs on this processor unless `--hit-tier` names a tier: AVX2 against
    /// AVX-512 on an Intel processor that runs both (AVX2, the tier it ran before races, first),
    /// none elsewhere. `asked` (`--hit-tier auto`) races them on any processor that runs both.
    pub fn on_this_processor(asked: bool) -> Option<TierRace> {
        let both = HitTier::detected() == HitTier::Avx512;
        let unknown = HitTier::preferred() != HitTier::detected();
        (both && (asked || unknown))
            .then(|| TierRace::new(HitTier::preferred(), other(HitTier::preferred())))
    }

    /// Whether passes are still being timed.
    pub fn racing(&self) -> bool {
        self.passes < ORDER.len()
    }

    /// The two tiers, in the order given.
    pub fn tiers(&self) -> [HitTier; 2] {
        self.tiers
    }

    /// The tier the next pass runs.
    pub fn tier(&self) -> HitTier {
        match ORDER.get(self.passes) {
            Some(&i) => self.tiers[i],
            None => self.outcome().map_or(self.tiers[0], |o| o.winner),
        }
    }

    /// The pass that ran [`TierRace::tier`] took `secs` seconds for `spp` samples per pixel.
    pub fn record(&mut self, secs: f64, spp: u64) {
        if let Some(&i) = ORDER.get(self.passes) {
            if self.passes > 0 {
                self.secs[i] += secs;
                self.spp[i] += spp;
            }
            self.passes += 1;
        }
    }

    /// The winner, once every pass of the race is recorded: the tier with less time per sample per
    /// pixel (the first on a tie, or where a time is not a positive number).
    pub fn outcome(&self) -> Option<RaceOutcome> {
        if self.racing() {
            return None;
        }
        let per = |i: usize| self.secs[i] / self.spp[i].max(1) as f64;
        let (a, b) = (per(0), per(1));
        let second = a > 0.0 && b > 0.0 && b < a;
        let (w, l) = if second { (1, 0) } else { (0, 1) };
        let ratio = per(w) / per(l);
        Some(RaceOutcome {
            winner: self.tiers[w],
            loser: self.tiers[l],
            time_ratio: if ratio.is_finite() { ratio } else { 1.0 },
        })
    }
}

/// The other of AVX2 and AVX-512.
fn other(t: HitTier) -> HitTier {
    if t == HitTier::Avx512 {
        HitTier::Avx2
    } else {
        HitTier::Avx512
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use HitTier::{Avx2, Avx512};

    /// Run a race whose passes take `secs(tier, spp)` seconds, the passes growing as the renderer's
    /// do (1, 2, 4, ... samples per pixel); the tiers that ran, in order, and the outcome.
    fn run(
        secs: impl Fn(HitTier, u64) -> f64,
        passes: usize,
    ) -> (Vec<HitTier>, Option<RaceOutcome>) {
        let mut race = TierRace::new(Avx2, Avx512);
        let mut ran = Vec::new();
        for p in 0..passes {
            let (t, spp) = (race.tier(), 1u64 << p);
            ran.push(t);
            race.record(secs(t, spp), spp);
        }
        (ran, race.outcome())
    }

    #[test]
    fn the_faster_tier_wins_and_runs_every_pass_after_the_race() {
        // AVX-512 takes 0.8 of AVX2's time per sample.
        let (ran, out) = run(|t, spp| spp as f64 * if t == Avx512 { 0.8 } else { 1.0 }, 8);
        assert_eq!(
            ran,
            [Avx2, Avx2, Avx512, Avx512, Avx2, Avx512, Avx512, Avx512]
        );
        let out = out.unwrap();
        assert_eq!((out.winner, out.loser), (Avx512, Avx2));
        assert!((out.time_ratio - 0.8).abs() < 1e-12, "{out:?}");
        // And the other way round.
        let (ran, out) = run(
            |t, spp| spp as f64 * if t == Avx512 { 1.25 } else { 1.0 },
            7,
        );
        assert_eq!(ran[5..], [Avx2, Avx2]);
        assert_eq!(out.unwrap().winner, Avx2);
    }

    #[test]
    fn the_first_pass_is_not_counted_and_time_is_taken_per_sample() {
        // A slow start (the pool, the buffers' first touch) on the first pass, which runs AVX2,
        // must not make AVX-512 win; nor must the larger passes AVX-512 happens to get.
        let (_, out) = run(
            |t, spp| {
                let start = if spp == 1 { 100.0 } else { 0.0 };
                start + spp as f64 * if t == Avx512 { 1.1 } else { 1.0 }
            },
            6,
        );
        assert_eq!(out.unwrap().winner, Avx2);
    }

    #[test]
    fn no_outcome_before_the_race_ends_and_ties_or_nonsense_keep_the_first() {
        let (ran, out) = run(|_, spp| spp as f64, 4);
        assert_eq!(ran, [Avx2, Avx2, Avx512, Avx512]);
        assert_eq!(out, None);
        let (_, out) = run(|_, spp| spp as f64, 5);
        assert_eq!(out.unwrap().winner, Avx2);
        for bad in [0.0, f64::NAN] {
            let (_, out) = run(|t, spp| if t == Avx512 { bad } else { spp as f64 }, 5);
            let out = out.unwrap();
            assert_eq!(out.winner, Avx2, "{bad}");
            assert!(out.time_ratio.is_finite(), "{out:?}");
        }
    }
}
