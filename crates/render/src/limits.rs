//! What the renderer accepts: one rule for each value, whether it comes from the command line or a
//! scene file, so that everything accepted renders and everything else is refused before any work.
//!
//! - **Numbers in a scene file** are finite and at most [`MAX_MAGNITUDE`] in size, and quantities that
//!   must be positive (radii, densities, scales, the index of refraction, the focus distance) are at
//!   least [`MIN_POSITIVE`]: then squares and triple products of lengths, which intersection and the
//!   solid-angle densities form, stay finite and nonzero.
//! - **Paths** have between 1 and [`MAX_DEPTH`] intersections.
//! - **Images** are at most [`MAX_SIDE`] pixels on a side, and what a render needs
//!   ([`RENDER_BYTES_PER_PIXEL`] per pixel, its threads' stacks and malloc arenas, and the process:
//!   [`render_need`]) must fit in what each memory limit leaves, each compared with what it counts
//!   ([`Need`]).
//! - **Threads** number at most [`MAX_THREADS`].
//! - **Scenes** hold at most [`MAX_EXPANDED_OBJECTS`] objects once their instances are expanded, and
//!   nest groups at most [`MAX_NESTING`] deep: a few kilobytes of instances of instances would
//!   otherwise stand for 2^40 shapes, which the walks over the scene (the emitters, the glass spheres)
//!   and every ray would visit one by one.
//! - **Files**: a scene file is a regular file of at most [`MAX_SCENE_FILE_BYTES`] whose reading takes
//!   at most [`MAX_SCENE_READ_BYTES`] ([`toml_read_bytes`]) and the memory available, a texture file
//!   one of at most [`MAX_TEXTURE_FILE_BYTES`] that decodes to at most [`MAX_TEXTURE_PIXELS`] pixels,
//!   read from its header before anything is decoded, within the memory available.
//! - **Memory available** is the least of the machine's (`MemAvailable`), what the process's own
//!   limits (`ulimit -v`, `ulimit -d`) leave it and what its control group's limit (a container's)
//!   leaves ([`available_memory`]).

use std::fmt;
use std::path::Path;

mod memory;
mod need;
pub use memory::{
    Available, MemoryLimit, available_memory, available_of, control_group_available, limits_of,
    mem_available, memory_limits,
};
pub use need::{
    MALLOC_ARENA_BYTES, Need, PROCESS_BASE, RENDER_BYTES_PER_PIXEL, Shortfall, THREAD_ARENA_DATA,
    THREAD_MAPPINGS, THREAD_RESIDENT, arena_limit, cpu_list_len, malloc_arenas, merge_need,
    render_need, thread_stack_bytes, threads_need,
};

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
/// inline table (`{a=1},` took 1434 bytes in all) and a dot between the parts of a key (each part a
/// table of its own: `k.a.a...=1` took about 1260 a dot), 400 a key (`k=1` 380) and an array
/// (`[1],` 492), 160 an element (`1,` 154). 200,000 spheres (20 MB) bound at 1.0 GB (they took
/// 650 MB). A dot counts only in a key (a table header, or before the `=` at the start of a line or
/// of an inline table's entry), not in a number or a string; other characters inside strings and
/// comments count too: the bound is only looser for them.
pub fn toml_read_bytes(text: &str) -> u64 {
    let b = text.as_bytes();
    let mut cost: u64 = 8 * b.len() as u64;
    // What encloses the current byte: `{` an inline table, `[` an array.
    let mut open: Vec<u8> = Vec::new();
    // Whether a dot here separates a key's parts: in a header, or before a key's `=`.
    let mut in_key = true;
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'"' | b'\'' => {
                // A string, skipped whole (a quoted key's dots are one key): basic strings have
                // escapes, literal ones none; three quotes open a multi-line one.
                let q = b[i];
                let triple = b[i..].starts_with(&[q, q, q]);
                i += if triple { 3 } else { 1 };
                while i < b.len() {
                    if q == b'"' && b[i] == b'\\' {
                        i += 2;
                        continue;
                    }
                    if b[i] == q && (!triple || b[i..].starts_with(&[q, q, q])) {
                        i += if triple { 3 } else { 1 };
                        break;
                    }
                    if !triple && b[i] == b'\n' {
                        break;
                    }
                    i += 1;
                }
                continue;
            }
            b'#' => {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
                continue;
            }
            b'\n' => in_key = open.is_empty() || open.last() == Some(&b'{'),
            b'=' => {
                cost += 400;
                in_key = false;
            }
            b'{' => {
                cost += 1300;
                open.push(b'{');
                in_key = true;
            }
            b'[' => {
                cost += 400;
                if in_key && open.is_empty() {
                    // a table header: a key up to its `]`
                } else {
                    open.push(b'[');
                    in_key = false;
                }
            }
            b'}' | b']' => {
                if b[i] == b']' && open.last() != Some(&b'[') {
                    // the end of a header
                    in_key = false;
                } else {
                    open.pop();
                    in_key = false;
                }
            }
            b',' => {
                cost += 160;
                in_key = open.last() == Some(&b'{');
            }
            b'.' if in_key => cost += 1300,
            _ => {}
        }
        i += 1;
    }
    cost
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

