//! `--display web[:PORT][,wait=SECS][,timeout=SECS]`: a full-window page served on
//! `127.0.0.1`, like ArgyllCMS's web display (`dispcal -dweb`). Open the printed URL in a
//! browser on the display to calibrate, make it full screen, and put the instrument on it.
//!
//! A hand-written HTTP/1.1 responder (one short-lived connection per request,
//! `Connection: close`) serves three paths:
//!
//! | path | reply |
//! |---|---|
//! | `GET /` | the page: its background is the current patch, and a script polls `/patch` every 50 ms |
//! | `GET /patch` | `{"seq":N,"rgb":[r,g,b],"css":"rgb(R,G,B)"}`: the patch number and colour (8-bit in `css`) |
//! | `GET /shown?seq=N` | the page's acknowledgement that patch `N` is painted (sent two animation frames after setting the background) |
//!
//! [`WebDisplay::show`] returns once the page acknowledged the patch: it waits `wait` seconds
//! (default 300) for a browser to show the first patch and `timeout` seconds (default 10) for
//! each later one, and fails with a one-line error otherwise. The server listens on the
//! loopback interface only.

use super::PatchDisplay;
use crate::error::{CliError, Result};
use crate::io::device_spec::DeviceSpec;
use specpoly_core::quantize8;
use std::io::{BufRead, BufReader, Write};
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

#[derive(Debug, Default)]
struct State {
    seq: u64,
    rgb: [f64; 3],
    shown: u64,
    requests: u64,
}

#[derive(Debug, Default)]
struct Shared {
    state: Mutex<State>,
    changed: Condvar,
    stop: AtomicBool,
}

impl Shared {
    fn lock(&self) -> std::sync::MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// The web display: a tiny HTTP server and the patch it serves.
pub struct WebDisplay {
    addr: SocketAddr,
    shared: Arc<Shared>,
    server: Option<std::thread::JoinHandle<()>>,
    first_wait: Duration,
    timeout: Duration,
}

/// `rgb(R,G,B)` of device values, 8 bits per channel.
pub fn css(rgb: [f64; 3]) -> String {
    let b = rgb.map(|v| quantize8(v as f32));
    format!("rgb({},{},{})", b[0], b[1], b[2])
}

impl WebDisplay {
    /// Starts serving on `127.0.0.1:port` (`0`: an ephemeral port), showing black.
    pub fn start(port: u16) -> Result<Self> {
        let listener = TcpListener::bind(("127.0.0.1", port)).map_err(|e| {
            CliError::data(format!(
                "web display: cannot listen on 127.0.0.1:{port}: {e}"
            ))
        })?;
        let addr = listener
            .local_addr()
            .map_err(|e| CliError::data(format!("web display: {e}")))?;
        let shared = Arc::new(Shared::default());
        let s = shared.clone();
        let server = std::thread::Builder::new()
            .name("web-display".into())
            .spawn(move || serve(listener, s))
            .map_err(|e| CliError::data(format!("web display: cannot start the server: {e}")))?;
        Ok(Self {
            addr,
            shared,
            server: Some(server),
            first_wait: Duration::from_secs(300),
            timeout: Duration::from_secs(10),
        })
    }

    /// Parses `web[:PORT][,wait=SECS][,timeout=SECS]` and starts serving.
    pub fn from_spec(spec: &DeviceSpec<'_>) -> Result<Self> {
        let port = match spec.arg {
            None => 0,
            Some(p) => p.parse::<u16>().map_err(|_| {
                CliError::usage(format!(
                    "--display `{}`: expected `web` or `web:PORT`",
                    spec.text
                ))
            })?,
        };
        let mut first_wait = Duration::from_secs(300);
        let mut timeout = Duration::from_secs(10);
        for &(k, v) in &spec.options {
            match k {
                "wait" => first_wait = spec.seconds(k, v)?,
                "timeout" => timeout = spec.seconds(k, v)?,
                _ => return Err(spec.unknown(k, "wait, timeout")),
            }
        }
        let mut d = Self::start(port)?;
        d.first_wait = first_wait;
        d.timeout = timeout;
        Ok(d)
    }

