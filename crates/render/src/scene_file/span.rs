//! Places in a scene file: byte spans, their line and column, the dotted field a span lies in, and
//! the typed error that names them (`FILE:LINE:COL: field `objects[2].radius`: message`).

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// A byte range of the file's text.
pub(super) type Span = Range<usize>;
/// A TOML value with its span.
pub(super) type Val<'i> = Spanned<DeValue<'i>>;

/// A place in a scene file: the file as named, and the 1-based line and column.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Place {
    pub file: PathBuf,
    pub line: usize,
    pub col: usize,
}

impl fmt::Display for Place {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.file.display(), self.line, self.col)
    }
}

/// The dotted path of a field (`objects[2].radius`); empty for an error about the file as a whole.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Field(pub String);

impl fmt::Display for Field {
    /// "field `objects[2].radius`: ", or nothing for the file as a whole.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_empty() {
            Ok(())
        } else {
            // (a key may hold what a terminal would act on: written out, not sent)
            write!(f, "field `{}`: ", crate::text::shown(&self.0))
        }
    }
}

/// Why a scene file cannot be loaded. Its message always starts with the place: the file, and for
/// anything inside it the line, the column and the field.
#[derive(Debug, thiserror::Error)]
pub enum SceneFileError {
    /// The file cannot be read, or is not one to read: not a regular file, too large, not UTF-8.
    /// The message names the file.
    #[error("{message}")]
    Read { path: PathBuf, message: String },
    /// The text is not TOML.
    #[error("{place}: {message}")]
    Syntax { place: Place, message: String },
    /// The TOML does not describe a scene we can render: a wrong type, an unknown name, a value out of
    /// its range.
    #[error("{place}: {field}{message}")]
    Invalid {
        place: Place,
        field: Field,
        message: String,
    },
}

impl SceneFileError {
    /// The place of the error inside the file (`None` if the file could not be read).
    pub fn place(&self) -> Option<&Place> {
        match self {
            SceneFileError::Read { .. } => None,
            SceneFileError::Syntax { place, .. } | SceneFileError::Invalid { place, .. } => {
                Some(place)
            }
        }
    }

    /// A TOML syntax error in `text` (read from `file`).
    pub(super) fn syntax(file: &Path, text: &str, e: &toml::de::Error) -> Self {
        let (line, col) = e.span().map_or((1, 1), |s| line_col(text, s.start));
        SceneFileError::Syntax {
            place: Place {
                file: file.to_path_buf(),
                line,
                col,
            },
            message: match e.message().trim_end() {
                "recursion limit" => "the file nests tables or arrays deeper than the TOML reader \
                                      allows (recursion limit)"
                    .to_owned(),
                "duplicate key" => match e.span() {
                    Some(span) => duplicate_key(text, span),
                    None => "duplicate key".to_owned(),
                },
                m => m.to_owned(),
            },
        }
    }
}

/// The TOML reader's "duplicate key" (at `span`, the second key) with the key, the table it is
/// defined twice in, and where it was first: "duplicate key `radius` in [[objects]] (first at line
/// 9:1)", "duplicate key `camera`: the table [camera] is defined twice (first at line 1:1)". (The
/// reader's error holds the first key's place but does not give it out: it is looked for again.)
fn duplicate_key(text: &str, span: Span) -> String {
    let Some(key) = text.get(span.clone()).map(str::trim) else {
        return "duplicate key".to_owned();
    };
    let bare = key.trim_matches(|c| c == '"' || c == '\'');
    let line_start = text[..span.start].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[span.start..]
        .find('\n')
        .map_or(text.len(), |i| span.start + i);
    let line = &text[line_start..line_end];
    let header = |l: &str| {
        let l = l.trim();
        l.starts_with('[').then(|| {
            // the header up to its closing bracket (a comment may follow)
            let end = l.rfind(']').map_or(l.len(), |i| i + 1);
            l[..end].to_owned()
        })
    };
    let first_at = |offset: usize| {
        let (line, col) = line_col(text, offset);
        format!(" (first at line {line}:{col})")
    };
    // Lines before the key's, with their offsets, last first.
    let before = || {
        text[..line_start]
            .split_inclusive('\n')
            .scan(0, |at, l| {
                let start = *at;
                *at += l.len();
                Some((start, l))
            })
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
    };
    if let Some(h) = header(line) {
        // A table header names a table already defined.
        let first = before()
            .find(|(_, l)| header(l).as_deref() == Some(h.as_str()))
            .map_or(String::new(), |(at, l)| {
                first_at(at + l.len() - l.trim_start().len())
            });
        return format!(
            "duplicate key `{}`: the table {} is defined twice{first}",
            crate::text::shown(bare),
            crate::text::shown(&h)
        );
    }
    // The table the key is in: the inline table around it, or the last header before it.
    let tree = DeTable::parse_recoverable(text).0;
    let inline = field_at(tree.get_ref(), &span);
    let (table, from) = match before().find(|(_, l)| header(l).is_some()) {
        _ if !inline.is_empty() => (format!("in `{}`", crate::text::shown(&inline)), 0),
        Some((at, l)) => (
            format!("in {}", crate::text::shown(&header(l).unwrap_or_default())),
            at,
        ),
        None => ("at the top level of the file".to_owned(), 0),
    };
    // Its first definition: the last key of that name before this one, after the table starts.
    let mut first = None;
    find_keys(tree.get_ref(), bare, &mut |s: &Span| {
        if s.start >= from && s.start < span.start && first.is_none_or(|f| s.start > f) {
            first = Some(s.start);
        }
    });
    let first = first.map_or(String::new(), first_at);
    format!(
        "duplicate key `{}` {table}{first}",
        crate::text::shown(bare)
    )
}

