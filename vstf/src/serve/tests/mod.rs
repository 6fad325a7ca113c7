//! The server over loopback, as the attacks tried it and as the page uses
//! it: raw HTTP over a `TcpStream` to a server on a free port, serving a
//! scratch project of one small fixture.

use super::*;
use std::io::{Read, Write};
use std::net::TcpStream;
use std::path::PathBuf;
use std::time::Instant;

/// A small fixture: a square moving at 0.8c, one view.
mod limits;
mod views;

const TINY: &str = r#"{
  "camera": {"position": [0.0, 0.0, 10.0], "t": 10.0, "look_at": [0.0, 0.0, 0.0], "vfov_deg": 40.0},
  "light": {"position": [0.0, 20.0, 20.0], "color": [0.0, 0.0, 0.0], "ambient": 1.0},
  "background": [0.0, 0.0, 0.0],
  "model": "relativistic",
  "image": {"width": 64, "height": 48, "spp": 1},
  "objects": [
    {"name": "front face", "kind": "V_obj",
     "mesh": {"quad": {"corner": [-1.0, -1.0, 1.0], "u": [2.0, 0.0, 0.0], "v": [0.0, 2.0, 0.0]}},
     "worldline": {"start": [-50.0, -40.0, 0.0, 0.0], "extrusion": [100.0, 80.0, 0.0, 0.0]},
     "material": {"color": [0.2, 0.45, 0.95]}}
  ],
  "views": [{"name": "t = 10", "t": 10.0}]
}"#;

/// A folder under the system's temporary one, removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str) -> Scratch {
        static N: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
        let dir = std::env::temp_dir().join(format!(
            "vstf-serve-{}-{name}-{}",
            std::process::id(),
            N.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
        ));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("fixtures")).unwrap();
        Scratch(dir)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A running server on a scratch project holding `tiny`.
struct Running {
    addr: SocketAddr,
    site: Arc<Site>,
    dir: Scratch,
}

fn start(name: &str, limits: Limits) -> Running {
    let dir = Scratch::new(name);
    std::fs::write(dir.0.join("fixtures/tiny.json"), TINY).unwrap();
    let server = Server::bind(Project::at(&dir.0).unwrap(), 0, limits).unwrap();
    let (addr, site) = (server.addr(), server.site());
    std::thread::spawn(move || server.run());
    Running { addr, site, dir }
}

/// Sends `raw` and reads the answer to its end: status and body.
fn exchange(addr: SocketAddr, raw: &[u8]) -> (u16, String) {
    let mut s = TcpStream::connect(addr).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(60))).unwrap();
    s.write_all(raw).unwrap();
    let mut answer = Vec::new();
    let _ = s.read_to_end(&mut answer);
    parse_answer(&answer)
}

fn parse_answer(answer: &[u8]) -> (u16, String) {
    let text = String::from_utf8_lossy(answer);
    let status = text
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or(0);
    let body = text.split_once("\r\n\r\n").map_or("", |(_, b)| b);
    (status, body.to_string())
}

impl Running {
    fn host(&self) -> String {
        format!("127.0.0.1:{}", self.addr.port())
    }

    /// A request with `headers` (a Host naming the server unless given).
    fn send(
        &self,
        method: &str,
        target: &str,
        headers: &[(&str, &str)],
        body: &str,
    ) -> (u16, String) {
        let mut raw = format!("{method} {target} HTTP/1.1\r\n");
        if !headers.iter().any(|(k, _)| k.eq_ignore_ascii_case("host")) {
            raw.push_str(&format!("Host: {}\r\n", self.host()));
        }
        for (k, v) in headers {
            raw.push_str(&format!("{k}: {v}\r\n"));
        }
        raw.push_str(&format!("Content-Length: {}\r\n\r\n{body}", body.len()));
        exchange(self.addr, raw.as_bytes())
    }

    /// A GET with the token: the answer's header `name`, if sent.
    fn get_header(&self, target: &str, name: &str) -> Option<String> {
        let raw = format!(
            "GET {target} HTTP/1.1\r\nHost: {}\r\nX-Vstf-Token: {}\r\nContent-Length: 0\r\n\r\n",
            self.host(),
            self.site.token()
        );
        let mut s = TcpStream::connect(self.addr).unwrap();
        s.set_read_timeout(Some(Duration::from_secs(60))).unwrap();
        s.write_all(raw.as_bytes()).unwrap();
        let mut answer = Vec::new();
        let _ = s.read_to_end(&mut answer);
        let text = String::from_utf8_lossy(&answer);
        let head = text.split_once("\r\n\r\n").map_or("", |(h, _)| h);
        head.lines()
            .filter_map(|l| l.split_once(':'))
            .find(|(k, _)| k.trim().eq_ignore_ascii_case(name))
            .map(|(_, v)| v.trim().to_string())
    }