    /// The page's URL.
    pub fn url(&self) -> String {
        format!("http://{}/", self.addr)
    }

    /// Sets the patch without waiting for the page (returns its sequence number).
    pub fn post(&self, rgb: [f64; 3]) -> u64 {
        let mut s = self.shared.lock();
        s.seq += 1;
        s.rgb = rgb;
        self.shared.changed.notify_all();
        s.seq
    }

    /// Waits until the page acknowledged patch `seq`, at most `timeout`.
    pub fn wait_shown(&self, seq: u64, timeout: Duration) -> bool {
        let deadline = Instant::now() + timeout;
        let mut s = self.shared.lock();
        while s.shown < seq {
            let now = Instant::now();
            if now >= deadline {
                return false;
            }
            s = match self.shared.changed.wait_timeout(s, deadline - now) {
                Ok((g, _)) => g,
                Err(e) => e.into_inner().0,
            };
        }
        true
    }

    /// How many HTTP requests were served so far.
    pub fn requests(&self) -> u64 {
        self.shared.lock().requests
    }
}

impl Drop for WebDisplay {
    fn drop(&mut self) {
        self.shared.stop.store(true, Ordering::SeqCst);
        // wake the accept loop
        let _ = TcpStream::connect_timeout(&self.addr, Duration::from_millis(200));
        if let Some(h) = self.server.take() {
            let _ = h.join();
        }
    }
}

impl PatchDisplay for WebDisplay {
    fn describe(&self) -> String {
        format!(
            "web display: open {} in a browser on the display, full screen",
            self.url()
        )
    }

    fn show(&mut self, rgb: [f64; 3]) -> Result<()> {
        let seq = self.post(rgb);
        let wait = if seq == 1 {
            self.first_wait
        } else {
            self.timeout
        };
        if !self.wait_shown(seq, wait) {
            return Err(CliError::data(format!(
                "web display: no browser showed patch {seq} ({}) within {:.0} s — is {} open and visible?",
                css(rgb),
                wait.as_secs_f64(),
                self.url()
            )));
        }
        Ok(())
    }

