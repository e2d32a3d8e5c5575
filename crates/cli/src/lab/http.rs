//! The lab's HTTP/1.1, on `std::net`: one request per connection (`Connection: close`), read with
//! fixed limits and deadlines, so what a client declares or sends never decides how much memory or
//! time the lab spends on it:
//!
//! - the request line and headers: at most [`MAX_HEAD`] bytes (a fixed buffer) and [`MAX_HEADERS`]
//!   lines, within [`READ_TIMEOUT`] (else 414, 431 or 408);
//! - the body: the lab's requests carry none, so a `Content-Length` above [`MAX_BODY`] is refused with
//!   413 before a byte of it is read, a body of unknown length (`Transfer-Encoding`, e.g. chunked) with
//!   411, and a smaller one is read into a fixed buffer and thrown away;
//! - the answer: written within [`WRITE_TIMEOUT`]; then what the client still sends is read through a
//!   fixed buffer and thrown away for at most [`LINGER`] (so that closing does not reset the connection
//!   before the client has read the answer), and the connection is closed.
//!
//! Why not tiny_http (which the lab used at first): it drains an unread body on drop into a buffer
//! of the size the client declared (`Content-Length: 99999999999` aborted the process), reads a header
//! line of any length into memory, and stops accepting connections for good after one failed
//! `accept` (e.g. out of file descriptors). Routing is the caller's ([`super::server`]).

use std::io::{self, ErrorKind, Read, Write};
use std::net::{Shutdown, TcpStream};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

/// The longest request head (request line and headers) the lab reads.
pub const MAX_HEAD: usize = 32 * 1024;
/// The most header lines in a request.
pub const MAX_HEADERS: usize = 100;
/// The longest request body the lab reads (and throws away): its requests carry none.
pub const MAX_BODY: u64 = 1024;
/// Time for a client to send its request, head and body.
pub const READ_TIMEOUT: Duration = Duration::from_secs(10);
/// Time for a client to take its answer.
pub const WRITE_TIMEOUT: Duration = Duration::from_secs(30);
/// After the answer, how long what the client still sends is read and thrown away before closing.
pub const LINGER: Duration = Duration::from_secs(1);

/// A request as the routes see it.
#[derive(Debug, PartialEq)]
pub struct Request {
    pub method: String,
    /// The request target as sent: path and query (`/api/mc/run?n=4`), not decoded.
    pub target: String,
    /// The `Host` header, if any.
    pub host: Option<String>,
}

/// An answer. `Content-Length`, `Date` and `Connection: close` are added when it is written.
#[derive(Debug)]
pub struct Response {
    pub status: u16,
    pub headers: Vec<(&'static str, String)>,
    pub body: Vec<u8>,
}

/// Why a request was not read to the end.
#[derive(Debug, PartialEq)]
pub enum Refusal {
    /// Answer with this status and message (the caller words the body).
    Answer(u16, String),
    /// The client closed the connection, or it failed, before a request: nothing to answer.
    Gone,
}

fn refuse<T>(status: u16, message: impl Into<String>) -> Result<T, Refusal> {
    Err(Refusal::Answer(status, message.into()))
}

/// A connection whose every read and write must end by `deadline` (`ErrorKind::TimedOut` after it).
pub struct Timed<'a> {
    pub stream: &'a TcpStream,
    pub deadline: Instant,
}

impl Timed<'_> {
    fn remaining(&self) -> io::Result<Duration> {
        let left = self.deadline.saturating_duration_since(Instant::now());
        if left.is_zero() {
            Err(io::Error::new(ErrorKind::TimedOut, "deadline passed"))
        } else {
            Ok(left)
        }
    }
}

/// A read that timed out, whichever way the platform says so.
fn timed_out(e: &io::Error) -> bool {
    matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock)
}

impl Read for Timed<'_> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        self.stream.set_read_timeout(Some(self.remaining()?))?;
        let mut s = self.stream;
        s.read(buf).map_err(|e| {
            if timed_out(&e) {
                io::Error::new(ErrorKind::TimedOut, e)
            } else {
                e
            }
        })
    }
}

impl Write for Timed<'_> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.stream.set_write_timeout(Some(self.remaining()?))?;
        let mut s = self.stream;
        s.write(buf)
    }
    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

