//! The one typed layer for the numbers the command line takes: every count, size, frame and
//! run number has a range whose top comes from memory or from time, every real number a range
//! of its own, and both are checked by the option's value parser, before any work. A refusal
//! names the option, the value as typed and the range, with why the range is what it is:
//!
//! `--size -5: not a size in pixels: it is negative; give a whole number from 8 to 4096 (...)`
//!
//! [`prepare`] lets every numeric option take a value that starts with `-` (clap would
//! otherwise read `-5` as an unknown flag and suggest `-- -5`, which turns it into a positional
//! argument), so that a negative value reaches its option's own check, and writes each range
//! into its option's help (`[range: from 1 to 1000 (why)]`), from the parser that checks it,
//! so the two cannot differ. [`kind_of`] says what an option takes, from the type its parser
//! gives; the tests walk every option with it.

use clap::builder::{PossibleValue, TypedValueParser};
use std::any::TypeId;
use std::ffi::OsStr;
use std::marker::PhantomData;

/// The memory a command may plan to use: half of what the system reports available (the
/// software renderer and the rest of the machine keep the other half), or 2 GiB where that
/// cannot be read.
pub fn memory_budget() -> u64 {
    available_memory().unwrap_or(4 << 30) / 2
}

/// `MemAvailable` of /proc/meminfo, in bytes.
fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// The most units of `bytes_each` that fit the memory budget.
pub fn fit_in_memory(bytes_each: u64) -> u64 {
    units_in(memory_budget(), bytes_each)
}

/// How many units of `bytes_each` fit in `budget` (a zero-sized unit counts as one byte).
fn units_in(budget: u64, bytes_each: u64) -> u64 {
    budget / bytes_each.max(1)
}

/// A byte count for messages: `1.5 GiB`.
pub fn gib(bytes: u64) -> String {
    format!("{:.1} GiB", bytes as f64 / (1u64 << 30) as f64)
}

/// Where the top of a count's range comes from.
#[derive(Clone, Copy, Debug)]
pub enum Most {
    /// A fixed top, and why (time: "a run of every timed measurement; 1000 take hours").
    Fixed(u64, &'static str),
    /// What fits in [`memory_budget`] at `bytes_each` a unit (`unit` names it in the
    /// message), and never more than `cap`, a limit of its own that `cap_why` explains (time,
    /// or the renderer's limits).
    Memory {
        bytes_each: u64,
        unit: &'static str,
        cap: u64,
        cap_why: &'static str,
    },
}

/// A whole number an option takes: what it counts (for messages) and its range.
#[derive(Clone, Copy, Debug)]
pub struct Count {
    /// "a number of frames", "a size": what the value is, for "is not NOUN".
    pub noun: &'static str,
    pub least: u64,
    pub most: Most,
}

impl Count {
    /// `least` to `most`, the top explained by `why`.
    pub const fn new(noun: &'static str, least: u64, most: u64, why: &'static str) -> Count {
        Count {
            noun,
            least,
            most: Most::Fixed(most, why),
        }
    }

    /// `least` to what fits in memory at `bytes_each` per `unit`.
    pub const fn in_memory(
        noun: &'static str,
        least: u64,
        bytes_each: u64,
        unit: &'static str,
    ) -> Count {
        Count {
            noun,
            least,
            most: Most::Memory {
                bytes_each,
                unit,
                cap: u64::MAX,
                cap_why: "",
            },
        }
    }

    /// The same range, never above `cap` (`why` says where that comes from).
    pub const fn at_most(self, cap: u64, why: &'static str) -> Count {
        let most = match self.most {
            Most::Memory {
                bytes_each, unit, ..
            } => Most::Memory {
                bytes_each,
                unit,
                cap,
                cap_why: why,
            },
            Most::Fixed(..) => Most::Fixed(cap, why),
        };
        Count { most, ..self }
    }

    /// The top of the range on this machine, now.
    pub fn most(&self) -> u64 {
        match self.most {
            Most::Fixed(most, _) => most,
            Most::Memory {
                bytes_each, cap, ..
            } => fit_in_memory(bytes_each).min(cap).max(self.least),
        }
    }

    /// "from 1 to 10000 (why)".
    pub fn range(&self) -> String {
        let why = match self.most {
            Most::Fixed(_, why) => why.to_string(),
            Most::Memory {
                bytes_each,
                unit,
                cap,
                cap_why,
            } => {
                let fits = fit_in_memory(bytes_each);
                if fits >= cap {
                    cap_why.to_string()
                } else {
                    format!(
                        "what half of this machine's available memory, {}, holds at about \
                         {bytes_each} bytes a {unit}",
                        gib(memory_budget())
                    )
                }
            }
        };
        format!("from {} to {} ({why})", self.least, self.most())
    }

