//! The lab's side of HTTP: routes, the page's embedded assets, and the answers (JSON, PNG, or an
//! error with a JSON message). Each connection is served on a thread of its own ([`super::http`]
//! reads it, within limits), so a long Monte Carlo run never holds up the render's frames; at most
//! [`MAX_IN_FLIGHT`] at once, and one computation of the Monte Carlo and sampling benches at a time
//! (the others wait their turn).

use super::cornell::{self, Bench};
use super::glue::{self, Settings};
use super::http::{self, Refusal, Request, Response};
use super::params::{BadRequest, Query, bad, bad_param};
use super::{mc, sampling};
use crate::study::render::heat;
use rtl_render::render::check_mixture_weight;
use serde_json::{Value, json};
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Connections served at once (each a request: reading it, answering it); more are answered 503.
pub const MAX_IN_FLIGHT: usize = 32;

/// The page and its assets, in the binary.
const ASSETS: [(&str, &str, &[u8]); 4] = [
    (
        "/",
        "text/html; charset=utf-8",
        include_bytes!("assets/index.html"),
    ),
    (
        "/lab.css",
        "text/css; charset=utf-8",
        include_bytes!("assets/lab.css"),
    ),
    (
        "/lab.js",
        "text/javascript; charset=utf-8",
        include_bytes!("assets/lab.js"),
    ),
    (
        "/favicon.ico",
        "image/svg+xml",
        include_bytes!("assets/favicon.svg"),
    ),
];

/// The colours of the page's heat maps (the sphere's grids, the keys) in [`HEAT_STEPS`] steps: the
/// variance map's own colour map (`rtl study render`'s [`heat`]) at `k / (HEAT_STEPS - 1)`, served
/// by `GET /api/heat`, so that the page keeps no copy of its stops.
pub const HEAT_STEPS: usize = 256;

fn heat_json() -> Value {
    let colours: Vec<[u8; 3]> = (0..HEAT_STEPS)
        .map(|k| heat(k as f64 / (HEAT_STEPS - 1) as f64))
        .collect();
    json!({
        "about": "rtl study render's heat colour map, dark blue (0) to yellow-white (1): colour k is t = k / (steps - 1)",
        "colours": colours,
    })
}

/// What the handlers share.
pub struct App {
    pub bench: Arc<Bench>,
    /// One Monte Carlo or sampling computation at a time.
    pub compute: Mutex<()>,
    /// Host names the page may be reached by (empty: any, when bound beyond loopback).
    pub hosts: Vec<String>,
    /// The built book (`mdbook build book`), served under `/book/`.
    pub book_dir: PathBuf,
    in_flight: AtomicUsize,
}

impl App {
    /// `run` in the Monte Carlo and sampling benches' turn (the others wait). The answer says
    /// whether the Cornell bench was using the cores meanwhile (`shared_cores`: its render goes on
    /// for [`cornell::IDLE_AFTER`] after its page stops asking, and a reference to its end), when
    /// the times measured are slower than alone.
    fn one_at_a_time(
        &self,
        run: impl FnOnce() -> Result<Value, BadRequest>,
    ) -> Result<Answer, BadRequest> {
        let _turn = self.compute.lock().unwrap_or_else(|e| e.into_inner());
        let busy = self.bench.is_busy();
        let mut v = run()?;
        let shared = busy || self.bench.is_busy();
        if let Some(o) = v.as_object_mut() {
            o.insert("shared_cores".into(), json!(shared));
        }
        Ok(Answer::Json(v))
    }

    pub fn new(bench: Arc<Bench>, hosts: Vec<String>, book_dir: PathBuf) -> App {
        App {
            bench,
            compute: Mutex::new(()),
            hosts,
            book_dir,
            in_flight: AtomicUsize::new(0),
        }
    }
}

