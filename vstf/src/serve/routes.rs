//! One request answered: who may ask (`Host`, `Origin`, the token), how
//! (`GET` to read and render, `POST` of JSON to change state), what (a
//! fixture and view named in the project, never a path), and how many
//! renders at once.

use super::frame::{query, Frame};
use super::http::{Request, Response};
use super::Site;
use crate::fixture::Fixture;
use serde_json::Value;
use std::collections::HashMap;

/// The page (HTML, CSS and script in one file); `__VSTF_TOKEN__` is
/// replaced by the process's token when served.
const PAGE: &str = include_str!("serve.html");

/// The page may run its own inline script and style, fetch from its own
/// origin and show its own and blob images; nothing else, and no framing.
const POLICY: &str = "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; \
     img-src 'self' blob:; connect-src 'self'; base-uri 'none'; form-action 'none'; \
     frame-ancestors 'none'";

/// The most characters of a name a message repeats.
const ECHOED: usize = 64;

/// What the server answers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Route {
    Page,
    Fixtures,
    Render,
    Debug,
    Image,
    Check,
    Approve,
    Reject,
}

impl Route {
    fn of(path: &str) -> Option<Route> {
        Some(match path {
            "/" => Route::Page,
            "/api/fixtures" => Route::Fixtures,
            "/api/render" => Route::Render,
            "/api/debug" => Route::Debug,
            "/api/image" => Route::Image,
            "/api/check" => Route::Check,
            "/api/approve" => Route::Approve,
            "/api/reject" => Route::Reject,
            _ => return None,
        })
    }

    /// Whether it changes state (`POST` of JSON; else `GET`).
    fn changes(self) -> bool {
        matches!(self, Route::Check | Route::Approve | Route::Reject)
    }

    /// Whether it renders (a slot of [`super::Limits::renders`]).
    fn renders(self) -> bool {
        matches!(self, Route::Render | Route::Debug | Route::Check)
    }
}

fn text(status: u16, message: impl Into<String>) -> Response {
    Response::text(status, message)
}

/// `name` quoted and escaped for a message, at most [`ECHOED`] characters.
fn echo(name: &str) -> String {
    let short: String = name.chars().take(ECHOED).collect();
    let more = if short.len() < name.len() { "…" } else { "" };
    format!("{short:?}{more}")
}

/// A JSON body's string field.
fn field<'a>(body: &'a Value, key: &str) -> Result<&'a str, Response> {
    body.get(key)
        .and_then(Value::as_str)
        .ok_or_else(|| text(400, format!("the JSON body needs a string {key:?}")))
}

impl Site {
    /// Answers one request.
    pub(super) fn handle(&self, req: &Request) -> Response {
        let (Ok(r) | Err(r)) = self.answer(req);
        r.with("Cache-Control", "no-store")
            .with("X-Content-Type-Options", "nosniff")
            .with("X-Frame-Options", "DENY")
            .with("Referrer-Policy", "no-referrer")
            .with("Content-Security-Policy", POLICY)
    }

    fn answer(&self, req: &Request) -> Result<Response, Response> {
        let route = self.admit(req)?;
        if route == Route::Page {
            let page = PAGE.replace("__VSTF_TOKEN__", self.guard.token());
            return Ok(Response::new(
                200,
                "text/html; charset=utf-8",
                page.into_bytes(),
            ));
        }
        let q = query(&req.target);
        self.authorize(req, route, &q)?;
        let _slot = match route.renders() {
            true => Some(self.busy.take().ok_or_else(|| {
                text(
                    503,
                    "busy: as many renders as allowed are running; try again",
                )
                .with("Retry-After", "1")
            })?),
            false => None,
        };
        if route.changes() {
            let body: Value = serde_json::from_slice(&req.body)
                .map_err(|e| text(400, format!("the body is not JSON: {e}")))?;
            return self.change(route, &body);
        }
        self.read(route, &q)
    }