/// `read` that retries on `Interrupted` and turns errors into refusals: a timeout is a 408, anything
/// else means the client is gone.
fn read_some(r: &mut impl Read, buf: &mut [u8]) -> Result<usize, Refusal> {
    loop {
        match r.read(buf) {
            Ok(n) => return Ok(n),
            Err(e) if e.kind() == ErrorKind::Interrupted => continue,
            Err(e) if timed_out(&e) => {
                return refuse(
                    408,
                    format!(
                        "the request did not arrive within {} s",
                        READ_TIMEOUT.as_secs()
                    ),
                );
            }
            Err(_) => return Err(Refusal::Gone),
        }
    }
}

/// Where the head ends in `b` (just after its empty line), searching from `from`.
fn head_end(b: &[u8], from: usize) -> Option<usize> {
    (from..b.len()).find_map(|i| {
        if b[i] != b'\n' {
            None
        } else if b.get(i + 1) == Some(&b'\n') {
            Some(i + 2)
        } else if b.get(i + 1..i + 3) == Some(b"\r\n") {
            Some(i + 3)
        } else {
            None
        }
    })
}

/// A token of RFC 9110 (method names, header names).
fn is_token(s: &[u8]) -> bool {
    !s.is_empty()
        && s.iter()
            .all(|&c| c.is_ascii_alphanumeric() || b"!#$%&'*+-.^_`|~".contains(&c))
}

/// What the head says about the body.
#[derive(Debug, Default)]
struct Framing {
    content_length: Vec<Vec<u8>>,
    transfer_encoding: bool,
    expect: Option<Vec<u8>>,
}

/// The number of body bytes to read: at most `limit`, or a refusal (413 above it, 411 for a body of
/// unknown length, 400 for a malformed or ambiguous length). Nothing is allocated by the size.
fn body_length(f: &Framing, limit: u64) -> Result<u64, Refusal> {
    if f.transfer_encoding {
        if !f.content_length.is_empty() {
            return refuse(400, "both Transfer-Encoding and Content-Length");
        }
        return refuse(
            411,
            "a request body of unknown length (Transfer-Encoding): the lab's requests carry no body",
        );
    }
    let value = match f.content_length.as_slice() {
        [] => return Ok(0),
        [v] => v,
        _ => return refuse(400, "more than one Content-Length"),
    };
    // Digits only: `+5`, `-1`, ` 5`, `0x10`, `5, 5` are refused (`u64::from_str` would take `+5`).
    if value.is_empty() || !value.iter().all(u8::is_ascii_digit) {
        return refuse(
            400,
            format!(
                "Content-Length `{}` is not a number of bytes",
                String::from_utf8_lossy(value)
            ),
        );
    }
    // Past u64::MAX it is just as much too large.
    let n = value.iter().fold(0u64, |n, &d| {
        n.saturating_mul(10).saturating_add(u64::from(d - b'0'))
    });
    if n > limit {
        return refuse(
            413,
            format!(
                "a request body of {} bytes: the lab reads at most {limit} (its requests carry none)",
                String::from_utf8_lossy(value)
            ),
        );
    }
    Ok(n)
}