    /// A GET with the token.
    fn get(&self, target: &str) -> (u16, String) {
        self.send("GET", target, &[("X-Vstf-Token", self.site.token())], "")
    }

    /// The page's own POST: JSON, the token, its origin.
    fn post(&self, path: &str, body: &str) -> (u16, String) {
        let origin = format!("http://{}", self.host());
        let headers = [
            ("X-Vstf-Token", self.site.token()),
            ("Content-Type", "application/json"),
            ("Origin", &origin),
        ];
        self.send("POST", path, &headers, body)
    }

    fn golden(&self) -> PathBuf {
        self.dir.0.join("golden/tiny/t-10.png")
    }

    /// Makes the view pending (checked without a golden).
    fn make_pending(&self) {
        let project = Project::at(&self.dir.0).unwrap();
        let _ = crate::check::run(&project, &["tiny".into()], &crate::Effort::QUICK);
        assert!(self
            .dir
            .0
            .join("target/vstf/tiny/t-10/actual.png")
            .is_file());
    }
}

fn ci() -> bool {
    crate::golden::ci_is_set(std::env::var("CI").ok().as_deref())
}

#[test]
fn a_foreign_host_is_refused_everywhere() {
    let s = start("host", Limits::default());
    let token = s.site.token().to_string();
    let port = s.addr.port();
    let hosts = [
        format!("evil.example:{port}"),
        "evil.example".into(),
        "127.0.0.1".into(),
        format!("127.0.0.1:{}", port.wrapping_add(1)),
        format!("localhost.evil.example:{port}"),
    ];
    for host in &hosts {
        for target in ["/", "/api/fixtures"] {
            let (status, body) = s.send(
                "GET",
                target,
                &[("Host", host), ("X-Vstf-Token", &token)],
                "",
            );
            assert_eq!(status, 403, "{host} {target}: {body}");
            assert!(!body.contains("tiny") && !body.contains(&token), "{body}");
        }
    }
    let (status, _) = exchange(s.addr, b"GET / HTTP/1.1\r\n\r\n");
    assert_eq!(status, 403, "no Host at all");
}

#[test]
fn a_foreign_origin_is_refused() {
    let s = start("origin", Limits::default());
    s.make_pending();
    for origin in [
        "http://evil.example",
        "null",
        "http://127.0.0.1:1",
        "https://127.0.0.1",
    ] {
        let headers = [
            ("X-Vstf-Token", s.site.token()),
            ("Content-Type", "application/json"),
            ("Origin", origin),
        ];
        let body = r#"{"fixture": "tiny", "view": "t = 10"}"#;
        let (status, said) = s.send("POST", "/api/approve", &headers, body);
        assert_eq!(status, 403, "{origin}: {said}");
    }
    assert!(!s.golden().exists(), "a foreign origin approved");
}

