//! A small HTTP/1.1 server on `std::net`, just enough for the page: one
//! request per connection, answered with `Connection: close`. Everything a
//! client can make it hold is bounded: the request line and headers (16 KiB),
//! the body (64 KiB, by `Content-Length`; no chunked bodies), the time the
//! whole request may take to arrive, and the number of connections served
//! at once (beyond it a connection gets 503 and is closed).

use std::io::{Read, Write};
use std::net::{Shutdown, TcpListener, TcpStream};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The most bytes of request line and headers read.
pub(super) const MAX_HEAD: usize = 16 * 1024;

/// The most bytes of body read.
pub(super) const MAX_BODY: usize = 64 * 1024;

/// The most bytes read and thrown away after refusing a request, so that
/// the refusal reaches the client before the connection closes.
const MAX_DRAIN: usize = 1024 * 1024;

/// A request as read: method, target (path and query), headers (names in
/// lower case) and body.
#[derive(Debug)]
pub(super) struct Request {
    pub(super) method: String,
    pub(super) target: String,
    pub(super) headers: Vec<(String, String)>,
    pub(super) body: Vec<u8>,
}

impl Request {
    /// The value of header `name` (lower case), if sent once; `None` if not
    /// sent (a repeated header is refused when the request is read).
    pub(super) fn header(&self, name: &str) -> Option<&str> {
        self.headers
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    /// The target's path.
    pub(super) fn path(&self) -> &str {
        self.target.split('?').next().unwrap_or("")
    }
}

/// A response: status, headers and body.
#[derive(Debug)]
pub(super) struct Response {
    pub(super) status: u16,
    headers: Vec<(&'static str, String)>,
    pub(super) body: Vec<u8>,
}

impl Response {
    /// A response of `status` with a body of `content_type`.
    pub(super) fn new(status: u16, content_type: &str, body: Vec<u8>) -> Response {
        Response {
            status,
            headers: vec![("Content-Type", content_type.to_string())],
            body,
        }
    }

    /// A plain-text response.
    pub(super) fn text(status: u16, message: impl Into<String>) -> Response {
        Response::new(
            status,
            "text/plain; charset=utf-8",
            message.into().into_bytes(),
        )
    }

    /// The response with one more header.
    pub(super) fn with(mut self, name: &'static str, value: impl Into<String>) -> Response {
        self.headers.push((name, value.into()));
        self
    }

