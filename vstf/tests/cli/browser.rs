//! `vstf serve` driven in a real browser (Debian's chromium through
//! chromedriver, spoken to in W3C WebDriver over plain HTTP): the page
//! loads a view, moving the time slider changes the image, a click on a
//! pixel shows its hit, approving a pending view writes its golden, and
//! checking the fixture shows its rows beside the view measured; and a
//! page of another origin that submits a cross-site form to the approve
//! endpoint (the attack `vstf serve` once fell to) changes nothing.
//!
//! Without chromedriver and chromium the test says so loudly and skips;
//! with `VSTF_REQUIRE_BROWSER` set (as `.ci/run` does once it has installed
//! them) their absence is a failure.

use crate::support::{copy_tree, repo_root, tamper, vstf, RunExt, Scratch};
use serde_json::{json, Value};
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

fn on_path(names: &[&str]) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .flat_map(|d| names.iter().map(move |n| d.join(n)))
        .find(|p| p.is_file())
}

/// One HTTP/1.1 request; the status and the body.
pub(crate) fn http(addr: &str, method: &str, path: &str, body: Option<&Value>) -> (u16, String) {
    let mut s = TcpStream::connect(addr).unwrap_or_else(|e| panic!("connect {addr}: {e}"));
    s.set_read_timeout(Some(Duration::from_secs(60))).unwrap();
    let body = body.map(Value::to_string).unwrap_or_default();
    write!(
        s,
        "{method} {path} HTTP/1.1\r\nHost: {addr}\r\nContent-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{body}",
        body.len()
    )
    .unwrap();
    // Read the head, then exactly Content-Length bytes (a server may keep
    // the connection open whatever the request asked).
    let mut reader = BufReader::new(s);
    let mut head = String::new();
    loop {
        let mut line = String::new();
        if reader.read_line(&mut line).unwrap() == 0 || line == "\r\n" {
            break;
        }
        head.push_str(&line);
    }
    let status = head
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or(0);
    let lower = head.to_ascii_lowercase();
    let length = lower
        .lines()
        .find_map(|l| l.strip_prefix("content-length:"))
        .and_then(|n| n.trim().parse::<usize>().ok());
    let body = match length {
        Some(n) => {
            let mut b = vec![0; n];
            reader.read_exact(&mut b).unwrap();
            String::from_utf8_lossy(&b).into_owned()
        }
        None => {
            let mut rest = String::new();
            reader.read_to_string(&mut rest).unwrap();
            if lower.contains("transfer-encoding: chunked") {
                dechunk(&rest)
            } else {
                rest
            }
        }
    };
    (status, body)
}

fn dechunk(mut s: &str) -> String {
    let mut out = String::new();
    while let Some((size, rest)) = s.split_once("\r\n") {
        let n = usize::from_str_radix(size.trim(), 16).unwrap_or(0);
        if n == 0 || rest.len() < n {
            break;
        }
        out.push_str(&rest[..n]);
        s = rest[n..].trim_start_matches("\r\n");
    }
    out
}

/// A WebDriver session.
pub(crate) struct Driver {
    pub(crate) addr: String,
    pub(crate) session: String,
}

impl Driver {
    pub(crate) fn call(&self, method: &str, path: &str, body: Option<Value>) -> Value {
        let (status, text) = http(
            &self.addr,
            method,
            &format!("/session/{}{path}", self.session),
            body.as_ref(),
        );
        let v: Value = serde_json::from_str(&text).unwrap_or(Value::Null);
        assert!(status == 200, "WebDriver {method} {path}: {status} {text}");
        v["value"].clone()
    }

    pub(crate) fn script(&self, js: &str) -> Value {
        self.call(
            "POST",
            "/execute/sync",
            Some(json!({"script": js, "args": []})),
        )
    }

    /// Polls `js` until `ok` holds of its value (at most 60 s).
    pub(crate) fn wait_for(&self, what: &str, js: &str, ok: impl Fn(&Value) -> bool) -> Value {
        let start = Instant::now();
        loop {
            let v = self.script(js);
            if ok(&v) {
                return v;
            }
            assert!(
                start.elapsed() < Duration::from_secs(60),
                "timed out waiting for {what}: last {v}"
            );
            std::thread::sleep(Duration::from_millis(100));
        }
    }

    pub(crate) fn click(&self, css: &str) {
        let el = self.call(
            "POST",
            "/element",
            Some(json!({"using": "css selector", "value": css})),
        );
        let id = el
            .as_object()
            .and_then(|o| o.values().next())
            .and_then(Value::as_str)
            .unwrap()
            .to_string();
        self.call("POST", &format!("/element/{id}/click"), Some(json!({})));
    }
}

