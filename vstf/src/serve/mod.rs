//! `vstf serve`: a local page for looking at a project's views, bound to
//! 127.0.0.1 only. Every view of every fixture, its golden and pending
//! images, a flip between render and golden, approve and reject, sliders
//! for the camera time and (with one moving object) its speed, a model
//! switch, and a click on a pixel for its debug variables (the functions
//! `vstf debug` runs), and a fixture's check run on request (its rows
//! shown beside the view they were measured in, as `vstf check` judges
//! them). Frames render on demand; each scene's database is built once and
//! kept while the cache's byte budget allows. The page has no external
//! assets: it works offline.
//!
//! Only the page itself may use the server (docs/security.md): requests
//! must name it by its loopback address (`Host`), come from its own origin
//! when a browser says (`Origin`), and carry the process's random token,
//! which only the page served at `/` holds; what changes state is a `POST`
//! of JSON. Fixtures and views are named, never given as paths. Memory and
//! CPU are bounded: the cache's budget, a few renders at once, small
//! requests, slow clients timed out, a bounded number of connections.

mod cache;
mod frame;
mod guard;
mod http;
mod routes;
#[cfg(test)]
mod tests;

pub use crate::fixture::single_mover;
pub use cache::CacheUsage;

use crate::error::Error;
use crate::fixture::with_speed;
use crate::fixture::{Fixture, Overrides, View};
use crate::golden::{slug, Store};
use crate::project::Project;
use crate::Budget;
use cache::{Entry, Lru};
use frame::Frame;
use guard::Guard;
use http::Slots;
use renderer::Traversal;
use std::collections::HashMap;
use std::io::Cursor;
use std::net::{SocketAddr, TcpListener};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// What the server allows itself and its clients.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// The database cache's budget, bytes (`--cache-mb`).
    pub cache_bytes: u64,
    /// Renders, debug traces and checks at once; more get 503.
    pub renders: usize,
    /// Connections served at once; more get 503.
    pub connections: usize,
    /// The time a request may take to arrive, and each write.
    pub timeout: Duration,
}

impl Default for Limits {
    /// 512 MB of databases, 2 renders, 32 connections, 10 s.
    fn default() -> Limits {
        Limits {
            cache_bytes: 512 * 1024 * 1024,
            renders: 2,
            connections: 32,
            timeout: Duration::from_secs(10),
        }
    }
}

/// The server's state: the project, its guard (port and token), the
/// databases kept, each fixture's last check and the render slots.
pub struct Site {
    project: Project,
    guard: Guard,
    databases: Mutex<Lru<Entry>>,
    checked: Mutex<HashMap<String, serde_json::Value>>,
    busy: Arc<Slots>,
}

impl Site {
    /// The site of `project` served on `port` within `limits`.
    pub fn new(project: Project, port: u16, limits: &Limits) -> Result<Site, Error> {
        Ok(Site {
            project,
            guard: Guard::new(port)?,
            databases: Mutex::new(Lru::new(limits.cache_bytes)),
            checked: Mutex::new(HashMap::new()),
            busy: Slots::new(limits.renders),
        })
    }

    /// How full the database cache is.
    pub fn cache_usage(&self) -> CacheUsage {
        self.databases
            .lock()
            .map(|c| c.usage())
            .unwrap_or_else(|p| p.into_inner().usage())
    }

    /// The page's token (what the page sends with every request).
    pub fn token(&self) -> &str {
        self.guard.token()
    }

    fn store(&self) -> Store {
        self.project.store()
    }

    /// The project's fixture `name`, loaded from its `fixtures/` folder.
    fn load(&self, name: &str) -> Result<Fixture, String> {
        let file = self.project.fixtures_dir().join(format!("{name}.json"));
        Fixture::load_within(&file, &Budget::DEFAULT).map_err(|e| e.to_string())
    }

    /// The database of `fixture` as sped up, kept or built (and kept if it
    /// fits the budget).
    fn database(&self, key: cache::Key, fixture: Fixture) -> Result<Entry, String> {
        let lock = || {
            self.databases
                .lock()
                .map_err(|_| "the database cache is poisoned")
        };
        if let Some(e) = lock()?.get(&key) {
            return Ok(e);
        }
        let bytes = crate::budget::kept_database_bytes(&fixture.scene);
        lock()?.make_room(bytes);
        let db = crate::run::database(&fixture, key.2, Traversal::Bvh)?;
        let e = Arc::new((fixture, db));
        lock()?.put(key, e.clone(), bytes);
        Ok(e)
    }