    fn write_to(&self, w: &mut impl Write) -> std::io::Result<()> {
        let mut head = format!("HTTP/1.1 {} {}\r\n", self.status, reason(self.status));
        for (k, v) in &self.headers {
            head.push_str(&format!("{k}: {v}\r\n"));
        }
        head.push_str(&format!(
            "Content-Length: {}\r\nConnection: close\r\n\r\n",
            self.body.len()
        ));
        w.write_all(head.as_bytes())?;
        w.write_all(&self.body)?;
        w.flush()
    }
}

fn reason(status: u16) -> &'static str {
    match status {
        200 => "OK",
        400 => "Bad Request",
        403 => "Forbidden",
        404 => "Not Found",
        405 => "Method Not Allowed",
        408 => "Request Timeout",
        413 => "Content Too Large",
        415 => "Unsupported Media Type",
        431 => "Request Header Fields Too Large",
        501 => "Not Implemented",
        503 => "Service Unavailable",
        _ => "",
    }
}

/// Why a request was not read: the answer to give, or none (the client is
/// gone).
#[derive(Debug)]
enum Unread {
    Refused(Response),
    Gone,
}

fn refuse(status: u16, message: &str) -> Unread {
    Unread::Refused(Response::text(status, message))
}

/// Reads into `buf` before `deadline`.
fn read_some(stream: &mut TcpStream, buf: &mut [u8], deadline: Instant) -> Result<usize, Unread> {
    let left = deadline.saturating_duration_since(Instant::now());
    let timed_out = || refuse(408, "the request took too long to arrive");
    if left.is_zero() {
        return Err(timed_out());
    }
    stream
        .set_read_timeout(Some(left))
        .map_err(|_| Unread::Gone)?;
    match stream.read(buf) {
        Ok(0) => Err(Unread::Gone),
        Ok(n) => Ok(n),
        Err(e)
            if matches!(
                e.kind(),
                std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut
            ) =>
        {
            Err(timed_out())
        }
        Err(_) => Err(Unread::Gone),
    }
}

/// Reads the request line and headers (at most [`MAX_HEAD`] bytes): the
/// head, and the bytes after it already read.
fn read_head(stream: &mut TcpStream, deadline: Instant) -> Result<(String, Vec<u8>), Unread> {
    let mut buf = Vec::with_capacity(4096);
    let mut chunk = [0u8; 4096];
    loop {
        if let Some(end) = buf.windows(4).position(|w| w == b"\r\n\r\n") {
            let rest = buf.split_off(end + 4);
            buf.truncate(end);
            let head = String::from_utf8(buf)
                .map_err(|_| refuse(400, "the request's head is not UTF-8"))?;
            return Ok((head, rest));
        }
        let room = MAX_HEAD + 4 - buf.len();
        if room == 0 {
            return Err(refuse(
                431,
                "request line and headers over 16 KiB: refused unread",
            ));
        }
        let n = read_some(stream, &mut chunk[..room.min(4096)], deadline)?;
        buf.extend_from_slice(&chunk[..n]);
    }
}

/// The request of a head (its body still empty).
fn parse_head(head: &str) -> Result<Request, Unread> {
    let mut lines = head.split("\r\n");
    let line = lines.next().unwrap_or("");
    let parts: Vec<&str> = line.split(' ').collect();
    let [method, target, version] = parts[..] else {
        return Err(refuse(400, "a malformed request line"));
    };
    if !matches!(version, "HTTP/1.1" | "HTTP/1.0") || !target.starts_with('/') {
        return Err(refuse(400, "a malformed request line"));
    }
    let mut headers: Vec<(String, String)> = Vec::new();
    for l in lines {
        let (k, v) = l
            .split_once(':')
            .filter(|(k, _)| !k.is_empty() && !k.contains([' ', '\t']))
            .ok_or_else(|| refuse(400, "a malformed header line"))?;
        let k = k.to_ascii_lowercase();
        if headers.iter().any(|(seen, _)| *seen == k) {
            return Err(refuse(400, "a header sent twice"));
        }
        headers.push((k, v.trim().to_string()));
    }
    Ok(Request {
        method: method.to_string(),
        target: target.to_string(),
        headers,
        body: Vec::new(),
    })
}

/// Reads one request within the limits, before `timeout` has passed.
fn read_request(stream: &mut TcpStream, timeout: Duration) -> Result<Request, Unread> {
    let deadline = Instant::now() + timeout;
    let (head, mut body) = read_head(stream, deadline)?;
    let mut req = parse_head(&head)?;
    if req.header("transfer-encoding").is_some() {
        return Err(refuse(501, "chunked request bodies are not accepted"));
    }
    let length = match req.header("content-length") {
        None => 0,
        Some(n) => n
            .parse::<usize>()
            .map_err(|_| refuse(400, "a malformed Content-Length"))?,
    };
    if length > MAX_BODY {
        return Err(refuse(413, "a request body over 64 KiB"));
    }
    let mut chunk = [0u8; 4096];
    while body.len() < length {
        let n = read_some(stream, &mut chunk, deadline)?;
        body.extend_from_slice(&chunk[..n]);
    }
    body.truncate(length);
    req.body = body;
    Ok(req)
}

/// Sends `response` and closes, reading and dropping (at most
/// [`MAX_DRAIN`] bytes, for a second) what the client still sends, so
/// that the close does not reset the connection before the answer is read.
fn send_and_close(stream: &mut TcpStream, response: &Response, drain: bool) {
    let _ = response.write_to(stream);
    let _ = stream.shutdown(Shutdown::Write);
    if drain {
        let deadline = Instant::now() + Duration::from_secs(1);
        let mut chunk = [0u8; 4096];
        let mut dropped = 0;
        while dropped < MAX_DRAIN {
            match read_some(stream, &mut chunk, deadline) {
                Ok(n) => dropped += n,
                Err(_) => break,
            }
        }
    }
}

/// One connection: its request read and answered by `handle`.
fn serve_connection(
    mut stream: TcpStream,
    timeout: Duration,
    handle: &(dyn Fn(&Request) -> Response + Sync),
) {
    let _ = stream.set_write_timeout(Some(timeout));
    match read_request(&mut stream, timeout) {
        Ok(req) => send_and_close(&mut stream, &handle(&req), false),
        Err(Unread::Refused(r)) => send_and_close(&mut stream, &r, true),
        Err(Unread::Gone) => {}
    }
}

/// A count of things in use, at most `max` at once.
#[derive(Debug)]
pub(super) struct Slots {
    used: AtomicUsize,
    max: usize,
}

/// One slot taken from [`Slots`], given back when dropped.
pub(super) struct Slot(Arc<Slots>);

impl Slots {
    /// At most `max` at once.
    pub(super) fn new(max: usize) -> Arc<Slots> {
        Arc::new(Slots {
            used: AtomicUsize::new(0),
            max,
        })
    }

