//! Helpers for the `calibrate run` tests: run the real binary with a deadline, find the web
//! display's URL in its output, play the part of the browser (poll `/patch`, acknowledge), and
//! find Chromium.
#![allow(dead_code)]

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

pub use super::cli;

#[allow(unused_imports)]
pub use cli::calibrate_run as calibrate_args;

/// The binary under test.
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_specpoly"))
}

/// A finished run.
#[derive(Debug)]
pub struct Finished {
    /// Exit code (`None`: killed at the deadline).
    pub code: Option<i32>,
    /// Everything on stdout.
    pub stdout: String,
    /// Everything on stderr.
    pub stderr: String,
}

impl Finished {
    /// Asserts exit `code` and exactly one line on stderr; that line.
    pub fn one_line_error(&self, code: i32) -> &str {
        assert_eq!(self.code, Some(code), "{self:?}");
        let err = self.stderr.trim();
        assert_eq!(err.lines().count(), 1, "{err}");
        err
    }
}

/// A running `specpoly` whose stdout lines are collected as they come.
pub struct Running {
    child: Child,
    lines: mpsc::Receiver<String>,
    seen: Vec<String>,
    stderr: std::thread::JoinHandle<String>,
}

/// Starts `specpoly ARGS` with piped stdout/stderr (and stdin).
pub fn start(args: &[&str]) -> Running {
    let mut child = cli::spawn_piped(bin().args(args));
    let out = child.stdout.take().unwrap();
    let mut err = child.stderr.take().unwrap();
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        for l in BufReader::new(out).lines().map_while(Result::ok) {
            if tx.send(l).is_err() {
                break;
            }
        }
    });
    let stderr = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = err.read_to_string(&mut s);
        s
    });
    Running {
        child,
        lines: rx,
        seen: Vec::new(),
        stderr,
    }
}

impl Running {
    /// Waits (at most `timeout`) for a stdout line containing `needle`.
    pub fn wait_line(&mut self, needle: &str, timeout: Duration) -> String {
        let deadline = Instant::now() + timeout;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.lines.recv_timeout(left) {
                Ok(l) => {
                    self.seen.push(l.clone());
                    if l.contains(needle) {
                        return l;
                    }
                }
                Err(_) => {
                    let _ = self.child.kill();
                    panic!(
                        "no `{needle}` on stdout within {timeout:?}; got {:?}",
                        self.seen
                    );
                }
            }
        }
    }

    /// The web display's base URL (`http://127.0.0.1:PORT/`), from the first lines of output.
    pub fn web_url(&mut self) -> String {
        let l = self.wait_line("http://127.0.0.1:", Duration::from_secs(30));
        let i = l.find("http://").unwrap();
        l[i..].split_whitespace().next().unwrap().to_string()
    }

    /// The child's process id (to signal it).
    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    /// Writes to the child's stdin.
    pub fn stdin(&mut self, text: &str) {
        if let Some(s) = self.child.stdin.as_mut() {
            let _ = s.write_all(text.as_bytes());
            let _ = s.flush();
        }
    }

    /// Waits for the exit, killing the process at `timeout`.
    pub fn finish(mut self, timeout: Duration) -> Finished {
        drop(self.child.stdin.take());
        let deadline = Instant::now() + timeout;
        let code = loop {
            if let Some(st) = self.child.try_wait().unwrap() {
                break st.code();
            }
            if Instant::now() >= deadline {
                let _ = self.child.kill();
                let _ = self.child.wait();
                break None;
            }
            std::thread::sleep(Duration::from_millis(20));
        };
        let mut stdout = self.seen.join("\n");
        while let Ok(l) = self.lines.recv_timeout(Duration::from_millis(200)) {
            stdout.push('\n');
            stdout.push_str(&l);
        }
        let stderr = self.stderr.join().unwrap_or_default();
        Finished {
            code,
            stdout,
            stderr,
        }
    }
}

/// Runs `specpoly ARGS` to the end (at most `timeout`).
pub fn run(args: &[&str], timeout: Duration) -> Finished {
    start(args).finish(timeout)
}

/// Starts `specpoly calibrate run --display web,wait=20,timeout=10 ARGS` with a fake browser
/// as the screen, writing each patch it is shown into `shown`.
pub fn start_web(args: &[&str], shown: Arc<Mutex<[f64; 3]>>) -> (Running, FakeBrowser) {
    let mut all = vec!["calibrate", "run", "--display", "web,wait=20,timeout=10"];
    all.extend_from_slice(args);
    let mut run = start(&all);
    let url = run.web_url();
    let browser = fake_browser_into(&url, shown);
    (run, browser)
}

/// `specpoly calibrate run --display DISPLAY --instrument INSTRUMENT MORE… -o OUT` to the end
/// (at most `timeout`).
pub fn calibrate(
    display: &str,
    instrument: &str,
    more: &[&str],
    out: &str,
    timeout: Duration,
) -> Finished {
    run(&cli::calibrate_run(display, instrument, more, out), timeout)
}

/// One HTTP GET on the loopback with `cookie` (a `Cookie:` value, or empty); the body.
pub fn http_get(base: &str, path: &str, cookie: &str) -> Option<String> {
    http_get_full(base, path, cookie).map(|(_, b)| b)
}

