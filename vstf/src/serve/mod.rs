//! `vstf serve`: a local page for looking at a project's views, bound to
//! 127.0.0.1 only. Every view of every fixture, its golden and pending
//! images, a flip between render and golden, approve and reject, sliders
//! for the camera time and (with one moving object) its speed, a model
//! switch, and a click on a pixel for its debug variables (the functions
//! `vstf debug` runs), and a fixture's check run on request (its rows
//! shown beside the view they were measured in, as `vstf check` judges
//! them). Frames render on demand; each scene's database is built once and
//! kept. The page has no external assets: it works offline.

mod cache;
mod guard;

use crate::error::Error;
use crate::fixture::{Fixture, Overrides, View};
use crate::golden::{slug, Store};
use crate::project::Project;
use crate::Budget;
use glam::DVec3;
use renderer::{Database, Model, Motion, Traversal};
use std::collections::HashMap;
use std::io::Cursor;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use tiny_http::{Header, Method, Request, Response, Server};

/// The page (HTML, CSS and script in one file).
const PAGE: &str = include_str!("serve.html");

/// What a render request asks for: a declared view, at a camera time and
/// in a model, with the moving object's speed scaled.
#[derive(Clone, Debug, PartialEq)]
struct Frame {
    fixture: String,
    view: String,
    t: Option<f64>,
    model: Option<Model>,
    speed: f64,
}

type Cache = cache::Lru<(String, String, bool, u64), (Fixture, Database)>;

/// The default byte budget of the database cache.
pub const DEFAULT_CACHE_BYTES: u64 = 512 << 20;

/// Most renders, debug traces and checks running at once; more get 503.
const MAX_BUSY: usize = 2;

/// Most requests handled at once; more are answered 503 at once.
const MAX_CONNECTIONS: usize = 16;

/// The server's state: the project, its token and own addresses, the
/// databases built so far (within a byte budget) and each fixture's last
/// check.
pub struct Site {
    project: Project,
    token: String,
    hosts: [String; 3],
    databases: Mutex<Cache>,
    checked: Mutex<HashMap<String, serde_json::Value>>,
    busy: AtomicUsize,
}

fn query(url: &str) -> HashMap<String, String> {
    let q = url.split_once('?').map_or("", |(_, q)| q);
    q.split('&')
        .filter_map(|kv| kv.split_once('='))
        .map(|(k, v)| (decode(k), decode(v)))
        .collect()
}

