//! Which form of the closest-hit traversal runs ([`HitTier`]): the portable one, AVX2 or AVX-512,
//! chosen once per process from the processor's features (CPUID), or named by the user.

use std::sync::atomic::{AtomicU8, Ordering};

/// [`HitTier::cached`]'s store: 0 before the first traversal, then the detected tier plus one.
static TIER: AtomicU8 = AtomicU8::new(0);

/// Which form of the closest-hit traversal runs: chosen at run time from the processor's features
/// ([`HitTier::detected`], [`HitTier::preferred`]). Every tier finds bit-identical hits: the same
/// `f64` operations in the same order, lane by lane, and no fused multiply-adds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum HitTier {
    /// Any processor: the quad packets lane by lane (which the compiler may vectorise for SSE2).
    Portable,
    /// x86-64 with AVX2: the quad packets four lanes to an instruction.
    Avx2,
    /// x86-64 with AVX-512F and VL (and AVX2): a small flat group's quads eight lanes to an
    /// instruction, in [`Accel::packets8`]; the trees as [`HitTier::Avx2`] ([`Scene::hit_group`]
    /// sends only the small groups to this tier's code).
    ///
    /// [`Accel::packets8`]: crate::traversal::Accel::packets8
    /// [`Scene::hit_group`]: crate::scene::Scene::hit_group
    Avx512,
}

impl HitTier {
    /// The best tier this processor runs.
    #[inline]
    pub fn detected() -> HitTier {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx512f")
                && std::arch::is_x86_feature_detected!("avx512vl")
                && std::arch::is_x86_feature_detected!("avx2")
            {
                return HitTier::Avx512;
            }
            if std::arch::is_x86_feature_detected!("avx2") {
                return HitTier::Avx2;
            }
        }
        HitTier::Portable
    }

    /// The tier traversals run unless one is [`HitTier::select`]ed: the [`HitTier::detected`] one,
    /// except on an Intel processor, where [`HitTier::Avx2`] runs even if AVX-512 is there. Measured
    /// side by side on an Intel Xeon (family 6 model 207), the 8-lane packets made the Cornell box's
    /// `mixture` 1.08x and `mis` 1.03x *slower* (render-speed.md, "Issue 16, seventh round"); on
    /// Intel's cores a 512-bit instruction takes the vector units of two ports, so eight lanes a
    /// time buy no throughput over two four-lane instructions. (That was measured before paths were
    /// traced side by side in the lanes, `crate::paths8`; the Intel choice is not measured
    /// since.) AMD keeps them: on a Zen 5 they were 1.04-1.11x faster, and with the paths in the
    /// lanes on a Zen 4 `mixture` 1.12-1.24x and `mis` 1.06-1.24x (README, "Speed"). So on Intel
    /// `rtl render` times both on its first passes ([`crate::tier_race`]) and keeps the faster;
    /// this is the tier that races first, and the one that runs where nothing races.
    pub fn preferred() -> HitTier {
        match HitTier::detected() {
            HitTier::Avx512 if intel() => HitTier::Avx2,
            t => t,
        }
    }

    /// [`HitTier::preferred`], found once and kept: one load per traversal (three feature tests
    /// each time cost the AVX2 tier ~1% more instructions on the Cornell box).
    #[inline(always)]
    pub(crate) fn cached() -> HitTier {
        match TIER.load(Ordering::Relaxed) {
            1 => HitTier::Portable,
            2 => HitTier::Avx2,
            3 => HitTier::Avx512,
            _ => Self::detect_once(),
        }
    }

    #[cold]
    fn detect_once() -> HitTier {
        let t = HitTier::preferred();
        TIER.store(t as u8 + 1, Ordering::Relaxed);
        t
    }

    /// Does this processor run the tier?
    pub fn available(self) -> bool {
        match (self, HitTier::detected()) {
            (HitTier::Portable, _) | (HitTier::Avx2, HitTier::Avx2 | HitTier::Avx512) => true,
            (t, d) => t == d,
        }
    }

    /// The tier's name, as `--explain` prints it.
    pub fn name(self) -> &'static str {
        match self {
            HitTier::Portable => "portable (no AVX2)",
            HitTier::Avx2 => "AVX2 (4-lane f64 quad packets)",
            HitTier::Avx512 => "AVX-512 (8-lane f64 quad packets in small groups, AVX2 elsewhere)",
        }
    }

    /// Every tier, slowest first.
    pub const ALL: [HitTier; 3] = [HitTier::Portable, HitTier::Avx2, HitTier::Avx512];

    /// The tier's key, as `--hit-tier` takes it: `portable`, `avx2` or `avx512`.
    pub fn key(self) -> &'static str {
        match self {
            HitTier::Portable => "portable",
            HitTier::Avx2 => "avx2",
            HitTier::Avx512 => "avx512",
        }
    }

    /// Run this tier in every traversal from now on instead of the detected one (to measure the tiers
    /// side by side on one processor, or one that a processor without AVX-512 would run). The hits
    /// are bit-identical in every tier, so this changes the speed only. Refused if the processor
    /// does not run the tier.
    pub fn select(self) -> Result<(), HitTierError> {
        TIER.store(self.runnable()? as u8 + 1, Ordering::Relaxed);
        Ok(())
    }

    /// This tier if the processor runs it, else the refusal that names the best one it does.
    pub fn runnable(self) -> Result<HitTier, HitTierError> {
        if self.available() {
            Ok(self)
        } else {
            Err(HitTierError::Unavailable {
                tier: self.key(),
                best: HitTier::detected().key(),
            })
        }
    }

    /// The tier traversals run: the one [`HitTier::select`]ed, else the [`HitTier::preferred`] one.
    pub fn current() -> HitTier {
        HitTier::cached()
    }
}

/// Is this an Intel processor (CPUID leaf 0's vendor string "GenuineIntel")?
fn intel() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        // SAFETY: CPUID exists on every x86-64 processor.
        #[allow(unused_unsafe)]
        let r = unsafe { std::arch::x86_64::__cpuid(0) };
        let mut vendor = [0u8; 12];
        vendor[..4].copy_from_slice(&r.ebx.to_le_bytes());
        vendor[4..8].copy_from_slice(&r.edx.to_le_bytes());
        vendor[8..].copy_from_slice(&r.ecx.to_le_bytes());
        &vendor == b"GenuineIntel"
    }
    #[cfg(not(target_arch = "x86_64"))]
    false
}

/// Why a tier could not be chosen.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum HitTierError {
    #[error("unknown intersection tier '{0}' (portable, avx2 or avx512)")]
    Unknown(String),
    #[error("this processor does not run the {tier} tier (the best it runs is {best})")]
    Unavailable {
        tier: &'static str,
        best: &'static str,
    },
}

impl std::str::FromStr for HitTier {
    type Err = HitTierError;

    /// A tier by its [`HitTier::key`].
    fn from_str(s: &str) -> Result<HitTier, HitTierError> {
        HitTier::ALL
            .into_iter()
            .find(|t| t.key() == s)
            .ok_or_else(|| HitTierError::Unknown(s.into()))
    }
}
