//! Scene files: the built-in objects described in TOML, so users write scenes without recompiling.
//!
//! For now the file is parsed (a syntax error names the file, line and column) and then refused: the
//! mapping from TOML tables to a [`crate::scene::SceneBuilder`] is still to come.

use crate::scenes::Built;
use std::path::Path;

/// 1-based line and column of a byte offset in `text`.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// Parse `text` (read from `path`) as TOML; errors read `path:line:col: message`.
pub fn parse(path: &Path, text: &str) -> Result<toml::Table, String> {
    text.parse::<toml::Table>().map_err(|e| {
        let (line, col) = e.span().map_or((1, 1), |s| line_col(text, s.start));
        format!(
            "{}:{line}:{col}: {}",
            path.display(),
            e.message().trim_end()
        )
    })
}

/// Load the scene in the file at `path`.
pub fn load(path: &Path) -> Result<Built, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("{}: cannot read scene file: {e}", path.display()))?;
    let _table = parse(path, &text)?;
    Err(format!(
        "{}: scene files are not yet supported (the TOML is well-formed; the scene-file loader is still to come)",
        path.display()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_syntax_error_names_file_line_and_column() {
        let err = parse(Path::new("bad.toml"), "ok = 1\nnot = a [scene\n").unwrap_err();
        assert!(err.starts_with("bad.toml:2:"), "{err}");
    }
}