/// Percent-decoding of a query component (`+` is a space; a `%` not
/// followed by two hex digits stays as it is).
fn decode(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = b
            .get(i + 1..i + 3)
            .and_then(|h| std::str::from_utf8(h).ok())
            .and_then(|h| u8::from_str_radix(h, 16).ok());
        match (b[i], hex) {
            (b'+', _) => out.push(b' '),
            (b'%', Some(v)) => {
                out.push(v);
                i += 2;
            }
            (c, _) => out.push(c),
        }
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

fn model_named(s: &str) -> Option<Model> {
    match s {
        "infinite" => Some(Model::INFINITE),
        "classical" => Some(Model::CLASSICAL),
        "relativistic" => Some(Model::RELATIVISTIC),
        _ => None,
    }
}

impl Frame {
    fn of(q: &HashMap<String, String>) -> Result<Frame, String> {
        let get = |k: &str| q.get(k).ok_or_else(|| format!("missing {k}"));
        let number = |k: &str| -> Result<Option<f64>, String> {
            match q.get(k).filter(|v| !v.is_empty()) {
                None => Ok(None),
                Some(v) => v
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .map(Some)
                    .ok_or_else(|| format!("{k}={v}: not a number")),
            }
        };
        let model = match q.get("model").map(String::as_str) {
            None | Some("") | Some("view") => None,
            Some(m) => Some(
                model_named(m)
                    .ok_or_else(|| format!("model={m}: infinite, classical or relativistic"))?,
            ),
        };
        Ok(Frame {
            fixture: get("fixture")?.clone(),
            view: get("view")?.clone(),
            t: number("t")?,
            model,
            speed: number("speed")?.unwrap_or(1.0),
        })
    }
}

/// The one uniformly moving object of a fixture, if it has exactly one.
pub fn single_mover(f: &Fixture) -> Option<usize> {
    let movers: Vec<usize> = f
        .scene
        .objects
        .iter()
        .enumerate()
        .filter(|(_, o)| o.motion.velocity().is_some_and(|v| v != DVec3::ZERO))
        .map(|(i, _)| i)
        .collect();
    (movers.len() == 1).then(|| movers[0])
}

/// The fixture with its single moving object's velocity scaled by `k`
/// (its start event kept).
fn with_speed(f: &Fixture, k: f64) -> Result<Fixture, String> {
    if k == 1.0 {
        return Ok(f.clone());
    }
    let i =
        single_mover(f).ok_or("the speed slider needs a fixture with exactly one moving object")?;
    let mut f = f.clone();
    match &mut f.scene.objects[i].motion {
        Motion::Extrusion { extrusion, .. } => extrusion.x *= k,
        Motion::Velocity { velocity, .. } => *velocity *= k,
        _ => return Err("only uniform motion can be sped up".into()),
    }
    Ok(f)
}

impl Site {
    /// The site of `project` served at `port`, keeping at most
    /// `cache_bytes` of databases.
    pub fn new(project: Project, port: u16, cache_bytes: u64) -> Result<Site, Error> {
        let token = guard::new_token()
            .map_err(|e| Error::io("/dev/urandom", format!("cannot make a token: {e}")))?;
        Ok(Site {
            project,
            token,
            hosts: guard::own_hosts(port),
            databases: Mutex::new(cache::Lru::new(cache_bytes)),
            checked: Mutex::new(HashMap::new()),
            busy: AtomicUsize::new(0),
        })
    }

    /// The token the page carries, for a front end in the same process.
    pub fn token(&self) -> &str {
        &self.token
    }

    /// The bytes of databases kept now.
    pub fn cached_bytes(&self) -> u64 {
        self.databases.lock().map_or(0, |c| c.used())
    }

    /// `name` if it is one of the project's fixtures; a 404 that repeats
    /// only a short, quoted form of the name otherwise.
    fn known(&self, name: &str) -> Result<(), (u16, String)> {
        if self.project.fixture_names().iter().any(|n| n == name) {
            return Ok(());
        }
        let shown: String = name.chars().take(64).collect();
        Err((404, format!("no fixture named {shown:?} in this project")))
    }

    /// Runs `work` if fewer than [`MAX_BUSY`] are running; 503 otherwise.
    fn when_free<T>(&self, work: impl FnOnce() -> Result<T, String>) -> Result<T, (u16, String)> {
        if self.busy.fetch_add(1, Ordering::SeqCst) >= MAX_BUSY {
            self.busy.fetch_sub(1, Ordering::SeqCst);
            return Err((503, "busy: try again in a moment".into()));
        }
        let result = work();
        self.busy.fetch_sub(1, Ordering::SeqCst);
        result.map_err(|e| (400, e))
    }

    fn store(&self) -> Store {
        self.project.store()
    }

    /// The fixture, view and database of a frame (the database built once
    /// per fixture, view, Lorentz setting and speed).
    fn prepare(&self, fr: &Frame) -> Result<(Arc<(Fixture, Database)>, View), String> {
        let loaded = self
            .project
            .load_within(&fr.fixture, &Budget::DEFAULT)
            .map_err(|e| e.to_string())?;
        let (fixture, golden) = crate::check::golden_view(&loaded, &fr.view)?;
        let fixture = with_speed(&fixture, fr.speed)?;
        let model = fr.model.unwrap_or(golden.model);
        let overrides = Overrides {
            model: Some(model),
            camera_t: Some(fr.t.unwrap_or(golden.camera_t)),
            width: Some(golden.camera.width),
            height: Some(golden.camera.height),
            spp: Some(golden.settings.spp),
            doppler: golden.settings.effects.doppler,
            searchlight: golden.settings.effects.searchlight,
        };
        let view = crate::run::view(&fixture, &overrides)?;
        let key = (
            fr.fixture.clone(),
            fr.view.clone(),
            model.lorentz,
            fr.speed.to_bits(),
        );
        let mut cache = self
            .databases
            .lock()
            .map_err(|_| "the database cache is poisoned")?;
        let entry = match cache.get(&key) {
            Some(e) => e,
            None => {
                drop(cache);
                let bytes = crate::budget::database_bytes(&fixture.scene);
                let db = crate::run::database(&fixture, model.lorentz, Traversal::Bvh)?;
                let e = Arc::new((fixture, db));
                self.databases
                    .lock()
                    .map_err(|_| "the database cache is poisoned")?
                    .insert(key, e.clone(), bytes);
                e
            }
        };
        Ok((entry, view))
    }

    fn render(&self, fr: &Frame) -> Result<Vec<u8>, String> {
        let (entry, view) = self.prepare(fr)?;
        let img = crate::output::rgb8(&crate::run::render_with(&entry.1, &entry.0, &view)?);
        let mut png = Vec::new();
        img.write_to(&mut Cursor::new(&mut png), image::ImageFormat::Png)
            .map_err(|e| e.to_string())?;
        Ok(png)
    }

    fn debug(&self, fr: &Frame, (x, y): (u32, u32)) -> Result<String, String> {
        let (entry, view) = self.prepare(fr)?;
        let mut log = crate::debug::trace_pixel(&entry.0, &view, &entry.1, x, y)?;
        log.drop_candidates();
        Ok(crate::debug::describe(&log))
    }

    /// Runs `fixture`'s checks as `vstf check` does (pending images written
    /// where a golden differs): whether all passed, each row with the views
    /// it was measured in, and each golden comparison. Kept for the list.
    fn check(&self, fixture: &str) -> Result<serde_json::Value, String> {
        let reports =
            crate::check::run(&self.project, &[fixture.to_string()], &crate::Effort::FULL)?;
        let r = reports.first().ok_or("no report")?;
        let rows: Vec<serde_json::Value> = r
            .rows
            .iter()
            .map(|x| {
                let views: Vec<&str> = r
                    .views
                    .iter()
                    .filter(|v| v.measured.contains(&x.quantity))
                    .map(|v| v.name.as_str())
                    .collect();
                serde_json::json!({
                    "quantity": x.quantity, "measured": x.measured, "expected": x.expected,
                    "tolerance": x.tolerance, "unit": x.unit.as_str(), "pass": x.pass, "views": views,
                })
            })
            .collect();
        let goldens: Vec<serde_json::Value> = r
            .goldens
            .iter()
            .map(|g| serde_json::json!({"view": g.view, "pass": g.pass, "said": g.to_string()}))
            .collect();
        let value = serde_json::json!({"fixture": r.fixture, "passed": r.passed(), "rows": rows, "goldens": goldens});
        self.checked
            .lock()
            .map_err(|_| "the check cache is poisoned")?
            .insert(fixture.to_string(), value.clone());
        Ok(value)
    }

    /// Every fixture with its declared views, each with whether it has a
    /// golden and a pending image, and the view's camera time; whether the
    /// fixture has one moving object (the speed slider); and its last
    /// check on this page, if any.
    fn fixtures(&self) -> serde_json::Value {
        let store = self.store();
        let checked = self.checked.lock().map(|c| c.clone()).unwrap_or_default();
        let list: Vec<serde_json::Value> = self
            .project
            .fixture_names()
            .into_iter()
            .filter_map(|name| {
                let f = self.project.load_within(&name, &Budget::DEFAULT).ok()?;
                let views: Vec<serde_json::Value> = f
                    .spec
                    .views
                    .iter()
                    .map(|v| {
                        serde_json::json!({
                            "name": v.name,
                            "t": v.t.unwrap_or(f.spec.camera.t),
                            "golden": store.golden_path(&name, &v.name).is_file(),
                            "pending": store.pending_dir(&name, &v.name).join("actual.png").is_file(),
                        })
                    })
                    .collect();
                Some(serde_json::json!({"name": name, "views": views, "one_mover": single_mover(&f).is_some(),
                    "checked": checked.get(&name)}))
            })
            .collect();
        serde_json::Value::Array(list)
    }

    /// A golden or pending image of a view, as PNG bytes.
    fn image(&self, fixture: &str, view: &str, kind: &str) -> Result<Vec<u8>, String> {
        let store = self.store();
        let path = match kind {
            "golden" => store.golden_path(fixture, view),
            "actual" | "expected" | "diff" => {
                store.pending_dir(fixture, view).join(format!("{kind}.png"))
            }
            _ => return Err(format!("kind={kind}: golden, actual, expected or diff")),
        };
        std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))
    }

    fn decide(&self, fixture: &str, view: &str, approve: bool) -> Result<String, String> {
        let store = self.store();
        let name = [format!("{fixture}/{}", slug(view))];
        if approve {
            let ci = crate::golden::ci_is_set(std::env::var("CI").ok().as_deref());
            store.approve(Some(&name), ci)?;
            Ok(format!(
                "approved: {}",
                store.golden_path(fixture, view).display()
            ))
        } else {
            store.reject(Some(&name))?;
            Ok(format!("rejected {fixture} / {view}"))
        }
    }

    /// Answers one request: the guard first ([`guard`]), then the page or
    /// the endpoint asked for, by fixture and view names of this project.
    pub fn handle(&self, req: Request) {
        let url = req.url().to_string();
        let path = url.split('?').next().unwrap_or("").to_string();
        let q = query(&url);
        let result = self.answer(&req, &path, &q);
        let response = match result {
            Ok((kind, body)) => Response::from_data(body).with_header(header("Content-Type", kind)),
            Err((code, e)) => Response::from_data(e.into_bytes())
                .with_status_code(code)
                .with_header(header("Content-Type", "text/plain; charset=utf-8")),
        };
        let _ = req.respond(response.with_header(header("Cache-Control", "no-store")));
    }

    /// The answer to `req` for `path`: its content type and body, or a
    /// status and message.
    fn answer(&self, req: &Request, path: &str, q: &Query) -> Answer {
        let named = |name: &'static str| {
            req.headers()
                .iter()
                .find(|h| h.field.equiv(name))
                .map(|h| h.value.as_str())
        };
        let asked = guard::Asked {
            host: named("Host"),
            origin: named("Origin"),
            token: named(guard::TOKEN_HEADER).or(q.get("token").map(String::as_str)),
            content_type: named("Content-Type"),
            post: *req.method() == Method::Post,
        };
        if path == "/" {
            guard::page(&asked, &self.hosts)?;
            let page = PAGE.replace("{{VSTF_TOKEN}}", &self.token);
            return Ok(("text/html; charset=utf-8", page.into_bytes()));
        }
        let changes = matches!(path, "/api/approve" | "/api/reject" | "/api/check");
        guard::api(&asked, (&self.hosts, &self.token), changes)?;
        if changes && !asked.post {
            return Err((405, "this endpoint takes POST".into()));
        }
        if let Some(f) = q.get("fixture") {
            self.known(f)?;
        }
        self.endpoint(path, q)
    }

    /// The endpoint `path` with its query `q`, the guard passed.
    fn endpoint(&self, path: &str, q: &Query) -> Answer {
        let text = |s: String| ("text/plain; charset=utf-8", s.into_bytes());
        let need = |k: &str| q.get(k).ok_or((400, format!("{k} is needed")));
        match path {
            "/api/fixtures" => Ok(("application/json", self.fixtures().to_string().into_bytes())),
            "/api/render" => {
                let fr = Frame::of(q).map_err(|e| (400, e))?;
                self.when_free(|| self.render(&fr))
                    .map(|b| ("image/png", b))
            }
            "/api/debug" => {
                let fr = Frame::of(q).map_err(|e| (400, e))?;
                let at = |k: &str| {
                    q.get(k)
                        .and_then(|v| v.parse::<u32>().ok())
                        .ok_or((400, format!("{k}: a pixel index")))
                };
                let (x, y) = (at("x")?, at("y")?);
                self.when_free(|| self.debug(&fr, (x, y))).map(text)
            }
            "/api/image" => {
                let (f, v, k) = (need("fixture")?, need("view")?, need("kind")?);
                self.image(f, v, k)
                    .map(|b| ("image/png", b))
                    .map_err(|e| (404, e))
            }
            "/api/check" => {
                let f = need("fixture")?;
                self.when_free(|| self.check(f))
                    .map(|v| ("application/json", v.to_string().into_bytes()))
            }
            "/api/approve" | "/api/reject" => {
                let (f, v) = (need("fixture")?, need("view")?);
                self.decide(f, v, path == "/api/approve")
                    .map(text)
                    .map_err(|e| (400, e))
            }
            _ => Err((404, format!("no such page: {path}"))),
        }
    }
}