    /// The fixture, view and database of a frame (the database kept per
    /// fixture, view, Lorentz setting and speed).
    fn prepare(&self, fr: &Frame, loaded: &Fixture) -> Result<(Entry, View), String> {
        let (fixture, golden) = crate::check::golden_view(loaded, &fr.view)?;
        let fixture = with_speed(&fixture, fr.speed)?;
        let model = fr.model.unwrap_or(golden.model);
        let camera_t = match fr.tau {
            Some(tau) => lab_time_of(&fixture, tau)?,
            None => fr.t.unwrap_or(golden.camera_t),
        };
        let overrides = Overrides {
            model: Some(model),
            camera_t: Some(camera_t),
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
        Ok((self.database(key, fixture)?, view))
    }

    /// The frame as PNG bytes, and the camera's lab time it was rendered
    /// at.
    fn render(&self, fr: &Frame, loaded: &Fixture) -> Result<(Vec<u8>, f64), String> {
        let (entry, view) = self.prepare(fr, loaded)?;
        let img = crate::output::rgb8(&crate::run::render_with(&entry.1, &entry.0, &view)?);
        let mut png = Vec::new();
        img.write_to(&mut Cursor::new(&mut png), image::ImageFormat::Png)
            .map_err(|e| e.to_string())?;
        Ok((png, view.camera_t))
    }

    fn debug(&self, fr: &Frame, loaded: &Fixture, (x, y): (u32, u32)) -> Result<String, String> {
        let (entry, view) = self.prepare(fr, loaded)?;
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

    /// Every fixture with its views as `vstf check` names them (declared,
    /// rendered by a named check, or the fixture's own view `view`), each
    /// with whether it has a golden and a pending image, its camera time
    /// and model; the speed of its one moving object, if it has one (the
    /// speed slider); and its last check on this page, if any.
    fn fixtures(&self) -> serde_json::Value {
        let store = self.store();
        let checked = self.checked.lock().map(|c| c.clone()).unwrap_or_default();
        let list: Vec<serde_json::Value> = self
            .project
            .fixture_names()
            .into_iter()
            .filter_map(|name| {
                let f = self.load(&name).ok()?;
                let clock = camera_clock(&f);
                let views: Vec<serde_json::Value> = crate::check::views_of(&f)
                    .iter()
                    .map(|v| {
                        serde_json::json!({
                            "name": v.name,
                            "t": v.camera_t,
                            "tau": clock.as_ref().map(|c| c.proper_time(v.camera_t)),
                            "model": v.model.to_string(),
                            "golden": store.golden_path(&name, &v.name).is_file(),
                            "pending": store.pending_dir(&name, &v.name).join("actual.png").is_file(),
                        })
                    })
                    .collect();
                Some(serde_json::json!({"name": name, "views": views, "mover_speed": mover_speed(&f),
                    "clock": clock.map(|c| serde_json::json!({"tau_end": c.proper_end()})),
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
            _ => return Err("kind: golden, actual, expected or diff".into()),
        };
        std::fs::read(&path).map_err(|_| format!("no {kind} image of {fixture} / {view}"))
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
}

/// The speed (a fraction of c) of `f`'s one moving object, if it has
/// exactly one in uniform motion: what the speed slider scales.
fn mover_speed(f: &Fixture) -> Option<f64> {
    let i = single_mover(f)?;
    Some(f.scene.objects[i].motion.velocity()?.length())
}

/// A bound server, not yet answering: its address and site are known
/// (tests read the cache's usage while it runs).
pub struct Server {
    listener: TcpListener,
    site: Arc<Site>,
    limits: Limits,
}

impl Server {
    /// Binds 127.0.0.1:`port` (0: any free port) for `project`.
    pub fn bind(project: Project, port: u16, limits: Limits) -> Result<Server, Error> {
        let listener = TcpListener::bind(("127.0.0.1", port))
            .map_err(|e| Error::Other(format!("cannot listen on 127.0.0.1:{port}: {e}")))?;
        let addr = listener
            .local_addr()
            .map_err(|e| Error::Other(format!("no address for 127.0.0.1:{port}: {e}")))?;
        let site = Arc::new(Site::new(project, addr.port(), &limits)?);
        Ok(Server {
            listener,
            site,
            limits,
        })
    }

    /// The address it listens on.
    pub fn addr(&self) -> SocketAddr {
        self.listener
            .local_addr()
            .unwrap_or_else(|_| SocketAddr::from(([127, 0, 0, 1], 0)))
    }

    /// Its site.
    pub fn site(&self) -> Arc<Site> {
        self.site.clone()
    }

    /// Answers requests until the process ends.
    pub fn run(self) -> Result<(), Error> {
        let site = self.site;
        http::run(
            &self.listener,
            self.limits.connections,
            self.limits.timeout,
            Arc::new(move |req: &http::Request| site.handle(req)),
        );
        Ok(())
    }
}

/// Serves `project` on 127.0.0.1:`port` (0: any free port) within the
/// default [`Limits`], calling `ready` with the page's address once
/// listening; handles requests until the process ends.
pub fn serve(project: Project, port: u16, ready: impl FnOnce(&str)) -> Result<(), Error> {
    serve_with(project, port, Limits::default(), ready)
}

/// [`serve`] within `limits`.
pub fn serve_with(
    project: Project,
    port: u16,
    limits: Limits,
    ready: impl FnOnce(&str),
) -> Result<(), Error> {
    let server = Server::bind(project, port, limits)?;
    ready(&format!("http://{}/", server.addr()));
    server.run()
}

/// What the page needs to step an accelerating camera's proper time on
/// its time slider: the proper time at its worldline's end (`tau_end`;
/// each view gives its own `tau`); `null` for a camera without a
/// worldline. The page asks for a frame by its proper time (`tau=`), and
/// the server reads the lab time on the camera's clock, as views and
/// `animate --frames tau:` do ([`crate::fixture::CameraClock`]).
fn camera_clock(f: &Fixture) -> Option<crate::fixture::CameraClock> {
    crate::fixture::camera_clock(&f.spec.camera).ok().flatten()
}

/// The lab time where the camera of `f` reads proper time `tau`.
fn lab_time_of(f: &Fixture, tau: f64) -> Result<f64, String> {
    let clock = crate::fixture::camera_clock(&f.spec.camera)
        .map_err(|e| e.to_string())?
        .ok_or_else(|| {
            format!("tau={tau}: a proper time is for a camera with camera.worldline; give the lab time as t")
        })?;
    clock.lab_time(tau, "tau").map_err(|e| e.to_string())
}
