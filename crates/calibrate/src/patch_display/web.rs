//! `--display web[:PORT][,wait=SECS][,timeout=SECS][,size=F][,background=L]`: a page served on
//! `127.0.0.1`, like ArgyllCMS's web display (`dispcal -dweb`). Open the printed URL in a
//! browser on the display to calibrate, make it full screen, and put the instrument on it.
//!
//! A hand-written HTTP/1.1 responder (one short-lived connection per request,
//! `Connection: close`) serves three paths:
//!
//! | path | reply |
//! |---|---|
//! | `GET /?key=K` | the page, once: its background is the current patch, and a script polls `/patch` every 50 ms |
//! | `GET /patch` | `{"seq":N,"rgb":[r,g,b],"css":"rgb(R,G,B)"}`: the patch number and colour (8-bit in `css`) |
//! | `GET /shown?seq=N` | the page's acknowledgement that patch `N` is painted (sent two animation frames after setting the background) |
//!
//! **Who may drive the run.** The printed URL carries `K`, a random 128-bit key of this run
//! that works once: the first request with it is answered with the page and a session cookie
//! (`specpoly_PORT=S`, 128 random bits, `HttpOnly`, `SameSite=Strict`), and every route,
//! the page included, needs that cookie from then on. The key appears on the run's terminal
//! only; the session only in that one answer's `Set-Cookie`, never in a page or script. A
//! second use of the key means another client has it: it is refused and the run stops
//! ([`PatchDisplayError::KeyReused`]) rather than record readings for patches nobody saw. So a
//! local process of another user can connect, but every request it makes gets `403` and
//! learns nothing; if it reads the key before the browser uses it (e.g. from a browser's
//! command line in `/proc`), the run stops instead of being driven. See `docs/reliability.md`.
//!
//! Limits (see `docs/reliability.md`): the request line and headers at most [`MAX_HEAD`]
//! bytes (else `431`), read within [`HEAD_DEADLINE`]; no request bodies (`413`); GET only
//! (`405`); at most [`MAX_CONNECTIONS`] connections at once (else `503`); `Host` must be
//! `127.0.0.1:PORT` or `localhost:PORT` and `Origin`, when sent, `http://` one of those (else
//! `403`: DNS rebinding and other sites' pages).
//!
//! [`WebDisplay::show`] returns once the page acknowledged the patch: it waits `wait` seconds
//! (default 300) for a browser to show the first patch and `timeout` seconds (default 10) for
//! each later one, and fails with a one-line error otherwise. The server listens on the
//! loopback interface only. `size` is the fraction of the window's area the patch covers
//! (default 1: all of it; `0.1` is the "10 % window" OLED and local-dimming panels are
//! measured with), `background` the grey level around it (default 0) — see [`Window`].

use crate::error::{Error, PatchDisplayError, Result};
use crate::patch_display::PatchDisplay;
use specpoly_core::quantize8;
use specpoly_formats::device_spec::DeviceSpec;
use std::io::{Read, Write};
use std::net::{Shutdown, SocketAddr, TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

#[derive(Debug, Default)]
struct State {
    seq: u64,
    rgb: [f64; 3],
    shown: u64,
    requests: u64,
}

/// Most bytes of request line and headers together; more gets `431` and the connection closed.
pub const MAX_HEAD: usize = 16 * 1024;
/// Most connections served at once; one more gets `503` and is closed.
pub const MAX_CONNECTIONS: usize = 16;
/// Time a client has to send its request line and headers (and each read's timeout).
pub const HEAD_DEADLINE: Duration = Duration::from_secs(5);

#[derive(Debug, Default)]
struct Shared {
    window: Mutex<Window>,
    state: Mutex<State>,
    changed: Condvar,
    stop: AtomicBool,
    /// Connections being served.
    active: AtomicUsize,
    /// The port listened on (for the `Host` / `Origin` checks).
    port: u16,
    /// This run's one-time key (32 hex digits): the URL's `key=`.
    key: String,
    /// The session the key opened (32 hex digits): the cookie every route needs.
    session: String,
    /// Whether the key was used; a second use stops the run.
    key_used: AtomicBool,
    key_reused: AtomicBool,
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
    window: Window,
}

/// The patch window: the fraction of the screen's area the patch covers (a centred
/// rectangle with the screen's aspect ratio) and the grey level around it. Full-screen
/// patches make OLED and local-dimming panels limit their brightness; a 10 % window on a
/// dark surround is what such panels are measured with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Window {
    /// Fraction of the screen's area, `(0, 1]`.
    pub size: f64,
    /// Grey level around the patch, `[0, 1]` (8-bit on the page).
    pub background: f64,
}

