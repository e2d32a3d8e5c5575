//! What the renderer accepts: one rule for each value, whether it comes from the command line or a
//! scene file, so that everything accepted renders and everything else is refused before any work.
//!
//! - **Numbers in a scene file** are finite and at most [`MAX_MAGNITUDE`] in size, and quantities that
//!   must be positive (radii, densities, scales, the index of refraction, the focus distance) are at
//!   least [`MIN_POSITIVE`]: then squares and triple products of lengths, which intersection and the
//!   solid-angle densities form, stay finite and nonzero.
//! - **Paths** have between 1 and [`MAX_DEPTH`] intersections.
//! - **Images** are at most [`MAX_SIDE`] pixels on a side, and the buffers a render needs
//!   ([`BYTES_PER_PIXEL`] per pixel) must fit in the memory the machine has available.
//! - **Threads** number at most [`MAX_THREADS`].
//! - **Scenes** hold at most [`MAX_EXPANDED_OBJECTS`] objects once their instances are expanded, and
//!   nest groups at most [`MAX_NESTING`] deep: a few kilobytes of instances of instances would
//!   otherwise stand for 2^40 shapes, which the walks over the scene (the emitters, the glass spheres)
//!   and every ray would visit one by one.
//! - **Files**: a scene file is a regular file of at most [`MAX_SCENE_FILE_BYTES`] whose reading takes
//!   at most [`MAX_SCENE_READ_BYTES`] ([`toml_read_bytes`]) and the memory available, a texture file
//!   one of at most [`MAX_TEXTURE_FILE_BYTES`] that decodes to at most [`MAX_TEXTURE_PIXELS`] pixels,
//!   read from its header before anything is decoded, within the memory available.
//! - **Memory available** is the least of the machine's (`MemAvailable`) and what the process's own
//!   limits (`ulimit -v`, `ulimit -d`) leave it ([`available_memory`]).

use std::fmt;
use std::path::Path;

/// The largest magnitude of any number in a scene file.
pub const MAX_MAGNITUDE: f64 = 1e30;
/// The smallest value of a quantity that must be positive.
pub const MIN_POSITIVE: f64 = 1e-30;
/// The most intersections a path may have (book 3 uses 50).
pub const MAX_DEPTH: u32 = 10_000;
/// The largest image width or height, in pixels.
pub const MAX_SIDE: usize = 1 << 16;
/// The most worker threads.
pub const MAX_THREADS: usize = 1024;
/// The aspect ratios (width over height) a scene may ask for: one pixel by [`MAX_SIDE`] either way.
pub const ASPECT_RANGE: (f64, f64) = (1.0 / MAX_SIDE as f64, MAX_SIDE as f64);

/// The most objects a scene may hold once its instances are expanded: every sphere, quad and medium,
/// and every group or instance that places a group, counted once for each place it ends up in (an
/// instance counts itself and, again, every object of the group it places). 2^20: ten times the
/// 200,000 spheres of a 20 MB scene file, and enough for every built-in scene and shipped scene file
/// (book 2's final scene, the largest, holds about 3,500); at the limit the walks over the scene take
/// milliseconds, and a scene whose every object emits keeps its list of emitters (about 1 kB an
/// emitter) near 1 GB.
pub const MAX_EXPANDED_OBJECTS: u64 = 1 << 20;
/// The deepest groups may nest (a group or an instance inside a group, or a medium's boundary, counted
/// from the scene's top level): the walks over the scene stop there.
pub const MAX_NESTING: u32 = 64;
/// The largest scene file, in bytes: 32 MiB, 1.6 times the 20 MB of 200,000 spheres. The TOML
/// reader's memory peaks at about 40 times the size of such a file (650 MB for those spheres), but
/// at up to 240 times that of one written to be expensive (`[{a=1},{a=1},...]`: 8 GB at the limit):
/// [`toml_read_bytes`] bounds it from the text before it is read, within
/// [`MAX_SCENE_READ_BYTES`].
pub const MAX_SCENE_FILE_BYTES: u64 = 32 << 20;
/// The most memory the TOML reader may take for a scene file, as [`toml_read_bytes`] bounds it:
/// 2 GiB, 1.3 times the bound for 32 MiB of spheres (1.6 GB).
pub const MAX_SCENE_READ_BYTES: u64 = 2 << 30;

