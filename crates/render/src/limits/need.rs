//! What a render or a merge needs of each kind of memory limit, checked against each limit that
//! applies before any work.
//!
//! The limits count different things. The machine's free memory (`MemAvailable`) and a control
//! group's limit count pages in use; `ulimit -d` (`VmData`) counts private writable mappings, used
//! or not, so a thread's whole stack; `ulimit -v` (`VmSize`) counts every mapping, even one that
//! cannot be touched, so the 64 MiB that glibc reserves for each thread's malloc arena, which
//! holds a few kilobytes. A render of 600 x 600 pixels on two threads uses some 70 MB, but maps
//! some 300 MB: the arenas of its two workers and of the Ctrl-C handler's thread are 192 MiB of
//! it. So each limit is compared with what counts against it ([`Need::of`]): the arenas make a
//! render refused under `ulimit -v`, never on a machine short of free memory.
//!
//! What is mapped already when the check runs (the program, the scene, its textures) is no part
//! of a need: the limits are what is left ([`super::memory_limits`]).

use super::{Available, MemoryLimit};

/// Bytes of each kind a piece of work needs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Need {
    /// Memory it uses: what `MemAvailable` and a control group's limit count.
    pub resident: u64,
    /// Private writable mappings, used or not: what `ulimit -d` counts (`VmData`).
    pub data: u64,
    /// Address space, every mapping: what `ulimit -v` counts (`VmSize`).
    pub address_space: u64,
}

/// A limit that a [`Need`] exceeds, and how much of it the need takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shortfall {
    /// What the work needs of the kind that `available.limit` counts.
    pub needed: u64,
    pub available: Available,
}

impl Need {
    /// Buffers that are written whole: as much of every kind.
    pub const fn all(bytes: u64) -> Need {
        Need {
            resident: bytes,
            data: bytes,
            address_space: bytes,
        }
    }

    /// What counts against `limit`.
    pub fn of(&self, limit: MemoryLimit) -> u64 {
        match limit {
            MemoryLimit::Machine | MemoryLimit::ControlGroup => self.resident,
            MemoryLimit::DataSize => self.data,
            MemoryLimit::AddressSpace => self.address_space,
        }
    }

    /// The sum of two needs (saturating).
    pub fn plus(self, other: Need) -> Need {
        Need {
            resident: self.resident.saturating_add(other.resident),
            data: self.data.saturating_add(other.data),
            address_space: self.address_space.saturating_add(other.address_space),
        }
    }

    /// The limit of `limits` this need exceeds by most, if any: each limit is compared with the
    /// kind of memory it counts.
    pub fn exceeds(&self, limits: &[Available]) -> Option<Shortfall> {
        limits
            .iter()
            .filter(|a| self.of(a.limit) > a.bytes)
            .max_by_key(|a| self.of(a.limit) - a.bytes)
            .map(|&available| Shortfall {
                needed: self.of(available.limit),
                available,
            })
    }
}

/// What the process needs besides its buffers and threads, from the check on: the Ctrl-C handler's
/// thread is counted as a thread; this is the rest (the checkpoint's and the image files' write
/// buffers, the PNG encoder's tables, the progress bar). Measured (`VmPeak` and `VmHWM` less
/// `VmSize` and `VmRSS` at the check, as for [`RENDER_BYTES_PER_PIXEL`]) at 8 x 8 pixels with 1 to
/// 32 threads: 0.6 to 1.0 MiB of memory; of address space, nothing beyond the threads' (one worker:
/// 196.0 MiB, and [`threads_need`] counts 196.1). Counted: 16 MiB of each.
pub const PROCESS_BASE: Need = Need::all(16 << 20);

/// Bytes a pixel of a render needs at its peak: 80, and a tenth of margin.
/// - The passes: the accumulation (three f64 sums and two u64 counts, 40 bytes) and the copy of it
///   that the pass in flight adds to (40: a stopped pass is thrown away), 80 bytes.
/// - `--resume`: the checkpoint's bytes (40 a pixel) and the accumulation read from them (40),
///   80, the bytes gone before the pass's copy is made.
/// - The output, less: the accumulation is dropped once its image of means (24) is made, then the
///   8-bit encoding (3) with the PNG encoder's compressed data (3 at most, in a vector that may
///   double) and `--linear`'s 32-bit floats (12, a PFM's bytes or the OpenEXR encoder's input).
///
/// A checkpoint (`--checkpoint`, `--resume`) is streamed from the accumulation to its file through a
/// 64 KiB buffer ([`crate::checkpoint::CheckpointRef::write`]): no byte a pixel. (It had been copied
/// whole, 40, and then built in a vector that doubled past its first guess, 80 more; the pass's copy
/// had been made anew beside the old one, 40 more, and the output kept the accumulation: aborts on
/// allocation past a check of 159 bytes a pixel.)
///
/// Measured on the release build (x86-64, glibc 2.36): `VmPeak` and `VmHWM` of `rtl render quads
/// --spp 1 --threads 1` at the process's exit (read from `/proc/self/status` by a library preloaded
/// with a destructor) less `VmSize` and `VmRSS` at the check and the threads' allowance
/// ([`threads_need`]): 80.0 bytes a pixel of address space at 2000 x 2000 and 3000 x 3000, with and
/// without `--checkpoint` and `--linear` (PFM, OpenEXR), and 80.0 of memory too with `--resume`
/// (without, the counts' pages of the accumulation are never written at 1 sample per pixel: 64).
pub const RENDER_BYTES_PER_PIXEL: u64 = 88;

