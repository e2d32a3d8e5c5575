//! The memory a new allocation may take: the least of the machine's free memory, what the
//! process's own limits leave it, and what its control group's limit leaves (read from `/proc` and
//! `/sys/fs/cgroup`), so that a render, a merge or a file too large for it is refused before any
//! work rather than aborted half-way.

use super::Bytes;
use std::fmt;
use std::path::Path;

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

impl MemoryLimit {
    /// What the limit counts, for a message ("needs 300 MB of address space"): address space for
    /// `ulimit -v`, memory for the others.
    pub fn counts(self) -> &'static str {
        match self {
            MemoryLimit::AddressSpace => "address space",
            MemoryLimit::Machine | MemoryLimit::DataSize | MemoryLimit::ControlGroup => "memory",
        }
    }
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
    memory_limits().into_iter().min_by_key(|a| a.bytes)
}

/// Every limit on the memory of a new allocation that applies, each with what it leaves (empty
/// where nothing says): the limits count different things (a thread's malloc arena is address
/// space, `ulimit -v`, but neither data nor memory in use), so work that needs more of one kind
/// than of another is checked against each ([`super::Need`]).
pub fn memory_limits() -> Vec<Available> {
    let read = |path: &Path| std::fs::read_to_string(path).ok();
    let group = read(Path::new("/proc/self/cgroup"))
        .and_then(|c| control_group_available(&c, Path::new("/sys/fs/cgroup"), &read));
    let mut limits = limits_of(
        read(Path::new("/proc/meminfo")).as_deref(),
        read(Path::new("/proc/self/limits")).as_deref(),
        read(Path::new("/proc/self/status")).as_deref(),
    );
    limits.extend(group);
    limits
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
    limits_of(meminfo, limits, status)
        .into_iter()
        .min_by_key(|a| a.bytes)
}

/// Each of the machine's free memory, the address-space limit and the data-size limit that applies,
/// with what it leaves, from the texts of `/proc/meminfo`, `/proc/self/limits` and
/// `/proc/self/status`.
pub fn limits_of(
    meminfo: Option<&str>,
    limits: Option<&str>,
    status: Option<&str>,
) -> Vec<Available> {
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
    .collect()
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
    fn every_limit_is_listed_with_what_it_leaves() {
        let both = UNLIMITED
            .replacen(
                "Max address space         unlimited",
                "Max address space         1536000000",
                1,
            )
            .replacen(
                "Max data size             unlimited",
                "Max data size             104857600",
                1,
            );
        let limits = limits_of(Some(MEMINFO), Some(&both), Some(STATUS));
        let of = |l: MemoryLimit| limits.iter().find(|a| a.limit == l).map(|a| a.bytes);
        assert_eq!(limits.len(), 3);
        assert_eq!(of(MemoryLimit::Machine), Some(8_000_000 * 1024));
        assert_eq!(
            of(MemoryLimit::AddressSpace),
            Some(1_536_000_000 - 200_000 * 1024)
        );
        assert_eq!(of(MemoryLimit::DataSize), Some(104_857_600 - 50_000 * 1024));
        assert_eq!(limits_of(Some(MEMINFO), Some(UNLIMITED), None).len(), 1);
        assert!(limits_of(None, None, None).is_empty());
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
}