/// An upper bound of the memory the TOML reader takes to hold `text` as a tree of values with their
/// places: 8 bytes a byte of text, and for what makes a value (measured on files of nothing else,
/// peak resident memory of `rtl render` over the file's size, on x86-64): 1300 bytes an
/// inline table (`{a=1},` took 1434 bytes in all), 400 a key (`k=1` 380) and an array (`[1],` 492),
/// 160 an element (`1,` 154). 200,000 spheres (20 MB) bound at 1.0 GB (they took 650 MB).
/// Characters inside strings and comments count too: the bound is only looser for them.
pub fn toml_read_bytes(text: &str) -> u64 {
    let per_byte = |b: &u8| -> u64 {
        match b {
            b'{' => 1300,
            b'[' | b'=' => 400,
            b',' => 160,
            _ => 0,
        }
    };
    let structure: u64 = text.as_bytes().iter().map(per_byte).sum();
    structure.saturating_add(8 * text.len() as u64)
}

/// The largest texture file, in bytes.
pub const MAX_TEXTURE_FILE_BYTES: u64 = 256 << 20;
/// The most pixels an image texture may have: 2^25, an 8192 x 4096 longitude-latitude map (the book's
/// `earthmap.jpg` is 1024 x 512). Decoded to linear `f32` RGB it takes 12 bytes a pixel: 384 MiB.
pub const MAX_TEXTURE_PIXELS: u64 = 1 << 25;

/// What a walk over a scene's groups may still visit ([`MAX_EXPANDED_OBJECTS`] objects, the most a
/// scene file may hold once expanded): built scenes that were not read from a file (and could expand
/// to more) cannot make a walk run away.
#[derive(Debug)]
pub(crate) struct WalkBudget(u64);

impl WalkBudget {
    pub(crate) fn new() -> Self {
        WalkBudget(MAX_EXPANDED_OBJECTS)
    }

    /// Count one object visited: `false` once the budget is spent.
    #[inline]
    pub(crate) fn visit(&mut self) -> bool {
        match self.0.checked_sub(1) {
            Some(left) => {
                self.0 = left;
                true
            }
            None => false,
        }
    }
}

/// How many objects `scene` holds once its instances are expanded (as [`MAX_EXPANDED_OBJECTS`] counts
/// them, saturating at `u64::MAX`), computed once per group: what a walk over the whole scene visits.
/// Groups nested deeper than [`MAX_NESTING`] (or in a cycle, which the scene builder refuses) count
/// as `u64::MAX`.
pub fn expanded_objects(scene: &crate::scene::Scene) -> u64 {
    fn count(scene: &crate::scene::Scene, g: usize, depth: u32, memo: &mut [Option<u64>]) -> u64 {
        use crate::scene::Object;
        if depth > MAX_NESTING {
            return u64::MAX;
        }
        if let Some(n) = memo.get(g).copied().flatten() {
            return n;
        }
        let Some(group) = scene.groups.get(g) else {
            return 0;
        };
        let mut n = 0u64;
        for o in &group.objects {
            let inner = match o {
                Object::Instance { group, .. } | Object::Group(group) => {
                    count(scene, group.0 as usize, depth + 1, memo)
                }
                Object::Medium(m) => count(scene, m.boundary.0 as usize, depth + 1, memo),
                Object::Sphere(_) | Object::Quad(_) => 0,
            };
            n = n.saturating_add(1).saturating_add(inner);
            if n == u64::MAX {
                // (not kept: found too deep here, it may not be from higher up; stopping at once
                // keeps the walk linear)
                return n;
            }
        }
        memo[g] = Some(n);
        n
    }
    let mut memo = vec![None; scene.groups.len()];
    count(scene, 0, 0, &mut memo)
}

