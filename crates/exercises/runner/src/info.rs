//! `crates/exercises/info.toml`: every exercise, in the book's order, with its chapter, the section
//! of the book that explains it, its kind and its hints.

use std::fmt;
use std::path::Path;

/// What the learner does in an exercise.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Write the body of a function in place of its `todo!()`.
    Write,
    /// Find and fix the bug in a working-looking implementation (the bug museum).
    Bug,
}

/// One exercise of `info.toml`.
#[derive(Clone, Debug, PartialEq)]
pub struct Exercise {
    /// `chNN_name`: the file `exercises/<name>.rs` and the test target `<name>`.
    pub name: String,
    /// The page of the book whose Exercises section holds it: "N Title", e.g.
    /// "12 Cleaning Up PDF Management".
    pub chapter: String,
    /// The section of the book that explains it: "M Heading", e.g.
    /// "9 A sphere light: the cone it subtends" (M may differ from N).
    pub section: String,
    pub kind: Kind,
    /// Hints, from a nudge to the last step, which gives the formulas the stub leaves out; none is
    /// a line of the reference solution.
    pub hints: Vec<String>,
}

/// Why `info.toml` was refused.
#[derive(Debug)]
pub struct InfoError(pub String);

impl fmt::Display for InfoError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for InfoError {}

/// Reads and checks `path` (an `info.toml`).
pub fn load(path: &Path) -> Result<Vec<Exercise>, InfoError> {
    let text =
        std::fs::read_to_string(path).map_err(|e| InfoError(format!("{}: {e}", path.display())))?;
    parse(&text).map_err(|e| InfoError(format!("{}: {}", path.display(), e.0)))
}

/// Parses the text of an `info.toml`.
pub fn parse(text: &str) -> Result<Vec<Exercise>, InfoError> {
    let table: toml::Table = text
        .parse()
        .map_err(|e: toml::de::Error| InfoError(e.to_string().trim_end().replace('\n', " ")))?;
    let list = table
        .get("exercise")
        .and_then(|v| v.as_array())
        .ok_or_else(|| InfoError("no [[exercise]] tables".into()))?;
    let mut out: Vec<Exercise> = Vec::new();
    for (i, item) in list.iter().enumerate() {
        let at = |field: &str| format!("exercise[{i}].{field}");
        let t = item
            .as_table()
            .ok_or_else(|| InfoError(format!("exercise[{i}] is not a table")))?;
        let text_field = |field: &str| -> Result<String, InfoError> {
            t.get(field)
                .and_then(|v| v.as_str())
                .map(str::to_string)
                .ok_or_else(|| InfoError(format!("field `{}`: missing or not a string", at(field))))
        };
        let name = text_field("name")?;
        let well_formed = name.len() > 5
            && name.starts_with("ch")
            && name[2..4].chars().all(|c| c.is_ascii_digit())
            && name.as_bytes()[4] == b'_'
            && name[5..]
                .chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_');
        if !well_formed {
            return Err(InfoError(format!(
                "field `{}`: `{name}` is not of the form chNN_name",
                at("name")
            )));
        }
        if out.iter().any(|e| e.name == name) {
            return Err(InfoError(format!(
                "field `{}`: `{name}` appears twice",
                at("name")
            )));
        }
        let chapter = text_field("chapter")?;
        let section = text_field("section")?;
        for (field, value) in [("chapter", &chapter), ("section", &section)] {
            let numbered = value
                .split_once(' ')
                .is_some_and(|(n, rest)| n.parse::<u32>().is_ok() && !rest.trim().is_empty());
            if !numbered {
                return Err(InfoError(format!(
                    "field `{}`: `{value}` is not of the form \"N Title\" (a chapter number, then \
                     the heading)",
                    at(field)
                )));
            }
        }
        let kind = match text_field("kind")?.as_str() {
            "write" => Kind::Write,
            "bug" => Kind::Bug,
            other => {
                return Err(InfoError(format!(
                    "field `{}`: `{other}`, expected \"write\" or \"bug\"",
                    at("kind")
                )));
            }
        };
        let hints: Vec<String> = t
            .get("hints")
            .and_then(|v| v.as_array())
            .ok_or_else(|| InfoError(format!("field `{}`: missing or not a list", at("hints"))))?
            .iter()
            .map(|h| h.as_str().map(|s| s.trim().to_string()))
            .collect::<Option<_>>()
            .ok_or_else(|| InfoError(format!("field `{}`: a hint is not a string", at("hints"))))?;
        if hints.len() < 2 {
            return Err(InfoError(format!(
                "field `{}`: {} hint(s); every exercise has at least 2 levels",
                at("hints"),
                hints.len()
            )));
        }
        out.push(Exercise {
            name,
            chapter,
            section,
            kind,
            hints,
        });
    }
    Ok(out)
}

impl Exercise {
    /// The chapter's number: the N of "N Title".
    pub fn chapter_number(&self) -> &str {
        self.chapter.split_once(' ').map_or("", |(n, _)| n)
    }

    /// The section that explains it, in words: chapter 9, section "A sphere light: the cone it
    /// subtends".
    pub fn section_words(&self) -> String {
        match self.section.split_once(' ') {
            Some((n, heading)) => format!("chapter {n}, section \"{heading}\""),
            None => self.section.clone(),
        }
    }

    /// Where the book explains it, for a heading: "2 A Simple Monte Carlo Program: Estimating π", or
    /// "12 Cleaning Up PDF Management (explained in 9 A sphere light: the cone it subtends)" when
    /// the section is in another chapter.
    pub fn label(&self) -> String {
        match self.section.split_once(' ') {
            Some((n, heading)) if n == self.chapter_number() => {
                format!("{}: {heading}", self.chapter)
            }
            _ => format!("{} (explained in {})", self.chapter, self.section),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_names_the_field_of_a_mistake() {
        let ok = "[[exercise]]\nname = \"ch02_a\"\nchapter = \"2 X\"\nsection = \"2 Y\"\nkind = \"bug\"\nhints = [\"a\", \"b\"]\n";
        let e = parse(ok).unwrap();
        assert_eq!(e[0].kind, Kind::Bug);
        assert_eq!(e[0].hints, ["a", "b"]);
        assert_eq!(e[0].label(), "2 X: Y");
        assert_eq!(e[0].section_words(), "chapter 2, section \"Y\"");
        let elsewhere = parse(&ok.replace("\"2 Y\"", "\"9 Z\"")).unwrap();
        assert_eq!(elsewhere[0].label(), "2 X (explained in 9 Z)");
        let no_number = ok.replace("\"2 Y\"", "\"Y\"");
        let err = parse(&no_number).unwrap_err().0;
        assert!(
            err.contains("exercise[0].section") && err.contains("N Title"),
            "{err}"
        );
        let one_hint = ok.replace("[\"a\", \"b\"]", "[\"a\"]");
        let err = parse(&one_hint).unwrap_err().0;
        assert!(err.contains("exercise[0].hints"), "{err}");
        let bad_name = ok.replace("ch02_a", "two_a");
        assert!(parse(&bad_name).unwrap_err().0.contains("chNN_name"));
        let bad_kind = ok.replace("\"bug\"", "\"fix\"");
        assert!(parse(&bad_kind).unwrap_err().0.contains("exercise[0].kind"));
    }
}