/// One HTTP GET on the loopback: the head and the body.
fn http_get_full(base: &str, path: &str, cookie: &str) -> Option<(String, String)> {
    let rest = base.trim_start_matches("http://");
    let hostport = rest.split('/').next()?;
    let mut s = TcpStream::connect(hostport).ok()?;
    s.set_read_timeout(Some(Duration::from_secs(2))).ok()?;
    let cookie = if cookie.is_empty() {
        String::new()
    } else {
        format!("Cookie: {cookie}\r\n")
    };
    write!(s, "GET {path} HTTP/1.1\r\nHost: {hostport}\r\n{cookie}\r\n").ok()?;
    let mut out = String::new();
    s.read_to_string(&mut out).ok()?;
    out.split_once("\r\n\r\n")
        .map(|(h, b)| (h.to_string(), b.to_string()))
}

/// Plays the browser for a web display: polls `/patch`, records the colour, acknowledges it.
pub struct FakeBrowser {
    /// The patch the "page" shows.
    pub current: Arc<Mutex<[f64; 3]>>,
    stop: Arc<AtomicBool>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Drop for FakeBrowser {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::SeqCst);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// Starts polling the page at `url` (`http://127.0.0.1:PORT/?key=K`, as the run prints it).
pub fn fake_browser(url: &str) -> FakeBrowser {
    fake_browser_into(url, Arc::new(Mutex::new([0.0; 3])))
}

/// Starts polling the page at `url`, writing the colour shown into `current` before
/// acknowledging it.
pub fn fake_browser_into(url: &str, current: Arc<Mutex<[f64; 3]>>) -> FakeBrowser {
    let stop = Arc::new(AtomicBool::new(false));
    let (c, s, url) = (current.clone(), stop.clone(), url.to_string());
    let thread = std::thread::spawn(move || {
        let mut seq = 0u64;
        // like the browser: the printed URL's one-time key opens the page once and gives the
        // session cookie, which /patch and /shown need
        let keyed = url
            .find("/?")
            .map_or("/".to_string(), |i| url[i..].to_string());
        let mut cookie = String::new();
        while !s.load(Ordering::SeqCst) {
            if cookie.is_empty() {
                if let Some((head, _)) = http_get_full(&url, &keyed, "") {
                    cookie = head
                        .lines()
                        .find_map(|l| l.strip_prefix("Set-Cookie: "))
                        .and_then(|c| c.split(';').next())
                        .unwrap_or_default()
                        .to_string();
                    if cookie.is_empty() {
                        // the key was refused: nothing more this browser can do
                        return;
                    }
                } else {
                    std::thread::sleep(Duration::from_millis(5));
                }
                continue;
            }
            if let Some(body) = http_get(&url, "/patch", &cookie) {
                if let Ok(v) = serde_json::from_str::<serde_json::Value>(&body) {
                    let n = v["seq"].as_u64().unwrap_or(0);
                    if n != seq {
                        let rgb = &v["rgb"];
                        *c.lock().unwrap() = [0, 1, 2].map(|i| rgb[i].as_f64().unwrap_or(0.0));
                        seq = n;
                        let _ = http_get(&url, &format!("/shown?seq={n}"), &cookie);
                    }
                }
            }
            std::thread::sleep(Duration::from_millis(5));
        }
    });
    FakeBrowser {
        current,
        stop,
        thread: Some(thread),
    }
}

/// Chromium's executable: `$CHROMIUM`, else `chromium` or `chromium-browser` on the PATH.
/// Panics with how to install it when there is none: the browser tests must not pass
/// without a browser.
pub fn chromium() -> PathBuf {
    if let Some(p) = std::env::var_os("CHROMIUM") {
        return PathBuf::from(p);
    }
    let path = std::env::var_os("PATH").unwrap_or_default();
    for dir in std::env::split_paths(&path) {
        for name in ["chromium", "chromium-browser"] {
            let p = dir.join(name);
            if p.is_file() {
                return p;
            }
        }
    }
    panic!(
        "chromium not found (set $CHROMIUM or install it: apt-get update && apt-get install -y chromium); \
         the web display is tested in a real headless browser and this test does not skip"
    );
}

/// Chromium's headless flags, with a fresh profile in `profile`.
pub fn chromium_args(profile: &std::path::Path) -> Vec<String> {
    [
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-background-networking",
        "--disable-component-update",
        "--no-first-run",
        "--disable-quic",
        "--disable-sync",
        "--force-color-profile=srgb",
        "--hide-scrollbars",
        "--window-size=240,160",
    ]
    .iter()
    .map(|s| s.to_string())
    .chain([format!("--user-data-dir={}", profile.display())])
    .collect()
}

/// Rows of a .ti3 in cd/m² (read by the crate's reader): `[R, G, B (0–100), X, Y, Z]`.
pub fn ti3_rows(path: &Path) -> Vec<[f64; 6]> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let t = specpoly_formats::cgats::read_ti3(&text, &path.display().to_string()).unwrap();
    let (m, absolute) = t.best_units();
    assert!(absolute || m.len() < 2, "{}: not in cd/m²", path.display());
    m.iter()
        .map(|m| {
            [
                m.device[0] * 100.0,
                m.device[1] * 100.0,
                m.device[2] * 100.0,
                m.xyz[0],
                m.xyz[1],
                m.xyz[2],
            ]
        })
        .collect()
}