    /// The route of a request that names this server, from its own origin
    /// if any, with the route's method.
    fn admit(&self, req: &Request) -> Result<Route, Response> {
        if !self.guard.host_ok(req.header("host")) {
            return Err(text(
                403,
                "this server answers only to 127.0.0.1, localhost or [::1] with its port",
            ));
        }
        if !self.guard.origin_ok(req.header("origin")) {
            return Err(text(403, "requests from other origins are refused"));
        }
        let route = Route::of(req.path()).ok_or_else(|| text(404, "no such page"))?;
        let method = if route.changes() { "POST" } else { "GET" };
        if req.method != method {
            return Err(text(405, format!("{method} only")).with("Allow", method));
        }
        Ok(route)
    }

    /// Refuses a request without the token (a header; a `token=` query
    /// parameter for reading), and a change whose body is not JSON.
    fn authorize(
        &self,
        req: &Request,
        route: Route,
        q: &HashMap<String, String>,
    ) -> Result<(), Response> {
        let in_query = (!route.changes()).then(|| q.get("token").map(String::as_str));
        let token = req.header("x-vstf-token").or(in_query.flatten());
        if !self.guard.token_ok(token) {
            return Err(text(
                403,
                "a missing or wrong token: use the page this server serves at /",
            ));
        }
        let json = req
            .header("content-type")
            .and_then(|c| c.split(';').next())
            .is_some_and(|c| c.trim().eq_ignore_ascii_case("application/json"));
        if route.changes() && !json {
            return Err(text(
                415,
                "changes take a JSON body (Content-Type: application/json)",
            ));
        }
        Ok(())
    }

    /// The project's fixture `name` (404 for any other name).
    fn fixture_named(&self, name: &str) -> Result<Fixture, Response> {
        if !self.project.fixture_names().iter().any(|n| n == name) {
            return Err(text(
                404,
                format!("no fixture named {} in this project", echo(name)),
            ));
        }
        self.load(name).map_err(|e| text(400, e))
    }

    /// The project's fixture `fixture`, which has a view `view`.
    fn view_named(&self, fixture: &str, view: &str) -> Result<Fixture, Response> {
        let f = self.fixture_named(fixture)?;
        if !crate::check::views_of(&f).iter().any(|v| v.name == view) {
            return Err(text(
                404,
                format!("fixture {} has no view named {}", echo(fixture), echo(view)),
            ));
        }
        Ok(f)
    }

    fn read(&self, route: Route, q: &HashMap<String, String>) -> Result<Response, Response> {
        let png = |b| Response::new(200, "image/png", b);
        let failed = |e: String| text(400, e);
        if route == Route::Fixtures {
            let list = self.fixtures().to_string().into_bytes();
            return Ok(Response::new(200, "application/json", list));
        }
        let fr = Frame::of(q).map_err(failed)?;
        let loaded = self.view_named(&fr.fixture, &fr.view)?;
        match route {
            Route::Render => self
                .render(&fr, &loaded)
                .map(|(bytes, t)| png(bytes).with("X-Vstf-Camera-T", t.to_string()))
                .map_err(failed),
            Route::Debug => {
                let at = |k: &str| {
                    q.get(k)
                        .and_then(|v| v.parse::<u32>().ok())
                        .ok_or_else(|| text(400, format!("{k}: a pixel index")))
                };
                let said = self.debug(&fr, &loaded, (at("x")?, at("y")?));
                said.map(|s| text(200, s)).map_err(failed)
            }
            _ => {
                let kind = q.get("kind").map_or("", String::as_str);
                let image = self.image(&fr.fixture, &fr.view, kind);
                image.map(png).map_err(|e| text(404, e))
            }
        }
    }

    fn change(&self, route: Route, body: &Value) -> Result<Response, Response> {
        let fixture = field(body, "fixture")?;
        if route == Route::Check {
            self.fixture_named(fixture)?;
            let v = self.check(fixture).map_err(|e| text(400, e))?;
            return Ok(Response::new(
                200,
                "application/json",
                v.to_string().into_bytes(),
            ));
        }
        let view = field(body, "view")?;
        self.view_named(fixture, view)?;
        let said = self.decide(fixture, view, route == Route::Approve);
        said.map(|s| text(200, s)).map_err(|e| text(400, e))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_echoed_short_and_escaped() {
        assert_eq!(echo("x"), "\"x\"");
        assert_eq!(echo("a\nb\u{1b}"), "\"a\\nb\\u{1b}\"");
        let long = "y".repeat(1000);
        assert_eq!(echo(&long).len(), ECHOED + 2 + "…".len());
    }
}
