//! A study's CSV read back, for `--replot`: RFC 4180 fields (quoted where they hold a comma, a
//! quote or a line break), a header naming the columns, and errors that say file:line and column.

use std::path::{Path, PathBuf};
use std::str::FromStr;

/// The largest CSV `--replot` reads: the studies write well under a megabyte.
pub const MAX_CSV_BYTES: u64 = 64 << 20;

/// What is wrong with a study's CSV: each names the file, and the line and column where it can.
#[derive(Debug, thiserror::Error)]
pub enum CsvError {
    /// Not a readable regular file of at most [`MAX_CSV_BYTES`], or not UTF-8; `message` names the
    /// path and quotes the I/O error (not given as a source, so that it is printed once).
    #[error("{message} (--replot reads the CSV an earlier run of the study wrote there)")]
    Read { message: String },
    #[error("{}: empty, not even a header line", path.display())]
    Empty { path: PathBuf },
    #[error("{}:1: no column `{column}` in the header", path.display())]
    MissingColumn { path: PathBuf, column: String },
    #[error("{}:{line}: {found} fields, where the header has {expected}", path.display())]
    FieldCount {
        path: PathBuf,
        line: usize,
        expected: usize,
        found: usize,
    },
    #[error("{}:{line}: field {field} has a quote `\"` that is not closed, or not at its start", path.display())]
    Quote {
        path: PathBuf,
        line: usize,
        field: usize,
    },
    #[error("{}:{line}: field {field} (`{column}`): `{value}` is not {expected}", path.display())]
    Value {
        path: PathBuf,
        line: usize,
        field: usize,
        column: String,
        value: String,
        expected: &'static str,
    },
    #[error("{}:{line}: field {field} (`{column}`): {message}", path.display())]
    Invalid {
        path: PathBuf,
        line: usize,
        field: usize,
        column: String,
        message: String,
    },
    #[error("{}: a header and no rows: nothing to plot", path.display())]
    NoRows { path: PathBuf },
}

#[cfg(test)]
impl CsvError {
    /// The line the error is on (1 is the header), where there is one.
    pub fn line(&self) -> Option<usize> {
        match self {
            Self::MissingColumn { .. } => Some(1),
            Self::FieldCount { line, .. }
            | Self::Quote { line, .. }
            | Self::Value { line, .. }
            | Self::Invalid { line, .. } => Some(*line),
            Self::Read { .. } | Self::Empty { .. } | Self::NoRows { .. } => None,
        }
    }
}

/// `s` as one CSV field: as it is, or quoted (`"` doubled) if it holds a comma, a quote or a line
/// break (RFC 4180).
pub fn csv_field(s: &str) -> std::borrow::Cow<'_, str> {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\"")).into()
    } else {
        s.into()
    }
}

/// The fields of one line of CSV: split at commas outside quotes; a field that starts with `"` runs to
/// the next lone `"` (`""` inside it is one quote). `Err(k)`: field `k` (from 1) is badly quoted.
fn split_fields(line: &str) -> Result<Vec<String>, usize> {
    let mut fields = Vec::new();
    let mut chars = line.chars().peekable();
    loop {
        let k = fields.len() + 1;
        let mut field = String::new();
        if chars.peek() == Some(&'"') {
            chars.next();
            loop {
                match chars.next() {
                    None => return Err(k),
                    Some('"') if chars.peek() == Some(&'"') => {
                        chars.next();
                        field.push('"');
                    }
                    Some('"') => break,
                    Some(c) => field.push(c),
                }
            }
            match chars.next() {
                None => {
                    fields.push(field);
                    return Ok(fields);
                }
                Some(',') => fields.push(field),
                Some(_) => return Err(k),
            }
        } else {
            loop {
                match chars.next() {
                    None => {
                        fields.push(field);
                        return Ok(fields);
                    }
                    Some(',') => break,
                    Some('"') => return Err(k),
                    Some(c) => field.push(c),
                }
            }
            fields.push(field);
        }
    }
}

/// A CSV file a study wrote: its header and its rows, each with its line number, for errors that say
/// where.
pub struct CsvTable {
    path: PathBuf,
    header: Vec<String>,
    rows: Vec<(usize, Vec<String>)>,
}

/// What a value of a column must be, for error messages.
pub trait CsvValue: FromStr {
    const WHAT: &'static str;
}
impl CsvValue for f64 {
    const WHAT: &'static str = "a number";
}
impl CsvValue for u64 {
    const WHAT: &'static str = "a whole number";
}
impl CsvValue for usize {
    const WHAT: &'static str = "a whole number";
}

impl CsvTable {
    /// Reads and parses the CSV at `path`.
    pub fn read(path: &Path) -> Result<Self, CsvError> {
        let bytes = rtl_render::limits::read_regular_file(path, "the study's CSV", MAX_CSV_BYTES)
            .map_err(|message| CsvError::Read { message })?;
        let text = String::from_utf8(bytes).map_err(|e| CsvError::Read {
            message: format!(
                "{}: the study's CSV is not UTF-8 text (byte {})",
                path.display(),
                e.utf8_error().valid_up_to()
            ),
        })?;
        Self::parse(path, &text)
    }