/// Read one request from `r` (a [`Timed`] connection, or any reader in tests): its head into a
/// fixed buffer of [`MAX_HEAD`] bytes, then its body, of at most `body_limit` bytes, thrown away.
/// `interim` receives `100 Continue` when the client waits for it before sending a body.
pub fn read_request(
    r: &mut impl Read,
    interim: &mut impl Write,
    body_limit: u64,
) -> Result<Request, Refusal> {
    let mut buf = vec![0u8; MAX_HEAD];
    let mut filled = 0;
    let end = loop {
        if filled == buf.len() {
            return if buf.contains(&b'\n') {
                refuse(431, format!("request head longer than {MAX_HEAD} bytes"))
            } else {
                refuse(414, format!("request line longer than {MAX_HEAD} bytes"))
            };
        }
        let n = read_some(r, &mut buf[filled..])?;
        if n == 0 {
            return if filled == 0 {
                Err(Refusal::Gone)
            } else {
                refuse(400, "the connection ended inside the request head")
            };
        }
        let from = filled.saturating_sub(2);
        filled += n;
        if let Some(end) = head_end(&buf[..filled], from) {
            break end;
        }
    };
    let mut lines = buf[..end]
        .split(|&c| c == b'\n')
        .map(|l| l.strip_suffix(b"\r").unwrap_or(l));
    let request_line = lines.next().unwrap_or_default();
    let (method, target) = request_line_parts(request_line)?;
    let mut framing = Framing::default();
    let mut hosts = Vec::new();
    let mut count = 0;
    for line in lines.filter(|l| !l.is_empty()) {
        count += 1;
        if count > MAX_HEADERS {
            return refuse(431, format!("more than {MAX_HEADERS} header lines"));
        }
        if line[0] == b' ' || line[0] == b'\t' {
            return refuse(400, "a header line folded onto the next (obsolete)");
        }
        let Some(colon) = line.iter().position(|&c| c == b':') else {
            return refuse(400, "a header line without a colon");
        };
        let name = &line[..colon];
        if !is_token(name) {
            return refuse(400, "a malformed header name");
        }
        let value = line[colon + 1..].trim_ascii().to_vec();
        match name.to_ascii_lowercase().as_slice() {
            b"host" => hosts.push(value),
            b"content-length" => framing.content_length.push(value),
            b"transfer-encoding" => framing.transfer_encoding = true,
            b"expect" => framing.expect = Some(value),
            _ => {}
        }
    }
    if hosts.len() > 1 {
        return refuse(400, "more than one Host header");
    }
    let length = body_length(&framing, body_limit)?;
    if let Some(expect) = &framing.expect {
        if !expect.eq_ignore_ascii_case(b"100-continue") {
            return refuse(417, "the only expectation the lab meets is 100-continue");
        }
        if length > 0 && filled == end {
            // The client waits for this before it sends the body; if it cannot be sent, the read
            // below fails and says so.
            let _ = interim.write_all(b"HTTP/1.1 100 Continue\r\n\r\n");
        }
    }
    // The body: what came with the head, then the rest, through a small fixed buffer.
    let mut left = length.saturating_sub((filled - end) as u64);
    let mut sink = [0u8; 512];
    while left > 0 {
        let want = sink.len().min(left as usize);
        match read_some(r, &mut sink[..want])? {
            0 => return refuse(400, "the connection ended inside the request body"),
            n => left -= n as u64,
        }
    }
    Ok(Request {
        method,
        target,
        host: hosts
            .pop()
            .map(|h| String::from_utf8_lossy(&h).into_owned()),
    })
}

/// `METHOD /target HTTP/1.x`, or a refusal.
fn request_line_parts(line: &[u8]) -> Result<(String, String), Refusal> {
    let parts: Vec<&[u8]> = line.split(|&c| c == b' ').collect();
    let [method, target, version] = parts.as_slice() else {
        return refuse(400, "a malformed request line");
    };
    match *version {
        b"HTTP/1.1" | b"HTTP/1.0" => {}
        [b'H', b'T', b'T', b'P', b'/', a, b'.', b] if a.is_ascii_digit() && b.is_ascii_digit() => {
            return refuse(505, "the lab speaks HTTP/1.0 and HTTP/1.1");
        }
        _ => return refuse(400, "a malformed request line"),
    }
    if !is_token(method) || method.len() > 32 {
        return refuse(400, "a malformed method");
    }
    // An absolute path, in visible ASCII (a query's other bytes come %-escaped).
    if target.first() != Some(&b'/') || !target.iter().all(|&c| c.is_ascii_graphic()) {
        return refuse(400, "a malformed request target: the lab takes /path?query");
    }
    // Both checked to be ASCII above.
    let text = |b: &[u8]| String::from_utf8_lossy(b).into_owned();
    Ok((text(method), text(target)))
}

fn reason(status: u16) -> &'static str {
    match status {
        100 => "Continue",
        200 => "OK",
        308 => "Permanent Redirect",
        400 => "Bad Request",
        403 => "Forbidden",
        404 => "Not Found",
        405 => "Method Not Allowed",
        408 => "Request Timeout",
        411 => "Length Required",
        413 => "Payload Too Large",
        414 => "URI Too Long",
        417 => "Expectation Failed",
        431 => "Request Header Fields Too Large",
        500 => "Internal Server Error",
        503 => "Service Unavailable",
        505 => "HTTP Version Not Supported",
        _ => "",
    }
}