/// A request's query parameters.
type Query = HashMap<String, String>;

/// An answer: content type and body, or a status and message.
type Answer = Result<(&'static str, Vec<u8>), (u16, String)>;

fn header(k: &str, v: &str) -> Header {
    Header::from_bytes(k.as_bytes(), v.as_bytes()).expect("ASCII header")
}

/// Serves `project` on 127.0.0.1:`port` (0: any free port), calling
/// `ready` with the address once listening; handles requests until the
/// process ends.
pub fn serve(
    project: Project,
    (port, cache_bytes): (u16, u64),
    ready: impl FnOnce(&str, &Arc<Site>),
) -> Result<(), Error> {
    let server = Server::http(("127.0.0.1", port))
        .map_err(|e| format!("cannot listen on 127.0.0.1:{port}: {e}"))?;
    let bound = server.server_addr().to_ip().map_or(port, |a| a.port());
    let site = Arc::new(Site::new(project, bound, cache_bytes)?);
    ready(&format!("http://127.0.0.1:{bound}/"), &site);
    let open = Arc::new(AtomicUsize::new(0));
    for req in server.incoming_requests() {
        if open.fetch_add(1, Ordering::SeqCst) >= MAX_CONNECTIONS {
            open.fetch_sub(1, Ordering::SeqCst);
            let busy =
                Response::from_string("busy: too many requests at once").with_status_code(503);
            let _ = req.respond(busy);
            continue;
        }
        let (site, open) = (site.clone(), open.clone());
        std::thread::spawn(move || {
            site.handle(req);
            open.fetch_sub(1, Ordering::SeqCst);
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn queries_are_decoded() {
        let q = query("/api/render?fixture=flange&view=frame%20920&t=1171.5&model=classical");
        assert_eq!(q["view"], "frame 920");
        let fr = Frame::of(&q).unwrap();
        assert_eq!(
            (fr.t, fr.model, fr.speed),
            (Some(1171.5), Some(Model::CLASSICAL), 1.0)
        );
        assert!(Frame::of(&query("/x?fixture=a&view=b&t=soon")).is_err());
        assert_eq!(decode("a+b%2Cc%zz"), "a b,c%zz");
    }
}
