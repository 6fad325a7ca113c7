//! Who may talk to the server: requests naming it by its loopback address
//! (`Host`; this defeats DNS rebinding), from its own page when a browser
//! says where from (`Origin`), carrying the process's random token, which
//! only the page served at `/` knows.

use crate::error::Error;
use std::io::Read;

/// The token's length in random bytes (hex doubles it).
const TOKEN_BYTES: usize = 32;

/// The server's port, and its token.
pub(super) struct Guard {
    port: u16,
    token: String,
}

impl Guard {
    /// The guard of a server on `port`, with a fresh token from
    /// `/dev/urandom`.
    pub(super) fn new(port: u16) -> Result<Guard, Error> {
        let mut bytes = [0u8; TOKEN_BYTES];
        std::fs::File::open("/dev/urandom")
            .and_then(|mut f| f.read_exact(&mut bytes))
            .map_err(|e| Error::Io {
                path: "/dev/urandom".into(),
                message: format!("cannot read a random token: {e}"),
            })?;
        Ok(Guard {
            port,
            token: bytes.iter().map(|b| format!("{b:02x}")).collect(),
        })
    }

    /// The token (for the page).
    pub(super) fn token(&self) -> &str {
        &self.token
    }

    /// The host names the server answers to, with its port.
    fn hosts(&self) -> [String; 3] {
        let p = self.port;
        [
            format!("127.0.0.1:{p}"),
            format!("localhost:{p}"),
            format!("[::1]:{p}"),
        ]
    }

    /// Whether `host` (the `Host` header) names this server.
    pub(super) fn host_ok(&self, host: Option<&str>) -> bool {
        host.is_some_and(|h| self.hosts().iter().any(|k| k.eq_ignore_ascii_case(h)))
    }

    /// Whether `origin` (the `Origin` header, if sent) is this server's.
    pub(super) fn origin_ok(&self, origin: Option<&str>) -> bool {
        origin.is_none_or(|o| {
            self.hosts()
                .iter()
                .any(|k| o.eq_ignore_ascii_case(&format!("http://{k}")))
        })
    }

    /// Whether `given` is the token (compared in constant time).
    pub(super) fn token_ok(&self, given: Option<&str>) -> bool {
        given.is_some_and(|g| same(g.as_bytes(), self.token.as_bytes()))
    }
}

/// Whether `a` and `b` are equal, in a time that depends on their lengths
/// only.
fn same(a: &[u8], b: &[u8]) -> bool {
    a.len() == b.len() && a.iter().zip(b).fold(0u8, |d, (x, y)| d | (x ^ y)) == 0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hosts_origins_and_tokens() {
        let g = Guard::new(8117).unwrap();
        assert_eq!(g.token().len(), 64);
        assert_ne!(g.token(), Guard::new(8117).unwrap().token());
        for ok in [
            "127.0.0.1:8117",
            "localhost:8117",
            "LOCALHOST:8117",
            "[::1]:8117",
        ] {
            assert!(g.host_ok(Some(ok)), "{ok}");
        }
        for bad in [
            "evil.example:8117",
            "127.0.0.1",
            "127.0.0.1:8118",
            "localhost.evil:8117",
        ] {
            assert!(!g.host_ok(Some(bad)), "{bad}");
        }
        assert!(!g.host_ok(None));
        assert!(g.origin_ok(None) && g.origin_ok(Some("http://localhost:8117")));
        assert!(!g.origin_ok(Some("null")) && !g.origin_ok(Some("http://127.0.0.1:9000")));
        assert!(g.token_ok(Some(g.token())));
        assert!(!g.token_ok(Some("")) && !g.token_ok(None));
        assert!(!g.token_ok(Some(&g.token()[1..])));
    }
}