/// An HTTP date (RFC 9110, IMF-fixdate): `Sun, 06 Nov 1994 08:49:37 GMT`.
pub fn http_date(t: SystemTime) -> String {
    let secs = t.duration_since(UNIX_EPOCH).map_or(0, |d| d.as_secs());
    let (days, s) = ((secs / 86_400) as i64, secs % 86_400);
    let (year, month, day) = crate::calendar::civil_from_days(days);
    const WEEKDAYS: [&str; 7] = ["Thu", "Fri", "Sat", "Sun", "Mon", "Tue", "Wed"];
    const MONTHS: [&str; 12] = [
        "Jan", "Feb", "Mar", "Apr", "May", "Jun", "Jul", "Aug", "Sep", "Oct", "Nov", "Dec",
    ];
    format!(
        "{}, {day:02} {} {year} {:02}:{:02}:{:02} GMT",
        WEEKDAYS[days.rem_euclid(7) as usize],
        MONTHS[(month - 1) as usize],
        s / 3600,
        s / 60 % 60,
        s % 60
    )
}

/// The answer's bytes: status line, headers (with `Content-Length`, `Date`, `Connection: close`),
/// and the body unless `head_only` (a HEAD request).
pub fn encode(r: &Response, head_only: bool) -> Vec<u8> {
    let mut out = format!(
        "HTTP/1.1 {} {}\r\nDate: {}\r\nConnection: close\r\nContent-Length: {}\r\n",
        r.status,
        reason(r.status),
        http_date(SystemTime::now()),
        r.body.len()
    );
    for (name, value) in &r.headers {
        out.push_str(&format!("{name}: {value}\r\n"));
    }
    out.push_str("\r\n");
    let mut out = out.into_bytes();
    if !head_only {
        out.extend_from_slice(&r.body);
    }
    out
}

/// Send `response` on `stream` and close it: within [`WRITE_TIMEOUT`], then [`linger`]. A client
/// that went away is not an error of ours.
pub fn answer(stream: TcpStream, response: &Response, head_only: bool) {
    let mut w = Timed {
        stream: &stream,
        deadline: Instant::now() + WRITE_TIMEOUT,
    };
    if w.write_all(&encode(response, head_only)).is_ok() {
        linger(stream);
    }
}

/// Close after the answer: no more writes (the client sees the end of the answer), then read and
/// throw away what the client still sends, through a fixed buffer, until it closes or for at most
/// [`LINGER`]. Closing a socket with unread bytes resets the connection, and a client still sending
/// (a body refused unread) could lose the answer it has not read yet; a second is time to read it.
fn linger(stream: TcpStream) {
    let _ = stream.shutdown(Shutdown::Write);
    let mut r = Timed {
        stream: &stream,
        deadline: Instant::now() + LINGER,
    };
    let mut sink = [0u8; 4096];
    while let Ok(1..) = r.read(&mut sink) {}
}

