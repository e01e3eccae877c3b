//! Upper limits of the counts the commands take, checked before anything is allocated: each
//! derived from this machine's memory (what a unit of the count costs, measured) and, where
//! one applies, the renderer's limits. The error names the option, the value, the limit and
//! why.

use anyhow::bail;

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

/// Refuses `value` of `option` outside `1..=max`; `why` says where `max` comes from.
pub fn check_count(option: &str, value: u64, max: u64, why: &str) -> anyhow::Result<()> {
    if value == 0 {
        bail!("{option} 0: must be at least 1");
    }
    if value > max {
        bail!("{option} {value}: at most {max} on this machine ({why})");
    }
    Ok(())
}

/// Refuses a run whose planned memory, `units` of `bytes_each` (`what` says what a unit is),
/// is more than the budget; `options` names the options that set the count, `advice` what to
/// change.
pub fn check_memory(
    options: &str,
    units: u64,
    bytes_each: u64,
    what: &str,
    advice: &str,
) -> anyhow::Result<()> {
    let budget = memory_budget();
    let need = units.saturating_mul(bytes_each);
    if need > budget {
        bail!(
            "{options}: {units} {what} of about {bytes_each} bytes each need {}, more than the {} \
             this machine may use (half of the memory it has available); {advice}",
            gib(need),
            gib(budget)
        );
    }
    Ok(())
}

/// A byte count for messages: `1.5 GiB`.
pub fn gib(bytes: u64) -> String {
    format!("{:.1} GiB", bytes as f64 / (1u64 << 30) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_outside_the_range_name_the_option_and_the_reason() {
        assert!(check_count("--frames", 5, 10, "x").is_ok());
        let zero = check_count("--frames", 0, 10, "x").unwrap_err().to_string();
        assert_eq!(zero, "--frames 0: must be at least 1");
        let big = check_count("--frames", 11, 10, "memory")
            .unwrap_err()
            .to_string();
        assert_eq!(big, "--frames 11: at most 10 on this machine (memory)");
        assert!(memory_budget() > 0);
        // The available memory moves between two reads, so the arithmetic is checked apart.
        assert_eq!(units_in(100, 0), 100);
        assert_eq!(units_in(100, 7), 14);
        assert!(fit_in_memory(1 << 40) < fit_in_memory(1));
        let err = check_memory("--size 9 --steps 9", u64::MAX, 32, "numbers", "use fewer")
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with(
                "--size 9 --steps 9: 18446744073709551615 numbers of about 32 bytes each"
            ),
            "{err}"
        );
        assert!(err.ends_with("; use fewer"), "{err}");
        assert!(check_memory("--size", 1, 1, "numbers", "x").is_ok());
    }
}