    /// The value of `text` for `option`, or a message naming both and the range.
    pub fn parse(&self, option: &str, text: &str) -> Result<u64, String> {
        self.check(text).map_err(|problem| {
            format!(
                "{option} {}: not {}: {problem}; give a whole number {}",
                shown(text),
                self.noun,
                self.range()
            )
        })
    }

    /// The value of `text`, or what is wrong with it ("it is negative").
    fn check(&self, text: &str) -> Result<u64, String> {
        match whole_number(text) {
            Ok(n) if n < self.least as f64 => Err(format!("it is below {}", self.least)),
            Ok(n) if n > self.most() as f64 => Err(format!("it is above {}", self.most())),
            Ok(n) => Ok(n as u64),
            Err(problem) => Err(problem),
        }
    }

    /// The value parser of an option of type `T` (usize, u32, u64).
    pub const fn of<T>(self) -> CountParser<T> {
        CountParser {
            count: self,
            _type: PhantomData,
        }
    }
}

/// `text` as a whole number (also written 1e6), or what is wrong with it. Returned as f64 so
/// that 1e30 compares above any top instead of failing to parse.
fn whole_number(text: &str) -> Result<f64, String> {
    let t = text.trim();
    if t.is_empty() {
        return Err("it is empty".into());
    }
    if let Ok(n) = t.parse::<u64>() {
        return Ok(n as f64);
    }
    match t.parse::<f64>() {
        Ok(v) if v.is_nan() => Err("it is not a number".into()),
        Ok(v) if v < 0.0 || t.starts_with('-') => Err("it is negative".into()),
        Ok(v) if v.is_infinite() => Ok(f64::INFINITY),
        Ok(v) if v.fract() != 0.0 => Err("it is not a whole number".into()),
        Ok(v) => Ok(v),
        Err(_) if t.starts_with("--") => {
            Err("it is an option, not a value: give this option its value first".into())
        }
        Err(_) => Err("it is not a number".into()),
    }
}

/// A value as the user typed it, quoted when it has spaces or is empty.
fn shown(text: &str) -> String {
    if text.is_empty() || text.contains(char::is_whitespace) {
        format!("'{text}'")
    } else {
        text.to_string()
    }
}

/// A real number an option takes: what it is and its range (both ends included).
#[derive(Clone, Copy, Debug)]
pub struct Real {
    pub noun: &'static str,
    pub least: f64,
    pub most: f64,
    /// Why the range is what it is ("the method's range: ...").
    pub why: &'static str,
}

impl Real {
    pub const fn new(noun: &'static str, least: f64, most: f64, why: &'static str) -> Real {
        Real {
            noun,
            least,
            most,
            why,
        }
    }

    /// "from 0 to 1 (why)".
    pub fn range(&self) -> String {
        format!(
            "from {} to {} ({})",
            number(self.least),
            number(self.most),
            self.why
        )
    }

    /// The value of `text` for `option`, or a message naming both and the range.
    pub fn parse(&self, option: &str, text: &str) -> Result<f64, String> {
        let problem = match text.trim().parse::<f64>() {
            Ok(v) if v.is_nan() => "it is not a number".to_string(),
            Ok(v) if v.is_infinite() => "it is not finite".to_string(),
            Ok(v) if v < self.least => format!("it is below {}", number(self.least)),
            Ok(v) if v > self.most => format!("it is above {}", number(self.most)),
            Ok(v) => return Ok(v),
            Err(_) if text.trim().is_empty() => "it is empty".to_string(),
            Err(_) if text.starts_with("--") => {
                "it is an option, not a value: give this option its value first".to_string()
            }
            Err(_) => "it is not a number".to_string(),
        };
        Err(format!(
            "{option} {}: not {}: {problem}; give a number {}",
            shown(text),
            self.noun,
            self.range()
        ))
    }