/// Answer at once, without reading the request (the lab is busy): written only if the socket takes
/// it at once, then what has already arrived is thrown away, without waiting, so closing does not
/// reset the connection. For the accepting thread, which must never wait on a client.
pub fn answer_now(stream: TcpStream, response: &Response) {
    if stream.set_nonblocking(true).is_err() {
        return;
    }
    let mut s = &stream;
    let _ = s.write_all(&encode(response, false));
    let _ = stream.shutdown(Shutdown::Write);
    let mut sink = [0u8; 4096];
    for _ in 0..16 {
        match s.read(&mut sink) {
            Ok(n) if n > 0 => {}
            _ => break,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A reader that hands out `data` and then, instead of an end, fails as `end` says.
    struct Then<'a> {
        data: &'a [u8],
        end: ErrorKind,
    }

    impl Read for Then<'_> {
        fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
            if self.data.is_empty() {
                return Err(io::Error::new(self.end, "no more"));
            }
            let n = buf.len().min(self.data.len());
            buf[..n].copy_from_slice(&self.data[..n]);
            self.data = &self.data[n..];
            Ok(n)
        }
    }

    /// A reader of endless `x`, counting what was taken from it.
    struct Endless(u64);

    impl Read for Endless {
        fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
            buf.fill(b'x');
            self.0 += buf.len() as u64;
            Ok(buf.len())
        }
    }

    fn read(raw: &[u8]) -> Result<Request, Refusal> {
        read_request(&mut &raw[..], &mut io::sink(), MAX_BODY)
    }

    fn status<T: std::fmt::Debug>(r: Result<T, Refusal>) -> u16 {
        match r {
            Err(Refusal::Answer(s, _)) => s,
            other => panic!("not refused: {other:?}"),
        }
    }

    #[test]
    fn a_plain_request_is_read() {
        let r = read(b"GET /api/mc/list?x=1 HTTP/1.1\r\nHost: 127.0.0.1:8017\r\n\r\n").unwrap();
        assert_eq!(
            r,
            Request {
                method: "GET".into(),
                target: "/api/mc/list?x=1".into(),
                host: Some("127.0.0.1:8017".into())
            }
        );
        // Bare LF line ends, no Host, a small body read and thrown away.
        let r = read(b"POST /api/render/clear HTTP/1.0\nContent-Length: 5\n\nhello").unwrap();
        assert_eq!((r.method.as_str(), r.host), ("POST", None));
    }

    #[test]
    fn declared_bodies_above_the_limit_are_refused_unread() {
        for cl in [
            "99999999999",
            "1025",
            "18446744073709551616",
            "99999999999999999999999",
        ] {
            let raw = format!("GET / HTTP/1.1\r\nContent-Length: {cl}\r\n\r\n");
            // An endless body behind the head: refused without reading any of it.
            let mut body = Endless(0);
            let mut r = raw.as_bytes().chain(&mut body);
            let refused = read_request(&mut r, &mut io::sink(), MAX_BODY);
            assert_eq!(status(refused), 413, "{cl}");
            assert!(
                body.0 <= MAX_HEAD as u64,
                "{cl}: read {} bytes of the body",
                body.0
            );
        }
        // At the limit: read to its end, no further.
        let raw = format!("POST / HTTP/1.1\r\nContent-Length: {MAX_BODY}\r\n\r\n");
        let mut body = Endless(0);
        let mut r = raw.as_bytes().chain(&mut body);
        assert!(read_request(&mut r, &mut io::sink(), MAX_BODY).is_ok());
        assert!(body.0 >= MAX_BODY);
    }

    #[test]
    fn a_too_large_limit_would_let_a_declared_body_through() {
        // The wrong setup: with no limit, the size check passes a client's 99999999999 and the
        // reader goes on reading (through its fixed buffer) what the client sends: the refusal
        // above is the limit's doing, and `MAX_BODY` is what keeps it.
        let raw = b"GET / HTTP/1.1\r\nContent-Length: 99999999999\r\n\r\n";
        let f = Framing {
            content_length: vec![b"99999999999".to_vec()],
            ..Framing::default()
        };
        assert_eq!(body_length(&f, u64::MAX), Ok(99_999_999_999));
        assert_eq!(status(body_length(&f, MAX_BODY)), 413);
        let mut r = raw.chain(Then {
            data: &[b'x'; 100_000],
            end: ErrorKind::TimedOut,
        });
        assert_eq!(status(read_request(&mut r, &mut io::sink(), u64::MAX)), 408);
    }

    #[test]
    fn bodies_of_unknown_or_malformed_length_are_refused() {
        let head = |h: &str| format!("POST /api/render/clear HTTP/1.1\r\n{h}\r\n\r\n");
        let mut chunked = head("Transfer-Encoding: chunked").into_bytes();
        chunked.extend_from_slice(b"FFFFFFFFFFFFFFFF\r\n");
        let mut r = chunked.chain(Endless(0));
        assert_eq!(status(read_request(&mut r, &mut io::sink(), MAX_BODY)), 411);
        for (h, want) in [
            ("Content-Length: +5", 400),
            ("Content-Length: -1", 400),
            ("Content-Length: 0x10", 400),
            ("Content-Length: 5, 5", 400),
            ("Content-Length:", 400),
            ("Content-Length: 1\r\nContent-Length: 1", 400),
            ("Content-Length: 0\r\nTransfer-Encoding: chunked", 400),
            ("Expect: 200-ok", 417),
            ("Host: a\r\nHost: b", 400),
        ] {
            assert_eq!(status(read(head(h).as_bytes())), want, "{h}");
        }
    }

    #[test]
    fn a_client_that_waits_is_told_to_continue() {
        let mut interim = Vec::new();
        let raw = b"POST / HTTP/1.1\r\nExpect: 100-continue\r\nContent-Length: 2\r\n\r\nok";
        // The head alone, then the body (as a client that waits sends it).
        let mut parts = (&raw[..raw.len() - 2]).chain(&b"ok"[..]);
        assert!(read_request(&mut parts, &mut interim, MAX_BODY).is_ok());
        assert_eq!(interim, b"HTTP/1.1 100 Continue\r\n\r\n");
    }

    #[test]
    fn heads_are_bounded_in_size_count_and_time() {
        // A request line, or a header line, that never ends: a fixed buffer, then 414 or 431.
        let mut r = (&b"GET /"[..]).chain(Endless(0));
        assert_eq!(status(read_request(&mut r, &mut io::sink(), MAX_BODY)), 414);
        let mut r = (&b"GET / HTTP/1.1\r\nX: "[..]).chain(Endless(0));
        assert_eq!(status(read_request(&mut r, &mut io::sink(), MAX_BODY)), 431);
        let many = format!(
            "GET / HTTP/1.1\r\n{}\r\n",
            "X: y\r\n".repeat(MAX_HEADERS + 1)
        );
        assert_eq!(status(read(many.as_bytes())), 431);
        // A client that stops sending: 408 (the connection's deadline ends its reads).
        let mut r = Then {
            data: b"GET / HTTP/1.1\r\n",
            end: ErrorKind::WouldBlock,
        };
        assert_eq!(status(read_request(&mut r, &mut io::sink(), MAX_BODY)), 408);
        let mut r = Then {
            data: b"POST / HTTP/1.1\r\nContent-Length: 9\r\n\r\nabc",
            end: ErrorKind::TimedOut,
        };
        assert_eq!(status(read_request(&mut r, &mut io::sink(), MAX_BODY)), 408);
        // One that closes: before a request, nothing to answer; inside one, 400.
        assert_eq!(read(b""), Err(Refusal::Gone));
        assert_eq!(status(read(b"GET / HTTP/1.1\r\n")), 400);
        assert_eq!(
            status(read(b"POST / HTTP/1.1\r\nContent-Length: 9\r\n\r\nabc")),
            400
        );
    }

    #[test]
    fn malformed_request_lines_are_refused() {
        for (raw, want) in [
            (&b"GET / HTTP/2.0\r\n\r\n"[..], 505),
            (b"GET / HTTP/1.1 x\r\n\r\n", 400),
            (b"GET /\r\n\r\n", 400),
            (b"GET  / HTTP/1.1\r\n\r\n", 400),
            (b"GET http://a/ HTTP/1.1\r\n\r\n", 400),
            (b"GET * HTTP/1.1\r\n\r\n", 400),
            (b"G(T / HTTP/1.1\r\n\r\n", 400),
            (b"GET /\x01 HTTP/1.1\r\n\r\n", 400),
            (b"GET / HTTP/1.1\r\n folded\r\n\r\n", 400),
            (b"GET / HTTP/1.1\r\nno colon\r\n\r\n", 400),
            (b"GET / HTTP/1.1\r\nbad name: x\r\n\r\n", 400),
        ] {
            assert_eq!(status(read(raw)), want, "{}", String::from_utf8_lossy(raw));
        }
    }

    #[test]
    fn answers_are_framed_and_dated() {
        assert_eq!(http_date(UNIX_EPOCH), "Thu, 01 Jan 1970 00:00:00 GMT");
        let t = UNIX_EPOCH + Duration::from_secs(784_111_777);
        assert_eq!(http_date(t), "Sun, 06 Nov 1994 08:49:37 GMT");
        let t = UNIX_EPOCH + Duration::from_secs(951_782_400); // a leap day
        assert_eq!(http_date(t), "Tue, 29 Feb 2000 00:00:00 GMT");
        let r = Response {
            status: 405,
            headers: vec![("Allow", "GET, HEAD".into())],
            body: b"{}".to_vec(),
        };
        let text = String::from_utf8(encode(&r, false)).unwrap();
        assert!(
            text.starts_with("HTTP/1.1 405 Method Not Allowed\r\n"),
            "{text}"
        );
        assert!(
            text.contains("\r\nContent-Length: 2\r\n") && text.contains("\r\nAllow: GET, HEAD\r\n")
        );
        assert!(text.contains("\r\nConnection: close\r\n") && text.ends_with("\r\n\r\n{}"));
        let head = String::from_utf8(encode(&r, true)).unwrap();
        assert!(head.contains("Content-Length: 2") && head.ends_with("\r\n\r\n"));
    }
}