/// What a render of `pixels` pixels needs: its buffers ([`RENDER_BYTES_PER_PIXEL`]), `threads`
/// threads besides the main one (its workers and the Ctrl-C handler's: [`threads_need`]) and the
/// process ([`PROCESS_BASE`]). `resume_bytes` is the size of the checkpoint it resumes (0 if none):
/// reading one takes its bytes and the accumulation read from them, twice its size, which a file
/// of another image (refused once read) may make more than the image's own.
pub fn render_need(pixels: u64, threads: usize, resume_bytes: u64) -> Need {
    let buffers = pixels
        .saturating_mul(RENDER_BYTES_PER_PIXEL)
        .max(resume_bytes.saturating_mul(2));
    Need::all(buffers)
        .plus(threads_need(threads))
        .plus(PROCESS_BASE)
}

/// What `rtl merge` needs for parts whose files are `part_bytes` long: they are read one by one and
/// held together, and the one being read is held twice (its bytes and its accumulation); then the
/// merged accumulation is made beside them (as large as a part). So the sum of the parts and the
/// largest once more, with the render's tenth of margin ([`RENDER_BYTES_PER_PIXEL`]), and the
/// process ([`PROCESS_BASE`]). The merged part (`--part`) is streamed, and the parts and then the
/// merged accumulation are dropped before the image is encoded, which so needs less. No threads:
/// the merge runs on the main thread alone. Measured as for [`RENDER_BYTES_PER_PIXEL`]: two parts of
/// 2000 x 2000 pixels (160 MB each) took 480.0 MB of address space and about as much memory, one
/// part 320.0 MB (with `--part` and `--linear`, PFM or OpenEXR).
pub fn merge_need(part_bytes: &[u64]) -> Need {
    let total = part_bytes.iter().fold(0u64, |t, &b| t.saturating_add(b));
    let largest = part_bytes.iter().copied().max().unwrap_or(0);
    let reading = total.saturating_add(largest);
    Need::all(reading.saturating_add(reading / 10)).plus(PROCESS_BASE)
}

/// The stack of a thread that Rust spawns (rayon's workers, the Ctrl-C handler's): 2 MiB, or what
/// `RUST_MIN_STACK` says.
pub fn thread_stack_bytes() -> u64 {
    stack_bytes_of(std::env::var("RUST_MIN_STACK").ok().as_deref())
}

fn stack_bytes_of(rust_min_stack: Option<&str>) -> u64 {
    rust_min_stack
        .and_then(|s| s.trim().parse().ok())
        .unwrap_or(2 << 20)
}

/// What a thread maps besides its stack: glibc's guard page below the stack (4 KiB) and Rust's
/// signal stack with its guard page (16 KiB); measured 2,117,632 bytes a thread with the stack's
/// 2 MiB (the `mmap` calls of `strace -f`); counted 64 KiB, for a larger signal stack on
/// processors with larger registers to save.
pub const THREAD_MAPPINGS: u64 = 64 << 10;

/// The address space of each malloc arena of glibc's (`HEAP_MAX_SIZE` on 64-bit: twice the
/// largest mmap threshold, 32 MiB), reserved whole (`PROT_NONE`, counted only by `ulimit -v`) the
/// first time a thread allocates, and made writable as the thread's heap grows.
pub const MALLOC_ARENA_BYTES: u64 = 64 << 20;

/// What a thread uses of its arena and stack: a few pages of its stack, its arena's header, what
/// it allocates (a worker holds no pixel: it adds into the accumulation's rows). Measured: `VmHWM`
/// grew by under 10 KiB a thread from 1 to 32 threads; counted 256 KiB.
pub const THREAD_RESIDENT: u64 = 256 << 10;

/// What of a thread's arena is writable, counted by `ulimit -d`: its first heap (the arena's header
/// and glibc's 128 KiB top pad) and what it grows by; counted 1 MiB.
pub const THREAD_ARENA_DATA: u64 = 1 << 20;

