//! The record of the call in progress, which a panic report names: the function, its arguments
//! (lists summarised when long) and, for a generator, what it drew.

use glam::DVec3;
use std::cell::Cell;
use std::fmt;
use std::sync::Mutex;

use super::format::{count, num};
use super::rng::RngState;

/// A list handed to the learner's code, summarised for a panic report: its length, its first
/// values, and where its values that are not finite (NaN, infinite) lie.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct List {
    len: usize,
    head: [Item; LIST_HEAD],
    n_bad: usize,
    bad_at: [usize; LIST_BAD],
}

/// A value of a [`List`].
#[derive(Clone, Copy, Debug, PartialEq)]
enum Item {
    Real(f64),
    Vector(DVec3),
}

impl Item {
    fn is_finite(self) -> bool {
        match self {
            Item::Real(x) => x.is_finite(),
            Item::Vector(v) => v.is_finite(),
        }
    }
}

impl fmt::Display for Item {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Item::Real(x) => f.write_str(&num(*x)),
            Item::Vector(v) => write!(f, "{}", Arg::Vector(*v)),
        }
    }
}

/// How many reals of a [`List`] are shown (vectors: 3); a list of at most this many is shown whole.
const LIST_HEAD: usize = 6;
/// How many places of values that are not finite a [`List`] names.
const LIST_BAD: usize = 3;

impl List {
    fn of(items: impl ExactSizeIterator<Item = Item>) -> Self {
        let mut list = Self {
            len: items.len(),
            head: [Item::Real(0.0); LIST_HEAD],
            n_bad: 0,
            bad_at: [0; LIST_BAD],
        };
        for (i, item) in items.enumerate() {
            if i < LIST_HEAD {
                list.head[i] = item;
            }
            if !item.is_finite() {
                if list.n_bad < LIST_BAD {
                    list.bad_at[list.n_bad] = i;
                }
                list.n_bad += 1;
            }
        }
        list
    }

    /// A list of reals.
    pub fn reals(values: &[f64]) -> Self {
        Self::of(values.iter().map(|&x| Item::Real(x)))
    }

    /// A list of vectors.
    pub fn vectors(values: &[DVec3]) -> Self {
        Self::of(values.iter().map(|&v| Item::Vector(v)))
    }
}

impl fmt::Display for List {
    /// `[1, NaN]` whole; longer, `[0.25, 0.5, ...] (10,000 values; not finite at 17, 5,000, 9,999)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // Vectors are long: three of them.
        let head = match self.head[0] {
            Item::Vector(_) => 3,
            Item::Real(_) => LIST_HEAD,
        };
        let shown: Vec<String> = self.head[..self.len.min(head)]
            .iter()
            .map(Item::to_string)
            .collect();
        if self.len <= head {
            return write!(f, "[{}]", shown.join(", "));
        }
        write!(
            f,
            "[{}, ...] ({} values",
            shown.join(", "),
            count(self.len as u64)
        )?;
        if self.n_bad > 0 {
            let at: Vec<String> = self.bad_at[..self.n_bad.min(LIST_BAD)]
                .iter()
                .map(|&i| count(i as u64))
                .collect();
            let more = if self.n_bad > LIST_BAD {
                format!(" and {} more", count((self.n_bad - LIST_BAD) as u64))
            } else {
                String::new()
            };
            write!(f, "; not finite at {}{more}", at.join(", "))?;
        }
        f.write_str(")")
    }
}

/// An argument of a call to the learner's code, kept so that a panic report can name it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Arg {
    Real(f64),
    Vector(DVec3),
    Count(usize),
    /// A slice, summarised.
    List(List),
    /// A random-number source ([`Generator::arg`](super::Generator::arg)).
    Rng(RngState),
    /// A value the check states as code, such as a function: `|x| x * x`.
    Text(&'static str),
}

impl fmt::Display for Arg {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Arg::Real(x) => f.write_str(&num(*x)),
            Arg::Vector(v) => write!(f, "[{}, {}, {}]", num(v.x), num(v.y), num(v.z)),
            Arg::Count(n) => write!(f, "{n}"),
            Arg::List(list) => write!(f, "{list}"),
            Arg::Rng(rng) => write!(f, "{rng}"),
            Arg::Text(text) => f.write_str(text),
        }
    }
}