    /// Parses `text`; `path` only names it in errors. Every row must have as many fields as the
    /// header.
    pub fn parse(path: &Path, text: &str) -> Result<Self, CsvError> {
        let path = path.to_path_buf();
        let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
        let header = match lines.next() {
            Some((_, h)) if !h.trim().is_empty() => {
                split_fields(h).map_err(|field| CsvError::Quote {
                    path: path.clone(),
                    line: 1,
                    field,
                })?
            }
            _ => return Err(CsvError::Empty { path }),
        };
        let mut rows = Vec::new();
        for (line, l) in lines {
            if l.trim().is_empty() {
                continue;
            }
            let fields = split_fields(l).map_err(|field| CsvError::Quote {
                path: path.clone(),
                line,
                field,
            })?;
            if fields.len() != header.len() {
                return Err(CsvError::FieldCount {
                    path,
                    line,
                    expected: header.len(),
                    found: fields.len(),
                });
            }
            rows.push((line, fields));
        }
        if rows.is_empty() {
            return Err(CsvError::NoRows { path });
        }
        Ok(Self { path, header, rows })
    }

    /// The index of the column called `name`.
    pub fn column(&self, name: &str) -> Result<usize, CsvError> {
        column_of(&self.path, &self.header, name)
    }

    /// The rows, in the file's order.
    pub fn rows(&self) -> impl Iterator<Item = CsvRow<'_>> {
        self.rows.iter().map(move |(line, fields)| CsvRow {
            table: self,
            line: *line,
            fields,
        })
    }
}

fn column_of(path: &Path, header: &[String], name: &str) -> Result<usize, CsvError> {
    header
        .iter()
        .position(|h| h == name)
        .ok_or_else(|| CsvError::MissingColumn {
            path: path.to_path_buf(),
            column: name.to_string(),
        })
}

/// One row of a [`CsvTable`].
pub struct CsvRow<'a> {
    table: &'a CsvTable,
    line: usize,
    fields: &'a [String],
}

impl CsvRow<'_> {
    /// The text of column `c`.
    pub fn text(&self, c: usize) -> &str {
        &self.fields[c]
    }

    /// Column `c` parsed as a `T`.
    pub fn value<T: CsvValue>(&self, c: usize) -> Result<T, CsvError> {
        self.fields[c].trim().parse().map_err(|_| CsvError::Value {
            path: self.table.path.clone(),
            line: self.line,
            field: c + 1,
            column: self.table.header[c].clone(),
            value: self.fields[c].clone(),
            expected: T::WHAT,
        })
    }

    /// Column `c` parsed as a `T`, or `None` where it is empty.
    pub fn optional<T: CsvValue>(&self, c: usize) -> Result<Option<T>, CsvError> {
        if self.fields[c].trim().is_empty() {
            Ok(None)
        } else {
            self.value(c).map(Some)
        }
    }

    /// An error about column `c` of this row.
    pub fn invalid(&self, c: usize, message: impl Into<String>) -> CsvError {
        CsvError::Invalid {
            path: self.table.path.clone(),
            line: self.line,
            field: c + 1,
            column: self.table.header[c].clone(),
            message: message.into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_fields_are_quoted_only_when_they_must_be_and_split_back() {
        assert_eq!(csv_field("uniform sphere"), "uniform sphere");
        assert_eq!(csv_field("cosine, both sides"), "\"cosine, both sides\"");
        assert_eq!(csv_field("a \"b\""), "\"a \"\"b\"\"\"");
        let line = ["x", "cosine, both sides", "a \"b\"", ""]
            .map(|f| csv_field(f).into_owned())
            .join(",");
        assert_eq!(
            split_fields(&line).unwrap(),
            ["x", "cosine, both sides", "a \"b\"", ""]
        );
        assert_eq!(split_fields("a,\"b"), Err(2));
        assert_eq!(split_fields("a,b\"c"), Err(2));
        assert_eq!(split_fields("\"a\"b,c"), Err(1));
    }

    #[test]
    fn a_bad_csv_is_an_error_naming_the_file_line_and_column() {
        let p = Path::new("dir/t.csv");
        let t = CsvTable::parse(p, "a,b\n1,2\n3,x\n").unwrap();
        let b = t.column("b").unwrap();
        let values: Vec<Result<f64, CsvError>> = t.rows().map(|r| r.value(b)).collect();
        assert_eq!(values[0].as_ref().unwrap(), &2.0);
        let e = values[1].as_ref().unwrap_err();
        assert_eq!(e.line(), Some(3));
        assert_eq!(
            e.to_string(),
            "dir/t.csv:3: field 2 (`b`): `x` is not a number"
        );
        let e = t.column("c").err().unwrap();
        assert_eq!(e.to_string(), "dir/t.csv:1: no column `c` in the header");
        let e = CsvTable::parse(p, "a,b\n1,2\n3\n").err().unwrap();
        assert_eq!(
            e.to_string(),
            "dir/t.csv:3: 1 fields, where the header has 2"
        );
        assert!(matches!(
            CsvTable::parse(p, ""),
            Err(CsvError::Empty { .. })
        ));
        assert!(matches!(
            CsvTable::parse(p, "a,b\n"),
            Err(CsvError::NoRows { .. })
        ));
        let e = CsvTable::read(Path::new("/nonexistent/rtl/t.csv"))
            .err()
            .unwrap();
        assert!(e.to_string().starts_with("/nonexistent/rtl/t.csv: "), "{e}");
        // Not a regular file: refused before a byte is read (a device or pipe could give bytes without
        // end), naming the path.
        for path in ["/dev/zero", "/"] {
            let e = CsvTable::read(Path::new(path)).err().unwrap();
            assert!(matches!(e, CsvError::Read { .. }), "{path}: {e}");
            assert!(e.to_string().starts_with(path), "{e}");
        }
        let dir = std::env::temp_dir().join(format!("rtl-csv-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let latin1 = dir.join("latin1.csv");
        std::fs::write(&latin1, b"a,b\n1,\xe9\n").unwrap();
        let e = CsvTable::read(&latin1).err().unwrap();
        assert!(e.to_string().contains("not UTF-8"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