/// What `threads` threads besides the main one need: each its stack ([`thread_stack_bytes`]) and
/// other mappings ([`THREAD_MAPPINGS`]) of data and address space, what it uses
/// ([`THREAD_RESIDENT`]), and of address space a malloc arena ([`MALLOC_ARENA_BYTES`]) for each of
/// the first [`malloc_arenas`], with one more arena's worth while one is made: glibc maps twice an
/// arena's size to find an aligned one in it and unmaps the rest after (`strace -f`: a 128 MiB
/// `mmap`, then two `munmap` calls that leave 64 MiB), and one may be under way when the render
/// allocates its buffers.
///
/// Measured (release build, 2 cores, `VmPeak` less `VmSize` at the check, `rtl render cornell
/// --width 8 --spp 1 --threads N`): 196.0 MiB with one worker (two threads with the Ctrl-C
/// handler's; the model 196.1), 198.0 with two (the arena under way was the second's, before the
/// third was made; the model 262.2), 330.1 with four (394.3), 594.2 with eight (658.6), 994.3 with
/// sixteen (fifteen arenas, glibc's most on 2 cores besides the main thread's; 1,059.1), and 514.2
/// with 32, whose threads had shared arenas before the fifteenth was made (1,092.1).
pub fn threads_need(threads: usize) -> Need {
    let n = threads as u64;
    let mapped = n.saturating_mul(thread_stack_bytes().saturating_add(THREAD_MAPPINGS));
    let arenas = malloc_arenas(threads) as u64;
    let reserved = if arenas == 0 {
        0
    } else {
        (arenas + 1).saturating_mul(MALLOC_ARENA_BYTES)
    };
    Need {
        resident: n.saturating_mul(THREAD_RESIDENT),
        data: mapped.saturating_add(n.saturating_mul(THREAD_ARENA_DATA)),
        address_space: mapped.saturating_add(reserved),
    }
}

/// How many malloc arenas glibc makes for `threads` threads besides the main one (which has its
/// own): one for each, up to its limit less the main thread's ([`arena_limit`]). None where the C
/// library is not glibc.
pub fn malloc_arenas(threads: usize) -> usize {
    if !cfg!(all(target_os = "linux", target_env = "gnu")) {
        return 0;
    }
    let env = |name: &str| std::env::var(name).ok();
    let read = |path: &str| std::fs::read_to_string(path).ok();
    let processors = [
        read("/proc/self/status").and_then(|s| {
            s.lines()
                .find_map(|l| l.strip_prefix("Cpus_allowed_list:"))
                .and_then(cpu_list_len)
        }),
        read("/sys/devices/system/cpu/online").and_then(|s| cpu_list_len(&s)),
        std::thread::available_parallelism().ok().map(|n| n.get()),
    ]
    .into_iter()
    .flatten()
    .max()
    .unwrap_or(1);
    let limit = arena_limit(
        env("GLIBC_TUNABLES").as_deref(),
        env("MALLOC_ARENA_MAX").as_deref(),
        processors,
    );
    threads.min(limit.saturating_sub(1))
}

/// The most arenas glibc makes, the main thread's included: `arena_max` if set (the tunable
/// `glibc.malloc.arena_max` in `GLIBC_TUNABLES`, or `MALLOC_ARENA_MAX`), otherwise 8 a processor
/// (`processors`: the most of those the process may run on and those online, whichever glibc
/// counts) but at least 9 (glibc makes arenas without asking while it has at most `arena_test`,
/// 8, and only then counts the processors).
pub fn arena_limit(tunables: Option<&str>, arena_max: Option<&str>, processors: usize) -> usize {
    let number = |s: &str| -> Option<usize> {
        let s = s.trim();
        let n = match s.strip_prefix("0x").or_else(|| s.strip_prefix("0X")) {
            Some(hex) => usize::from_str_radix(hex, 16).ok(),
            None => s.parse().ok(),
        };
        n.filter(|&n| n > 0)
    };
    let tuned = tunables.and_then(|t| {
        t.split(':')
            .filter_map(|kv| kv.strip_prefix("glibc.malloc.arena_max="))
            .next_back()
            .and_then(number)
    });
    match tuned.or_else(|| arena_max.and_then(number)) {
        Some(max) => max,
        None => processors.saturating_mul(8).max(9),
    }
}