/// Serve forever, one thread per connection. A failed `accept` (say, out of file descriptors) is
/// waited out, never the end of the server.
pub fn serve(listener: TcpListener, app: Arc<App>) {
    let mut warned: Option<Instant> = None;
    for stream in listener.incoming() {
        let stream = match stream {
            Ok(s) => s,
            Err(e) => {
                if warned.is_none_or(|t| t.elapsed() > Duration::from_secs(10)) {
                    eprintln!("rtl lab: cannot accept a connection ({e}); going on");
                    warned = Some(Instant::now());
                }
                std::thread::sleep(Duration::from_millis(50));
                continue;
            }
        };
        if app.in_flight.fetch_add(1, Ordering::SeqCst) >= MAX_IN_FLIGHT {
            app.in_flight.fetch_sub(1, Ordering::SeqCst);
            // JSON like every other refusal: the page reads its `error`.
            http::answer_now(stream, &error(503, "too many requests at once"));
            continue;
        }
        let slot = InFlight(Arc::clone(&app));
        // No thread to be had (the connection, dropped, is closed): the server goes on.
        if let Err(e) = std::thread::Builder::new().spawn(move || connection(&slot.0, stream)) {
            eprintln!("rtl lab: cannot start a thread for a request: {e}");
        }
    }
}

/// A connection's place among the [`MAX_IN_FLIGHT`], given back when its thread ends, even by a
/// panic.
struct InFlight(Arc<App>);

impl Drop for InFlight {
    fn drop(&mut self) {
        self.0.in_flight.fetch_sub(1, Ordering::SeqCst);
    }
}

/// One request: read (bounded), answered, closed.
fn connection(app: &App, stream: TcpStream) {
    let deadline = Instant::now() + http::READ_TIMEOUT;
    let mut reader = http::Timed {
        stream: &stream,
        deadline,
    };
    let mut interim = http::Timed {
        stream: &stream,
        deadline,
    };
    let (response, head_only) = match http::read_request(&mut reader, &mut interim, http::MAX_BODY)
    {
        Ok(request) => {
            // A panic of a handler is a 500, not a connection closed without a word.
            let answer =
                std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| handle(app, &request)));
            (
                answer.unwrap_or_else(|_| error(500, "internal error (the lab goes on)")),
                request.method == "HEAD",
            )
        }
        Err(Refusal::Answer(status, message)) => (error(status, &message), false),
        Err(Refusal::Gone) => return,
    };
    http::answer(stream, &response, head_only);
}

/// Headers of every answer of ours: nothing cached, nothing loaded from anywhere but this server.
fn common(content_type: &str) -> Vec<(&'static str, String)> {
    vec![
        ("Content-Type", content_type.into()),
        ("Cache-Control", "no-store".into()),
        ("X-Content-Type-Options", "nosniff".into()),
        (
            "Content-Security-Policy",
            "default-src 'self'; img-src 'self' blob: data:; style-src 'self'; script-src 'self'; connect-src 'self'".into(),
        ),
    ]
}

fn json_response(status: u16, v: &Value) -> Response {
    Response {
        status,
        headers: common("application/json"),
        body: v.to_string().into_bytes(),
    }
}

fn error(status: u16, message: &str) -> Response {
    json_response(status, &json!({ "error": message }))
}

/// A 400 that names the parameter it refuses (the page marks that field).
fn refusal(e: &BadRequest) -> Response {
    match &e.parameter {
        Some(p) => json_response(400, &json!({ "error": e.message, "parameter": p })),
        None => error(400, &e.message),
    }
}

