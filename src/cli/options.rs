//! `classic-gpgpu options` (hidden): every command's options as JSON, as clap knows them (after
//! [`classic_gpgpu::values::prepare`]): for each command its path of names and each option's
//! id, long name, kind of value ([`classic_gpgpu::values::kind_of`]), role when it is a path
//! ([`super::paths::role`]), whether it takes several values, and its help. The tests walk
//! this list, so that a new option meets the rules of values and paths or fails a test.

use classic_gpgpu::values::{kind_of, Kind};
use serde_json::{json, Value};

pub fn run(command: &clap::Command) -> anyhow::Result<()> {
    let mut commands = Vec::new();
    walk(command, &mut Vec::new(), &mut commands);
    println!(
        "{}",
        serde_json::to_string_pretty(&json!({ "commands": commands }))?
    );
    Ok(())
}

/// `cmd`'s options under the names `path`, then its subcommands'.
fn walk(cmd: &clap::Command, path: &mut Vec<String>, out: &mut Vec<Value>) {
    let options: Vec<Value> = cmd
        .get_arguments()
        .filter(|a| !matches!(a.get_id().as_str(), "help" | "version"))
        .map(|a| {
            let kind = kind_of(a);
            json!({
                "id": a.get_id().as_str(),
                "long": a.get_long(),
                "positional": a.is_positional(),
                "kind": kind,
                "role": (kind == Kind::Path || a.get_id() == "png_every")
                    .then(|| super::paths::role(a.get_id().as_str())),
                "many": a.get_num_args().is_some_and(|n| n.max_values() > 1)
                    || a.get_value_delimiter().is_some(),
                "global": a.is_global_set(),
                "help": a.get_help().map(|h| h.to_string()).unwrap_or_default(),
            })
        })
        .collect();
    out.push(json!({
        "command": path.join(" "),
        "has_subcommands": cmd.has_subcommands(),
        "options": options,
    }));
    for sub in cmd.get_subcommands().filter(|s| s.get_name() != "help") {
        path.push(sub.get_name().to_string());
        walk(sub, path, out);
        path.pop();
    }
}