/// Why an image cannot be rendered at this size.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SizeError {
    #[error("the image would be {width}x{height} pixels: each side may be at most {MAX_SIDE}")]
    TooLarge { width: usize, height: usize },
    #[error(
        "the image would be {width}x{height} pixels, which needs {} of {} ({RENDER_BYTES_PER_PIXEL} \
         bytes a pixel, and {} for the process and its {threads} threads besides the main one{}), but \
         {available}",
        Bytes(*needed),
        available.limit.counts(),
        Bytes(needed.saturating_sub(*buffers)),
        match available.limit {
            MemoryLimit::AddressSpace => {
                ": their stacks and malloc arenas; fewer threads, or MALLOC_ARENA_MAX=1, map less"
            }
            MemoryLimit::DataSize => ": their stacks",
            _ => "",
        }
    )]
    OutOfMemory {
        width: usize,
        height: usize,
        /// Threads besides the main one.
        threads: usize,
        /// What the render needs of what `available` counts ([`Need::of`]).
        needed: u64,
        /// Of which its buffers.
        buffers: u64,
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

/// Check that a `width x height` render fits: each side at most [`MAX_SIDE`], and what it needs
/// with `threads` threads besides the main one (its workers and any other, [`render_need`]) and a
/// checkpoint of `resume_bytes` to read (0 if none) within every limit of `limits`
/// ([`memory_limits`]: none if nothing says). Returns what it needs.
pub fn check_image(
    width: usize,
    height: usize,
    threads: usize,
    resume_bytes: u64,
    limits: &[Available],
) -> Result<Need, SizeError> {
    if width > MAX_SIDE || height > MAX_SIDE {
        return Err(SizeError::TooLarge { width, height });
    }
    // Both sides are at most 2^16, so this cannot overflow.
    let pixels = width as u64 * height as u64;
    let need = render_need(pixels, threads, resume_bytes);
    match need.exceeds(limits) {
        Some(Shortfall { needed, available }) => Err(SizeError::OutOfMemory {
            width,
            height,
            threads,
            needed,
            buffers: render_need(pixels, 0, resume_bytes).of(available.limit)
                - PROCESS_BASE.of(available.limit),
            available,
        }),
        None => Ok(need),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_dot_costs_a_table_in_a_key_and_nothing_in_a_number_a_string_or_a_comment() {
        let same =
            |a: &str, b: &str| assert_eq!(toml_read_bytes(a), toml_read_bytes(b), "{a} / {b}");
        let dearer = |a: &str, b: &str| {
            assert_eq!(toml_read_bytes(a), toml_read_bytes(b) + 1300, "{a} / {b}")
        };
        dearer("x.y = 1\n", "x_y = 1\n");
        dearer("[a.b]\nk = 1\n", "[a_b]\nk = 1\n");
        dearer("[[a.b]]\n", "[[a_b]]\n");
        dearer("t = {x.y = 1}\n", "t = {x_y = 1}\n");
        dearer("t = [{p = 0, x.y = 1}]\n", "t = [{p = 0, x_y = 1}]\n");
        same("a = [1.5, 2.5]\nb = 0.73\n", "a = [1_5, 2_5]\nb = 0_73\n");
        same("\"x.y\" = 'a.b'\n", "\"x_y\" = 'a_b'\n");
        same(
            "k = \"\"\"one.\ntwo.\"\"\"\nm.n = 1\n",
            "k = \"\"\"one_\ntwo_\"\"\"\nm.n = 1\n",
        );
        same("k = 1 # a.b\n", "k = 1 # a_b\n");
        same("a = [\n  1.5,\n  2.5,\n]\n", "a = [\n  1_5,\n  2_5,\n]\n");
    }

    #[test]
    fn images_past_a_side_or_the_memory_are_refused() {
        let gib = [Available {
            bytes: 1 << 30,
            limit: MemoryLimit::Machine,
        }];
        assert!(check_image(600, 600, 2, 0, &gib).is_ok());
        assert_eq!(
            check_image(MAX_SIDE + 1, 1, 2, 0, &[]),
            Err(SizeError::TooLarge {
                width: MAX_SIDE + 1,
                height: 1
            })
        );
        let e = check_image(10_000, 10_000, 2, 0, &gib).unwrap_err();
        let text = e.to_string();
        for words in [
            "8.8 GB of memory",
            "88 bytes a pixel",
            "1.1 GB",
            "MemAvailable",
        ] {
            assert!(text.contains(words), "{words}: {e}");
        }
    }

    #[test]
    fn under_ulimit_v_the_threads_arenas_count_and_the_message_says_so() {
        // 600 x 600 pixels (31.7 MB) on two workers and the Ctrl-C handler's thread: within 100 MB of
        // memory, but their malloc arenas (64 MiB each, as address space) are not within 250 MB of
        // address space.
        let limits = [
            Available {
                bytes: 100_000_000,
                limit: MemoryLimit::Machine,
            },
            Available {
                bytes: 250_000_000,
                limit: MemoryLimit::AddressSpace,
            },
        ];
        let r = check_image(600, 600, 3, 0, &limits);
        if malloc_arenas(3) < 3 {
            return; // not glibc, or MALLOC_ARENA_MAX set: no arenas to count
        }
        let e = r.unwrap_err();
        let text = e.to_string();
        for words in [
            "600x600",
            "of address space",
            "3 threads besides the main one: their stacks and malloc arenas",
            "ulimit -v",
        ] {
            assert!(text.contains(words), "{words}: {e}");
        }
        // the machine's memory alone: it fits
        assert!(check_image(600, 600, 3, 0, &limits[..1]).is_ok());
    }
}
