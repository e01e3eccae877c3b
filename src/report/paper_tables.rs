//! The papers' published tables, transcribed in `assets/paper_tables.toml`.

/// The TOML text, compiled into the binary.
pub const PAPER_TABLES_TOML: &str = include_str!("../../assets/paper_tables.toml");

/// The parsed tables. The file is part of the source; a parse error is a bug caught by a test.
pub fn load() -> toml::Table {
    PAPER_TABLES_TOML
        .parse()
        .expect("assets/paper_tables.toml is valid TOML")
}