    /// The value parser of an option of type `T` (f32, f64).
    pub const fn of<T>(self) -> RealParser<T> {
        RealParser {
            real: self,
            _type: PhantomData,
        }
    }
}

/// The smallest number above 0 (a subnormal): the least of a range that is "positive".
pub const SMALLEST: f64 = 5e-324;

/// A number for messages: 0.25, 100, 1e-9, 1e6 (never 300 digits), and the ends of fp64 in
/// words.
pub fn number(v: f64) -> String {
    if v == f64::MAX {
        return "the largest finite number".into();
    }
    if v == -f64::MAX {
        return "minus the largest finite number".into();
    }
    if v == SMALLEST {
        return "the smallest number above 0".into();
    }
    if v != 0.0 && (v.abs() < 1e-3 || v.abs() >= 1e6) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// The name an option is given by in messages: `--size`, or `<ID>` for a positional one.
pub fn option_name(arg: Option<&clap::Arg>) -> String {
    match arg {
        Some(a) => match a.get_long() {
            Some(long) => format!("--{long}"),
            None => format!("<{}>", a.get_id().as_str().to_uppercase()),
        },
        None => "the value".into(),
    }
}

/// A refusal as clap shows its own (exit status 2, "For more information, try '--help'").
fn refusal(cmd: &clap::Command, message: String) -> clap::Error {
    clap::Error::raw(clap::error::ErrorKind::ValueValidation, message).format(&mut cmd.clone())
}

/// The text of an option's value, or a refusal naming the option when it is not UTF-8.
fn text_of<'a>(
    cmd: &clap::Command,
    arg: Option<&clap::Arg>,
    value: &'a OsStr,
) -> Result<&'a str, clap::Error> {
    value.to_str().ok_or_else(|| {
        refusal(
            cmd,
            format!(
                "{} {}: not text (not UTF-8)",
                option_name(arg),
                value.to_string_lossy()
            ),
        )
    })
}

/// [`Count`]'s value parser for an option of type `T`.
#[derive(Clone, Copy, Debug)]
pub struct CountParser<T> {
    count: Count,
    _type: PhantomData<fn() -> T>,
}

impl<T> TypedValueParser for CountParser<T>
where
    T: TryFrom<u64> + Clone + Send + Sync + 'static,
{
    type Value = T;

    fn parse_ref(
        &self,
        cmd: &clap::Command,
        arg: Option<&clap::Arg>,
        value: &OsStr,
    ) -> Result<T, clap::Error> {
        let option = option_name(arg);
        let text = text_of(cmd, arg, value)?;
        let n = self
            .count
            .parse(&option, text)
            .map_err(|m| refusal(cmd, m))?;
        T::try_from(n).map_err(|_| {
            refusal(
                cmd,
                format!("{option} {text}: does not fit this option's type; give a smaller number"),
            )
        })
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        carry_range(self.count.range())
    }
}

/// [`Real`]'s value parser for an option of type `T`.
#[derive(Clone, Copy, Debug)]
pub struct RealParser<T> {
    real: Real,
    _type: PhantomData<fn() -> T>,
}

/// The float types an option may have.
pub trait FromF64: Clone + Send + Sync + 'static {
    fn from_f64(v: f64) -> Self;
}

impl FromF64 for f64 {
    fn from_f64(v: f64) -> f64 {
        v
    }
}

impl FromF64 for f32 {
    fn from_f64(v: f64) -> f32 {
        v as f32
    }
}

impl<T: FromF64> TypedValueParser for RealParser<T> {
    type Value = T;

    fn parse_ref(
        &self,
        cmd: &clap::Command,
        arg: Option<&clap::Arg>,
        value: &OsStr,
    ) -> Result<T, clap::Error> {
        let option = option_name(arg);
        let text = text_of(cmd, arg, value)?;
        let v = self
            .real
            .parse(&option, text)
            .map_err(|m| refusal(cmd, m))?;
        Ok(T::from_f64(v))
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        carry_range(self.real.range())
    }
}

/// clap asks a value parser for one thing beyond the value, its possible values: so a
/// parser's range travels to [`prepare`] as a single hidden possible value named
/// `RANGE_TAG` + the range, and `prepare` writes it into the help (and hides the list).
const RANGE_TAG: &str = "range: ";

fn carry_range(range: String) -> Option<Box<dyn Iterator<Item = PossibleValue>>> {
    let carrier = PossibleValue::new(format!("{RANGE_TAG}{range}")).hide(true);
    Some(Box::new(std::iter::once(carrier)))
}

/// The range an option's parser carries (as its one hidden possible value), if it is one of
/// this module's.
pub fn range_of(arg: &clap::Arg) -> Option<String> {
    let values = arg.get_value_parser().possible_values()?;
    let mut values = values.filter_map(|v| v.get_name().strip_prefix(RANGE_TAG).map(String::from));
    values.next()
}

