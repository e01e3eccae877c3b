//! `classic-gpgpu compare`: several machines' results.json side by side, as a page or as the
//! README's table.

use classic_gpgpu::compare::{self, CompareArgs};

pub fn run(args: &CompareArgs, json: bool) -> anyhow::Result<()> {
    if args.markdown {
        print!("{}", compare::markdown::grouped(&args.results)?);
        return Ok(());
    }
    let runs = compare::read(&args.results)?;
    let comparison = compare::compare(runs)?;
    compare::write_page(&comparison, &args.out, &args.results, args.force)?;
    if json {
        println!("{}", serde_json::to_string_pretty(&comparison)?);
    } else {
        println!(
            "compared {} machine{} ({}): {}",
            comparison.machines.len(),
            if comparison.machines.len() == 1 {
                ""
            } else {
                "s"
            },
            comparison
                .machines
                .iter()
                .map(|m| m.label.as_str())
                .collect::<Vec<_>>()
                .join(", "),
            args.out.join("index.html").display()
        );
    }
    Ok(())
}
