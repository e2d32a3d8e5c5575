//! The machine and the clock of `rtl bench`: which processor this is (model, generation, vector
//! extensions), how many cores, and how long a child program took in processor time (user + system,
//! all threads, from /proc), which the load of a shared machine disturbs far less than the wall
//! clock.

use anyhow::{Context, Result, bail};
use std::process::{Command, Stdio};
use std::time::Instant;

/// The processor, from /proc/cpuinfo: its model name, which on a VM is often generic ("Intel(R)
/// Xeon(R) Processor", "AMD EPYC"), with the vendor, family and model that tell its generation, and
/// the vector extensions that decide the intersection tier.
pub(super) fn cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| cpu_of(&s))
        .unwrap_or_else(|| "unknown (no /proc/cpuinfo)".into())
}

/// [`cpu_model`] for the text of a /proc/cpuinfo (its first processor's block).
fn cpu_of(cpuinfo: &str) -> Option<String> {
    let block = cpuinfo.split("\n\n").next()?;
    let field = |name: &str| {
        block.lines().find_map(|l| {
            let (k, v) = l.split_once(':')?;
            (k.trim() == name).then(|| v.trim().to_string())
        })
    };
    let model_name = field("model name")?;
    let mut out = model_name;
    if let (Some(vendor), Some(family), Some(model)) =
        (field("vendor_id"), field("cpu family"), field("model"))
    {
        out.push_str(&format!(", {vendor} family {family} model {model}"));
    }
    let flags = field("flags").unwrap_or_default();
    let has = |f: &str| flags.split_whitespace().any(|x| x == f);
    let vector = match (has("avx2"), has("avx512f") && has("avx512vl")) {
        (_, true) => "AVX2 + AVX-512",
        (true, false) => "AVX2, no AVX-512",
        (false, false) => "no AVX2",
    };
    out.push_str(&format!(", {vector}"));
    Some(out)
}

/// The logical cores this process may run on.
pub(super) fn num_cores() -> usize {
    std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1)
}

/// The processor time (user + system) of this process's waited-for children so far, in seconds:
/// fields `cutime` and `cstime` of /proc/self/stat, in the kernel's fixed 100 ticks a second.
fn children_cpu_seconds() -> Option<f64> {
    children_cpu_of(&std::fs::read_to_string("/proc/self/stat").ok()?)
}

/// `cutime + cstime` of a /proc/PID/stat line, in seconds.
fn children_cpu_of(stat: &str) -> Option<f64> {
    // The command name (field 2) is parenthesised and may hold spaces: count from its end.
    let rest = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    // Fields 16 and 17 of the whole line are 14 and 15 after the name (state is field 3).
    let ticks = fields.get(13)?.parse::<f64>().ok()? + fields.get(14)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

/// Seconds a render took: processor time (all threads, summed) where the system tells it, which a
/// shared machine's load disturbs far less than the wall clock, else wall-clock time.
#[derive(Clone, Copy, Debug)]
pub(super) struct Took {
    pub(super) wall: f64,
    pub(super) cpu: Option<f64>,
}

impl Took {
    pub(super) fn seconds(&self) -> f64 {
        self.cpu.filter(|c| *c > 0.0).unwrap_or(self.wall)
    }
}

/// Runs `cmd`, returning its stdout and how long it took; a failure names the command.
pub(super) fn timed(cmd: &mut Command, what: &str) -> Result<(Vec<u8>, Took)> {
    timed_with_stderr(cmd, what).map(|(out, _, took)| (out, took))
}

/// [`timed`], keeping what the program wrote to stderr too.
pub(super) fn timed_with_stderr(cmd: &mut Command, what: &str) -> Result<(Vec<u8>, String, Took)> {
    let cpu0 = children_cpu_seconds();
    let start = Instant::now();
    let out = cmd
        .stdin(Stdio::null())
        .output()
        .with_context(|| format!("{what}: could not start {cmd:?}"))?;
    let wall = start.elapsed().as_secs_f64();
    let cpu = cpu0.zip(children_cpu_seconds()).map(|(a, b)| b - a);
    let secs = Took { wall, cpu };
    if !out.status.success() {
        let stderr = String::from_utf8_lossy(&out.stderr);
        let lines: Vec<&str> = stderr.lines().collect();
        let tail = lines[lines.len().saturating_sub(20)..].join("\n");
        bail!("{what}: {cmd:?} failed ({}):\n{tail}", out.status);
    }
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    Ok((out.stdout, stderr, secs))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cpu_names_its_generation_and_vector_extensions() {
        let info = "processor\t: 0\nvendor_id\t: GenuineIntel\ncpu family\t: 6\nmodel\t\t: 207\n\
                    model name\t: Intel(R) Xeon(R) Processor\nflags\t\t: fpu avx avx2 avx512f avx512vl\n\n\
                    processor\t: 1\nmodel name\t: other\n";
        assert_eq!(
            cpu_of(info).as_deref(),
            Some("Intel(R) Xeon(R) Processor, GenuineIntel family 6 model 207, AVX2 + AVX-512")
        );
        let amd = "vendor_id\t: AuthenticAMD\ncpu family\t: 25\nmodel\t\t: 1\nmodel name\t: AMD EPYC\n\
                   flags\t\t: avx avx2 avx512f\n";
        assert_eq!(
            cpu_of(amd).as_deref(),
            Some("AMD EPYC, AuthenticAMD family 25 model 1, AVX2, no AVX-512")
        );
        assert_eq!(cpu_of("model name\t: X\n").as_deref(), Some("X, no AVX2"));
        assert_eq!(cpu_of("processor\t: 0\n"), None);
    }

    #[test]
    fn children_cpu_time_is_read_past_the_command_name() {
        // pid (comm) state ppid pgrp session tty tpgid flags minflt cminflt majflt cmajflt utime stime
        // cutime cstime ...
        let line = "42 (rtl (x) y) S 1 42 42 0 -1 4194304 10 20 0 0 7 3 250 50 20 0 1 0";
        assert_eq!(children_cpu_of(line), Some(3.0));
        assert_eq!(children_cpu_of("42 (rtl) S 1"), None);
        let now = children_cpu_seconds().expect("Linux has /proc/self/stat");
        assert!(now >= 0.0);
    }
}