/// A file that may be read whole: a regular file (not a directory, a device such as `/dev/zero`, or
/// a pipe, which could give bytes without end) of at most `max` bytes, read at most to `max`. `what`
/// names it in errors ("scene file", "texture file"). The error is the whole message, naming the path.
pub fn read_regular_file(path: &Path, what: &str, max: u64) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let name = path.display();
    let io = |e: std::io::Error| format!("{name}: cannot read {what}: {e}");
    // Looked at before it is opened: opening a pipe would wait for a writer.
    let meta = std::fs::metadata(path).map_err(io)?;
    if !meta.is_file() {
        return Err(format!(
            "{name}: cannot read {what}: it is not a regular file (a directory, a device or a pipe)"
        ));
    }
    let too_large = |len: u64| {
        format!(
            "{name}: cannot read {what}: it is {} ({len} bytes), more than the {} ({max} bytes) a \
             {what} may be",
            Bytes(len),
            Bytes(max)
        )
    };
    if meta.len() > max {
        return Err(too_large(meta.len()));
    }
    let file = std::fs::File::open(path).map_err(io)?;
    let mut bytes = Vec::new();
    bytes.try_reserve_exact(meta.len() as usize).map_err(|_| {
        format!(
            "{name}: cannot read {what}: no memory for its {}",
            Bytes(meta.len())
        )
    })?;
    // (a file that grows while it is read stops at one byte past the limit)
    file.take(max.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > max {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// What is wrong with a maximum path depth of `d` (`None` if nothing): "must be at least 1" or "must be
/// at most 10000, got 20000". The command line and scene files both ask this.
pub fn max_depth_problem(d: u32) -> Option<String> {
    if d == 0 {
        Some(
            "must be at least 1 (a path of 0 intersections sees nothing: the image would be black)"
                .into(),
        )
    } else if d > MAX_DEPTH {
        Some(format!("must be at most {MAX_DEPTH}, got {d}"))
    } else {
        None
    }
}

/// Bytes of memory one pixel of a render needs at most: the accumulation (three f64 sums and two u64
/// counts) and its copy for the pass in flight, a checkpoint's bytes, the image of means, and its
/// linear (3 f32) and 8-bit (3 u8) encodings.
pub const BYTES_PER_PIXEL: u64 = 40 + 40 + 40 + 24 + 12 + 3;

/// Why an image cannot be rendered at this size.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SizeError {
    #[error("the image would be {width}x{height} pixels: each side may be at most {MAX_SIDE}")]
    TooLarge { width: usize, height: usize },
    #[error(
        "the image would be {width}x{height} pixels, which needs {} of memory ({BYTES_PER_PIXEL} bytes \
         a pixel), but {available}",
        Bytes(*needed)
    )]
    OutOfMemory {
        width: usize,
        height: usize,
        needed: u64,
        available: Available,
    },
}

/// A byte count in readable units.
pub struct Bytes(pub u64);

impl fmt::Display for Bytes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let b = self.0 as f64;
        match self.0 {
            0..1_000 => write!(f, "{} B", self.0),
            1_000..1_000_000 => write!(f, "{:.1} kB", b / 1e3),
            1_000_000..1_000_000_000 => write!(f, "{:.1} MB", b / 1e6),
            1_000_000_000..1_000_000_000_000 => write!(f, "{:.1} GB", b / 1e9),
            _ => write!(f, "{:.1} TB", b / 1e12),
        }
    }
}

/// What bounds the memory a new allocation may take.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MemoryLimit {
    /// The machine's free memory: `MemAvailable` of `/proc/meminfo`.
    Machine,
    /// The process's address-space limit (`ulimit -v`, `RLIMIT_AS`) less what it has mapped
    /// (`VmSize`): past it every allocation fails, whatever the machine has free.
    AddressSpace,
    /// The process's data-size limit (`ulimit -d`, `RLIMIT_DATA`) less its data (`VmData`).
    DataSize,
    /// The memory limit of the process's control group or one above it (a container's limit:
    /// `memory.max` in cgroup v2, `memory.limit_in_bytes` in v1) less what the group uses but
    /// cannot give back (its usage less its inactive file cache, as container tools count it).
    ControlGroup,
}

/// The memory a new allocation may take, in bytes, and the limit that says so.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Available {
    pub bytes: u64,
    pub limit: MemoryLimit,
}

impl fmt::Display for Available {
    /// The end of a refusal: "... needs 2.5 GB, but this machine has 1.1 GB available (MemAvailable
    /// in /proc/meminfo)".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let b = Bytes(self.bytes);
        match self.limit {
            MemoryLimit::Machine => {
                write!(
                    f,
                    "this machine has {b} available (MemAvailable in /proc/meminfo)"
                )
            }
            MemoryLimit::AddressSpace => write!(
                f,
                "this process may map only {b} more (its address-space limit, ulimit -v, less what \
                 it has mapped: VmSize in /proc/self/status)"
            ),
            MemoryLimit::DataSize => write!(
                f,
                "this process may allocate only {b} more (its data-size limit, ulimit -d, less its \
                 data: VmData in /proc/self/status)"
            ),
            MemoryLimit::ControlGroup => write!(
                f,
                "this process's control group (a container's memory limit) leaves {b} (memory.max \
                 or memory.limit_in_bytes less the group's usage, /sys/fs/cgroup)"
            ),
        }
    }
}

