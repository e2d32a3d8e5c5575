//! `rtl lab` over plain HTTP: the page is served from the binary, every bad parameter is refused with
//! a 400 that names it (and the server lives on), hostile request bodies are refused without being
//! read (and the server lives on), a port in use is a clear error, `--bind` beyond loopback warns, and
//! the render stops when nobody watches. Each test starts its own `rtl lab
//! --port 0` as a child process and bounds every wait.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::{TcpListener, TcpStream};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// A running `rtl lab`, killed when dropped.
struct Lab {
    child: Child,
    port: u16,
    _dir: TempDir,
}

struct TempDir(std::path::PathBuf);

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn temp_dir(tag: &str) -> TempDir {
    let d = std::env::temp_dir().join(format!("rtl-lab-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    TempDir(d)
}

impl Drop for Lab {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The exit status of `child`, which must end within `limit` (else it is killed and the test fails
/// with `what`).
fn wait_exit(child: &mut Child, limit: Duration, what: &str) -> std::process::ExitStatus {
    let start = Instant::now();
    loop {
        if let Some(s) = child.try_wait().unwrap() {
            return s;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            panic!("{what}");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

fn rtl() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rtl"))
}

/// The first line `child` prints on its (piped) stdout, waiting at most a minute.
fn first_line(child: &mut Child) -> Option<String> {
    let stdout = child.stdout.take().expect("a piped stdout");
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let mut line = String::new();
        let _ = BufReader::new(stdout).read_line(&mut line);
        let _ = tx.send(line);
    });
    rx.recv_timeout(Duration::from_secs(60)).ok()
}

/// Start `rtl lab --port 0 ...` and read the port from the URL it prints.
fn start(tag: &str, extra: &[&str]) -> Lab {
    let dir = temp_dir(tag);
    let mut child = rtl()
        .args([
            "lab",
            "--port",
            "0",
            "--width",
            "16",
            "--reference-spp",
            "16",
        ])
        .arg("--reference-dir")
        .arg(&dir.0)
        .args(extra)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("rtl runs");
    let line = first_line(&mut child).expect("rtl lab prints its URL");
    let port = line
        .split("http://127.0.0.1:")
        .nth(1)
        .and_then(|r| r.split('/').next())
        .and_then(|p| p.parse().ok())
        .unwrap_or_else(|| panic!("no URL in {line:?}"));
    Lab {
        child,
        port,
        _dir: dir,
    }
}

struct Reply {
    status: u16,
    headers: String,
    body: Vec<u8>,
}

impl Reply {
    fn text(&self) -> String {
        String::from_utf8_lossy(&self.body).into_owned()
    }
}

impl Lab {
    fn request_with_host(&self, method: &str, path: &str, host: &str) -> Reply {
        let mut s = TcpStream::connect(("127.0.0.1", self.port)).expect("connects");
        s.set_read_timeout(Some(Duration::from_secs(60))).unwrap();
        write!(
            s,
            "{method} {path} HTTP/1.1\r\nHost: {host}\r\nConnection: close\r\nContent-Length: 0\r\n\r\n"
        )
        .unwrap();
        let mut raw = Vec::new();
        s.read_to_end(&mut raw).expect("an answer");
        let split = raw
            .windows(4)
            .position(|w| w == b"\r\n\r\n")
            .expect("a header");
        let headers = String::from_utf8_lossy(&raw[..split]).into_owned();
        let status = headers
            .split_whitespace()
            .nth(1)
            .and_then(|c| c.parse().ok())
            .expect("a status");
        Reply {
            status,
            headers,
            body: raw[split + 4..].to_vec(),
        }
    }

    fn request(&self, method: &str, path: &str) -> Reply {
        self.request_with_host(method, path, &format!("127.0.0.1:{}", self.port))
    }

    fn get(&self, path: &str) -> Reply {
        self.request("GET", path)
    }
}

/// The text after `"key":` in a JSON text, to the next `,` or `}` (enough for these flat answers).
fn field<'a>(json: &'a str, key: &str) -> &'a str {
    let pat = format!("\"{key}\":");
    let at = json.find(&pat).unwrap_or_else(|| panic!("{key} in {json}")) + pat.len();
    let rest = &json[at..];
    &rest[..rest.find([',', '}']).unwrap_or(rest.len())]
}

/// The number after `"key":` in a JSON text (enough for these flat answers).
fn number(json: &str, key: &str) -> f64 {
    let pat = format!("\"{key}\":");
    let at = json.find(&pat).unwrap_or_else(|| panic!("{key} in {json}")) + pat.len();
    let rest = &json[at..];
    let end = rest
        .find(|c: char| !(c.is_ascii_digit() || ".-+eE".contains(c)))
        .unwrap_or(rest.len());
    rest[..end]
        .parse()
        .unwrap_or_else(|_| panic!("{key} in {json}"))
}

#[test]
fn the_page_comes_from_the_binary() {
    let book = concat!(env!("CARGO_MANIFEST_DIR"), "/../../book/book");
    let lab = start("page", &["--book-dir", book]);
    let page = lab.get("/");
    assert_eq!(page.status, 200);
    let html = page.text();
    assert!(html.contains("rtl lab") && html.contains("/lab.js"));
    assert!(!html.contains("http://") && !html.contains("https://"));
    assert!(
        page.headers
            .contains("Content-Security-Policy: default-src 'self'")
    );
    for asset in ["/lab.js", "/lab.css", "/favicon.ico"] {
        let r = lab.get(asset);
        assert_eq!(r.status, 200, "{asset}");
        assert!(!r.body.is_empty());
    }
    assert!(!lab.get("/lab.js").text().contains("https://"));
    // The heat colours come from the server (the Rust colour map), not from a copy in the script.
    let heat = lab.get("/api/heat");
    assert_eq!(heat.status, 200, "{}", heat.text());
    let colours = heat.text();
    assert_eq!(colours.matches("],[").count() + 1, 256, "{colours}");
    assert!(!lab.get("/lab.js").text().contains("0.05, 0.03, 0.25"));
    assert_eq!(lab.get("/nope").status, 404);
    // The benches link to the book's chapters: the built page, or else the chapter's source.
    let chapter = lab.get("/book/ch02-a-simple-monte-carlo-program.html");
    assert_eq!(chapter.status, 200);
    assert!(chapter.text().contains("A Simple Monte Carlo Program"));
    assert_eq!(lab.get("/book/ch99-none.html").status, 404);
    assert_eq!(lab.get("/?x=1").status, 400);
    // The book's pages link relatively: /book is /book/.
    let r = lab.get("/book");
    assert_eq!(r.status, 308, "{}", r.text());
    assert!(r.headers.contains("\r\nLocation: /book/"), "{}", r.headers);
    // The page asks for what the server takes: the mixture weight's step makes the book's 0.5 a
    // valid value, and no field has a fixed width in pixels that a phone cannot show.
    assert!(html.contains(r#"id="c-weight" type="number" min="0.01" max="0.99" step="0.01""#));
    assert!(html.contains(r#"id="mc-max" type="number" min="4" max="20""#));
    assert!(html.contains(r#"role="tablist""#) && html.contains(r#"aria-selected="true""#));
    let css = lab.get("/lab.css").text();
    assert!(!css.contains("width: 380px") && !css.contains("width: 600px"));
}

#[test]
fn a_missing_page_of_a_built_book_is_its_404_page() {
    // A stand-in for `mdbook build book`: a page and the 404 page mdBook writes beside it.
    let built = temp_dir("built-book");
    std::fs::write(built.0.join("index.html"), "<h1>the book</h1>").unwrap();
    std::fs::write(
        built.0.join("404.html"),
        "<h1>Document not found (404)</h1>",
    )
    .unwrap();
    let lab = start("book404", &["--book-dir", built.0.to_str().unwrap()]);
    assert_eq!(lab.get("/book/").status, 200);
    for missing in ["/book/ch99-none.html", "/book/part/deeper/page.html"] {
        let r = lab.get(missing);
        assert_eq!(r.status, 404, "{missing}");
        assert!(r.text().contains("Document not found"), "{missing}");
        assert!(r.headers.contains("text/html"), "{missing}");
    }
}

#[test]
fn every_bad_parameter_is_refused_with_a_message() {
    let lab = start("bad", &[]);
    let long = format!("/api/mc/run?integral={}", "x".repeat(5000));
    let cases: &[(&str, &str, &str)] = &[
        (
            "GET",
            "/api/mc/run?integral=x_sq&estimator=uniform&log2_n=99",
            "log2_n",
        ),
        (
            "GET",
            "/api/mc/run?integral=x_sq&estimator=uniform&log2_n=abc",
            "log2_n",
        ),
        (
            "GET",
            "/api/mc/run?integral=nope&estimator=uniform",
            "integral",
        ),
        (
            "GET",
            "/api/mc/run?integral=x_sq&estimator=nope",
            "estimator",
        ),
        ("GET", "/api/mc/run?integral=x_sq", "estimator"),
        (
            "GET",
            "/api/mc/run?integral=x_sq&estimator=uniform&log2_n=5&log2_n=6",
            "twice",
        ),
        ("GET", "/api/mc/run?integral=%zz", "escape"),
        ("GET", &long, "at most"),
        (
            "GET",
            "/api/mc/list?x=1",
            "unknown parameter `x`; this request takes none",
        ),
        ("GET", "/api/heat?x=1", "unknown parameter"),
        ("GET", "/api/sampling/line?samples=999999999", "samples"),
        ("GET", "/api/sampling/line?samples=-5", "samples"),
        ("GET", "/api/sampling/line?n=1", "`n=1`"),
        ("GET", "/api/sampling/line?n=100000000", "`n="),
        ("GET", "/api/sampling/line?bins=100000", "bins"),
        (
            "GET",
            "/api/sampling/line?method=numeric&samples=300000",
            "numerical inversion",
        ),
        ("GET", "/api/sampling/line?tolerance=NaN", "tolerance"),
        ("GET", "/api/sampling/line?tolerance=0", "tolerance"),
        ("GET", "/api/sampling/line?density=nope", "density"),
        ("GET", "/api/sampling/line?method=quicksort", "method"),
        (
            "GET",
            "/api/sampling/line?density=book_sin2&method=analytic",
            "analytic",
        ),
        ("GET", "/api/sampling/sphere?cells=1000", "cells"),
        ("GET", "/api/sampling/sphere?pdf=nope", "pdf"),
        ("GET", "/api/sampling/sphere?seed=-1", "seed"),
        ("POST", "/api/render/settings?width=100000", "width"),
        ("POST", "/api/render/settings?width=0", "width"),
        ("POST", "/api/render/settings?strategy=best", "strategy"),
        ("POST", "/api/render/settings?seed=-1", "seed"),
        ("POST", "/api/render/settings?max_depth=0", "max_depth"),
        ("POST", "/api/render/settings?rr=maybe", "rr"),
        (
            "POST",
            "/api/render/settings?mixture_weight=1",
            "mixture_weight=1",
        ),
        (
            "POST",
            "/api/render/settings?mixture_weight=0",
            "mixture_weight=0",
        ),
        (
            "POST",
            "/api/render/settings?mixture_weight=NaN",
            "mixture_weight",
        ),
        (
            "POST",
            "/api/render/settings?mixture_weight=-0.5",
            "mixture_weight",
        ),
        (
            "POST",
            "/api/render/settings?mixture_weight=half",
            "mixture_weight",
        ),
        (
            "POST",
            "/api/render/settings?colour=red",
            "unknown parameter",
        ),
        ("GET", "/api/render/image?kind=depth", "kind"),
        ("GET", "/api/render/state?peek=2", "peek"),
        ("GET", "/book/../Cargo.toml", "not a page"),
        ("GET", "/book/.hidden", "not a page"),
    ];
    for (method, path, names) in cases {
        let r = lab.request(method, path);
        let text = r.text();
        assert_eq!(r.status, 400, "{method} {path}: {text}");
        assert!(
            text.starts_with("{\"error\":") && text.contains(names),
            "{method} {path}: {text} should name {names}"
        );
    }
    // Wrong methods (405, with the methods the path takes) and hosts.
    assert_eq!(lab.get("/api/render/settings?width=32").status, 405);
    let r = lab.request("POST", "/api/mc/run");
    assert_eq!(r.status, 405);
    assert!(r.headers.contains("\r\nAllow: GET, HEAD"), "{}", r.headers);
    let r = lab.request("DELETE", "/");
    assert_eq!(r.status, 405, "{}", r.text());
    assert!(r.headers.contains("\r\nAllow: GET, HEAD"), "{}", r.headers);
    let r = lab.get("/api/render/clear");
    assert!(r.status == 405 && r.headers.contains("\r\nAllow: POST"));
    assert_eq!(lab.request("DELETE", "/nope").status, 404);
    // A %-escape is two hex digits: `%+5` is not byte 5.
    let r = lab.get("/api/mc/run?integral=%+5&estimator=uniform");
    assert!(
        r.status == 400 && r.text().contains("escape"),
        "{}",
        r.text()
    );
    let r = lab.request_with_host("GET", "/api/mc/list", "evil.example:80");
    assert_eq!(r.status, 403, "{}", r.text());
    // Still alive and answering well-formed requests after all that.
    assert_eq!(lab.get("/").status, 200);
    let r = lab.get("/api/mc/run?integral=x_sq&estimator=uniform&log2_n=8");
    assert_eq!(r.status, 200, "{}", r.text());
    assert_eq!(number(&r.text(), "n"), 256.0);
    let r = lab.get("/api/sampling/line?density=linear&method=analytic&samples=1000&bins=10");
    assert_eq!(r.status, 200, "{}", r.text());
    let r = lab.get("/api/sampling/sphere?pdf=cosine&samples=1000&cells=4");
    assert_eq!(r.status, 200, "{}", r.text());
}

/// The status of the answer to `head`, sent raw; with `endless`, the head announces a chunked body
/// and a thread of its own sends chunks for as long as the server takes them (up to 1 GiB or 30 s).
/// An error if the connection or the answer fails.
fn raw_status(port: u16, head: &str, endless: bool) -> Result<u16, String> {
    let mut s = TcpStream::connect(("127.0.0.1", port)).map_err(|e| format!("connect: {e}"))?;
    s.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    s.set_write_timeout(Some(Duration::from_secs(30))).unwrap();
    s.write_all(head.as_bytes())
        .map_err(|e| format!("sending {head:?}: {e}"))?;
    let writer = endless.then(|| {
        let mut w = s.try_clone().unwrap();
        std::thread::spawn(move || {
            let mut chunk = b"1000\r\n".to_vec();
            chunk.extend_from_slice(&[b'x'; 0x1000]);
            chunk.extend_from_slice(b"\r\n");
            let start = Instant::now();
            let mut sent = 0u64;
            while sent < 1 << 30 && start.elapsed() < Duration::from_secs(30) {
                if w.write_all(&chunk).is_err() {
                    break;
                }
                sent += chunk.len() as u64;
            }
            sent
        })
    });
    // The status line is enough (a connection reset after it, by a server that stopped reading a
    // body, is no failure of the request).
    let mut raw = Vec::new();
    let mut buf = [0u8; 1024];
    while !raw.windows(2).any(|w| w == b"\r\n") {
        match s.read(&mut buf) {
            Ok(0) => break,
            Ok(n) => raw.extend_from_slice(&buf[..n]),
            Err(e) => return Err(format!("answer to {head:?}: {e}")),
        }
    }
    drop(s);
    if let Some(w) = writer {
        w.join().unwrap();
    }
    let line = String::from_utf8_lossy(&raw);
    line.strip_prefix("HTTP/1.1 ")
        .and_then(|r| r.get(..3))
        .and_then(|c| c.parse().ok())
        .ok_or_else(|| format!("no status in the answer to {head:?}: {line:?}"))
}

/// The hostile-input round: bodies declared far too large (GET and POST, no body sent) and a chunked
/// body that never ends must each get a 4xx (413 for a declared length), and the server must still
/// answer a plain request afterwards.
fn hostile_round(port: u16) -> Result<(), String> {
    let host = format!("Host: 127.0.0.1:{port}\r\n");
    let rounds = [
        (
            format!("GET /api/mc/list HTTP/1.1\r\n{host}Content-Length: 99999999999\r\n\r\n"),
            false,
            Some(413),
        ),
        (
            format!("POST /api/render/clear HTTP/1.1\r\n{host}Content-Length: 99999999999\r\n\r\n"),
            false,
            Some(413),
        ),
        (
            format!(
                "POST /api/render/settings HTTP/1.1\r\n{host}Transfer-Encoding: chunked\r\n\r\n"
            ),
            true,
            None,
        ),
    ];
    for (head, endless, want) in &rounds {
        let status = raw_status(port, head, *endless)?;
        let ok = match want {
            Some(w) => status == *w,
            None => (400..500).contains(&status),
        };
        if !ok {
            return Err(format!(
                "{status} to {head:?}; expected {want:?} (or a 4xx)"
            ));
        }
    }
    std::thread::sleep(Duration::from_millis(200));
    let plain = format!("GET / HTTP/1.1\r\n{host}Connection: close\r\n\r\n");
    match raw_status(port, &plain, false) {
        Ok(200) => Ok(()),
        other => Err(format!("after the hostile requests, GET / gave {other:?}")),
    }
}

#[test]
fn hostile_bodies_are_refused_and_the_lab_lives_on() {
    let mut lab = start("hostile", &[]);
    for round in 0..2 {
        hostile_round(lab.port).unwrap_or_else(|e| panic!("round {round}: {e}"));
        assert!(lab.child.try_wait().unwrap().is_none(), "rtl lab exited");
    }
    // The refusals are the lab's JSON, and say why.
    let mut s = TcpStream::connect(("127.0.0.1", lab.port)).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    write!(
        s,
        "POST /api/render/clear HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nContent-Length: 18446744073709551616\r\n\r\n",
        lab.port
    )
    .unwrap();
    let mut answer = String::new();
    s.read_to_string(&mut answer).unwrap();
    assert!(answer.starts_with("HTTP/1.1 413 "), "{answer}");
    assert!(
        answer.contains("{\"error\":") && answer.contains("at most 1024"),
        "{answer}"
    );
    // A weight far from 0.5 is labelled readably (not 0.000...0001).
    let r = lab.request(
        "POST",
        "/api/render/settings?strategy=mixture&mixture_weight=1e-320",
    );
    assert_eq!(r.status, 200, "{}", r.text());
    assert!(
        r.text().contains("\"label\":\"mixture w=1e-320 seed"),
        "{}",
        r.text()
    );
    assert_eq!(lab.get("/").status, 200);
}

/// A stand-in server for [`hostile_round`]'s own test: answers every request (no body read) with
/// 200, or, when `refuses`, with the statuses the round asks for; when `dies`, it stops listening
/// after answering a declared length of 99999999999, as the lab did when tiny_http aborted it.
fn fake_server(refuses: bool, dies: bool) -> u16 {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let port = listener.local_addr().unwrap().port();
    std::thread::spawn(move || {
        for stream in listener.incoming() {
            let Ok(mut stream) = stream else { continue };
            stream
                .set_read_timeout(Some(Duration::from_secs(10)))
                .unwrap();
            let mut head = Vec::new();
            let mut byte = [0u8];
            while !head.ends_with(b"\r\n\r\n") && stream.read(&mut byte).unwrap_or(0) == 1 {
                head.push(byte[0]);
            }
            let head = String::from_utf8_lossy(&head).into_owned();
            let huge = head.contains("Content-Length: 99999999999");
            let status = match (refuses, huge, head.contains("chunked")) {
                (true, true, _) => 413,
                (true, _, true) => 411,
                _ => 200,
            };
            let _ = write!(
                stream,
                "HTTP/1.1 {status} X\r\nContent-Length: 0\r\nConnection: close\r\n\r\n"
            );
            if dies && huge {
                return;
            }
            // As the lab does: read what is still coming for a while, so that closing does not
            // reset the connection before the client has read the answer.
            let _ = stream.shutdown(std::net::Shutdown::Write);
            let until = Instant::now() + Duration::from_secs(1);
            let mut sink = [0u8; 4096];
            while Instant::now() < until && stream.read(&mut sink).is_ok_and(|n| n > 0) {}
        }
    });
    port
}

#[test]
fn the_hostile_round_fails_against_a_server_that_dies_or_takes_the_body() {
    // The round passes a server that refuses and lives on...
    hostile_round(fake_server(true, false)).unwrap();
    // ... and fails one that refuses but then dies, one that takes the body, and the unfixed lab's
    // behaviour: answer 200, then abort.
    for (refuses, dies) in [(true, true), (false, false), (false, true)] {
        let r = hostile_round(fake_server(refuses, dies));
        assert!(r.is_err(), "refuses {refuses}, dies {dies}: passed");
    }
}

#[test]
fn the_render_restarts_on_a_change_and_stops_when_nobody_watches() {
    let lab = start("render", &[]);
    let r = lab.request(
        "POST",
        "/api/render/settings?strategy=cosine&width=16&seed=3",
    );
    assert_eq!(r.status, 200, "{}", r.text());
    let generation = number(&r.text(), "generation");
    let start = Instant::now();
    let spp = loop {
        // Watching (no peek): the worker renders.
        let s = lab.get("/api/render/state").text();
        let frame = &s[s.find("\"frame\"").unwrap()..];
        if number(frame, "generation") == generation && number(frame, "spp") >= 2.0 {
            break number(frame, "spp");
        }
        assert!(start.elapsed() < Duration::from_secs(60), "no frame: {s}");
        std::thread::sleep(Duration::from_millis(50));
    };
    assert!(spp >= 2.0);
    let png = lab.get("/api/render/image?kind=image");
    assert_eq!(png.status, 200);
    assert!(png.body.starts_with(b"\x89PNG"));
    assert!(png.headers.contains("image/png"));
    let png = lab.get("/api/render/image?kind=variance");
    assert!(png.body.starts_with(b"\x89PNG"));
    // Nobody watches (peeks do not count): within a few seconds the render stops.
    let start = Instant::now();
    loop {
        let s = lab.get("/api/render/state?peek=1").text();
        if s.contains("\"rendering\":false") {
            break;
        }
        assert!(start.elapsed() < Duration::from_secs(30), "still rendering");
        std::thread::sleep(Duration::from_millis(200));
    }
    let spp_of = || {
        let s = lab.get("/api/render/state?peek=1").text();
        number(&s[s.find("\"frame\"").unwrap()..], "spp")
    };
    let stopped = spp_of();
    std::thread::sleep(Duration::from_millis(1000));
    assert_eq!(spp_of(), stopped, "the render went on with nobody watching");
    // Alone on the cores now: a Monte Carlo answer says so; while the render runs, it says that
    // the cores were shared (its times are slower).
    let mc = "/api/mc/run?integral=x_sq&estimator=uniform&log2_n=6";
    let r = lab.get(mc);
    assert!(r.text().contains("\"shared_cores\":false"), "{}", r.text());
    lab.get("/api/render/state");
    let r = lab.get(mc);
    assert!(r.text().contains("\"shared_cores\":true"), "{}", r.text());
}

#[test]
fn a_port_in_use_is_a_clear_error() {
    let taken = TcpListener::bind("127.0.0.1:0").unwrap();
    let port = taken.local_addr().unwrap().port().to_string();
    let mut child = rtl()
        .args(["lab", "--port", &port])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let status = wait_exit(
        &mut child,
        Duration::from_secs(60),
        "rtl lab did not stop on a port in use",
    );
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    assert!(!status.success());
    assert!(
        err.contains(&format!("port {port}")) && err.contains("in use") && err.contains("--port 0"),
        "{err}"
    );
    drop(taken);
}

#[test]
fn binding_beyond_loopback_warns() {
    let dir = temp_dir("bind");
    let mut child = rtl()
        .args(["lab", "--port", "0", "--bind", "0.0.0.0", "--reference-dir"])
        .arg(&dir.0)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let line = first_line(&mut child);
    let _ = child.kill();
    let _ = child.wait();
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    assert!(line.expect("a URL").contains("http://127.0.0.1:"));
    assert!(err.contains("warning") && err.contains("0.0.0.0"), "{err}");
}

/// The state of the render (watching: the render goes on).
fn state(lab: &Lab) -> String {
    let r = lab.get("/api/render/state");
    assert_eq!(r.status, 200, "{}", r.text());
    r.text()
}

/// The `"settings":{...}` object of a state.
fn settings_of(state: &str) -> &str {
    let at = state.find("\"settings\":").expect("settings");
    &state[at..at + state[at..].find('}').unwrap()]
}

/// The points `(seconds, spp, rmse)` of the curve labelled `label` in a state, if there is one.
fn curve(state: &str, label: &str) -> Option<Vec<(f64, u64, f64)>> {
    let curves = &state[state.find("\"curves\":").expect("curves")..];
    let curves = &curves[..curves.find("\"floors\":").expect("floors after curves")];
    let at = curves.find(&format!("\"label\":\"{label}\""))?;
    let rest = &curves[at..];
    let points = &rest[rest.find("\"points\":[").unwrap() + 10..];
    let points = &points[..points.find("]]").map_or(0, |e| e + 1)];
    Some(
        points
            .split("],[")
            .filter(|p| !p.is_empty())
            .map(|p| {
                let v: Vec<&str> = p.trim_matches(['[', ']']).split(',').collect();
                (
                    v[0].parse().unwrap(),
                    v[1].parse().unwrap(),
                    v[2].parse().unwrap(),
                )
            })
            .collect(),
    )
}

/// Poll the state (watching) until `what` holds, for at most a minute.
fn wait_for(lab: &Lab, what: &str, ok: impl Fn(&str) -> bool) -> String {
    let start = Instant::now();
    loop {
        let s = state(lab);
        if ok(&s) {
            return s;
        }
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "waited a minute for {what}: {s}"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
}

#[test]
fn a_refused_setting_blocks_no_other_and_names_its_parameter() {
    let lab = start("refused", &[]);
    // Refused: a 400 that names the parameter (the page marks that field) ...
    let r = lab.request(
        "POST",
        "/api/render/settings?strategy=mixture&mixture_weight=1",
    );
    assert_eq!(r.status, 400, "{}", r.text());
    assert!(
        r.text().contains("\"parameter\":\"mixture_weight\""),
        "{}",
        r.text()
    );
    // ... and nothing of that request is taken (not even its valid strategy).
    let s = state(&lab);
    assert_eq!(field(settings_of(&s), "strategy"), "\"mis\"", "{s}");
    // Each parameter alone: one field's change is one parameter, and the others stay as they are
    // (another tab's strategy is not undone by this tab's seed).
    for (query, key, value) in [
        ("strategy=light", "strategy", "\"light\""),
        ("seed=5", "seed", "5"),
        ("max_depth=7", "max_depth", "7"),
    ] {
        let r = lab.request("POST", &format!("/api/render/settings?{query}"));
        assert_eq!(r.status, 200, "{query}: {}", r.text());
        assert_eq!(field(settings_of(&r.text()), key), value, "{}", r.text());
    }
    let s = state(&lab);
    let settings = settings_of(&s);
    assert_eq!(field(settings, "strategy"), "\"light\"", "{s}");
    assert_eq!(field(settings, "seed"), "5", "{s}");
    assert_eq!(field(settings, "max_depth"), "7", "{s}");
    for (query, parameter) in [
        ("width=100000", "width"),
        ("seed=-1", "seed"),
        ("rr=maybe", "rr"),
        ("strategy=best", "strategy"),
    ] {
        let r = lab.request("POST", &format!("/api/render/settings?{query}"));
        assert_eq!(r.status, 400, "{query}");
        assert!(
            r.text().contains(&format!("\"parameter\":\"{parameter}\"")),
            "{query}: {}",
            r.text()
        );
    }
    assert_eq!(field(settings_of(&state(&lab)), "width"), "16");
    // The same settings again change nothing (no restart), nor does a weight that only `mixture`
    // uses.
    let g = number(
        &lab.request("POST", "/api/render/settings?seed=6").text(),
        "generation",
    );
    for same in ["seed=6", "mixture_weight=0.3"] {
        let r = lab.request("POST", &format!("/api/render/settings?{same}"));
        assert_eq!(number(&r.text(), "generation"), g, "{same}: {}", r.text());
    }
}

#[test]
fn every_setting_keeps_its_curve_and_clear_clears_them_all() {
    let lab = start("curves", &[]);
    let cosine = "cosine seed 1 16px";
    let r = lab.request("POST", "/api/render/settings?strategy=cosine");
    assert_eq!(r.status, 200, "{}", r.text());
    let s = wait_for(&lab, "a cosine curve of 3 points", |s| {
        curve(s, cosine).is_some_and(|c| c.len() >= 3)
    });
    let before = curve(&s, cosine).unwrap();
    // Another setting, long enough for its curve; then cosine again: its render continues where it
    // stopped, its curve with it (the old points kept, new ones after them).
    lab.request("POST", "/api/render/settings?strategy=uniform");
    wait_for(&lab, "a uniform curve", |s| {
        curve(s, "uniform seed 1 16px").is_some_and(|c| c.len() >= 2)
    });
    let g = number(
        &lab.request("POST", "/api/render/settings?strategy=cosine")
            .text(),
        "generation",
    );
    let s = wait_for(&lab, "a frame of cosine again", |s| {
        let frame = &s[s.find("\"frame\"").unwrap()..];
        number(frame, "generation") == g
    });
    let frame = &s[s.find("\"frame\"").unwrap()..];
    assert_eq!(field(frame, "resumed"), "true", "{s}");
    assert!(
        number(frame, "spp") > before.last().unwrap().1 as f64,
        "{s}"
    );
    let s = wait_for(&lab, "the cosine curve to go on", |s| {
        curve(s, cosine).is_some_and(|c| c.len() > before.len())
    });
    let after = curve(&s, cosine).unwrap();
    assert_eq!(after[..before.len()], before[..], "the old points are kept");
    assert!(after.windows(2).all(|w| w[0].0 < w[1].0 && w[0].1 < w[1].1));
    assert!(curve(&s, "uniform seed 1 16px").is_some());
    // Clear: every curve, the running render's too, which starts again from its first sample.
    let r = lab.request("POST", "/api/render/clear");
    assert_eq!(r.status, 200);
    let g = number(&r.text(), "generation");
    let s = wait_for(&lab, "a curve after the clear", |s| {
        let frame = &s[s.find("\"frame\"").unwrap()..];
        number(frame, "generation") == g && curve(s, cosine).is_some()
    });
    assert!(curve(&s, "uniform seed 1 16px").is_none(), "{s}");
    let fresh = curve(&s, cosine).unwrap();
    assert!(
        fresh[0].1 <= 2,
        "the curve starts again from the start: {fresh:?}"
    );
}

#[test]
fn the_reference_noise_floor_is_measured_by_a_twin_of_the_reference() {
    // On cosine, the bench measures the reference's noise itself: a render like the reference
    // under seed 998, to the reference's 16 spp (a twin of it: MSE = 2 variances).
    let lab = start("floor", &[]);
    lab.request("POST", "/api/render/settings?strategy=cosine");
    let s = wait_for(&lab, "a floor", |s| s.contains("\"measured_spp\":"));
    assert_eq!(number(&s, "reference_spp"), 16.0);
    let floors = &s[s.find("\"floors\":").unwrap()..];
    assert_eq!(number(floors, "measured_spp"), 16.0, "{floors}");
    assert_eq!(number(floors, "width"), 16.0, "{floors}");
    assert!(
        field(floors, "measured_by").contains("mis+rr+lds seed 998 16px"),
        "{floors}"
    );
    let floor = number(floors, "rmse");
    assert!(floor > 0.0 && floor.is_finite(), "{floors}");
    assert!(s.contains("a 16-spp render with mis (seed 999)"), "{s}");
    // A render like the reference stops a pass at the reference's spp, where it is its twin.
    lab.request("POST", "/api/render/settings?strategy=mis&seed=3");
    let s = wait_for(&lab, "the mis curve past 16 spp", |s| {
        curve(s, "mis+rr+lds seed 3 16px").is_some_and(|c| c.last().unwrap().1 > 16)
    });
    let points = curve(&s, "mis+rr+lds seed 3 16px").unwrap();
    assert!(points.iter().any(|p| p.1 == 16), "{points:?}");
}

/// The page in headless Chromium, offline (every other host unreachable): what a first-time reader
/// found broken stays fixed. Driven by playwright-core, from `book/check/node_modules` (the book's
/// check) or `target/lab-browser/node_modules` (`crates/cli/tests/browser/run.sh`); skipped, saying
/// so, where Chromium, Node.js or playwright-core is missing. About 5 s.
#[test]
fn the_page_works_in_a_browser() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let modules = ["book/check/node_modules", "target/lab-browser/node_modules"]
        .iter()
        .map(|d| root.join(d))
        .find(|d| d.join("playwright-core").is_dir());
    let node = Command::new("node")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    let (true, true, Some(modules)) = (Path::new("/usr/bin/chromium").exists(), node, modules)
    else {
        eprintln!(
            "skipped: no Chromium (/usr/bin/chromium), Node.js or playwright-core \
             (crates/cli/tests/browser/run.sh installs them)"
        );
        return;
    };
    let lab = start("browser", &[]);
    let dir = temp_dir("browser-check");
    let script = dir.0.join("check.cjs");
    std::fs::write(&script, BROWSER_CHECK).unwrap();
    let mut child = Command::new("node")
        .arg(&script)
        .arg(format!("http://127.0.0.1:{}/", lab.port))
        .env("NODE_PATH", &modules)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("node runs");
    let status = wait_exit(
        &mut child,
        Duration::from_secs(300),
        "the browser check took more than 5 minutes",
    );
    let (mut out, mut err) = (String::new(), String::new());
    child
        .stdout
        .take()
        .unwrap()
        .read_to_string(&mut out)
        .unwrap();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    eprintln!("{out}");
    assert!(status.success(), "the browser check failed:\n{out}\n{err}");
}

/// The browser check's script (`node check.cjs URL`, playwright-core on `NODE_PATH`).
const BROWSER_CHECK: &str = r##"// The lab's page in headless Chromium, offline: what a first-time reader found broken stays fixed.
// usage: node check.cjs URL   (playwright-core on NODE_PATH; Chromium at /usr/bin/chromium)
"use strict";
const { chromium } = require("playwright-core");
const url = process.argv[2];
const fails = [];
const check = (ok, what) => { console.log(`${ok ? "ok  " : "FAIL"} ${what}`); if (!ok) fails.push(what); };
(async () => {
  const browser = await chromium.launch({ executablePath: "/usr/bin/chromium", headless: true,
    args: ["--no-sandbox", "--disable-gpu", "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1"] });
  const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
  page.setDefaultTimeout(30000);
  const errors = [], outside = [];
  page.on("pageerror", (e) => errors.push(String(e)));
  page.on("request", (r) => {
    const u = new URL(r.url());
    if (!(u.protocol === "data:" || u.protocol === "blob:" || u.hostname === "127.0.0.1")) outside.push(r.url());
  });
  const status = () => page.textContent("#c-status");
  const wait = (f, arg) => page.waitForFunction(f, arg);

  // The bench named in the address opens, and switching benches names it there.
  await page.goto(url + "#cornell");
  await wait(() => window.labReady === true);
  // From the book's settings, whatever the server was left with.
  await page.evaluate(() => fetch("/api/render/settings?strategy=mis&mixture_weight=0.5&seed=1&max_depth=50", { method: "POST" }));
  check(await page.getAttribute("#tab-cornell", "aria-selected") === "true", "#cornell opens the Cornell bench (aria-selected)");
  await page.click("#tab-sampling");
  check(page.url().endsWith("#sampling"), `switching benches updates the address (${page.url()})`);
  await page.click("#tab-cornell");
  await wait(() => / spp in /.test(document.querySelector("#c-status").textContent));

  // The heat colours are the server's (the Rust colour map of the variance map): its key, step by step.
  const heat = (await (await page.request.get(url + "api/heat")).json()).colours;
  const key = await page.evaluate(() => [...document.querySelectorAll("#c-key rect:not(.axis)")].map((r) => r.getAttribute("fill")));
  const keyWant = key.map((_, i) => `rgb(${heat[Math.round((i + 0.5) / key.length * (heat.length - 1))].join(",")})`);
  check(heat.length === 256 && key.length === 64 && key.every((c, i) => c === keyWant[i]),
    `the variance map's key has the server's heat colours (${key.length} steps; ${key[0]} .. ${key[key.length - 1]})`);

  // A refused value stays, marked, and blocks no other change.
  await page.selectOption("#c-strategy", "mixture");
  await wait(() => /^mixture seed/.test(document.querySelector("#c-status").textContent));
  check(await page.evaluate(() => document.querySelector("#c-weight").validity.valid), "the book's weight 0.5 is valid in its box");
  await page.fill("#c-weight", "1");
  await page.press("#c-weight", "Tab");
  await wait(() => document.querySelector("#c-weight").getAttribute("aria-invalid") === "true");
  await page.fill("#c-seed", "4");
  await page.press("#c-seed", "Tab");
  await wait(() => /^mixture seed 4 /.test(document.querySelector("#c-status").textContent));
  const weight = await page.evaluate(() => ({ value: document.querySelector("#c-weight").value,
    invalid: document.querySelector("#c-weight").getAttribute("aria-invalid"),
    message: (document.getElementById("c-weight-msg") || {}).textContent || "" }));
  check(weight.value === "1" && weight.invalid === "true" && /goes on with 0\.5/.test(weight.message),
    `a refused weight stays, marked, saying what the render uses (${JSON.stringify(weight)})`);
  check(/seed 4/.test(await status()), "a seed changed after a refused weight is taken");

  // Another tab's change: the controls follow the server.
  await page.evaluate(() => fetch("/api/render/settings?strategy=light", { method: "POST" }));
  await wait(() => document.querySelector("#c-strategy").value === "light");
  const w = await page.evaluate(() => ({ disabled: document.querySelector("#c-weight").disabled,
    invalid: document.querySelector("#c-weight").getAttribute("aria-invalid"), value: document.querySelector("#c-weight").value }));
  check(w.disabled && !w.invalid && w.value === "0.5", `another tab's strategy shows here; the unused weight is not refused (${JSON.stringify(w)})`);

  // Fixed colours, a legend outside the plot.
  await wait(() => [...document.querySelectorAll("#c-curves .curve")].some((c) => c.dataset.label.startsWith("light")));
  const look = await page.evaluate(() => {
    const light = [...document.querySelectorAll("#c-curves .curve")].find((c) => c.dataset.label.startsWith("light"));
    const svg = document.querySelector("#c-curves").getBoundingClientRect();
    const legend = document.querySelector("#c-curves-legend").getBoundingClientRect();
    return { colour: light.getAttribute("stroke"), below: legend.top >= svg.bottom - 1, items: document.querySelectorAll("#c-curves-legend .item").length };
  });
  check(look.colour === "#009E73" && look.below && look.items >= 2, `light is bluish green, the legend under the plot (${JSON.stringify(look)})`);

  // Clear clears every curve, and the running render starts again.
  await page.click("#c-clear");
  const cleared = await page.evaluate(async () => {
    for (let i = 0; i < 200; i++) {
      const s = await (await fetch("/api/render/state")).json();
      if (s.curves.length === 1 && s.curves[0].points.length) return s.curves.map((c) => [c.label, c.points[0][1]]);
      await new Promise((ok) => setTimeout(ok, 100));
    }
    return null;
  });
  check(cleared && cleared[0][0].startsWith("light") && cleared[0][1] <= 2, `Clear leaves only the running render's new curve (${JSON.stringify(cleared)})`);

  // The server gone: a banner, the live parts grey, and back by itself.
  await page.route("**/api/**", (r) => r.abort());
  await page.waitForSelector("#offline:not([hidden])");
  check(await page.evaluate(() => document.body.classList.contains("offline")), "no answer: the banner shows and the page is greyed");
  await page.click("#c-clear");
  // Changes made meanwhile wait, the latest value of each field, marked on it and counted on the
  // banner; back, each goes as its own parameter (a refused one stays on its field and blocks none
  // of the others), and the fields show what the server uses. The test asks the server itself
  // (page.request is not blocked).
  const server = async () => (await (await page.request.get(url + "api/render/state?peek=1")).json()).settings;
  const was = await server();
  await page.selectOption("#c-strategy", "cosine");
  await page.fill("#c-depth", "7");
  await page.press("#c-depth", "Tab");
  await page.fill("#c-depth", "8");
  await page.press("#c-depth", "Tab");
  await page.fill("#c-seed", "99999999999999999999999"); // past u64::MAX: the server refuses it
  await page.press("#c-seed", "Tab");
  const queued = await page.evaluate(() => ({ banner: document.querySelector("#offline-queue").textContent,
    marked: [...document.querySelectorAll("[data-queued]")].map((e) => e.id).sort(),
    depth: (document.getElementById("c-depth-msg") || {}).textContent || "" }));
  check(/^3 changes waiting for the server \(strategy cosine, seed 99999999999999999999999, max depth 8\)/.test(queued.banner)
    && queued.marked.join() === "c-depth,c-seed,c-strategy" && /waiting for the server/.test(queued.depth),
    `changes made while the server is gone wait, marked and counted (${JSON.stringify(queued)})`);
  const meanwhile = await server();
  check(meanwhile.strategy === was.strategy && meanwhile.max_depth === was.max_depth,
    `nothing reached the server meanwhile (${JSON.stringify(meanwhile)})`);
  await page.unroute("**/api/**");
  await page.waitForSelector("#offline[hidden]", { state: "attached", timeout: 15000 });
  await wait(() => document.body.dataset.queuedChanges === "0" && !document.querySelector("[data-queued]"));
  const got = await server();
  check(got.strategy === "cosine" && got.max_depth === 8 && got.seed === was.seed,
    `back, the server got the waiting changes, the latest of each, all but the refused seed (${JSON.stringify(got)} was ${JSON.stringify(was)})`);
  await wait(() => document.querySelector("#c-seed").getAttribute("aria-invalid") === "true");
  const shown = await page.evaluate(() => ({ strategy: document.querySelector("#c-strategy").value,
    depth: document.querySelector("#c-depth").value, seed: document.querySelector("#c-seed").value,
    message: (document.getElementById("c-seed-msg") || {}).textContent || "", banner: document.querySelector("#offline-queue").textContent }));
  check(shown.strategy === "cosine" && shown.depth === "8" && shown.seed === "99999999999999999999999"
    && new RegExp(`goes on with ${was.seed}$`).test(shown.message) && shown.banner === "",
    `the fields show what the server uses; the refused seed stays, marked (${JSON.stringify(shown)})`);
  const before = await status();
  await wait((b) => document.querySelector("#c-status").textContent !== b, before);
  check(!(await page.evaluate(() => document.body.classList.contains("offline"))), "the server back: the page goes on by itself");

  // Sampling: the real limits on the boxes; a refused run marks the old results stale.
  await page.click("#tab-sampling");
  await page.click("#s-run");
  await wait(() => /samples/.test(document.querySelector("#s-status").textContent));
  await page.selectOption("#s-method", "numeric");
  check(await page.getAttribute("#s-samples", "max") === "200000", "numerical inversion: the samples box says 200000 at most");
  await page.fill("#s-samples", "2000000");
  await page.click("#s-run");
  const stale = await page.evaluate(() => ({ fig: document.querySelector("#s-figure").classList.contains("stale"),
    invalid: document.querySelector("#s-samples").getAttribute("aria-invalid") }));
  check(stale.fig && stale.invalid === "true", `too many samples: marked, and the last results marked stale (${JSON.stringify(stale)})`);
  const bars = await page.evaluate(() => {
    const line = document.querySelector("#s-hist .expected");
    return line ? line.getAttribute("d").split("L").length : 0;
  });
  check(bars >= 2 * 80, `the expected count is drawn per histogram bin (${bars} points)`);

  // On the sphere: every cell in a heat colour of the server's.
  await page.fill("#d-samples", "20000");
  await page.fill("#d-cells", "8");
  await page.click("#d-run");
  await wait(() => /directions in 8 x 8 cells/.test(document.querySelector("#d-status").textContent));
  const cells = await page.evaluate(() => [...document.querySelectorAll("#d-observed rect:not(.axis), #d-expected rect:not(.axis)")]
    .map((r) => r.getAttribute("fill")));
  const served = new Set(heat.map((c) => `rgb(${c.join(",")})`));
  check(cells.length === 128 && cells.every((c) => served.has(c)) && new Set(cells).size > 3,
    `the sphere's cells are drawn in the server's heat colours (${cells.length} cells, ${new Set(cells).size} colours)`);

  // Monte Carlo: Clear during a run stops it and leaves the plots empty.
  await page.click("#tab-mc");
  await page.fill("#mc-max", "16");
  await page.click("#mc-run");
  await wait(() => document.querySelectorAll("#mc-vs-n .curve").length === 1);
  await page.click("#mc-clear");
  await wait(() => !document.querySelector("#mc-run").disabled);
  const mc = await page.evaluate(() => ({ curves: document.querySelectorAll("#mc-vs-n .curve").length,
    status: document.querySelector("#mc-status").textContent }));
  check(mc.curves === 0 && /stopped/.test(mc.status), `Clear stops a run (${JSON.stringify(mc)})`);

  // A phone: no bench scrolls sideways.
  await page.setViewportSize({ width: 390, height: 844 });
  for (const b of ["mc", "sampling", "cornell"]) {
    await page.click(`#tab-${b}`);
    const w = await page.evaluate(() => document.documentElement.scrollWidth);
    check(w <= 390, `${b} at 390 px: no sideways scrolling (${w})`);
  }
  check(errors.length === 0, `no uncaught error${errors.length ? ": " + errors.join(" | ") : ""}`);
  check(outside.length === 0, `nothing from another host${outside.length ? ": " + outside.join(" ") : ""}`);
  await browser.close();
  console.log(fails.length ? `${fails.length} check(s) failed` : "all checks hold");
  process.exit(fails.length ? 1 : 0);
})().catch((e) => { console.error(e); process.exit(1); });
"##;