/// Kills the child when dropped (a failing test leaves no process behind).
pub(crate) struct Reaper(Child);

impl Drop for Reaper {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
}

/// A project of one fixture whose golden frame 920 is tampered, checked so
/// that the view is pending: its folder, the golden's path and the pending
/// render.
fn pending_project() -> (Scratch, PathBuf, Vec<u8>) {
    let repo = repo_root();
    let dir = Scratch::new("browser");
    std::fs::create_dir_all(dir.join("fixtures")).unwrap();
    std::fs::copy(
        repo.join("fixtures/flange.json"),
        dir.join("fixtures/flange.json"),
    )
    .unwrap();
    copy_tree(&repo.join("golden/flange"), &dir.join("golden/flange"));
    let golden = dir.join("golden/flange/frame-920.png");
    tamper(&golden);
    let checked = vstf()
        .current_dir(&dir)
        .args(["check", "flange", "--quick"])
        .run();
    assert!(!checked.success(), "the tampered golden passed: {checked}");
    let actual = std::fs::read(dir.join("target/vstf/flange/frame-920/actual.png")).unwrap();

    (dir, golden, actual)
}

/// `vstf serve` on a free port in `dir`, and its page's address.
pub(crate) fn start_server(dir: &Path) -> (Reaper, String) {
    let mut server = Reaper(
        vstf()
            .current_dir(dir)
            .args(["serve", "--port", "0"])
            .env_remove("CI")
            .stdout(Stdio::piped())
            .spawn()
            .unwrap(),
    );
    let mut line = String::new();
    BufReader::new(server.0.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let page = line
        .split_whitespace()
        .find(|w| w.starts_with("http://"))
        .expect("the address")
        .to_string();

    (server, page)
}

/// chromedriver on a free port with a headless chromium session.
pub(crate) fn start_browser(driver: &Path, browser: &Path) -> (Reaper, Driver) {
    let port = free_port();
    let chromedriver = Reaper(
        Command::new(driver)
            .arg(format!("--port={port}"))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap(),
    );
    let addr = format!("127.0.0.1:{port}");
    let start = Instant::now();
    while TcpStream::connect(&addr).is_err() {
        assert!(
            start.elapsed() < Duration::from_secs(30),
            "chromedriver did not start"
        );
        std::thread::sleep(Duration::from_millis(100));
    }
    let caps = json!({"capabilities": {"alwaysMatch": {"browserName": "chrome", "goog:chromeOptions": {
        "binary": browser, "args": ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage"]}}}});
    let (status, text) = http(&addr, "POST", "/session", Some(&caps));
    assert_eq!(status, 200, "no browser session: {text}");
    let v: Value = serde_json::from_str(&text).unwrap();
    let d = Driver {
        addr: addr.clone(),
        session: v["value"]["sessionId"].as_str().unwrap().to_string(),
    };

    (chromedriver, d)
}

/// A page on another local port (another origin) that submits, as soon as
/// it loads, a `text/plain` form to `page`'s approve endpoint whose body
/// reads as the JSON of an approval; its address.
fn attacker(page: &str) -> String {
    let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let addr = listener.local_addr().unwrap();
    let html = format!(
        "<!doctype html><form id=f method=POST enctype=text/plain \
         action='{page}api/approve?fixture=flange&view=frame%20920'>\
         <input name='{{\"fixture\":\"flange\",\"view\":\"frame 920\",\"x\":\"' value='\"}}'>\
         </form><script>document.getElementById('f').submit()</script>"
    );
    std::thread::spawn(move || {
        for stream in listener.incoming().flatten() {
            let mut stream = stream;
            let mut head = [0u8; 4096];
            let _ = stream.read(&mut head);
            let _ = write!(
                stream,
                "HTTP/1.1 200 OK\r\nContent-Type: text/html\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{html}",
                html.len()
            );
        }
    });
    format!("http://{addr}/")
}

/// The attacker's form, submitted in the browser, reaches the server and
/// is refused; the golden is as it was.
fn a_cross_site_form_does_not_approve(d: &Driver, page: &str, golden: &Path) {
    let before = std::fs::read(golden).unwrap();
    d.call("POST", "/url", Some(json!({"url": attacker(page)})));
    let answer = d.wait_for(
        "the form's answer",
        "return location.href.includes('/api/approve') ? document.body.textContent : ''",
        |v| v.as_str().is_some_and(|s| !s.is_empty()),
    );
    let answer = answer.as_str().unwrap();
    assert!(
        answer.contains("other origins") || answer.contains("token"),
        "{answer}"
    );
    assert_eq!(
        std::fs::read(golden).unwrap(),
        before,
        "a cross-site form changed the golden"
    );
}

/// chromedriver and chromium, if both are on PATH; else `None`, having
/// said loudly that a browser test did not run (a failure with
/// `VSTF_REQUIRE_BROWSER` set).
pub(crate) fn browser_tools() -> Option<(PathBuf, PathBuf)> {
    let (Some(driver), Some(browser)) = (
        on_path(&["chromedriver"]),
        on_path(&["chromium", "chromium-browser", "google-chrome"]),
    ) else {
        let msg =
            "no chromedriver and chromium on PATH: the browser test of vstf serve did not run \
                   (apt-get install chromium chromium-driver)";
        assert!(std::env::var_os("VSTF_REQUIRE_BROWSER").is_none(), "{msg}");
        eprintln!("SKIPPED: {msg}");
        return None;
    };
    Some((driver, browser))
}

#[test]
fn the_page_renders_debugs_and_approves_in_a_real_browser() {
    let Some((driver, browser)) = browser_tools() else {
        return;
    };
    let (dir, golden, actual) = pending_project();
    let (server, page) = start_server(&dir);
    let (_chromedriver, d) = start_browser(&driver, &browser);
    // Another origin's form, submitted while the view is pending.
    a_cross_site_form_does_not_approve(&d, &page, &golden);
    // Load the pending view; its render arrives.
    d.call(
        "POST",
        "/url",
        Some(json!({"url": format!("{page}?fixture=flange&view=frame%20920")})),
    );
    let hash = |v: &Value| v.as_str().is_some_and(|s| !s.is_empty());
    let first = d.wait_for(
        "the first render",
        "return document.getElementById('hash').textContent",
        hash,
    );
    // The time slider: another camera time, another image.
    d.script(
        "const s = document.getElementById('t'); s.value = 8; s.dispatchEvent(new Event('input'));",
    );
    d.wait_for(
        "a new render",
        "return document.getElementById('hash').textContent",
        |v| hash(v) && *v != first,
    );
    // A click on the image shows that pixel's variables.
    d.script(
        "const s = document.getElementById('t'); s.value = 0; s.dispatchEvent(new Event('input'));",
    );
    d.wait_for(
        "the render back",
        "return document.getElementById('hash').textContent",
        |v| *v == first,
    );
    d.click("#render");
    let debug = d.wait_for(
        "the debug text",
        "return document.getElementById('debug').textContent",
        |v| v.as_str().is_some_and(|s| s.contains("Primary ray")),
    );
    let debug = debug.as_str().unwrap();
    assert!(
        debug.starts_with("pixel (") && (debug.contains("HIT") || debug.contains("met nothing")),
        "{debug}"
    );
    // Approve the pending view: the golden becomes the render.
    d.click("#approve");
    d.wait_for(
        "approval",
        "return document.getElementById('status').textContent",
        |v| v.as_str().is_some_and(|s| s.starts_with("approved")),
    );
    assert_eq!(
        std::fs::read(&golden).unwrap(),
        actual,
        "the golden is not the approved render"
    );
    // Check the fixture: its rows appear beside the view they were
    // measured in, and the list shows their count.
    d.click("#check");
    let said = d.wait_for(
        "the check",
        "return document.getElementById('status').textContent",
        |v| v.as_str().is_some_and(|s| s.starts_with("flange checked")),
    );
    assert!(
        said.as_str().unwrap().starts_with("flange checked: pass"),
        "{said}"
    );
    let here = d.script(
        "return [...document.querySelectorAll('#here tr.pass td:first-child')].map(c => c.textContent)",
    );
    let here: Vec<&str> = here
        .as_array()
        .unwrap()
        .iter()
        .filter_map(Value::as_str)
        .collect();
    assert!(!here.is_empty(), "no rows shown beside frame 920");
    let listed = d.script("return document.getElementById('fixtures').textContent");
    assert!(
        listed
            .as_str()
            .unwrap()
            .contains(&format!("frame 920 — golden, rows {0}/{0}", here.len())),
        "{listed}"
    );
    let _ = http(&d.addr, "DELETE", &format!("/session/{}", d.session), None);
    drop(server);
    drop(dir);
}