impl Default for Window {
    fn default() -> Self {
        Self {
            size: 1.0,
            background: 0.0,
        }
    }
}

/// `rgb(R,G,B)` of device values, 8 bits per channel.
pub fn css(rgb: [f64; 3]) -> String {
    let b = rgb.map(|v| quantize8(v as f32));
    format!("rgb({},{},{})", b[0], b[1], b[2])
}

impl WebDisplay {
    /// Starts serving on `127.0.0.1:port` (`0`: an ephemeral port), showing black.
    pub fn start(port: u16) -> Result<Self, PatchDisplayError> {
        let listener = TcpListener::bind(("127.0.0.1", port))
            .map_err(|source| PatchDisplayError::Listen { port, source })?;
        let addr = listener.local_addr().map_err(PatchDisplayError::Socket)?;
        let shared = Arc::new(Shared {
            port: addr.port(),
            key: new_secret(),
            session: new_secret(),
            ..Shared::default()
        });
        let s = shared.clone();
        let server = std::thread::Builder::new()
            .name("web-display".into())
            .spawn(move || serve(listener, s))
            .map_err(PatchDisplayError::Server)?;
        Ok(Self {
            addr,
            shared,
            server: Some(server),
            first_wait: Duration::from_secs(300),
            timeout: Duration::from_secs(10),
            window: Window::default(),
        })
    }

    /// Parses `web[:PORT][,wait=SECS][,timeout=SECS][,size=F][,background=L]` and starts serving.
    pub fn from_spec(spec: &DeviceSpec<'_>) -> Result<Self> {
        let port = match spec.arg {
            None => 0,
            Some(p) => p.parse::<u16>().map_err(|_| Error::WebPort {
                spec: spec.text.to_string(),
            })?,
        };
        let mut first_wait = Duration::from_secs(300);
        let mut timeout = Duration::from_secs(10);
        let mut window = Window::default();
        for &(k, v) in &spec.options {
            match k {
                "wait" => first_wait = spec.seconds(k, v)?,
                "timeout" => timeout = spec.seconds(k, v)?,
                "size" => {
                    window.size = spec.number(k, v)?;
                    if !(window.size > 0.0 && window.size <= 1.0) {
                        return Err(spec
                            .bad(k, v, "expected a fraction of the area in (0, 1]")
                            .into());
                    }
                }
                "background" => {
                    window.background = spec.number(k, v)?;
                    if !(0.0..=1.0).contains(&window.background) {
                        return Err(spec.bad(k, v, "expected a grey level in [0, 1]").into());
                    }
                }
                _ => return Err(spec.unknown(k, "wait, timeout, size, background").into()),
            }
        }
        let mut d = Self::start(port)?;
        d.first_wait = first_wait;
        d.timeout = timeout;
        d.window = window;
        *d.shared.window.lock().unwrap_or_else(|e| e.into_inner()) = window;
        Ok(d)
    }

    /// The page's URL with this run's one-time key: open it once, in the browser on the
    /// display.
    pub fn url(&self) -> String {
        format!("http://{}/?key={}", self.addr, self.shared.key)
    }

    /// The address served (`127.0.0.1:PORT`).
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// The cookie's name, `specpoly_PORT` (cookies are shared by all ports of a host; the
    /// port keeps two runs' sessions apart).
    pub fn cookie_name(&self) -> String {
        cookie_name(self.shared.port)
    }

    /// Sets the patch without waiting for the page (returns its sequence number).
    pub fn post(&self, rgb: [f64; 3]) -> u64 {
        let mut s = self.shared.lock();
        s.seq += 1;
        s.rgb = rgb;
        self.shared.changed.notify_all();
        s.seq
    }