/// An answer before it is sent.
enum Answer {
    Json(Value),
    Bytes(&'static str, Vec<u8>),
    /// A page of the built book, with its status (200, or 404 for the book's own 404 page): its own
    /// scripts and styles, so no Content-Security-Policy of ours.
    Book(u16, &'static str, Vec<u8>),
    Error(u16, String),
    /// A 400 of a parameter refused.
    Refused(BadRequest),
    /// 308 to the path given (the same with a slash at the end, say).
    Redirect(String),
    /// 405: the path is there for the methods in `allow` (the `Allow` header).
    WrongMethod {
        allow: &'static str,
        message: String,
    },
}

impl From<BadRequest> for Answer {
    fn from(e: BadRequest) -> Answer {
        Answer::Refused(e)
    }
}

fn handle(app: &App, request: &Request) -> Response {
    let (path, query) = request
        .target
        .split_once('?')
        .unwrap_or((&request.target, ""));
    let answer = if !host_allowed(app, request.host.as_deref()) {
        Answer::Error(
            403,
            "the Host header names another site: the lab answers only to its own address".into(),
        )
    } else {
        route(app, &request.method, path, query)
    };
    match answer {
        Answer::Json(v) => json_response(200, &v),
        Answer::Bytes(t, body) => Response {
            status: 200,
            headers: common(t),
            body,
        },
        Answer::Book(status, t, body) => Response {
            status,
            headers: vec![
                ("Content-Type", t.into()),
                ("Cache-Control", "no-store".into()),
            ],
            body,
        },
        Answer::Error(status, msg) => error(status, &msg),
        Answer::Refused(e) => refusal(&e),
        Answer::Redirect(to) => {
            let mut r = error(308, &format!("moved to {to}"));
            r.headers.push(("Location", to));
            r
        }
        Answer::WrongMethod { allow, message } => {
            let mut r = error(405, &message);
            r.headers.push(("Allow", allow.into()));
            r
        }
    }
}

/// Refuse requests whose `Host` is not the lab's own (a page elsewhere that resolves its name to
/// 127.0.0.1, "DNS rebinding", cannot drive the lab).
fn host_allowed(app: &App, host: Option<&str>) -> bool {
    if app.hosts.is_empty() {
        return true;
    }
    match host {
        None => true,
        Some(h) => app.hosts.contains(&h.to_ascii_lowercase()),
    }
}

fn route(app: &App, method: &str, path: &str, query: &str) -> Answer {
    let get = method == "GET" || method == "HEAD";
    let post = method == "POST";
    let wrong = |allow: &'static str| Answer::WrongMethod {
        allow,
        message: format!("{path}: wrong method {method}; it takes {allow}"),
    };
    if let Some((_, t, body)) = ASSETS.iter().find(|a| a.0 == path) {
        if !get {
            return wrong("GET, HEAD");
        }
        if !query.is_empty() {
            return Answer::Error(400, format!("{path} takes no parameters"));
        }
        return Answer::Bytes(t, body.to_vec());
    }
    // The book's pages link to each other relatively: its index must be /book/, not /book.
    if path == "/book" {
        if !get {
            return wrong("GET, HEAD");
        }
        return Answer::Redirect("/book/".into());
    }
    if let Some(rest) = path.strip_prefix("/book/") {
        if !get {
            return wrong("GET, HEAD");
        }
        return book_page(&app.book_dir, rest);
    }
    let handler: fn(&App, &str) -> Result<Answer, BadRequest> = match path {
        "/api/mc/list" => |_, q| no_query(q).map(|()| Answer::Json(mc::list())),
        "/api/mc/run" => |app, q| app.one_at_a_time(|| mc::run(q)),
        "/api/sampling/list" => |_, q| no_query(q).map(|()| Answer::Json(sampling::list())),
        "/api/sampling/line" => |app, q| app.one_at_a_time(|| sampling::run_line(q)),
        "/api/sampling/sphere" => |app, q| app.one_at_a_time(|| sampling::run_sphere(q)),
        "/api/heat" => |_, q| no_query(q).map(|()| Answer::Json(heat_json())),
        "/api/render/list" => |app, q| no_query(q).map(|()| Answer::Json(render_list(app))),
        "/api/render/settings" => |app, q| set_render(app, q).map(Answer::Json),
        "/api/render/state" => |app, q| render_state(app, q).map(Answer::Json),
        "/api/render/image" => render_image,
        "/api/render/clear" => |app, q| {
            no_query(q).map(|()| {
                let generation = app.bench.clear_curves();
                Answer::Json(json!({ "cleared": true, "generation": generation }))
            })
        },
        p => return Answer::Error(404, format!("no page {p}")),
    };
    // What changes the render is a POST; everything else a GET (or HEAD).
    let wants_post = matches!(path, "/api/render/settings" | "/api/render/clear");
    if wants_post && !post {
        return wrong("POST");
    }
    if !wants_post && !get {
        return wrong("GET, HEAD");
    }
    handler(app, query).unwrap_or_else(Answer::from)
}

fn no_query(query: &str) -> Result<(), BadRequest> {
    Query::parse(query, &[]).map(|_| ())
}

fn render_list(app: &App) -> Value {
    json!({
        "strategies": glue::strategy_names(),
        "widths": [cornell::WIDTHS.0, cornell::WIDTHS.1],
        "current": settings_json(&app.bench.settings()),
    })
}

fn settings_json(s: &Settings) -> Value {
    let o = glue::mis_options(s.strategy);
    json!({
        "width": s.width, "strategy": s.strategy.name(), "seed": s.seed, "max_depth": s.max_depth,
        "rr": o.russian_roulette, "lds": o.low_discrepancy, "sph_rect": o.spherical_rectangles,
        "mixture_weight": s.mixture_weight, "label": cornell::label(s),
    })
}

/// `POST /api/render/settings?strategy=S&width=W&seed=K&max_depth=D&rr=1&lds=1&sph_rect=0&
/// mixture_weight=0.5`; what is not given stays as it is.
fn set_render(app: &App, query: &str) -> Result<Value, BadRequest> {
    let q = Query::parse(
        query,
        &[
            "strategy",
            "width",
            "seed",
            "max_depth",
            "rr",
            "lds",
            "sph_rect",
            "mixture_weight",
        ],
    )?;
    let d = app.bench.settings();
    let o = glue::mis_options(d.strategy);
    let names = glue::strategy_names();
    let name = q.choice("strategy", d.strategy.name(), &names)?;
    let width = q.number("width", d.width, cornell::WIDTHS.0, cornell::WIDTHS.1)?;
    let seed = q.number("seed", d.seed, 0, u64::MAX)?;
    let max_depth = q.number("max_depth", d.max_depth, 1, 200)?;
    let strategy = glue::strategy(
        name,
        q.flag("rr", o.russian_roulette)?,
        q.flag("lds", o.low_discrepancy)?,
        q.flag("sph_rect", o.spherical_rectangles)?,
    )
    .map_err(bad)?;
    let w = q.number("mixture_weight", d.mixture_weight, 0.0, 1.0)?;
    let mixture_weight = check_mixture_weight(w)
        .map_err(|e| bad_param("mixture_weight", format!("`mixture_weight={w}`: {e}")))?;
    let s = Settings {
        width,
        strategy,
        seed,
        max_depth,
        mixture_weight,
    };
    let generation = app.bench.set(s);
    Ok(json!({ "generation": generation, "settings": settings_json(&s) }))
}

/// `GET /api/render/state[?peek=1]`: the latest frame's numbers and the curves; `peek=1` does not
/// count as the page watching (for tests of the idle stop).
fn render_state(app: &App, query: &str) -> Result<Value, BadRequest> {
    let q = Query::parse(query, &["peek"])?;
    if !q.flag("peek", false)? {
        app.bench.touch();
    }
    let s = app.bench.settings();
    let f = app.bench.frame.lock().unwrap();
    let curves = app.bench.curves.lock().unwrap().clone();
    Ok(json!({
        "generation": app.bench.generation(),
        "settings": settings_json(&s),
        "rendering": !app.bench.is_idle(),
        "frame": {
            "id": f.id, "generation": f.generation, "width": f.width, "height": f.height,
            "spp": f.spp, "seconds": f.seconds, "rays_per_second": f.rays_per_second, "rmse": f.rmse,
            "resumed": f.resumed,
        },
        "reference": app.bench.reference_note(s.width),
        "reference_spp": app.bench.reference_spp(s.width),
        "floors": app.bench.floors(),
        "curves": curves,
    }))
}

/// `GET /api/render/image?kind=image|variance`: the latest frame as PNG.
fn render_image(app: &App, query: &str) -> Result<Answer, BadRequest> {
    let q = Query::parse(query, &["kind", "frame"])?;
    let kind = q.choice("kind", "image", &["image", "variance"])?;
    q.number("frame", 0u64, 0, u64::MAX)?; // a cache-buster of the page, not used
    app.bench.touch();
    let png = {
        let f = app.bench.frame.lock().unwrap();
        if f.id == 0 {
            return Ok(Answer::Error(503, "no frame yet".into()));
        }
        Arc::clone(if kind == "image" {
            &f.image_png
        } else {
            &f.variance_png
        })
    };
    // Copied out of the frame's lock, which the render's worker waits for.
    Ok(Answer::Bytes("image/png", png.to_vec()))
}

/// A file of the built book: `rest` is a relative path of plain names (no `..`, nothing hidden).
fn book_page(dir: &Path, rest: &str) -> Answer {
    let rest = if rest.is_empty() { "index.html" } else { rest };
    let plain = rest.len() <= 200
        && rest.split('/').all(|part| {
            !part.is_empty()
                && !part.starts_with('.')
                && part
                    .bytes()
                    .all(|b| b.is_ascii_alphanumeric() || b"._-".contains(&b))
        });
    if !plain {
        return Answer::Error(400, format!("/book/{rest}: not a page of the book"));
    }
    let kind = match rest.rsplit_once('.').map(|(_, e)| e) {
        Some("html") => "text/html; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        Some("js") => "text/javascript; charset=utf-8",
        Some("svg") => "image/svg+xml",
        Some("png") => "image/png",
        Some("json") => "application/json",
        Some("woff2") => "font/woff2",
        Some("woff") => "font/woff",
        Some("ttf") => "font/ttf",
        _ => "application/octet-stream",
    };
    if let Ok(body) = std::fs::read(dir.join(rest)) {
        return Answer::Book(200, kind, body);
    }
    // Not built: the chapter's source (book/src/NAME.md beside book/book), as text.
    let source = rest
        .strip_suffix(".html")
        .zip(dir.parent())
        .map(|(stem, book)| book.join("src").join(format!("{stem}.md")));
    if let Some(body) = source.and_then(|p| std::fs::read(p).ok()) {
        return Answer::Book(200, "text/plain; charset=utf-8", body);
    }
    // A built book has a page for this (its links and styles from /book/, book.toml's site-url).
    if let Ok(body) = std::fs::read(dir.join("404.html")) {
        return Answer::Book(404, "text/html; charset=utf-8", body);
    }
    Answer::Error(
        404,
        format!(
            "no page /book/{rest} in {} (build the book with `mdbook build book`)",
            dir.display()
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The page's heat colours are the variance map's: the Rust colour map itself, step by step.
    #[test]
    fn the_heat_colours_are_the_variance_maps() {
        let v = heat_json();
        let colours = v["colours"].as_array().unwrap();
        assert_eq!(colours.len(), HEAT_STEPS);
        for (k, c) in colours.iter().enumerate() {
            let want = heat(k as f64 / (HEAT_STEPS - 1) as f64);
            assert_eq!(c, &json!(want), "step {k}");
        }
        // The colour map's own stops, written out: dark blue, the green at 0.6, pale yellow.
        assert_eq!(colours[0], json!([12, 7, 63]));
        assert_eq!(colours[153], json!([25, 178, 127]));
        assert_eq!(colours[HEAT_STEPS - 1], json!([255, 255, 229]));
    }
}