    fn default_settle(&self) -> Duration {
        Duration::from_millis(500)
    }
}

fn serve(listener: TcpListener, shared: Arc<Shared>) {
    for conn in listener.incoming() {
        if shared.stop.load(Ordering::SeqCst) {
            return;
        }
        let Ok(stream) = conn else { continue };
        let s = shared.clone();
        // one thread per connection: a slow client never holds up the page's polling
        let _ = std::thread::Builder::new()
            .name("web-display-conn".into())
            .spawn(move || {
                let _ = handle(stream, &s);
            });
    }
}

const PAGE: &str = r#"<!doctype html>
<html><head><meta charset="utf-8"><title>specpoly calibration patch</title>
<style>html,body{margin:0;width:100%;height:100%;overflow:hidden;cursor:none}</style></head>
<body style="background:__CSS__">
<script>
"use strict";
let seq = __SEQ__;
function ack(n) {
  requestAnimationFrame(() => requestAnimationFrame(() =>
    fetch("/shown?seq=" + n, {cache: "no-store"}).catch(() => {})));
}
async function tick() {
  try {
    const r = await fetch("/patch", {cache: "no-store"});
    const p = await r.json();
    if (p.seq !== seq) {
      document.body.style.background = p.css;
      seq = p.seq;
      ack(seq);
    }
  } catch (e) {}
  setTimeout(tick, 50);
}
ack(seq);
tick();
</script></body></html>
"#;

fn respond(w: &mut TcpStream, status: &str, ctype: &str, body: &str) -> std::io::Result<()> {
    write!(
        w,
        "HTTP/1.1 {status}\r\nContent-Type: {ctype}\r\nContent-Length: {}\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n{body}",
        body.len()
    )?;
    w.flush()
}

fn handle(stream: TcpStream, shared: &Shared) -> std::io::Result<()> {
    stream.set_read_timeout(Some(Duration::from_secs(5)))?;
    stream.set_write_timeout(Some(Duration::from_secs(5)))?;
    let mut reader = BufReader::new(stream.try_clone()?);
    let mut request = String::new();
    reader.read_line(&mut request)?;
    // skip the headers
    loop {
        let mut h = String::new();
        if reader.read_line(&mut h)? == 0 || h == "\r\n" || h == "\n" {
            break;
        }
    }
    let mut w = stream;
    let mut it = request.split_whitespace();
    let (method, target) = (it.next().unwrap_or(""), it.next().unwrap_or(""));
    if method != "GET" {
        return respond(&mut w, "405 Method Not Allowed", "text/plain", "GET only\n");
    }
    let (path, query) = target.split_once('?').unwrap_or((target, ""));
    let (seq, rgb) = {
        let mut s = shared.lock();
        s.requests += 1;
        (s.seq, s.rgb)
    };
    match path {
        "/" | "/index.html" => {
            let page = PAGE
                .replace("__CSS__", &css(rgb))
                .replace("__SEQ__", &seq.to_string());
            respond(&mut w, "200 OK", "text/html; charset=utf-8", &page)
        }
        "/patch" => {
            let body = format!(
                "{{\"seq\":{seq},\"rgb\":[{},{},{}],\"css\":\"{}\"}}",
                rgb[0],
                rgb[1],
                rgb[2],
                css(rgb)
            );
            respond(&mut w, "200 OK", "application/json", &body)
        }
        "/shown" => {
            let n = query
                .split('&')
                .find_map(|kv| kv.strip_prefix("seq="))
                .and_then(|v| v.parse::<u64>().ok());
            match n {
                Some(n) => {
                    let mut s = shared.lock();
                    if n > s.shown && n <= s.seq {
                        s.shown = n;
                    }
                    shared.changed.notify_all();
                    drop(s);
                    respond(&mut w, "204 No Content", "text/plain", "")
                }
                None => respond(&mut w, "400 Bad Request", "text/plain", "seq=N\n"),
            }
        }
        "/favicon.ico" => respond(&mut w, "204 No Content", "text/plain", ""),
        _ => respond(&mut w, "404 Not Found", "text/plain", "not found\n"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Read;

    fn get(addr: SocketAddr, path: &str) -> String {
        let mut s = TcpStream::connect(addr).unwrap();
        write!(s, "GET {path} HTTP/1.1\r\nHost: x\r\n\r\n").unwrap();
        let mut out = String::new();
        s.read_to_string(&mut out).unwrap();
        out
    }

    #[test]
    fn serves_patch_and_takes_acks() {
        let mut d = WebDisplay::start(0).unwrap();
        d.first_wait = Duration::from_millis(100);
        let seq = d.post([1.0, 0.5, 0.0]);
        let r = get(d.addr, "/patch");
        assert!(r.starts_with("HTTP/1.1 200"), "{r}");
        assert!(r.contains("\"css\":\"rgb(255,128,0)\""), "{r}");
        assert!(get(d.addr, "/").contains("background:rgb(255,128,0)"));
        assert!(!d.wait_shown(seq, Duration::from_millis(20)));
        assert!(get(d.addr, &format!("/shown?seq={seq}")).starts_with("HTTP/1.1 204"));
        assert!(d.wait_shown(seq, Duration::from_millis(20)));
        assert!(get(d.addr, "/nope").starts_with("HTTP/1.1 404"));
        // nobody acknowledges the next patch: a clear error
        d.timeout = Duration::from_millis(50);
        let e = d.show([0.0; 3]).unwrap_err().to_string();
        assert!(e.contains("no browser showed patch 2"), "{e}");
    }
}