impl From<f64> for Arg {
    fn from(x: f64) -> Self {
        Arg::Real(x)
    }
}

impl From<DVec3> for Arg {
    fn from(v: DVec3) -> Self {
        Arg::Vector(v)
    }
}

impl From<usize> for Arg {
    fn from(n: usize) -> Self {
        Arg::Count(n)
    }
}

impl From<&[f64]> for Arg {
    fn from(values: &[f64]) -> Self {
        Arg::List(List::reals(values))
    }
}

impl From<&[DVec3]> for Arg {
    fn from(values: &[DVec3]) -> Self {
        Arg::List(List::vectors(values))
    }
}

/// The most arguments a recorded call keeps.
const MAX_ARGS: usize = 5;

/// A call to the learner's code in progress: the function's name, its named arguments, and for a
/// method, the state of the value it is called on.
#[derive(Clone, Copy)]
struct Call {
    function: &'static str,
    args: [(&'static str, Arg); MAX_ARGS],
    n_args: usize,
    state: Option<(&'static str, Arg)>,
}

/// The 64-bit values a [`Generator`] handed out since the call in progress began: how many, and the
/// last [`DRAWS_KEPT`] of them (a ring).
#[derive(Clone, Copy, Default)]
struct Draws {
    count: u64,
    last: [u64; DRAWS_KEPT],
}

const DRAWS_KEPT: usize = 4;

impl Draws {
    /// "which drew u = 0.25, 0.5", as `rng.random::<f64>()` reads the values.
    fn describe(&self) -> String {
        let kept = self.count.min(DRAWS_KEPT as u64) as usize;
        let u: Vec<String> = (self.count as usize - kept..self.count as usize)
            .map(|i| num((self.last[i % DRAWS_KEPT] >> 11) as f64 / (1u64 << 53) as f64))
            .collect();
        match self.count {
            0 => "which drew nothing from rng".to_string(),
            n if n as usize <= DRAWS_KEPT => format!("which drew u = {}", u.join(", ")),
            n => format!(
                "which drew {} uniforms, the last u = {}",
                count(n),
                u.join(", ")
            ),
        }
    }
}

thread_local! {
    static CALL: Cell<Option<Call>> = const { Cell::new(None) };
    static DRAWS: Cell<Draws> = const { Cell::new(Draws { count: 0, last: [0; DRAWS_KEPT] }) };
    /// Whether this thread's calls are copied to [`PUBLISHED`] ([`publish_calls`]).
    static PUBLISHING: Cell<bool> = const { Cell::new(false) };
}

/// The call in progress on the thread that [`publish_calls`] chose, readable from another thread.
static PUBLISHED: Mutex<Option<Call>> = Mutex::new(None);

/// Held by the tests that publish calls, which would otherwise read each other's.
#[cfg(test)]
pub(crate) static PUBLISHING_TEST: Mutex<()> = Mutex::new(());

/// Makes the calls recorded on this thread readable from other threads ([`published_call`]): the
/// harness does so on the thread that runs the checks, so that the runner can name the call in
/// progress when the checks run out of time. Costs a lock per recorded call.
pub fn publish_calls(on: bool) {
    PUBLISHING.with(|p| p.set(on));
    publish(None);
}

fn publish(call: Option<Call>) {
    if PUBLISHING.with(Cell::get) {
        *PUBLISHED.lock().unwrap_or_else(|e| e.into_inner()) = call;
    }
}

/// The call in progress on the thread that publishes its calls ([`publish_calls`]), as text
/// without what it drew: "estimate_pi(n = 100000, rng = rtl_exercises::check::seeded(2))".
pub fn published_call() -> Option<String> {
    let call = (*PUBLISHED.lock().unwrap_or_else(|e| e.into_inner()))?;
    Some(call.describe())
}

/// Notes a 64-bit draw of a [`Generator`] for the report of the call in progress.
pub(super) fn note_draw(x: u64) {
    DRAWS.with(|d| {
        let mut draws = d.get();
        draws.last[(draws.count % DRAWS_KEPT as u64) as usize] = x;
        draws.count += 1;
        d.set(draws);
    });
}

/// Calls `f`, which calls the learner's `function` with `args` (name, value), and records the call
/// while it runs, so that a panic inside it is reported with the input that caused it
/// ("while calling sample_linear(u = 0.5)"; see [`call_in_progress`]). An argument of
/// [`Generator::arg`] is reported as the expression that rebuilds the generator, with the uniforms
/// the call drew from it. Costs a few stores of a thread-local: cheap enough for every sample of a
/// chi-square test.
///
/// [`Generator::arg`]: super::Generator::arg
pub fn calling<T>(
    function: &'static str,
    args: &[(&'static str, Arg)],
    f: impl FnOnce() -> T,
) -> T {
    record(Call::new(function, args, None), f)
}

/// [`calling`] for a method of a value that the report describes by how it came to be, `state`
/// (words, then a value): `add(sample = [NaN, 0, 0]) on PixelAccumulator::new() after adding
/// [0.5, 0.5]` is `calling_method("add", &[("sample", ...)], ("on PixelAccumulator::new() after
/// adding", list), f)`.
pub fn calling_method<T>(
    function: &'static str,
    args: &[(&'static str, Arg)],
    state: (&'static str, Arg),
    f: impl FnOnce() -> T,
) -> T {
    record(Call::new(function, args, Some(state)), f)
}

impl Call {
    fn new(
        function: &'static str,
        args: &[(&'static str, Arg)],
        state: Option<(&'static str, Arg)>,
    ) -> Self {
        let mut call = Call {
            function,
            args: [("", Arg::Count(0)); MAX_ARGS],
            n_args: args.len().min(MAX_ARGS),
            state,
        };
        call.args[..call.n_args].copy_from_slice(&args[..call.n_args]);
        call
    }
}

/// Runs `f` with `call` recorded (and a fresh record of draws), then restores the record of the
/// call around it, if any.
fn record<T>(call: Call, f: impl FnOnce() -> T) -> T {
    let outer = CALL.with(|c| c.replace(Some(call)));
    let outer_draws = DRAWS.with(|d| d.replace(Draws::default()));
    publish(Some(call));
    let out = f();
    CALL.with(|c| c.set(outer));
    DRAWS.with(|d| d.set(outer_draws));
    publish(outer);
    out
}

impl Call {
    /// "f(u = 0.5, w = [0, 0, 1])", with the state of the value of a method.
    fn describe(&self) -> String {
        let shown: Vec<String> = self.args[..self.n_args]
            .iter()
            .map(|(name, value)| format!("{name} = {value}"))
            .collect();
        let mut text = format!("{}({})", self.function, shown.join(", "));
        if let Some((words, value)) = self.state {
            text += &format!(" {words} {value}");
        }
        text
    }
}

/// The recorded call in progress on this thread, as text ("sample_linear(u = 0.5)"), if any; with
/// a generator among its arguments, what the call drew from it
/// ("generate(rng = rtl_exercises::check::seeded(7)), which drew u = 0.5").
pub fn call_in_progress() -> Option<String> {
    let call = CALL.with(Cell::get)?;
    let mut text = call.describe();
    if call.args[..call.n_args]
        .iter()
        .any(|(_, a)| matches!(a, Arg::Rng(_)))
    {
        text += ", ";
        text += &DRAWS.with(Cell::get).describe();
        text += ",";
    }
    Some(text)
}

/// Forgets the recorded call (a panic skips the end of [`calling`]).
pub fn forget_call() {
    CALL.with(|c| c.set(None));
    DRAWS.with(|d| d.set(Draws::default()));
    publish(None);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::*;
    use rand::RngCore;

    #[test]
    fn a_recorded_call_is_named_while_it_runs_and_forgotten_after() {
        let inside = calling(
            "f",
            &[("u", 0.5.into()), ("w", DVec3::Z.into())],
            call_in_progress,
        );
        assert_eq!(inside.as_deref(), Some("f(u = 0.5, w = [0, 0, 1])"));
        assert_eq!(call_in_progress(), None);
    }

    #[test]
    fn a_recorded_call_with_a_generator_says_what_it_drew() {
        let mut g = Generator::scripted(&[0.5, 0.25], 1);
        let args = [("rng", g.arg())];
        let drew_two = calling("f", &args, || {
            g.next_u64();
            g.next_u64();
            call_in_progress()
        });
        assert_eq!(
            drew_two.as_deref(),
            Some(
                "f(rng = rtl_exercises::check::ScriptedRng::new(&[0.5, 0.25], 1)), which drew \
                 u = 0.5, 0.25,"
            )
        );
        // Many draws: how many, and the last four. Draws before the call are not counted.
        let mut g = Generator::scripted(&[0.5, 0.25, 0.125, 0.0625], 1);
        g.next_u64();
        let args = [("n", Arg::Count(3)), ("rng", g.arg())];
        let text = calling("g", &args, || {
            let nothing = call_in_progress().unwrap();
            for _ in 0..5 {
                g.next_u64();
            }
            (nothing, call_in_progress().unwrap())
        });
        assert_eq!(
            text.0,
            "g(n = 3, rng = rtl_exercises::check::ScriptedRng::new(&[0.25, 0.125, 0.0625], 1)), \
             which drew nothing from rng,"
        );
        let mut rest = seeded(1);
        rest.next_u64();
        let u = num((rest.next_u64() >> 11) as f64 / (1u64 << 53) as f64);
        assert!(
            text.1.ends_with(&format!(
                "which drew 5 uniforms, the last u = 0.125, 0.0625, {}, {u},",
                num((seeded(1).next_u64() >> 11) as f64 / (1u64 << 53) as f64)
            )),
            "{}",
            text.1
        );
    }

    #[test]
    fn lists_are_shown_whole_when_short_and_summarised_when_long() {
        let nan = f64::NAN;
        assert_eq!(Arg::from(&[1.0, nan][..]).to_string(), "[1, NaN]");
        assert_eq!(Arg::from(&[][..] as &[f64]).to_string(), "[]");
        let mut long = vec![0.5; 1000];
        for i in [3, 17, 500, 999] {
            long[i] = f64::INFINITY;
        }
        assert_eq!(
            Arg::from(long.as_slice()).to_string(),
            "[0.5, 0.5, 0.5, inf, 0.5, 0.5, ...] (1,000 values; not finite at 3, 17, 500 and 1 more)"
        );
        let v = [DVec3::ONE, DVec3::NAN, DVec3::ZERO, DVec3::ONE];
        assert_eq!(
            Arg::from(&v[..]).to_string(),
            "[[1, 1, 1], [NaN, NaN, NaN], [0, 0, 0], ...] (4 values; not finite at 1)"
        );
    }

    #[test]
    fn a_published_call_is_readable_from_another_thread_while_it_runs() {
        let _one_at_a_time = PUBLISHING_TEST.lock().unwrap_or_else(|e| e.into_inner());
        let (inside, go_on) = (std::sync::Barrier::new(2), std::sync::Barrier::new(2));
        std::thread::scope(|s| {
            s.spawn(|| {
                publish_calls(true);
                calling("f", &[("u", 0.5.into())], || {
                    calling("g", &[], || {});
                    inside.wait();
                    go_on.wait();
                });
                inside.wait();
                publish_calls(false);
            });
            inside.wait();
            // The inner call has ended: the outer one is in progress again.
            assert_eq!(published_call().as_deref(), Some("f(u = 0.5)"));
            go_on.wait();
            inside.wait();
            assert_eq!(published_call(), None);
        });
        // A thread that does not publish leaves nothing to read.
        calling("h", &[], || assert_eq!(published_call(), None));
    }

    #[test]
    fn a_method_call_is_named_with_the_state_of_its_value() {
        let state = ("on X::new() after adding", Arg::from(&[0.5][..]));
        let text = calling_method("add", &[("x", Arg::Real(2.0))], state, call_in_progress);
        assert_eq!(
            text.as_deref(),
            Some("add(x = 2) on X::new() after adding [0.5]")
        );
        // A call inside another restores the outer record when it ends.
        let outer = calling("outer", &[], || {
            calling("inner", &[], || {});
            call_in_progress()
        });
        assert_eq!(outer.as_deref(), Some("outer()"));
    }
}