    /// A slot, if one is free.
    pub(super) fn take(self: &Arc<Self>) -> Option<Slot> {
        self.used
            .fetch_update(Ordering::AcqRel, Ordering::Acquire, |n| {
                (n < self.max).then_some(n + 1)
            })
            .ok()
            .map(|_| Slot(self.clone()))
    }
}

impl Drop for Slot {
    fn drop(&mut self) {
        self.0.used.fetch_sub(1, Ordering::AcqRel);
    }
}

/// Accepts connections on `listener` forever, each on a thread of its own,
/// at most `connections` at once; `timeout` bounds each request's arrival
/// and each write.
pub(super) fn run(
    listener: &TcpListener,
    connections: usize,
    timeout: Duration,
    handle: Arc<dyn Fn(&Request) -> Response + Send + Sync>,
) {
    let slots = Slots::new(connections);
    for stream in listener.incoming() {
        let Ok(mut stream) = stream else { continue };
        let Some(slot) = slots.take() else {
            let _ = stream.set_write_timeout(Some(Duration::from_millis(200)));
            let busy =
                Response::text(503, "too many connections; try again").with("Retry-After", "1");
            let _ = busy.write_to(&mut stream);
            continue;
        };
        let handle = handle.clone();
        let spawned = std::thread::Builder::new()
            .name("vstf-serve".into())
            .spawn(move || {
                let _slot = slot;
                serve_connection(stream, timeout, &*handle);
            });
        drop(spawned);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heads_are_parsed_and_bad_ones_refused() {
        let r = parse_head("GET /a?b=c HTTP/1.1\r\nHost: x:1\r\nX-Y:  z ").unwrap();
        assert_eq!((r.method.as_str(), r.path()), ("GET", "/a"));
        assert_eq!(r.header("x-y"), Some("z"));
        assert_eq!(
            r.headers,
            vec![("host".into(), "x:1".into()), ("x-y".into(), "z".into())]
        );
        for bad in [
            "GET /a",
            "GET a HTTP/1.1",
            "GET /a HTTP/2\r\n",
            "GET /a HTTP/1.1\r\nno colon",
            "GET /a HTTP/1.1\r\nHost: a\r\nhost: b",
            "GET /a HTTP/1.1\r\n folded: x",
        ] {
            assert!(parse_head(bad).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn slots_are_bounded_and_given_back() {
        let s = Slots::new(2);
        let a = s.take().unwrap();
        let _b = s.take().unwrap();
        assert!(s.take().is_none());
        drop(a);
        assert!(s.take().is_some());
    }
}
