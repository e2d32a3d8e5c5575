//! The book's formulas pass through Markdown before KaTeX sees them, and Markdown eats a backslash
//! before ASCII punctuation: `\,` (a thin space) arrives as `,`, `\{` as `{`. Inside `\\( ... \\)` and
//! `\\[ ... \\]` such a backslash must be written twice (`\\,`). This test finds every formula that
//! would lose one, with its file and line, so no chapter shows `p(t),dt` for `p(t)\,dt`.
//! (The browser check, book/check/run, sees the rendered page; this one runs without a browser.)

use std::fs;
use std::path::Path;

/// Problems in one chapter's Markdown: `(line, message)` for each formula with a single backslash
/// before punctuation, or a formula left open.
fn lost_escapes(text: &str) -> Vec<(usize, String)> {
    let mut problems = Vec::new();
    let mut in_fence = false;
    let mut open: Option<(usize, &[u8])> = None; // (line of the opening delimiter, closing delimiter)
    for (n, line) in text.lines().enumerate() {
        let n = n + 1;
        if line.trim_start().starts_with("```") {
            in_fence = !in_fence;
            continue;
        }
        if in_fence {
            continue;
        }
        let b = line.as_bytes();
        let mut i = 0;
        let mut in_code = false;
        while i < b.len() {
            if b[i] == b'`' {
                in_code = !in_code;
                i += 1;
                continue;
            }
            if in_code {
                i += 1;
                continue;
            }
            let rest = &b[i..];
            match open {
                None => {
                    if rest.starts_with(b"\\\\(") {
                        open = Some((n, b"\\\\)"));
                        i += 3;
                    } else if rest.starts_with(b"\\\\[") {
                        open = Some((n, b"\\\\]"));
                        i += 3;
                    } else {
                        i += 1;
                    }
                }
                Some((_, close)) => {
                    if rest.starts_with(close) {
                        open = None;
                        i += 3;
                    } else if rest.starts_with(b"\\\\") {
                        i += 2; // a backslash Markdown keeps
                    } else if b[i] == b'\\' && i + 1 < b.len() && b[i + 1].is_ascii_punctuation() {
                        problems.push((
                            n,
                            format!(
                                "`\\{}` in a formula: Markdown drops the backslash; write `\\\\{}`",
                                b[i + 1] as char,
                                b[i + 1] as char
                            ),
                        ));
                        i += 2;
                    } else {
                        i += 1;
                    }
                }
            }
        }
    }
    if let Some((n, close)) = open {
        problems.push((
            n,
            format!(
                "formula opened here is never closed by `{}`",
                String::from_utf8_lossy(close)
            ),
        ));
    }
    problems
}

#[test]
fn no_formula_loses_a_backslash_to_markdown() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../book/src");
    let mut all = Vec::new();
    let mut chapters = 0;
    for entry in fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "md") {
            chapters += 1;
            let text = fs::read_to_string(&path).unwrap();
            for (line, message) in lost_escapes(&text) {
                all.push(format!("{}:{line}: {message}", path.display()));
            }
        }
    }
    assert!(
        chapters >= 14,
        "found only {chapters} chapters in {}",
        dir.display()
    );
    assert!(all.is_empty(), "{}", all.join("\n"));
}

#[test]
fn the_checker_finds_a_lost_thin_space_and_an_unclosed_formula() {
    let bad = "a \\\\(p(t)\\,dt\\\\) b\n\\\\[ x \\{ \\\\]\nc \\\\( y";
    let found = lost_escapes(bad);
    assert_eq!(found.len(), 3, "{found:?}");
    assert_eq!(found[0].0, 1);
    assert_eq!(found[1].0, 2);
    assert!(found[2].1.contains("never closed"));
    // the right spelling, a backslash outside formulas and one in code pass
    let good = "a \\\\(p(t)\\\\,dt\\\\) b \\* `\\\\( \\, \\\\)`\n```\n\\\\( \\, \\\\)\n```";
    assert!(lost_escapes(good).is_empty(), "{:?}", lost_escapes(good));
}

/// Lines that Markdown and KaTeX would silently mangle: a control character (a `\t`, `\b` or `\r`
/// that an editor or a script turned from the two characters of `\times`, `\bar` or `\rfloor` into
/// one), or a formula opened with a single backslash, `\(`, which Markdown reads as an escaped
/// parenthesis, so KaTeX never sees a formula (code spans and fences are skipped).
fn mangled_lines(text: &str) -> Vec<(usize, String)> {
    let mut problems = Vec::new();
    let mut in_fence = false;
    for (n, line) in text.lines().enumerate() {
        let n = n + 1;
        if let Some(c) = line.chars().find(|c| c.is_control()) {
            problems.push((n, format!("control character {:?}", c)));
        }
        if line.trim_start().starts_with("```") {
            in_fence = !in_fence;
            continue;
        }
        if in_fence {
            continue;
        }
        let b = line.as_bytes();
        let mut in_code = false;
        for i in 0..b.len() {
            if b[i] == b'`' {
                in_code = !in_code;
            }
            let single = b[i] == b'\\'
                && (i == 0 || b[i - 1] != b'\\')
                && b.get(i + 1).is_some_and(|c| b"()[]".contains(c));
            if single && !in_code {
                problems.push((
                    n,
                    "a formula delimiter with one backslash: write \\\\( \\\\)".into(),
                ));
                break;
            }
        }
    }
    problems
}

#[test]
fn no_line_of_the_book_is_mangled_by_a_control_character_or_a_single_backslash_delimiter() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../book/src");
    let mut all = Vec::new();
    for entry in fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "md") {
            let text = fs::read_to_string(&path).unwrap();
            for (line, message) in mangled_lines(&text) {
                all.push(format!("{}:{line}: {message}", path.display()));
            }
        }
    }
    assert!(all.is_empty(), "{}", all.join("\n"));
}

#[test]
fn the_mangling_checker_finds_a_tab_for_times_and_a_single_backslash_formula() {
    let bad = "a \\\\(1.8 \times 10\\\\)\nb \\(k\\) c";
    let found = mangled_lines(bad);
    assert_eq!(found.len(), 2, "{found:?}");
    assert_eq!((found[0].0, found[1].0), (1, 2));
    let good = "a \\\\(1.8 \\\\times 10\\\\) `\\(code\\)`\n```\n\\(fenced\\)\n```";
    assert!(mangled_lines(good).is_empty(), "{:?}", mangled_lines(good));
}