/// The memory available to a new allocation (`None` where nothing says): the least of the machine's
/// (`MemAvailable`), what the process's own limits leave it (`ulimit -v` and `ulimit -d`, which
/// an allocation past them fails, and the program aborts, however much the machine has free) and
/// what its control group's limit leaves (a container's: past it the kernel kills the process).
pub fn available_memory() -> Option<Available> {
    let read = |path: &Path| std::fs::read_to_string(path).ok();
    let group = read(Path::new("/proc/self/cgroup"))
        .and_then(|c| control_group_available(&c, Path::new("/sys/fs/cgroup"), &read));
    let rest = available_of(
        read(Path::new("/proc/meminfo")).as_deref(),
        read(Path::new("/proc/self/limits")).as_deref(),
        read(Path::new("/proc/self/status")).as_deref(),
    );
    [rest, group].into_iter().flatten().min_by_key(|a| a.bytes)
}

/// What the memory limits of the process's control group and of every group above it leave, the
/// least of them (`None` if none is set): `cgroup` is the text of `/proc/self/cgroup`, `root` where
/// the groups are mounted, `read` reads a file. Version 2 (`0::/path`, `memory.max`,
/// `memory.current`) and version 1 (`N:memory:/path`, under `root/memory`, `memory.limit_in_bytes`,
/// `memory.usage_in_bytes`) alike; the inactive file cache (`memory.stat`) counts as free, since the
/// kernel reclaims it before it refuses.
pub fn control_group_available(
    cgroup: &str,
    root: &Path,
    read: &dyn Fn(&Path) -> Option<String>,
) -> Option<Available> {
    // (the hierarchy's directory, the group's path in it, limit file, usage file, inactive key)
    let mut found = None;
    for line in cgroup.lines() {
        let mut parts = line.splitn(3, ':');
        let (Some(id), Some(controllers), Some(path)) = (parts.next(), parts.next(), parts.next())
        else {
            continue;
        };
        if id == "0" && controllers.is_empty() {
            found.get_or_insert((
                root.to_path_buf(),
                path,
                "memory.max",
                "memory.current",
                "inactive_file",
            ));
        } else if controllers.split(',').any(|c| c == "memory") {
            // Version 1's memory hierarchy wins over a version 2 line (a hybrid mount).
            found = Some((
                root.join("memory"),
                path,
                "memory.limit_in_bytes",
                "memory.usage_in_bytes",
                "total_inactive_file",
            ));
        }
    }
    let (base, path, limit_file, usage_file, inactive) = found?;
    let number =
        |dir: &Path, file: &str| -> Option<u64> { read(&dir.join(file))?.trim().parse().ok() };
    let mut least: Option<u64> = None;
    let mut dir = path.trim_start_matches('/');
    loop {
        let at = base.join(dir);
        // "max" (v2) does not parse: no limit; v1's "no limit" is a number near 2^63.
        if let Some(limit) = number(&at, limit_file).filter(|&l| l < 1 << 62) {
            let usage = number(&at, usage_file).unwrap_or(0);
            let cache = read(&at.join("memory.stat"))
                .and_then(|s| {
                    s.lines().find_map(|l| {
                        l.strip_prefix(inactive)?
                            .strip_prefix(' ')?
                            .trim()
                            .parse()
                            .ok()
                    })
                })
                .unwrap_or(0u64);
            let left = limit.saturating_sub(usage.saturating_sub(cache));
            least = Some(least.map_or(left, |l| l.min(left)));
        }
        if dir.is_empty() {
            break;
        }
        dir = dir.rsplit_once('/').map_or("", |(parent, _)| parent);
    }
    least.map(|bytes| Available {
        bytes,
        limit: MemoryLimit::ControlGroup,
    })
}