#[test]
fn without_the_token_nothing_but_the_page_answers() {
    let s = start("token", Limits::default());
    s.make_pending();
    let wrong = "0".repeat(64);
    for token in [
        None,
        Some(""),
        Some(wrong.as_str()),
        Some(&s.site.token()[..63]),
    ] {
        let headers: Vec<(&str, &str)> = token.map(|t| ("X-Vstf-Token", t)).into_iter().collect();
        for target in [
            "/api/fixtures",
            "/api/render?fixture=tiny&view=t%20%3D%2010",
            "/api/image?fixture=tiny&view=t%20%3D%2010&kind=actual",
            "/api/debug?fixture=tiny&view=t%20%3D%2010&x=1&y=1",
        ] {
            let (status, body) = s.send("GET", target, &headers, "");
            assert_eq!(status, 403, "{target} with {token:?}: {body}");
        }
        let mut post = headers.clone();
        post.push(("Content-Type", "application/json"));
        let (status, _) = s.send(
            "POST",
            "/api/approve",
            &post,
            r#"{"fixture":"tiny","view":"t = 10"}"#,
        );
        assert_eq!(status, 403);
    }
    // The token in the query does for an image, not for a change.
    let q = format!("/api/approve?token={}", s.site.token());
    let json = [("Content-Type", "application/json")];
    let (status, _) = s.send("POST", &q, &json, r#"{"fixture":"tiny","view":"t = 10"}"#);
    assert_eq!(status, 403);
    assert!(!s.golden().exists(), "approved without the token");
    let (status, page) = s.send("GET", "/", &[], "");
    assert_eq!(status, 200);
    assert!(page.contains(&format!("const TOKEN = '{}'", s.site.token())));
    let (_, list) = s.get("/api/fixtures");
    assert!(
        list.contains("tiny") && !list.contains(s.site.token()),
        "{list}"
    );
}

#[test]
fn a_form_cannot_change_anything() {
    let s = start("form", Limits::default());
    s.make_pending();
    let token = s.site.token().to_string();
    for kind in [
        "text/plain",
        "application/x-www-form-urlencoded",
        "multipart/form-data; boundary=x",
    ] {
        let headers = [("X-Vstf-Token", token.as_str()), ("Content-Type", kind)];
        let body = r#"{"fixture": "tiny", "view": "t = 10", "x": "="}"#;
        for path in [
            "/api/approve?fixture=tiny&view=t%20%3D%2010",
            "/api/reject",
            "/api/check",
        ] {
            let (status, said) = s.send("POST", path, &headers, body);
            assert_eq!(status, 415, "{kind} {path}: {said}");
        }
    }
    for path in [
        "/api/approve?fixture=tiny&view=t%20%3D%2010",
        "/api/reject",
        "/api/check",
    ] {
        let (status, _) = s.get(path);
        assert_eq!(status, 405, "GET {path}");
    }
    assert!(!s.golden().exists(), "a form approved");
    assert!(
        s.dir.0.join("target/vstf/tiny/t-10/actual.png").is_file(),
        "a form rejected"
    );
}

#[test]
fn paths_are_not_names() {
    let s = start("paths", Limits::default());
    let outside = Scratch::new("outside");
    let secret = outside.0.join("secret.json");
    std::fs::write(&secret, "SECRET-CONTENT {").unwrap();
    let abs_fixture = s.dir.0.join("fixtures/tiny.json");
    let spellings = [
        "/etc/passwd".to_string(),
        "../fixtures/tiny".into(),
        "..%2ffixtures%2ftiny".into(),
        "%2e%2e%2ffixtures%2ftiny".into(),
        "%2e%2e/%2e%2e/%2e%2e/etc/passwd".into(),
        secret.display().to_string(),
        abs_fixture.display().to_string(),
        "fixtures/tiny".into(),
        "tiny.json".into(),
        "x".repeat(5000),
    ];
    let no_leak = |body: &str| {
        assert!(
            !body.contains("SECRET") && !body.contains("root:") && body.len() < 300,
            "{body}"
        );
    };
    for f in &spellings {
        for target in [
            format!("/api/render?fixture={f}&view=t%20%3D%2010"),
            format!("/api/image?fixture={f}&view=t%20%3D%2010&kind=golden"),
            format!("/api/debug?fixture={f}&view=t%20%3D%2010&x=0&y=0"),
        ] {
            let (status, body) = s.get(&target);
            assert_eq!(status, 404, "{target}: {body}");
            assert!(body.starts_with("no fixture named"), "{body}");
            no_leak(&body);
        }
        let decoded = frame::query(&format!("?f={f}"))["f"].clone();
        for path in ["/api/approve", "/api/check"] {
            let body = serde_json::json!({"fixture": decoded, "view": "t = 10"}).to_string();
            let (status, said) = s.post(path, &body);
            assert_eq!(status, 404, "{path} {decoded}: {said}");
            no_leak(&said);
        }
    }
    for v in [
        "../../../etc/passwd",
        "%2e%2e%2f%2e%2e%2fetc%2fpasswd",
        "t-10",
    ] {
        let (status, body) = s.get(&format!("/api/image?fixture=tiny&view={v}&kind=golden"));
        assert_eq!(status, 404, "{v}: {body}");
        assert!(
            body.starts_with("fixture \"tiny\" has no view named"),
            "{body}"
        );
    }
}

#[test]
fn the_page_renders_and_approves() {
    let s = start("page", Limits::default());
    let (status, png) = s.get("/api/render?fixture=tiny&view=t%20%3D%2010&speed=0.9");
    assert_eq!(status, 200, "{png}");
    assert!(png.starts_with("\u{fffd}PNG"), "not a PNG");
    s.make_pending();
    let q = format!(
        "/api/image?fixture=tiny&view=t%20%3D%2010&kind=actual&token={}",
        s.site.token()
    );
    assert_eq!(s.send("GET", &q, &[], "").0, 200, "an <img>'s URL");
    let (status, said) = s.post("/api/approve", r#"{"fixture": "tiny", "view": "t = 10"}"#);
    if ci() {
        assert_eq!(status, 400, "{said}");
    } else {
        assert_eq!(
            (status, said.starts_with("approved")),
            (200, true),
            "{said}"
        );
        assert!(s.golden().is_file());
    }
}
