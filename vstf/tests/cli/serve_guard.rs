//! `vstf serve` against the requests a hostile page can make, sent as raw
//! HTTP on loopback as they were tried: a foreign `Host` (DNS rebinding),
//! a foreign `Origin`, no token, a cross-site form's `text/plain` body, a
//! GET that would change something, paths instead of fixture names. Each
//! with the control that the page's own request still works.

use crate::browser::{pending_project, start_server};
use std::io::{Read, Write};
use std::net::TcpStream;
use std::time::Duration;

/// Sends `head` (request line and headers, without the blank line) and
/// `body`; the status and the answer's body.
fn raw(addr: &str, head: &str, body: &str) -> (u16, String) {
    let mut s = TcpStream::connect(addr).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(120))).unwrap();
    write!(
        s,
        "{head}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{body}",
        body.len()
    )
    .unwrap();
    let mut bytes = Vec::new();
    let _ = s.read_to_end(&mut bytes);
    let answer = String::from_utf8_lossy(&bytes);
    let status = answer
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or(0);
    let body = answer
        .split_once("\r\n\r\n")
        .map_or("", |(_, b)| b)
        .to_string();
    (status, body)
}

/// The token the served page carries.
fn token_of(addr: &str) -> String {
    let (status, page) = raw(addr, &format!("GET / HTTP/1.1\r\nHost: {addr}"), "");
    assert_eq!(status, 200, "{page}");
    let at = page.find("const TOKEN = '").expect("the page's token") + 15;
    page[at..at + 64].to_string()
}

#[test]
fn serve_answers_only_its_own_page() {
    let (dir, golden, actual) = pending_project("serve-guard");
    let (_server, page) = start_server(&dir);
    let addr = page
        .trim_start_matches("http://")
        .trim_end_matches('/')
        .to_string();
    let token = token_of(&addr);
    let approve = "POST /api/approve?fixture=flange&view=frame%20920 HTTP/1.1";
    let before = std::fs::read(&golden).unwrap();
    let attacks = [
        (format!("{approve}\r\nHost: evil.example:80\r\nOrigin: http://evil.example\r\nContent-Type: text/plain"), "x=1", 403),
        (format!("{approve}\r\nHost: {addr}\r\nOrigin: http://evil.example\r\nX-Vstf-Token: {token}\r\nContent-Type: application/json"), "{}", 403),
        (format!("{approve}\r\nHost: {addr}\r\nContent-Type: application/json"), "{}", 403),
        (format!("{approve}\r\nHost: {addr}\r\nX-Vstf-Token: {token}\r\nContent-Type: text/plain"), "x=1", 415),
        (format!("GET /api/approve?fixture=flange&view=frame%20920&token={token} HTTP/1.1\r\nHost: {addr}"), "", 405),
        (format!("GET /api/fixtures HTTP/1.1\r\nHost: evil.example:{}", addr.rsplit(':').next().unwrap()), "", 403),
        ("GET / HTTP/1.1\r\nHost: rebound.example".to_string(), "", 403),
    ];
    for (head, body, want) in &attacks {
        let (status, said) = raw(&addr, head, body);
        assert_eq!(status, *want, "{head}: {said}");
    }
    assert_eq!(
        std::fs::read(&golden).unwrap(),
        before,
        "an attack approved"
    );
    // Paths instead of names, in every spelling: 404, no content echoed.
    std::fs::write(
        dir.join("secret.json"),
        r#"{"api_token": "TOPSECRET-STRING"}"#,
    )
    .unwrap();
    let secret = dir.join("secret.json").display().to_string();
    for name in [
        secret.as_str(),
        "/etc/passwd",
        "../fixtures/flange",
        "%2e%2e%2fsecret",
        "..%2fsecret",
        "fixtures/../secret",
    ] {
        let head = format!(
            "GET /api/render?fixture={name}&view=view&token={token} HTTP/1.1\r\nHost: {addr}"
        );
        let (status, said) = raw(&addr, &head, "");
        assert_eq!(status, 404, "{name}: {said}");
        assert!(
            !said.contains("TOPSECRET") && !said.contains("api_token"),
            "{said}"
        );
    }
    // Controls: the page's own render and approve.
    let (status, _) = raw(&addr, &format!("GET /api/render?fixture=flange&view=frame%20920&token={token} HTTP/1.1\r\nHost: {addr}"), "");
    assert_eq!(status, 200);
    let own = format!("{approve}\r\nHost: {addr}\r\nOrigin: http://{addr}\r\nX-Vstf-Token: {token}\r\nContent-Type: application/json");
    let (status, said) = raw(&addr, &own, "{}");
    assert_eq!(status, 200, "{said}");
    assert_eq!(
        std::fs::read(&golden).unwrap(),
        actual,
        "the page's own approve"
    );
}

/// 30 distinct speeds of the flange keep the database cache within its
/// budget (three of its databases here), and 48 renders asked at once are
/// answered, some with 503, none queued without bound.
#[test]
fn serve_memory_stays_within_its_budget() {
    let (dir, _, _) = pending_project("serve-memory");
    let project = vstf::Project::locate(Some(&dir)).unwrap();
    let f = project.load("flange").unwrap();
    let one = u64::try_from(f.database(false).unwrap().prism_count()).unwrap() * 300;
    let budget = 3 * one;
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        vstf::serve::serve(project, (0, budget), |addr, site| {
            tx.send((addr.to_string(), site.clone())).unwrap();
        })
    });
    let (page, site) = rx.recv().unwrap();
    let addr = page
        .trim_start_matches("http://")
        .trim_end_matches('/')
        .to_string();
    let token = site.token().to_string();
    let render = |speed: f64| {
        let head = format!(
            "GET /api/render?fixture=flange&view=frame%20920&speed={speed}&token={token} HTTP/1.1\r\nHost: {addr}"
        );
        raw(&addr, &head, "").0
    };
    for k in 0..30 {
        assert_eq!(render(0.5 + f64::from(k) / 100.0), 200);
        assert!(
            site.cached_bytes() <= budget,
            "{} > {budget}",
            site.cached_bytes()
        );
    }
    let statuses: Vec<u16> = std::thread::scope(|s| {
        let asks: Vec<_> = (0..24)
            .map(|k| s.spawn(move || render(0.2 + f64::from(k) / 100.0)))
            .collect();
        asks.into_iter().map(|a| a.join().unwrap()).collect()
    });
    assert!(
        statuses.iter().all(|c| *c == 200 || *c == 503),
        "{statuses:?}"
    );
    assert!(
        statuses.contains(&503),
        "48 renders at once all ran: {statuses:?}"
    );
    assert!(site.cached_bytes() <= budget);
}
