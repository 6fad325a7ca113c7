//! A one-machine Slurm cluster for one test: `munged`, `slurmctld` and
//! `slurmd` on this host, every file of theirs (configuration, munge key
//! and socket, state, spool, logs) in one scratch folder, the daemons
//! stopped (and any job left cancelled) when it is dropped.

use std::fmt::Write as _;
use std::io::Read;
use std::net::TcpListener;
use std::os::unix::fs::{MetadataExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// The programs a cluster needs: the three daemons and the clients the
/// test talks to them with.
const PROGRAMS: [&str; 7] = [
    "munged",
    "slurmctld",
    "slurmd",
    "sbatch",
    "squeue",
    "sinfo",
    "scancel",
];

/// Job states after which a job does nothing more.
const ENDED: [&str; 10] = [
    "COMPLETED",
    "FAILED",
    "CANCELLED",
    "TIMEOUT",
    "NODE_FAIL",
    "OUT_OF_MEMORY",
    "BOOT_FAIL",
    "DEADLINE",
    "PREEMPTED",
    "SPECIAL_EXIT",
];

/// Where `name` is: on PATH, or in the system folders that a root's PATH
/// has and a user's may not.
fn program(name: &str) -> Option<PathBuf> {
    let path = std::env::var_os("PATH").unwrap_or_default();
    std::env::split_paths(&path)
        .chain(["/usr/sbin", "/usr/local/sbin", "/sbin"].map(PathBuf::from))
        .map(|d| d.join(name))
        .find(|p| p.is_file())
}

/// Why no cluster can be started here (a program missing, not root), or
/// `None` when it can be tried.
pub fn cannot_run_here() -> Option<String> {
    let missing: Vec<&str> = PROGRAMS
        .into_iter()
        .filter(|p| program(p).is_none())
        .collect();
    if !missing.is_empty() {
        return Some(format!(
            "{} not installed (Debian: apt-get install slurm-wlm munge)",
            missing.join(", ")
        ));
    }
    match std::fs::metadata("/proc/self").map(|m| m.uid()) {
        Ok(0) => None,
        Ok(uid) => Some(format!(
            "slurmd launches jobs as root only; this test runs as uid {uid}"
        )),
        Err(e) => Some(format!("cannot tell who runs this test (/proc/self: {e})")),
    }
}

/// A daemon started by the cluster, its standard error in `log`.
struct Daemon {
    name: &'static str,
    child: Child,
    log: PathBuf,
}

/// One job (or array task) as `squeue` lists it.
#[derive(Clone, Debug)]
pub struct Job {
    /// Its id, `J` or `J_T` for task T of array J.
    pub id: String,
    /// Its `--job-name`.
    pub name: String,
    /// Its state (`COMPLETED`, `FAILED`, ...).
    pub state: String,
}

/// A running cluster of one node, this host.
pub struct Cluster {
    dir: PathBuf,
    conf: PathBuf,
    daemons: Vec<Daemon>,
}

/// A free TCP port on this host (the kernel's choice, released at once).
fn free_port() -> u16 {
    TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .map(|a| a.port())
        .expect("no free TCP port on 127.0.0.1")
}

/// This host's short name, which Slurm matches against `SlurmctldHost`
/// and `NodeName`.
fn host() -> String {
    let name = std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap();
    name.trim().split('.').next().unwrap().to_string()
}

/// The last `n` lines of the file at `path` (or why it cannot be read).
pub fn tail(path: &Path, n: usize) -> String {
    match std::fs::read_to_string(path) {
        Ok(text) => {
            let lines: Vec<&str> = text.lines().collect();
            lines[lines.len().saturating_sub(n)..].join("\n")
        }
        Err(e) => format!("({}: {e})", path.display()),
    }
}

impl Cluster {
    /// Writes the configuration and a fresh munge key into `dir` and
    /// starts the daemons, waiting (30 s at most) until the node is idle.
    /// The error carries the daemons' own words: the tail of the log of a
    /// daemon that exited, or of every log if the node never came up.
    pub fn start(dir: &Path) -> Result<Cluster, String> {
        let mut cluster = Cluster {
            dir: dir.to_path_buf(),
            conf: dir.join("slurm.conf"),
            daemons: Vec::new(),
        };
        cluster
            .lay_out()
            .map_err(|e| format!("{}: {e}", dir.display()))?;
        let munge = cluster.dir.join("munge");
        let socket = cluster.dir.join("socket/munge.socket");
        cluster.spawn(
            "munged",
            &[
                "--foreground".into(),
                format!("--key-file={}", munge.join("munge.key").display()),
                format!("--socket={}", socket.display()),
                format!("--pid-file={}", munge.join("munged.pid").display()),
                format!("--seed-file={}", munge.join("munged.seed").display()),
            ],
        )?;
        cluster.await_file(&socket, "munged")?;
        let conf = cluster.conf.display().to_string();
        cluster.spawn("slurmctld", &["-D".into(), "-f".into(), conf.clone()])?;
        cluster.spawn("slurmd", &["-D".into(), "-f".into(), conf])?;
        cluster.await_idle()?;
        Ok(cluster)
    }

    /// The folders, the munge key (1024 random bytes, readable by root
    /// only) and `slurm.conf`.
    fn lay_out(&self) -> std::io::Result<()> {
        for (sub, mode) in [
            ("munge", 0o700),
            ("socket", 0o755),
            ("state", 0o700),
            ("spool", 0o755),
            ("log", 0o755),
        ] {
            let d = self.dir.join(sub);
            std::fs::create_dir_all(&d)?;
            std::fs::set_permissions(&d, std::fs::Permissions::from_mode(mode))?;
        }
        let mut key = Vec::new();
        std::fs::File::open("/dev/urandom")?
            .take(1024)
            .read_to_end(&mut key)?;
        let key_file = self.dir.join("munge/munge.key");
        std::fs::write(&key_file, key)?;
        std::fs::set_permissions(&key_file, std::fs::Permissions::from_mode(0o600))?;
        std::fs::write(&self.conf, self.conf_text())
    }

    /// `slurm.conf`: this host as controller and only node (its cores as
    /// the node's CPUs, taken from the configuration rather than probed),
    /// root as the Slurm user, processes tracked without cgroups, cores
    /// allocated (memory not), ports the kernel found free, and a job whose
    /// dependency can never be met cancelled rather than left pending.
    fn conf_text(&self) -> String {
        let d = |sub: &str| self.dir.join(sub).display().to_string();
        let host = host();
        let cpus = std::thread::available_parallelism().map_or(1, |n| n.get());
        format!(
            "ClusterName=vstf\n\
             SlurmctldHost={host}(127.0.0.1)\n\
             SlurmUser=root\n\
             SlurmdUser=root\n\
             SlurmctldPort={ctld}\n\
             SlurmdPort={slurmd}\n\
             AuthType=auth/munge\n\
             CredType=cred/munge\n\
             AuthInfo=socket={socket}\n\
             StateSaveLocation={state}\n\
             SlurmdSpoolDir={spool}\n\
             SlurmctldPidFile={log}/slurmctld.pid\n\
             SlurmdPidFile={log}/slurmd.pid\n\
             SlurmctldLogFile={log}/slurmctld.log\n\
             SlurmdLogFile={log}/slurmd.log\n\
             ProctrackType=proctrack/linuxproc\n\
             TaskPlugin=task/none\n\
             SelectType=select/cons_tres\n\
             SelectTypeParameters=CR_Core\n\
             SchedulerType=sched/builtin\n\
             DependencyParameters=kill_invalid_depend\n\
             SlurmdParameters=config_overrides\n\
             MpiDefault=none\n\
             MailProg=/bin/true\n\
             ReturnToService=2\n\
             MinJobAge=3600\n\
             AccountingStorageType=accounting_storage/none\n\
             JobAcctGatherType=jobacct_gather/none\n\
             NodeName={host} NodeAddr=127.0.0.1 CPUs={cpus} State=UNKNOWN\n\
             PartitionName=vstf Nodes={host} Default=YES MaxTime=INFINITE State=UP\n",
            ctld = free_port(),
            slurmd = free_port(),
            socket = d("socket/munge.socket"),
            state = d("state"),
            spool = d("spool"),
            log = d("log"),
        )
    }

    /// Starts the daemon `name` with `args`, its stdout and stderr into
    /// `log/NAME.err`.
    fn spawn(&mut self, name: &'static str, args: &[String]) -> Result<(), String> {
        let log = self.dir.join(format!("log/{name}.err"));
        let out = std::fs::File::create(&log).map_err(|e| format!("{}: {e}", log.display()))?;
        let err = out.try_clone().unwrap();
        let child = Command::new(program(name).unwrap())
            .args(args)
            .env("SLURM_CONF", &self.conf)
            .stdin(Stdio::null())
            .stdout(out)
            .stderr(err)
            .spawn()
            .map_err(|e| format!("{name} did not start: {e}"))?;
        self.daemons.push(Daemon { name, child, log });
        Ok(())
    }

    /// An error if a daemon has exited, with its status and its log's tail.
    fn all_alive(&mut self) -> Result<(), String> {
        for d in &mut self.daemons {
            if let Ok(Some(status)) = d.child.try_wait() {
                return Err(format!(
                    "{} exited ({status}) saying:\n{}",
                    d.name,
                    tail(&d.log, 20)
                ));
            }
        }
        Ok(())
    }

    /// Waits (10 s at most) for `path` to appear, written by `by`.
    fn await_file(&mut self, path: &Path, by: &str) -> Result<(), String> {
        let start = Instant::now();
        while !path.exists() {
            self.all_alive()?;
            if start.elapsed() > Duration::from_secs(10) {
                return Err(format!(
                    "{by} made no {} in 10 s:\n{}",
                    path.display(),
                    self.logs()
                ));
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        Ok(())
    }

    /// Waits (30 s at most) until `sinfo` reports the node idle.
    fn await_idle(&mut self) -> Result<(), String> {
        let start = Instant::now();
        loop {
            self.all_alive()?;
            let out = self.client("sinfo").args(["-h", "-o", "%T"]).output();
            if let Ok(out) = &out {
                if String::from_utf8_lossy(&out.stdout).trim() == "idle" {
                    return Ok(());
                }
            }
            if start.elapsed() > Duration::from_secs(30) {
                return Err(format!(
                    "the node was not idle 30 s after the daemons started (sinfo: {out:?}):\n{}",
                    self.logs()
                ));
            }
            std::thread::sleep(Duration::from_millis(200));
        }
    }

    /// Its `slurm.conf`, for `SLURM_CONF`.
    pub fn conf(&self) -> &Path {
        &self.conf
    }

    /// A Slurm client program (`sbatch`, `squeue`, ...) talking to this
    /// cluster.
    pub fn client(&self, name: &str) -> Command {
        let mut c = Command::new(program(name).unwrap_or_else(|| name.into()));
        c.env("SLURM_CONF", &self.conf);
        c
    }

    /// Every job and array task the controller knows, finished or not.
    pub fn jobs(&self) -> Vec<Job> {
        let out = self
            .client("squeue")
            .args(["-h", "-t", "all", "-o", "%i|%j|%T"])
            .output()
            .expect("squeue did not start");
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .filter_map(|l| {
                let mut f = l.split('|');
                Some(Job {
                    id: f.next()?.to_string(),
                    name: f.next()?.to_string(),
                    state: f.next()?.to_string(),
                })
            })
            .collect()
    }

    /// Waits until every job has ended, `timeout` at most, polling
    /// `squeue`; the jobs as they ended, or an error with the queue and
    /// the daemons' logs.
    pub fn wait(&mut self, timeout: Duration) -> Result<Vec<Job>, String> {
        let start = Instant::now();
        loop {
            self.all_alive()?;
            let jobs = self.jobs();
            if !jobs.is_empty() && jobs.iter().all(|j| ENDED.contains(&j.state.as_str())) {
                return Ok(jobs);
            }
            if start.elapsed() > timeout {
                return Err(format!(
                    "jobs still unfinished after {timeout:?}:\n{}",
                    self.diagnosis()
                ));
            }
            std::thread::sleep(Duration::from_millis(250));
        }
    }

    /// The queue as `squeue` and `scontrol` describe it, then every
    /// daemon's log tail.
    pub fn diagnosis(&self) -> String {
        let mut s = String::new();
        for (program, args) in [
            ("squeue", &["-t", "all", "-o", "%i %j %T %r %M"][..]),
            ("scontrol", &["show", "job"][..]),
        ] {
            let out = self.client(program).args(args).output();
            let text = out.map_or_else(
                |e| e.to_string(),
                |o| String::from_utf8_lossy(&o.stdout).into_owned(),
            );
            let _ = writeln!(s, "--- {program} {}\n{text}", args.join(" "));
        }
        s + &self.logs()
    }

    /// The tail of every daemon's log.
    fn logs(&self) -> String {
        let mut s = String::new();
        for name in [
            "munged.err",
            "slurmctld.log",
            "slurmctld.err",
            "slurmd.log",
            "slurmd.err",
        ] {
            let _ = writeln!(
                s,
                "--- {name}\n{}",
                tail(&self.dir.join("log").join(name), 15)
            );
        }
        s
    }

    /// Cancels every job still queued or running and waits (10 s at most)
    /// until none is, so that no job step outlives its `slurmd`.
    fn cancel_all(&self) {
        let unfinished: Vec<Job> = self
            .jobs()
            .into_iter()
            .filter(|j| !ENDED.contains(&j.state.as_str()))
            .collect();
        if unfinished.is_empty() {
            return;
        }
        let _ = self
            .client("scancel")
            .args(unfinished.iter().map(|j| j.id.as_str()))
            .status();
        let start = Instant::now();
        while start.elapsed() < Duration::from_secs(10)
            && self
                .jobs()
                .iter()
                .any(|j| !ENDED.contains(&j.state.as_str()))
        {
            std::thread::sleep(Duration::from_millis(200));
        }
    }
}

impl Drop for Cluster {
    /// Cancels what is left, then stops the daemons in the reverse order of
    /// their start: SIGTERM, and SIGKILL for one still there after 5 s.
    fn drop(&mut self) {
        let controller_up = self
            .daemons
            .iter_mut()
            .any(|d| d.name == "slurmctld" && matches!(d.child.try_wait(), Ok(None)));
        if controller_up {
            self.cancel_all();
        }
        while let Some(mut d) = self.daemons.pop() {
            let _ = Command::new("kill")
                .args(["-TERM", &d.child.id().to_string()])
                .status();
            let start = Instant::now();
            while matches!(d.child.try_wait(), Ok(None)) {
                if start.elapsed() > Duration::from_secs(5) {
                    let _ = d.child.kill();
                    let _ = d.child.wait();
                    break;
                }
                std::thread::sleep(Duration::from_millis(50));
            }
        }
    }
}
