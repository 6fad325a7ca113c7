//! Who may ask `vstf serve` for what. The server listens on loopback, but
//! every web page its user has open can send requests there: a request is
//! answered only if it names the server's own address as its `Host` (so a
//! DNS-rebinding page cannot read it), comes from the server's own page
//! when it says where it comes from (`Origin`), and carries the
//! per-process token that only that page was given. Requests that change
//! something must also be POSTs with a JSON body, which no cross-site form
//! can send.

use std::io::Read;

/// A refused request: the HTTP status and what the answer says.
pub(super) type Refusal = (u16, String);

/// The header the page sends its token in.
pub(super) const TOKEN_HEADER: &str = "X-Vstf-Token";

/// A new random token: 32 bytes of the system's randomness, in hex.
pub(super) fn new_token() -> std::io::Result<String> {
    let mut bytes = [0u8; 32];
    std::fs::File::open("/dev/urandom")?.read_exact(&mut bytes)?;
    Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
}

/// The server's own names at `port`: what `Host` may say.
pub(super) fn own_hosts(port: u16) -> [String; 3] {
    [
        format!("127.0.0.1:{port}"),
        format!("localhost:{port}"),
        format!("[::1]:{port}"),
    ]
}

/// What a request shows of itself, as the guard reads it.
pub(super) struct Asked<'a> {
    /// The `Host` header.
    pub host: Option<&'a str>,
    /// The `Origin` header.
    pub origin: Option<&'a str>,
    /// The token, from its header or the `token` query parameter.
    pub token: Option<&'a str>,
    /// The `Content-Type` header.
    pub content_type: Option<&'a str>,
    /// Whether the method is POST.
    pub post: bool,
}

/// Whether `asked` may reach the page itself (`Host` only).
pub(super) fn page(asked: &Asked, hosts: &[String; 3]) -> Result<(), Refusal> {
    match asked.host {
        Some(h) if hosts.iter().any(|o| o == h) => Ok(()),
        _ => Err((403, "forbidden: not this server's address".into())),
    }
}

/// Whether `asked` may reach an endpoint of the API; `changes` for those
/// that change the project or run its checks.
pub(super) fn api(
    asked: &Asked,
    (hosts, token): (&[String; 3], &str),
    changes: bool,
) -> Result<(), Refusal> {
    page(asked, hosts)?;
    if let Some(origin) = asked.origin {
        let own = hosts.iter().any(|h| origin == format!("http://{h}"));
        if !own {
            return Err((403, "forbidden: a request from another origin".into()));
        }
    }
    if !asked
        .token
        .is_some_and(|t| same(t.as_bytes(), token.as_bytes()))
    {
        return Err((
            403,
            "forbidden: no valid token (open the page vstf serve printed)".into(),
        ));
    }
    if changes {
        if !asked.post {
            return Err((405, "this endpoint takes POST".into()));
        }
        let json = asked.content_type.is_some_and(|c| {
            c.split(';')
                .next()
                .is_some_and(|m| m.trim() == "application/json")
        });
        if !json {
            return Err((415, "this endpoint takes an application/json body".into()));
        }
    }
    Ok(())
}

/// Equality of two byte strings in time that depends only on their lengths.
fn same(a: &[u8], b: &[u8]) -> bool {
    a.len() == b.len() && a.iter().zip(b).fold(0u8, |d, (x, y)| d | (x ^ y)) == 0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn asked<'a>(host: &'a str, origin: Option<&'a str>, token: Option<&'a str>) -> Asked<'a> {
        Asked {
            host: Some(host),
            origin,
            token,
            content_type: Some("application/json"),
            post: true,
        }
    }

    #[test]
    fn only_the_own_page_with_its_token_gets_through() {
        let hosts = own_hosts(8117);
        let t = new_token().unwrap();
        assert_eq!(t.len(), 64);
        assert_ne!(t, new_token().unwrap());
        let ok = asked("127.0.0.1:8117", Some("http://127.0.0.1:8117"), Some(&t));
        assert!(api(&ok, (&hosts, &t), true).is_ok());
        assert!(api(&asked("localhost:8117", None, Some(&t)), (&hosts, &t), true).is_ok());
        let cases = [
            asked("evil.example:8117", Some("http://evil.example"), Some(&t)),
            asked("127.0.0.1:8117", Some("http://evil.example"), Some(&t)),
            asked("127.0.0.1:8117", Some("http://127.0.0.1:9000"), Some(&t)),
            asked("127.0.0.1:8117", None, None),
            asked("127.0.0.1:8117", None, Some("0000")),
        ];
        for a in &cases {
            assert_eq!(api(a, (&hosts, &t), false).unwrap_err().0, 403);
        }
        let form = Asked {
            content_type: Some("text/plain"),
            ..asked("127.0.0.1:8117", None, Some(&t))
        };
        assert_eq!(api(&form, (&hosts, &t), true).unwrap_err().0, 415);
        let get = Asked {
            post: false,
            ..asked("127.0.0.1:8117", None, Some(&t))
        };
        assert_eq!(api(&get, (&hosts, &t), true).unwrap_err().0, 405);
        assert!(api(&get, (&hosts, &t), false).is_ok());
    }
}