/// Calls `found` with the span of every key named `name` in `t`, at any depth.
fn find_keys(t: &DeTable, name: &str, found: &mut dyn FnMut(&Span)) {
    fn in_value(v: &Val, name: &str, found: &mut dyn FnMut(&Span)) {
        match v.get_ref() {
            DeValue::Table(t) => find_keys(t, name, found),
            DeValue::Array(a) => a.iter().for_each(|v| in_value(v, name, found)),
            _ => {}
        }
    }
    for (k, v) in t.iter() {
        if k.get_ref().as_ref() == name {
            found(&k.span());
        }
        in_value(v, name, found);
    }
}

/// 1-based line and column of a byte offset in `text`.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// An error at a span of the file.
#[derive(Debug)]
pub(super) struct Fail {
    pub(super) span: Span,
    pub(super) msg: String,
}

impl From<toml::de::Error> for Fail {
    fn from(e: toml::de::Error) -> Self {
        Fail {
            span: e.span().unwrap_or(0..0),
            msg: e.message().trim_end().to_owned(),
        }
    }
}

pub(super) fn fail<T>(span: Span, msg: impl Into<String>) -> Result<T, Fail> {
    Err(Fail {
        span,
        msg: msg.into(),
    })
}

impl Fail {
    /// The error at its place in `text` (the file `file`): line, column and the field found from the
    /// span.
    pub(super) fn locate(self, file: &Path, text: &str, tree: &DeTable) -> SceneFileError {
        let (line, col) = line_col(text, self.span.start);
        // An empty span at the start marks an error about the file as a whole.
        let mut field = if self.span == (0..0) {
            String::new()
        } else {
            field_at(tree, &self.span)
        };
        let mut msg = self.msg;
        if let Some(name) = msg
            .strip_prefix("missing field `")
            .and_then(|r| r.split('`').next())
        {
            field = if field.is_empty() {
                name.to_owned()
            } else {
                format!("{field}.{name}")
            };
        }
        if msg.starts_with("unknown field `lights`")
            || msg.starts_with("unknown field `description`")
        {
            msg.push_str(" (top-level keys must come before the first [table] of the file)");
        }
        SceneFileError::Invalid {
            place: Place {
                file: file.to_path_buf(),
                line,
                col,
            },
            field: Field(field),
            message: msg,
        }
    }
}

/// The dotted path (`objects[2].radius`) of the smallest key or value whose span contains `span`.
pub(super) fn field_at(tree: &DeTable, span: &Span) -> String {
    let mut best = (usize::MAX, String::new());
    walk_table(tree, "", span, &mut best);
    best.1
}

fn consider(s: Span, path: &str, target: &Span, best: &mut (usize, String)) {
    // Ties go to the later (deeper) candidate: an array of tables has the span of its first item.
    if s.start <= target.start && target.end <= s.end && s.len() <= best.0 {
        *best = (s.len(), path.to_owned());
    }
}

fn walk_table(t: &DeTable, prefix: &str, target: &Span, best: &mut (usize, String)) {
    for (k, v) in t.iter() {
        let path = if prefix.is_empty() {
            k.get_ref().to_string()
        } else {
            format!("{prefix}.{}", k.get_ref())
        };
        consider(k.span(), &path, target, best);
        walk_value(v, &path, target, best);
    }
}

fn walk_value(v: &Val, path: &str, target: &Span, best: &mut (usize, String)) {
    consider(v.span(), path, target, best);
    match v.get_ref() {
        DeValue::Table(t) => walk_table(t, path, target, best),
        DeValue::Array(a) => {
            for (i, item) in a.iter().enumerate() {
                walk_value(item, &format!("{path}[{i}]"), target, best);
            }
        }
        _ => {}
    }
}