/// [`available_memory`] from the texts of `/proc/meminfo`, `/proc/self/limits` and
/// `/proc/self/status`.
pub fn available_of(
    meminfo: Option<&str>,
    limits: Option<&str>,
    status: Option<&str>,
) -> Option<Available> {
    let machine = meminfo.and_then(mem_available).map(|bytes| Available {
        bytes,
        limit: MemoryLimit::Machine,
    });
    let left = |name: &str, used: &str, limit: MemoryLimit| {
        let max = soft_limit(limits?, name)?;
        let used = status.and_then(|s| status_kib(s, used)).unwrap_or(0);
        Some(Available {
            bytes: max.saturating_sub(used),
            limit,
        })
    };
    [
        machine,
        left("Max address space", "VmSize:", MemoryLimit::AddressSpace),
        left("Max data size", "VmData:", MemoryLimit::DataSize),
    ]
    .into_iter()
    .flatten()
    .min_by_key(|a| a.bytes)
}

/// `MemAvailable` of the text of `/proc/meminfo`, in bytes.
pub fn mem_available(meminfo: &str) -> Option<u64> {
    status_kib(meminfo, "MemAvailable:")
}

/// A `Name:   123 kB` line of `/proc/meminfo` or `/proc/self/status`, in bytes.
fn status_kib(text: &str, name: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with(name))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

/// The soft limit named `name` in the text of `/proc/self/limits`, in bytes (`None` if unlimited).
fn soft_limit(limits: &str, name: &str) -> Option<u64> {
    let line = limits.lines().find_map(|l| l.strip_prefix(name))?;
    line.split_whitespace().next()?.parse().ok()
}