/// How many processors a list such as `0-3,8,10-11` names (`None` if it does not parse).
pub fn cpu_list_len(list: &str) -> Option<usize> {
    let mut n = 0usize;
    for part in list.trim().split(',').filter(|p| !p.is_empty()) {
        n += match part.split_once('-') {
            Some((a, b)) => {
                let (a, b): (usize, usize) = (a.trim().parse().ok()?, b.trim().parse().ok()?);
                b.checked_sub(a)? + 1
            }
            None => {
                part.trim().parse::<usize>().ok()?;
                1
            }
        };
    }
    (n > 0).then_some(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    const MIB: u64 = 1 << 20;

    fn limit(bytes: u64, limit: MemoryLimit) -> Available {
        Available { bytes, limit }
    }

    #[test]
    fn each_limit_is_compared_with_what_it_counts() {
        let need = Need {
            resident: 100,
            data: 200,
            address_space: 1000,
        };
        // the machine has 150 free: the render fits it, whatever it maps
        assert_eq!(need.exceeds(&[limit(150, MemoryLimit::Machine)]), None);
        assert_eq!(need.exceeds(&[limit(150, MemoryLimit::ControlGroup)]), None);
        // but not a data-size limit of 150, nor an address-space limit of 900
        let limits = [
            limit(150, MemoryLimit::Machine),
            limit(150, MemoryLimit::DataSize),
            limit(900, MemoryLimit::AddressSpace),
        ];
        assert_eq!(
            need.exceeds(&limits),
            Some(Shortfall {
                needed: 1000,
                available: limits[2]
            })
        );
        assert_eq!(
            need.exceeds(&limits[..2]),
            Some(Shortfall {
                needed: 200,
                available: limits[1]
            })
        );
        assert_eq!(need.exceeds(&[]), None);
    }

    #[test]
    fn threads_count_their_arenas_only_as_address_space() {
        let one = threads_need(1);
        let three = threads_need(3);
        let stack = thread_stack_bytes() + THREAD_MAPPINGS;
        assert_eq!(three.resident - one.resident, 2 * THREAD_RESIDENT);
        assert_eq!(three.data - one.data, 2 * (stack + THREAD_ARENA_DATA));
        if malloc_arenas(3) == 3 {
            assert_eq!(
                three.address_space - one.address_space,
                2 * (stack + MALLOC_ARENA_BYTES)
            );
            // one arena's worth more while one is made
            assert_eq!(one.address_space, stack + 2 * MALLOC_ARENA_BYTES);
        }
        assert!(three.resident < MIB && three.data < 10 * MIB);
        assert_eq!(threads_need(0), Need::default());
    }

    #[test]
    fn a_render_needs_its_buffers_its_threads_and_the_process() {
        let n = render_need(600 * 600, 3, 0);
        assert_eq!(
            n.resident,
            600 * 600 * RENDER_BYTES_PER_PIXEL + 3 * THREAD_RESIDENT + PROCESS_BASE.resident
        );
        assert!(n.address_space >= n.data && n.data >= n.resident);
        // a checkpoint of a larger image to resume counts twice its size
        let big = render_need(600 * 600, 3, 100 << 20);
        assert_eq!(big.resident - n.resident, (200 << 20) - 600 * 600 * 88);
    }

    #[test]
    fn a_merge_needs_its_parts_and_the_largest_again() {
        let part = 40 * 1000 + 300;
        assert_eq!(
            merge_need(&[part, part]),
            Need::all(3 * part + 3 * part / 10).plus(PROCESS_BASE)
        );
        // one part: as much as a render of its image (88 bytes a pixel), near enough
        assert_eq!(
            merge_need(&[40 * 1000]),
            Need::all(1000 * RENDER_BYTES_PER_PIXEL).plus(PROCESS_BASE)
        );
        assert_eq!(merge_need(&[]), PROCESS_BASE);
    }

    #[test]
    fn glibcs_arena_limit() {
        assert_eq!(arena_limit(None, None, 2), 16);
        assert_eq!(arena_limit(None, None, 1), 9);
        assert_eq!(arena_limit(None, None, 64), 512);
        assert_eq!(arena_limit(None, Some("2"), 64), 2);
        assert_eq!(arena_limit(None, Some("0"), 4), 32);
        assert_eq!(arena_limit(None, Some("junk"), 4), 32);
        assert_eq!(
            arena_limit(
                Some("glibc.malloc.check=1:glibc.malloc.arena_max=0x4"),
                Some("2"),
                64
            ),
            4
        );
        assert_eq!(arena_limit(Some("glibc.malloc.check=1"), Some("3"), 64), 3);
        assert_eq!(stack_bytes_of(None), 2 * MIB);
        assert_eq!(stack_bytes_of(Some("8388608")), 8 * MIB);
        assert_eq!(stack_bytes_of(Some("lots")), 2 * MIB);
    }

    #[test]
    fn cpu_lists() {
        assert_eq!(cpu_list_len("0-1\n"), Some(2));
        assert_eq!(cpu_list_len("0-3,8,10-11"), Some(7));
        assert_eq!(cpu_list_len("5"), Some(1));
        assert_eq!(cpu_list_len(""), None);
        assert_eq!(cpu_list_len("3-1"), None);
        assert_eq!(cpu_list_len("a-b"), None);
    }
}