/// Two whole numbers in one value, `WIDTHxHEIGHT` (`x`) or `X,Y` (`,`), each a [`Count`].
#[derive(Clone, Copy, Debug)]
pub struct Pair {
    /// Each number's range ("a side in pixels").
    pub each: Count,
    /// What separates them: 'x' (also 'X') or ','.
    pub separator: char,
    /// The form in words, with an example: "WIDTHxHEIGHT (e.g. 800x600)".
    pub form: &'static str,
    /// The two numbers' names, for messages: ("width", "height").
    pub names: (&'static str, &'static str),
}

impl Pair {
    /// The two numbers of `text` for `option`, or a message naming both and the range.
    pub fn parse(&self, option: &str, text: &str) -> Result<(u32, u32), String> {
        let split = if self.separator == 'x' {
            text.split_once(['x', 'X'])
        } else {
            text.split_once(self.separator)
        };
        let Some((a, b)) = split else {
            return Err(format!(
                "{option} {}: not {}; each number is a whole number {}",
                shown(text),
                self.form,
                self.each.range()
            ));
        };
        let number = |name: &str, part: &str| {
            self.each.check(part).map_err(|problem| {
                format!(
                    "{option} {}: the {name} {} is not {}: {problem}; give {} with each number \
                     {}",
                    shown(text),
                    shown(part),
                    self.each.noun,
                    self.form,
                    self.each.range()
                )
            })
        };
        let (a, b) = (number(self.names.0, a)?, number(self.names.1, b)?);
        match (u32::try_from(a), u32::try_from(b)) {
            (Ok(a), Ok(b)) => Ok((a, b)),
            _ => Err(format!(
                "{option} {text}: does not fit; give smaller numbers"
            )),
        }
    }

    /// "WIDTHxHEIGHT (e.g. 800x600), each from 1 to 8192 (why)".
    pub fn range(&self) -> String {
        format!("{}, each {}", self.form, self.each.range())
    }
}

impl TypedValueParser for Pair {
    type Value = (u32, u32);

    fn parse_ref(
        &self,
        cmd: &clap::Command,
        arg: Option<&clap::Arg>,
        value: &OsStr,
    ) -> Result<(u32, u32), clap::Error> {
        let text = text_of(cmd, arg, value)?;
        self.parse(&option_name(arg), text)
            .map_err(|m| refusal(cmd, m))
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        carry_range(self.range())
    }
}

/// What an option takes, from the type its value parser gives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kind {
    /// No value (a switch).
    Flag,
    /// A whole number (any integer type).
    Count,
    /// A real number (f32, f64).
    Real,
    /// Two whole numbers (`WIDTHxHEIGHT`, `X,Y`).
    Pair,
    /// A path.
    Path,
    /// One of a fixed set of names.
    Choice,
    /// Any other text.
    Text,
}

/// What `arg` takes.
pub fn kind_of(arg: &clap::Arg) -> Kind {
    if !arg.get_action().takes_values() {
        return Kind::Flag;
    }
    let id = arg.get_value_parser().type_id();
    let is = |t: TypeId| id == t;
    let counts = [
        TypeId::of::<u8>(),
        TypeId::of::<u16>(),
        TypeId::of::<u32>(),
        TypeId::of::<u64>(),
        TypeId::of::<usize>(),
        TypeId::of::<i8>(),
        TypeId::of::<i16>(),
        TypeId::of::<i32>(),
        TypeId::of::<i64>(),
        TypeId::of::<isize>(),
    ];
    if counts.into_iter().any(is) {
        Kind::Count
    } else if is(TypeId::of::<f32>()) || is(TypeId::of::<f64>()) {
        Kind::Real
    } else if is(TypeId::of::<(u32, u32)>()) {
        Kind::Pair
    } else if is(TypeId::of::<std::path::PathBuf>()) {
        Kind::Path
    } else if arg.get_value_parser().possible_values().is_some() {
        Kind::Choice
    } else {
        Kind::Text
    }
}

/// Every numeric option of `cmd` and its subcommands takes a value that starts with `-`, so
/// that `--size -5` reaches the option's own check (a single value: any; one of several, as
/// `--triangles 100,-5`: a negative number, so that a following option is not taken); and an
/// option whose parser has a range says it in its help.
pub fn prepare(cmd: clap::Command) -> clap::Command {
    cmd.mut_args(|a| with_range_in_help(take_negative_values(a)))
        .mut_subcommands(prepare)
}

