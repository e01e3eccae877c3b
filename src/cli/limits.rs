//! Upper limits of what several counts take together (a size times a number of steps), checked
//! at a command's start before anything is allocated; each count alone is bounded by its
//! option's parser ([`classic_gpgpu::values`]). The error names the options, the values, the
//! memory needed and what may be used.

use anyhow::bail;
use classic_gpgpu::values::{gib, memory_budget};

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plan_beyond_memory_names_the_options_and_the_memory() {
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
