//! `rtl lab` over plain HTTP: the page is served from the binary, every bad parameter is refused with
//! a 400 that names it (and the server lives on), hostile request bodies are refused without being
//! read (and the server lives on), a port in use is a clear error, `--bind` beyond loopback warns, and
//! the render stops when nobody watches. Each test starts its own `rtl lab
//! --port 0` as a child process and bounds every wait.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::{TcpListener, TcpStream};
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
    assert_eq!(lab.get("/nope").status, 404);
    // The benches link to the book's chapters: the built page, or else the chapter's source.
    let chapter = lab.get("/book/ch02-a-simple-monte-carlo-program.html");
    assert_eq!(chapter.status, 200);
    assert!(chapter.text().contains("A Simple Monte Carlo Program"));
    assert_eq!(lab.get("/book/ch99-none.html").status, 404);
    assert_eq!(lab.get("/?x=1").status, 400);
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
        ("GET", "/api/mc/list?x=1", "unknown parameter"),
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
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > Duration::from_secs(60) {
            let _ = child.kill();
            panic!("rtl lab did not stop on a port in use");
        }
        std::thread::sleep(Duration::from_millis(50));
    };
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