fn take_negative_values(a: clap::Arg) -> clap::Arg {
    let numeric = matches!(kind_of(&a), Kind::Count | Kind::Real | Kind::Pair);
    let many = a.get_num_args().is_some_and(|n| n.max_values() > 1);
    if numeric && many {
        a.allow_negative_numbers(true)
    } else if numeric {
        a.allow_hyphen_values(true)
    } else {
        a
    }
}

fn with_range_in_help(a: clap::Arg) -> clap::Arg {
    let Some(range) = range_of(&a) else {
        return a;
    };
    let with_range = |help: Option<&clap::builder::StyledStr>| {
        let help = help.map(|h| h.to_string()).unwrap_or_default();
        format!("{} [range: {range}]", help.trim_end())
    };
    let help = with_range(a.get_help());
    let long_help = a.get_long_help().map(|h| with_range(Some(h)));
    let a = a.hide_possible_values(true).help(help);
    match long_help {
        Some(long) => a.long_help(long),
        None => a,
    }
}

/// Shared ranges.
pub mod ranges {
    use super::{Count, Real};

    /// `--runs`: every timed measurement runs this many times; the papers' sections time
    /// hundreds of measurements of up to seconds each, so 1000 runs already take days.
    pub const RUNS: Count = Count::new(
        "a number of runs",
        1,
        1000,
        "each run repeats every timed measurement; 1000 runs of a section take days",
    );

    /// `--frames` of a run that draws frames one after another (a frame is at least a
    /// millisecond of work, so a million is most of an hour at the least).
    pub const FRAMES: Count = Count::new("a number of frames", 1, 1_000_000, FRAMES_WHY);

    const FRAMES_WHY: &str = "a million frames take hours on a software renderer";

    /// [`FRAMES`] of a run that keeps `bytes_each` of results a frame: also what fits.
    pub const fn frames_kept(bytes_each: u64) -> Count {
        Count::in_memory("a number of frames", 1, bytes_each, "frame's results")
            .at_most(1_000_000, FRAMES_WHY)
    }

    /// A square render target's side (peels, views, pictures): the largest texture side of
    /// the GPUs of the papers' period (8192 on the GeForce 8800) and of Mesa's llvmpipe.
    pub const SIDE: Count = Count::new(
        "a size in pixels",
        1,
        8192,
        "the largest texture side of the papers' GPUs and of llvmpipe",
    );

    /// A seed of a random generator: any 64-bit number.
    pub const SEED: Count = Count::new("a seed", 0, u64::MAX, "any 64-bit number");

    /// A texture's or a render target's side in texels: the largest any OpenGL renderer has
    /// (the renderer's own maximum is checked when the command runs).
    pub const TEXTURE_SIDE: Count = Count::new(
        "a size in texels",
        1,
        32768,
        "the largest texture side of any OpenGL renderer; this renderer's is checked when it runs",
    );

    /// A picture's `WIDTHxHEIGHT` in pixels, each side from `least` to the largest texture
    /// side ([`TEXTURE_SIDE`]).
    pub const fn picture(least: u64) -> super::Pair {
        super::Pair {
            each: Count {
                least,
                ..TEXTURE_SIDE
            },
            separator: 'x',
            form: "WxH (e.g. 800x600)",
            names: ("width", "height"),
        }
    }

    /// Triangles of a generated or resampled mesh, `bytes_each` of memory a triangle (as
    /// measured by the command that makes them).
    pub const fn triangles(bytes_each: u64) -> Count {
        Count::in_memory("a number of triangles", 1, bytes_each, "triangle").at_most(
            u32::MAX as u64 / 3,
            "vertex indices are 32-bit, three a triangle",
        )
    }

    /// Triangles per leaf of a bounding-volume hierarchy: the exact tests of two leaves that
    /// overlap are n x n, so a leaf of 65536 already costs four billion tests a pair.
    pub const LEAF_SIZE: Count = Count::new(
        "a leaf size",
        1,
        65536,
        "two overlapping leaves of n triangles cost n x n exact tests",
    );