    /// Waits until the page acknowledged patch `seq`, at most `timeout` (false: not shown,
    /// or the key was used twice).
    pub fn wait_shown(&self, seq: u64, timeout: Duration) -> bool {
        let deadline = Instant::now() + timeout;
        let mut s = self.shared.lock();
        while s.shown < seq {
            if self.shared.key_reused.load(Ordering::SeqCst) {
                return false;
            }
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

    /// Whether a second client presented the one-time key (the run must stop).
    pub fn key_reused(&self) -> bool {
        self.shared.key_reused.load(Ordering::SeqCst)
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

    fn show(&mut self, rgb: [f64; 3]) -> Result<(), PatchDisplayError> {
        let seq = self.post(rgb);
        let wait = if seq == 1 {
            self.first_wait
        } else {
            self.timeout
        };
        let shown = self.wait_shown(seq, wait);
        if self.key_reused() {
            return Err(PatchDisplayError::KeyReused);
        }
        if !shown {
            return Err(PatchDisplayError::NotShown {
                seq,
                css: css(rgb),
                seconds: wait.as_secs_f64(),
                url: self.url(),
            });
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
        let Ok(mut stream) = conn else { continue };
        // a thread per connection (a slow client never holds up the page's polling), but at
        // most MAX_CONNECTIONS of them
        if shared.active.fetch_add(1, Ordering::SeqCst) >= MAX_CONNECTIONS {
            shared.active.fetch_sub(1, Ordering::SeqCst);
            let _ = stream.set_write_timeout(Some(Duration::from_millis(200)));
            let _ = respond(
                &mut stream,
                "503 Service Unavailable",
                "text/plain",
                "too many connections\n",
            );
            let _ = stream.shutdown(Shutdown::Both);
            continue;
        }
        let guard = Active(shared.clone());
        let _ = std::thread::Builder::new()
            .name("web-display-conn".into())
            .spawn(move || {
                let _ = handle(stream, &guard.0);
            });
    }
}

/// One served connection: gives its slot back when dropped (also if the thread never starts).
struct Active(Arc<Shared>);

impl Drop for Active {
    fn drop(&mut self) {
        self.0.active.fetch_sub(1, Ordering::SeqCst);
    }
}

fn cookie_name(port: u16) -> String {
    format!("specpoly_{port}")
}

/// 128 random bits as 32 hex digits: the operating system's generator (`/dev/urandom`), else
/// SipHash with std's randomly keyed `RandomState` (itself seeded by the operating system).
fn new_secret() -> String {
    let mut b = [0u8; 16];
    let ok = std::fs::File::open("/dev/urandom")
        .and_then(|mut f| f.read_exact(&mut b))
        .is_ok();
    if !ok {
        use std::hash::{BuildHasher, Hasher};
        let rs = std::collections::hash_map::RandomState::new();
        for (i, half) in b.chunks_mut(8).enumerate() {
            let mut h = rs.build_hasher();
            h.write_usize(i);
            h.write_u128(
                std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map_or(0, |d| d.as_nanos()),
            );
            half.copy_from_slice(&h.finish().to_le_bytes());
        }
    }
    b.iter().map(|x| format!("{x:02x}")).collect()
}

/// Equal strings, in time independent of where they differ.
fn same(a: &str, b: &str) -> bool {
    a.len() == b.len() && a.bytes().zip(b.bytes()).fold(0u8, |d, (x, y)| d | (x ^ y)) == 0
}

const PAGE: &str = r#"<!doctype html>
<html><head><meta charset="utf-8"><title>specpoly calibration patch</title>
<style>html,body{margin:0;width:100%;height:100%;overflow:hidden;cursor:none}
#patch{position:absolute;left:__OFF__%;top:__OFF__%;width:__SIDE__%;height:__SIDE__%}</style></head>
<body style="background:__BG__"><div id="patch" style="background:__CSS__"></div>
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
      document.getElementById("patch").style.background = p.css;
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
    respond_with(w, status, ctype, "", body)
}

/// Answers with `extra` header lines (each ending in `\r\n`).
fn respond_with(
    w: &mut TcpStream,
    status: &str,
    ctype: &str,
    extra: &str,
    body: &str,
) -> std::io::Result<()> {
    write!(
        w,
        "HTTP/1.1 {status}\r\nContent-Type: {ctype}\r\nContent-Length: {}\r\nCache-Control: no-store\r\nReferrer-Policy: no-referrer\r\n{extra}Connection: close\r\n\r\n{body}",
        body.len()
    )?;
    w.flush()
}

/// Reads the request line and headers (at most [`MAX_HEAD`] bytes, within [`HEAD_DEADLINE`]).
/// `Ok(None)`: too long.
fn read_head(stream: &mut TcpStream) -> std::io::Result<Option<String>> {
    let deadline = Instant::now() + HEAD_DEADLINE;
    let mut head = Vec::with_capacity(1024);
    let mut buf = [0u8; 2048];
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        if left.is_zero() {
            return Err(std::io::ErrorKind::TimedOut.into());
        }
        stream.set_read_timeout(Some(left))?;
        let n = stream.read(&mut buf)?;
        if n == 0 {
            return Err(std::io::ErrorKind::UnexpectedEof.into());
        }
        let from = head.len().saturating_sub(3);
        head.extend_from_slice(&buf[..n]);
        let end = head[from..]
            .windows(4)
            .position(|w| w == b"\r\n\r\n")
            .map(|i| from + i)
            .or_else(|| {
                head[from..]
                    .windows(2)
                    .position(|w| w == b"\n\n")
                    .map(|i| from + i)
            });
        match end {
            Some(e) if e <= MAX_HEAD => {
                return Ok(Some(String::from_utf8_lossy(&head[..e]).into()))
            }
            _ if head.len() > MAX_HEAD => return Ok(None),
            _ => {}
        }
    }
}

/// Answers and closes, reading (a bounded amount of) what the client still sends first, so
/// that closing does not reset the connection before the client read the answer.
fn refuse(mut w: TcpStream, status: &str, body: &str) -> std::io::Result<()> {
    respond(&mut w, status, "text/plain", body)?;
    let _ = w.shutdown(Shutdown::Write);
    let deadline = Instant::now() + Duration::from_secs(1);
    let mut sink = [0u8; 4096];
    let mut left = 4 * MAX_HEAD;
    while left > 0 {
        let wait = deadline.saturating_duration_since(Instant::now());
        if wait.is_zero() || w.set_read_timeout(Some(wait)).is_err() {
            break;
        }
        match w.read(&mut sink) {
            Ok(0) | Err(_) => break,
            Ok(n) => left = left.saturating_sub(n),
        }
    }
    Ok(())
}

fn handle(mut stream: TcpStream, shared: &Shared) -> std::io::Result<()> {
    stream.set_write_timeout(Some(Duration::from_secs(5)))?;
    let Some(head) = read_head(&mut stream)? else {
        return refuse(
            stream,
            "431 Request Header Fields Too Large",
            "request line and headers: at most 16 KiB\n",
        );
    };
    let mut lines = head.lines();
    let request = lines.next().unwrap_or("");
    let (mut host, mut origin, mut body, mut cookies) = (None, None, false, Vec::new());
    for h in lines {
        let Some((k, v)) = h.split_once(':') else {
            continue;
        };
        let v = v.trim();
        match k.trim().to_ascii_lowercase().as_str() {
            "host" => host = Some(v.to_ascii_lowercase()),
            "origin" => origin = Some(v.to_ascii_lowercase()),
            "cookie" => cookies.push(v.to_string()),
            "content-length" => body |= v != "0",
            "transfer-encoding" => body = true,
            _ => {}
        }
    }
    let mut it = request.split_whitespace();
    let (method, target) = (it.next().unwrap_or(""), it.next().unwrap_or(""));
    if method != "GET" {
        return refuse(stream, "405 Method Not Allowed", "GET only\n");
    }
    if body {
        return refuse(stream, "413 Content Too Large", "no request bodies\n");
    }
    let port = shared.port;
    let hosts = [format!("127.0.0.1:{port}"), format!("localhost:{port}")];
    if !host.is_some_and(|h| hosts.contains(&h)) {
        return refuse(stream, "403 Forbidden", "Host: 127.0.0.1:PORT only\n");
    }
    if origin.is_some_and(|o| !hosts.iter().any(|h| o == format!("http://{h}"))) {
        return refuse(stream, "403 Forbidden", "foreign Origin\n");
    }
    let mut w = stream;
    let (path, query) = target.split_once('?').unwrap_or((target, ""));
    let param = |name: &str| {
        query
            .split('&')
            .find_map(|kv| kv.strip_prefix(name)?.strip_prefix('='))
    };
    // the session: the cookie, or the one-time key on the page's first request
    let wanted = cookie_name(shared.port);
    let has_session = cookies
        .iter()
        .flat_map(|c| c.split(';'))
        .filter_map(|kv| kv.trim().split_once('='))
        .any(|(k, v)| k == wanted && same(v, &shared.session));
    let mut set_cookie = String::new();
    if !has_session {
        let keyed = matches!(path, "/" | "/index.html")
            && param("key").is_some_and(|k| same(k, &shared.key));
        if !keyed {
            return refuse(
                w,
                "403 Forbidden",
                "open the URL specpoly printed (it carries this run's key)\n",
            );
        }
        if shared.key_used.swap(true, Ordering::SeqCst) {
            shared.key_reused.store(true, Ordering::SeqCst);
            let _s = shared.lock();
            shared.changed.notify_all();
            drop(_s);
            return refuse(
                w,
                "403 Forbidden",
                "this run's link was already opened by another client; the run stops\n",
            );
        }
        set_cookie = format!(
            "Set-Cookie: {wanted}={}; HttpOnly; SameSite=Strict; Path=/\r\n",
            shared.session
        );
    }
    let (seq, rgb) = {
        let mut s = shared.lock();
        s.requests += 1;
        (s.seq, s.rgb)
    };
    match path {
        "/" | "/index.html" => {
            let win = *shared.window.lock().unwrap_or_else(|e| e.into_inner());
            let side = 100.0 * win.size.sqrt();
            let page = PAGE
                .replace("__SIDE__", &format!("{side:.4}"))
                .replace("__OFF__", &format!("{:.4}", (100.0 - side) / 2.0))
                .replace("__BG__", &css([win.background; 3]))
                .replace("__CSS__", &css(rgb))
                .replace("__SEQ__", &seq.to_string());
            respond_with(
                &mut w,
                "200 OK",
                "text/html; charset=utf-8",
                &set_cookie,
                &page,
            )
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
            let n = param("seq").and_then(|v| v.parse::<u64>().ok());
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

    /// `GET target` with the right `Host` and `extra` header lines; the whole reply.
    fn get(addr: SocketAddr, target: &str, extra: &str) -> String {
        let mut s = TcpStream::connect(addr).unwrap();
        write!(s, "GET {target} HTTP/1.1\r\nHost: {addr}\r\n{extra}\r\n").unwrap();
        let mut out = String::new();
        s.read_to_string(&mut out).unwrap();
        out
    }

    /// Opens the page with the key; its reply and the `Cookie:` line of the session.
    fn open(d: &WebDisplay) -> (String, String) {
        let url = d.url();
        let page = get(d.addr, &url[url.find("/?").unwrap()..], "");
        let set = page
            .lines()
            .find_map(|l| l.strip_prefix("Set-Cookie: "))
            .unwrap_or_else(|| panic!("no cookie: {page}"));
        let cookie = format!("Cookie: {}\r\n", set.split(';').next().unwrap());
        (page, cookie)
    }

    #[test]
    fn serves_patch_and_takes_acks() {
        let mut d = WebDisplay::start(0).unwrap();
        d.first_wait = Duration::from_millis(100);
        let seq = d.post([1.0, 0.5, 0.0]);
        let (page, c) = open(&d);
        assert!(page.starts_with("HTTP/1.1 200"), "{page}");
        assert!(page.contains("HttpOnly; SameSite=Strict"), "{page}");
        let r = get(d.addr, "/patch", &c);
        assert!(r.starts_with("HTTP/1.1 200"), "{r}");
        assert!(r.contains("\"css\":\"rgb(255,128,0)\""), "{r}");
        // a reload with the cookie: the page again, no new cookie
        let again = get(d.addr, "/", &c);
        assert!(again.contains("background:rgb(255,128,0)"), "{again}");
        assert!(!again.contains("Set-Cookie"), "{again}");
        assert!(!d.wait_shown(seq, Duration::from_millis(20)));
        assert!(get(d.addr, &format!("/shown?seq={seq}"), &c).starts_with("HTTP/1.1 204"));
        assert!(d.wait_shown(seq, Duration::from_millis(20)));
        assert!(get(d.addr, "/nope", &c).starts_with("HTTP/1.1 404"));
        // nobody acknowledges the next patch: a clear error
        d.timeout = Duration::from_millis(50);
        let e = d.show([0.0; 3]).unwrap_err().to_string();
        assert!(e.contains("no browser showed patch 2"), "{e}");
    }

    #[test]
    fn window_size_and_background() {
        let start = |s: &str| WebDisplay::from_spec(&DeviceSpec::parse(s));
        let d = start("web,size=0.1,background=0.2").unwrap();
        let (page, _) = open(&d);
        // a 10 % window: sides √0.1 = 31.6228 % of the screen's, centred
        assert!(page.contains("width:31.6228%;height:31.6228%"), "{page}");
        assert!(page.contains("left:34.1886%;top:34.1886%"), "{page}");
        assert!(
            page.contains("<body style=\"background:rgb(51,51,51)\">"),
            "{page}"
        );
        for bad in [
            "web,size=0",
            "web,size=1.5",
            "web,background=-0.1",
            "web,size=x",
        ] {
            assert!(start(bad).is_err(), "{bad}");
        }
    }
}