/// Check that a `width x height` render fits: each side at most [`MAX_SIDE`] and its buffers within
/// the memory `available` (if known). Returns the bytes it needs.
pub fn check_image(
    width: usize,
    height: usize,
    available: Option<Available>,
) -> Result<u64, SizeError> {
    if width > MAX_SIDE || height > MAX_SIDE {
        return Err(SizeError::TooLarge { width, height });
    }
    // Both sides are at most 2^16, so this cannot overflow.
    let needed = width as u64 * height as u64 * BYTES_PER_PIXEL;
    match available {
        Some(available) if needed > available.bytes => Err(SizeError::OutOfMemory {
            width,
            height,
            needed,
            available,
        }),
        _ => Ok(needed),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mem_available_reads_kib() {
        let text = "MemTotal:       16000000 kB\nMemFree:  1 kB\nMemAvailable:    8000000 kB\n";
        assert_eq!(mem_available(text), Some(8_000_000 * 1024));
        assert_eq!(mem_available("MemTotal: 5 kB\n"), None);
    }

    const MEMINFO: &str = "MemTotal:  16000000 kB\nMemAvailable:    8000000 kB\n";
    const UNLIMITED: &str = "Limit                     Soft Limit           Hard Limit           Units     \n\
        Max data size             unlimited            unlimited            bytes     \n\
        Max address space         unlimited            unlimited            bytes     \n";
    const STATUS: &str =
        "Name:\trtl\nVmPeak:\t  300000 kB\nVmSize:\t  200000 kB\nVmData:\t   50000 kB\n";

    #[test]
    fn a_control_groups_limit_counts_at_every_level_up_to_the_root() {
        use std::collections::HashMap;
        let files = |entries: &[(&str, &str)]| -> HashMap<std::path::PathBuf, String> {
            entries
                .iter()
                .map(|(p, t)| (std::path::PathBuf::from(p), t.to_string()))
                .collect()
        };
        let root = Path::new("/cg");
        // Version 2: the group's own limit is "max"; its parent's is 3 GB with 1 GB used, of
        // which 0.25 GB is inactive file cache (free to reclaim): 2.25 GB left.
        let v2 = files(&[
            ("/cg/box/job/memory.max", "max\n"),
            ("/cg/box/job/memory.current", "500000000\n"),
            ("/cg/box/memory.max", "3000000000\n"),
            ("/cg/box/memory.current", "1000000000\n"),
            (
                "/cg/box/memory.stat",
                "anon 1\ninactive_file 250000000\nactive_file 9\n",
            ),
        ]);
        let read = |p: &Path| v2.get(p).cloned();
        let a = control_group_available("0::/box/job\n", root, &read).unwrap();
        assert_eq!(
            a,
            Available {
                bytes: 2_250_000_000,
                limit: MemoryLimit::ControlGroup
            }
        );
        assert!(a.to_string().contains("control group"), "{a}");
        // Version 1 (a hybrid mount: the memory line wins), its "no limit" a number near 2^63.
        let v1 = files(&[
            (
                "/cg/memory/api/x/memory.limit_in_bytes",
                "9223372036854771712\n",
            ),
            ("/cg/memory/api/x/memory.usage_in_bytes", "484847616\n"),
            ("/cg/memory/api/memory.limit_in_bytes", "1073741824\n"),
            ("/cg/memory/api/memory.usage_in_bytes", "600000000\n"),
            (
                "/cg/memory/api/memory.stat",
                "cache 5\ntotal_inactive_file 100000000\n",
            ),
            ("/cg/memory/memory.limit_in_bytes", "9223372036854771712\n"),
        ]);
        let read = |p: &Path| v1.get(p).cloned();
        let text = "5:devices:/\n4:memory:/api/x\n0::/\n";
        assert_eq!(
            control_group_available(text, root, &read).map(|a| a.bytes),
            Some(1_073_741_824 - 500_000_000)
        );
        // No limit anywhere, or no group: nothing to say.
        let unlimited = files(&[("/cg/memory/memory.limit_in_bytes", "9223372036854771712\n")]);
        let read = |p: &Path| unlimited.get(p).cloned();
        assert_eq!(control_group_available("4:memory:/\n", root, &read), None);
        assert_eq!(control_group_available("", root, &read), None);
        // A group past its limit has nothing left.
        let full = files(&[
            ("/cg/memory.max", "1000\n"),
            ("/cg/memory.current", "5000\n"),
        ]);
        let read = |p: &Path| full.get(p).cloned();
        assert_eq!(
            control_group_available("0::/\n", root, &read).map(|a| a.bytes),
            Some(0)
        );
    }

    #[test]
    fn the_memory_available_is_the_least_the_machine_and_the_process_limits_leave() {
        let machine = Available {
            bytes: 8_000_000 * 1024,
            limit: MemoryLimit::Machine,
        };
        assert_eq!(
            available_of(Some(MEMINFO), Some(UNLIMITED), Some(STATUS)),
            Some(machine)
        );
        assert_eq!(available_of(Some(MEMINFO), None, None), Some(machine));
        assert_eq!(available_of(None, None, None), None);
        // `ulimit -v 1500000` (KiB): the limit less what the process has mapped already
        let as_limited = UNLIMITED.replacen(
            "Max address space         unlimited            unlimited",
            "Max address space         1536000000           unlimited",
            1,
        );
        let a = available_of(Some(MEMINFO), Some(&as_limited), Some(STATUS)).unwrap();
        assert_eq!(
            a,
            Available {
                bytes: 1_536_000_000 - 200_000 * 1024,
                limit: MemoryLimit::AddressSpace
            }
        );
        assert!(a.to_string().contains("ulimit -v"), "{a}");
        // without /proc/meminfo (or /proc/self/status), the limit alone
        assert_eq!(
            available_of(None, Some(&as_limited), None).map(|a| a.bytes),
            Some(1_536_000_000)
        );
        // `ulimit -d`, the tighter of the two
        let both = as_limited.replacen(
            "Max data size             unlimited",
            "Max data size             104857600",
            1,
        );
        let d = available_of(Some(MEMINFO), Some(&both), Some(STATUS)).unwrap();
        assert_eq!(d.limit, MemoryLimit::DataSize);
        assert_eq!(d.bytes, 104_857_600 - 50_000 * 1024);
        // a process already past its limit has nothing left
        let tight = UNLIMITED.replacen(
            "Max address space         unlimited",
            "Max address space         1000",
            1,
        );
        let none = available_of(Some(MEMINFO), Some(&tight), Some(STATUS)).unwrap();
        assert_eq!(none.bytes, 0);
    }

    #[test]
    fn images_past_a_side_or_the_memory_are_refused() {
        let gib = Some(Available {
            bytes: 1 << 30,
            limit: MemoryLimit::Machine,
        });
        assert!(check_image(600, 600, gib).is_ok());
        assert_eq!(
            check_image(MAX_SIDE + 1, 1, None),
            Err(SizeError::TooLarge {
                width: MAX_SIDE + 1,
                height: 1
            })
        );
        let e = check_image(10_000, 10_000, gib).unwrap_err();
        assert!(
            e.to_string().contains("15.9 GB") && e.to_string().contains("1.1 GB"),
            "{e}"
        );
        assert!(e.to_string().contains("MemAvailable"), "{e}");
    }
}
