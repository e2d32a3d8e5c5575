//! A request's query string, validated: every parameter known, every value in its range, or a
//! [`BadRequest`] that names the parameter and what it accepts (answered with HTTP 400).

use std::fmt::Display;
use std::str::FromStr;

/// A refused request: the message goes back to the page with status 400, with the name of the
/// parameter it refuses when there is one (the page marks that field).
#[derive(Debug, thiserror::Error)]
#[error("{message}")]
pub struct BadRequest {
    pub message: String,
    pub parameter: Option<String>,
}

/// Shorthand for a refusal.
pub fn bad(msg: impl Into<String>) -> BadRequest {
    BadRequest {
        message: msg.into(),
        parameter: None,
    }
}

/// A refusal of the parameter `name`.
pub fn bad_param(name: &str, msg: impl Into<String>) -> BadRequest {
    BadRequest {
        message: msg.into(),
        parameter: Some(name.to_string()),
    }
}

/// The longest query string the lab reads.
pub const MAX_QUERY: usize = 2048;

/// The decoded `name=value` pairs of a query string.
#[derive(Debug, Default)]
pub struct Query {
    pairs: Vec<(String, String)>,
}

/// `%XX` and `+` decoding; refuses malformed escapes and non-UTF-8.
fn decode(s: &str) -> Result<String, BadRequest> {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'+' => out.push(b' '),
            b'%' => {
                // Two hex digits: `u8::from_str_radix` alone would take `+5` (a sign) as 5.
                let hex = b
                    .get(i + 1..i + 3)
                    .filter(|h| h.iter().all(u8::is_ascii_hexdigit))
                    .and_then(|h| std::str::from_utf8(h).ok())
                    .and_then(|h| u8::from_str_radix(h, 16).ok())
                    .ok_or_else(|| bad(format!("malformed %-escape in `{s}`")))?;
                out.push(hex);
                i += 2;
            }
            c => out.push(c),
        }
        i += 1;
    }
    String::from_utf8(out).map_err(|_| bad(format!("`{s}` is not UTF-8")))
}

impl Query {
    /// Parse `query` (without the `?`), refusing names outside `known` and repeated names.
    pub fn parse(query: &str, known: &[&str]) -> Result<Query, BadRequest> {
        if query.len() > MAX_QUERY {
            return Err(bad(format!(
                "query string of {} bytes; at most {MAX_QUERY}",
                query.len()
            )));
        }
        let mut pairs: Vec<(String, String)> = Vec::new();
        for part in query.split('&').filter(|p| !p.is_empty()) {
            let (name, value) = part.split_once('=').unwrap_or((part, ""));
            let (name, value) = (decode(name)?, decode(value)?);
            if !known.contains(&name.as_str()) {
                let takes = if known.is_empty() {
                    "this request takes none".to_string()
                } else {
                    format!("this request takes: {}", known.join(", "))
                };
                return Err(bad_param(
                    &name,
                    format!("unknown parameter `{name}`; {takes}"),
                ));
            }
            if pairs.iter().any(|(n, _)| *n == name) {
                return Err(bad_param(&name, format!("parameter `{name}` given twice")));
            }
            pairs.push((name, value));
        }
        Ok(Query { pairs })
    }

    fn get(&self, name: &str) -> Option<&str> {
        self.pairs
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_str())
    }

    /// A number in `[lo, hi]`, `default` if absent.
    pub fn number<T>(&self, name: &str, default: T, lo: T, hi: T) -> Result<T, BadRequest>
    where
        T: FromStr + PartialOrd + Display + Copy,
    {
        let Some(v) = self.get(name) else {
            return Ok(default);
        };
        match v.trim().parse::<T>() {
            // `!(x >= lo && x <= hi)` also refuses NaN.
            Ok(x) if x >= lo && x <= hi => Ok(x),
            _ => Err(bad_param(
                name,
                format!("`{name}={v}`: expected a number from {lo} to {hi}"),
            )),
        }
    }

    /// One of `choices`, `default` if absent.
    pub fn choice<'a>(
        &self,
        name: &str,
        default: &'a str,
        choices: &[&'a str],
    ) -> Result<&'a str, BadRequest> {
        let Some(v) = self.get(name) else {
            return Ok(default);
        };
        choices.iter().copied().find(|c| *c == v).ok_or_else(|| {
            bad_param(
                name,
                format!("`{name}={v}`: expected one of {}", choices.join(", ")),
            )
        })
    }

    /// A switch: `1`/`true`/`on` or `0`/`false`/`off`, `default` if absent.
    pub fn flag(&self, name: &str, default: bool) -> Result<bool, BadRequest> {
        match self.get(name) {
            None => Ok(default),
            Some("1" | "true" | "on") => Ok(true),
            Some("0" | "false" | "off") => Ok(false),
            Some(v) => Err(bad_param(name, format!("`{name}={v}`: expected 1 or 0"))),
        }
    }

    /// A string that must be present.
    pub fn required(&self, name: &str) -> Result<&str, BadRequest> {
        self.get(name)
            .ok_or_else(|| bad_param(name, format!("missing parameter `{name}`")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_refuses() {
        let q = Query::parse(
            "n=16&name=importance+p+%3D+x%2F2&on=1",
            &["n", "name", "on"],
        )
        .unwrap();
        assert_eq!(q.number("n", 0u64, 1, 100).unwrap(), 16);
        assert_eq!(q.required("name").unwrap(), "importance p = x/2");
        assert!(q.flag("on", false).unwrap());
        let refused = q.number("n", 0u64, 17, 100).unwrap_err();
        assert_eq!(refused.parameter.as_deref(), Some("n"));
        assert!(Query::parse("x=1", &["n"]).is_err());
        assert!(Query::parse("n=1&n=2", &["n"]).is_err());
        assert!(Query::parse("n=%zz", &["n"]).is_err());
        for escape in ["%+5", "%-5", "%5", "%", "%5g", "% 5"] {
            assert!(
                Query::parse(&format!("n={escape}"), &["n"]).is_err(),
                "{escape}"
            );
        }
        let q = Query::parse("n=%41%2b%2F", &["n"]).unwrap();
        assert_eq!(q.required("n").unwrap(), "A+/");
        let q = Query::parse("t=NaN", &["t"]).unwrap();
        assert!(q.number("t", 1.0f64, 0.0, 2.0).is_err());
        let q = Query::parse("s=mis", &["s"]).unwrap();
        assert!(q.choice("s", "uniform", &["uniform", "cosine"]).is_err());
    }
}
