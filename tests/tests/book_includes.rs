//! The book includes its code from compiled, tested sources; these tests make sure every include still
//! resolves, so a renamed file or a deleted anchor breaks the build of the book here, not silently there.

use std::fs;
use std::path::{Path, PathBuf};

fn book_src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../book/src")
}

/// Every `{{#include path}}`, `{{#include path:anchor}}` and `{{#rustdoc_include ...}}` in a chapter.
fn includes(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(start) = rest.find("{{#") {
        let after = &rest[start + 3..];
        let Some(end) = after.find("}}") else { break };
        let directive = after[..end].trim();
        for kw in ["include ", "rustdoc_include "] {
            if let Some(arg) = directive.strip_prefix(kw) {
                out.push(arg.trim().to_string());
            }
        }
        rest = &after[end + 2..];
    }
    out
}

/// Checks one include argument relative to the chapter at `chapter`; returns a description of what
/// is wrong, if anything.
fn check_include(chapter: &Path, arg: &str) -> Option<String> {
    let mut parts = arg.splitn(2, ':');
    let file = parts.next().unwrap_or("");
    let selector = parts.next();
    let path = chapter.parent().unwrap().join(file);
    let Ok(source) = fs::read_to_string(&path) else {
        return Some(format!(
            "{}: includes {file}, which does not exist",
            chapter.display()
        ));
    };
    match selector {
        None => None,
        Some(sel) if sel.chars().all(|c| c.is_ascii_digit() || c == ':') => Some(format!(
            "{}: includes {arg} by line numbers; use a named anchor so edits cannot shift it",
            chapter.display()
        )),
        Some(anchor) => {
            let begin = format!("ANCHOR: {anchor}");
            let end = format!("ANCHOR_END: {anchor}");
            let has = |needle: &str| {
                source
                    .lines()
                    .any(|l| l.trim_end().ends_with(needle) && l.contains(needle))
            };
            if has(&begin) && has(&end) {
                None
            } else {
                Some(format!(
                    "{}: anchor `{anchor}` not found (both ANCHOR and ANCHOR_END) in {file}",
                    chapter.display()
                ))
            }
        }
    }
}

#[test]
fn every_book_include_resolves_to_a_file_and_anchor() {
    let mut problems = Vec::new();
    let mut count = 0;
    for entry in fs::read_dir(book_src()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "md") {
            let text = fs::read_to_string(&path).unwrap();
            for arg in includes(&text) {
                count += 1;
                problems.extend(check_include(&path, &arg));
            }
        }
    }
    assert!(
        problems.is_empty(),
        "broken includes:\n{}",
        problems.join("\n")
    );
    eprintln!("{count} includes checked");
}

#[test]
fn summary_lists_thirteen_chapters_and_every_file_exists() {
    let summary = fs::read_to_string(book_src().join("SUMMARY.md")).unwrap();
    let mut chapters = 0;
    for line in summary.lines() {
        if let (Some(a), Some(b)) = (line.find("]("), line.rfind(')')) {
            let file = &line[a + 2..b];
            assert!(
                book_src().join(file).exists(),
                "SUMMARY.md names {file}, which is missing"
            );
            if line.trim_start().starts_with("- [") && !line.starts_with(' ') {
                chapters += 1;
            }
        }
    }
    assert_eq!(
        chapters, 13,
        "the book has one chapter per chapter of book 3"
    );
}

#[test]
fn the_checker_catches_a_missing_anchor_and_a_missing_file() {
    let chapter = book_src().join("SUMMARY.md");
    assert!(check_include(&chapter, "../../Cargo.toml:no-such-anchor").is_some());
    assert!(check_include(&chapter, "../../no/such/file.rs").is_some());
    assert!(check_include(&chapter, "../../Cargo.toml").is_none());
    assert_eq!(
        includes("a {{#include x.rs:y}} b {{#title t}}"),
        vec!["x.rs:y".to_string()]
    );
}