    /// A distance or time step that must be positive and finite, at most `most`.
    pub const fn positive(noun: &'static str, most: f64, why: &'static str) -> Real {
        Real::new(noun, 1e-9, most, why)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FRAMES: Count = Count::new("a number of frames", 1, 10, "why");

    #[test]
    fn a_count_outside_its_range_names_the_option_the_value_and_the_range() {
        assert_eq!(FRAMES.parse("--frames", "5"), Ok(5));
        assert_eq!(FRAMES.parse("--frames", "1e1"), Ok(10));
        for (text, problem) in [
            ("-5", "it is negative"),
            ("0", "it is below 1"),
            ("11", "it is above 10"),
            ("1e30", "it is above 10"),
            ("18446744073709551616", "it is above 10"),
            ("2.5", "it is not a whole number"),
            ("nan", "it is not a number"),
            ("x", "it is not a number"),
            ("", "it is empty"),
            ("--json", "it is an option"),
        ] {
            let err = FRAMES.parse("--frames", text).unwrap_err();
            assert!(
                err.starts_with(&format!(
                    "--frames {}: not a number of frames: ",
                    shown(text)
                )) && err.contains(problem)
                    && err.ends_with("give a whole number from 1 to 10 (why)"),
                "{text}: {err}"
            );
        }
    }

    #[test]
    fn a_real_outside_its_range_is_refused_with_the_range() {
        let r = Real::new("a tolerance", 1e-9, 100.0, "the scene");
        assert_eq!(r.parse("--tolerance", "0.5"), Ok(0.5));
        for (text, problem) in [
            ("-1", "below 1e-9"),
            ("1e308", "above 100"),
            ("inf", "not finite"),
            ("-inf", "not finite"),
            ("nan", "not a number"),
        ] {
            let err = r.parse("--tolerance", text).unwrap_err();
            assert!(
                err.starts_with(&format!("--tolerance {text}: not a tolerance"))
                    && err.contains(problem)
                    && err.ends_with("from 1e-9 to 100 (the scene)"),
                "{text}: {err}"
            );
        }
    }

    #[test]
    fn a_memory_bound_is_what_fits_and_says_so() {
        let c = Count::in_memory("a number of bodies", 1, 1 << 30, "body");
        assert_eq!(c.most(), fit_in_memory(1 << 30).max(1));
        assert!(c.range().contains("available memory"), "{}", c.range());
        let capped = Count::in_memory("a size", 1, 1, "texel").at_most(8, "the cap");
        assert_eq!(capped.most(), 8);
        assert_eq!(capped.range(), "from 1 to 8 (the cap)");
        assert_eq!(units_in(100, 0), 100);
        assert_eq!(units_in(100, 7), 14);
        assert!(memory_budget() > 0);
    }

    #[test]
    fn pairs_check_each_number() {
        let size = Pair {
            each: Count::new("a side in pixels", 16, 100, "why"),
            separator: 'x',
            form: "WIDTHxHEIGHT (e.g. 20x30)",
            names: ("width", "height"),
        };
        assert_eq!(size.parse("--size", "20x30"), Ok((20, 30)));
        assert_eq!(size.parse("--size", "20X30"), Ok((20, 30)));
        let err = size.parse("--size", "-5x30").unwrap_err();
        assert!(
            err.starts_with("--size -5x30: the width -5 is not a side in pixels: it is negative"),
            "{err}"
        );
        let err = size.parse("--size", "20").unwrap_err();
        assert!(err.contains(": not WIDTHxHEIGHT"), "{err}");
    }

    #[test]
    fn negative_values_reach_the_option_check() {
        #[derive(clap::Parser, Debug)]
        struct Cli {
            /// Frames.
            #[arg(long, value_parser = FRAMES.of::<usize>())]
            frames: usize,
            #[arg(long)]
            json: bool,
        }
        use clap::{CommandFactory, FromArgMatches};
        let parse = |args: &[&str]| {
            let cmd = prepare(Cli::command());
            cmd.try_get_matches_from(args)
                .and_then(|m| Cli::from_arg_matches(&m))
        };
        let err = parse(&["x", "--frames", "-1"]).unwrap_err().to_string();
        assert!(
            err.contains("--frames -1: not a number of frames: it is negative"),
            "{err}"
        );
        assert_eq!(parse(&["x", "--frames", "3", "--json"]).unwrap().frames, 3);
        assert!(parse(&["x", "--frames", "3", "--json"]).unwrap().json);
        let cmd = prepare(Cli::command());
        let frames = cmd
            .get_arguments()
            .find(|a| a.get_id() == "frames")
            .unwrap();
        assert_eq!(kind_of(frames), Kind::Count);
        let help = frames.get_help().unwrap().to_string();
        assert!(
            help.starts_with("Frames") && help.ends_with(" [range: from 1 to 10 (why)]"),
            "{help}"
        );
    }
}
