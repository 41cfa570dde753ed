//! The web display in a real headless Chromium: the colour the page shows is read back from a
//! screenshot, the live page follows the patches, and a whole `calibrate run --display web`
//! completes with Chromium as the screen. Without Chromium these tests fail (never skip):
//! install it with `apt-get update && apt-get install -y chromium`.

use crate::common::calibrate_run as common;

use specpoly_calibrate::patch_display::web::{WebDisplay, MAX_CONNECTIONS, MAX_HEAD};
use specpoly_calibrate::patch_display::PatchDisplay;
use specpoly_formats::device_spec::DeviceSpec;
use std::io::{Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

fn quant(v: f64) -> u8 {
    (v * 255.0).round() as u8
}

/// Runs Chromium to completion (at most 60 s).
fn run_chromium(args: &[String]) -> std::process::ExitStatus {
    let mut c = Command::new(common::chromium())
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("start chromium");
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        if let Some(s) = c.try_wait().unwrap() {
            return s;
        }
        if Instant::now() > deadline {
            let _ = c.kill();
            let _ = c.wait();
            panic!("chromium did not finish within 60 s");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

struct Browser(Child);

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// A headless Chromium that keeps `url` open until dropped.
fn open_live(url: &str, profile: &std::path::Path) -> Browser {
    let mut args = common::chromium_args(profile);
    args.push("--remote-debugging-port=0".into());
    args.push(url.into());
    Browser(
        Command::new(common::chromium())
            .args(&args)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("start chromium"),
    )
}

#[test]
fn screenshot_shows_the_patch_colour() {
    let dir = tempfile::tempdir().unwrap();
    for (i, rgb) in [[1.0, 0.5, 0.0], [0.2, 0.4, 0.6], [0.0, 0.0, 0.0]]
        .into_iter()
        .enumerate()
    {
        // the link works once: a display per browser
        let d = WebDisplay::start(0).unwrap();
        d.post(rgb);
        let shot = dir.path().join(format!("shot{i}.png"));
        let mut args = common::chromium_args(&dir.path().join(format!("profile{i}")));
        args.push(format!("--screenshot={}", shot.display()));
        args.push(d.url());
        let st = run_chromium(&args);
        assert!(st.success(), "chromium failed: {st}");
        let decoder = png::Decoder::new(std::fs::File::open(&shot).expect("a screenshot"));
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).unwrap();
        let ch = info.color_type.samples();
        let (w, h) = (info.width as usize, info.height as usize);
        let at = |x: usize, y: usize| {
            let o = (y * w + x) * ch;
            [buf[o], buf[o + 1], buf[o + 2]]
        };
        let want = rgb.map(quant);
        assert_eq!(at(w / 2, h / 2), want, "centre pixel of patch {rgb:?}");
        assert_eq!(
            at(2, 2),
            want,
            "corner pixel of patch {rgb:?} (full window)"
        );
    }
}

#[test]
fn live_page_follows_the_patches() {
    let dir = tempfile::tempdir().unwrap();
    let mut d = WebDisplay::from_spec(&DeviceSpec::parse("web,wait=60,timeout=20")).unwrap();
    let _b = open_live(&d.url(), &dir.path().join("profile"));
    // each show() returns only once the page acknowledged the new colour
    for rgb in [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.5, 0.5, 0.5],
    ] {
        let t = Instant::now();
        d.show(rgb).unwrap_or_else(|e| panic!("{e}"));
        assert!(t.elapsed() < Duration::from_secs(20));
    }
    assert!(d.requests() >= 5);
}

#[test]
fn calibrate_run_with_chromium_as_the_screen() {
    let dir = tempfile::tempdir().unwrap();
    let cal = dir.path().join("cal.toml");
    let mut run = common::start(&common::calibrate_args(
        "web,wait=60,timeout=20",
        "sim:crt,noise=0.0005",
        &["--ramp-steps", "4", "--verify", "3", "--settle", "0"],
        cal.to_str().unwrap(),
    ));
    let url = run.web_url();
    let _b = open_live(&url, &dir.path().join("profile"));
    let done = run.finish(Duration::from_secs(120));
    assert_eq!(done.code, Some(0), "{done:?}");
    assert!(cal.is_file(), "no calibration written: {done:?}");
    let ti3 = std::fs::read_to_string(dir.path().join("cal.ti3")).unwrap();
    assert!(ti3.starts_with("CTI3"), "{ti3}");
}

/// The server's port.
fn port(d: &WebDisplay) -> u16 {
    d.addr().port()
}

/// The request target of the printed URL (`/?key=K`).
fn keyed(d: &WebDisplay) -> String {
    let url = d.url();
    url[url.find("/?").expect("a key in the URL")..].to_string()
}

/// Opens the page with the one-time key; the `Cookie:` header line of the session.
fn session(d: &WebDisplay) -> String {
    let page = get(d, &keyed(d), "");
    assert!(page.starts_with("HTTP/1.1 200"), "{page}");
    let set = page
        .lines()
        .find_map(|l| l.strip_prefix("Set-Cookie: "))
        .unwrap_or_else(|| panic!("no session cookie: {page}"));
    format!("Cookie: {}\r\n", set.split(';').next().unwrap())
}

/// Sends `raw` on a fresh connection and reads the whole reply (at most 5 s).
fn exchange(d: &WebDisplay, raw: &[u8]) -> String {
    let mut s = TcpStream::connect(("127.0.0.1", port(d))).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
    s.write_all(raw).unwrap();
    let mut out = Vec::new();
    let _ = s.read_to_end(&mut out);
    String::from_utf8_lossy(&out).into_owned()
}

/// `GET path` with the right `Host` and extra header lines.
fn get(d: &WebDisplay, path: &str, headers: &str) -> String {
    let raw = format!(
        "GET {path} HTTP/1.1\r\nHost: 127.0.0.1:{}\r\n{headers}\r\n",
        port(d)
    );
    exchange(d, raw.as_bytes())
}

#[test]
fn oversized_headers_and_bodies_are_refused() {
    let d = WebDisplay::start(0).unwrap();
    let big = format!(
        "GET / HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nX-Pad: {}\r\n\r\n",
        port(&d),
        "a".repeat(MAX_HEAD + 1)
    );
    let r = exchange(&d, big.as_bytes());
    assert!(r.starts_with("HTTP/1.1 431"), "{r}");
    // many small headers add up too
    let many = format!(
        "GET / HTTP/1.1\r\nHost: 127.0.0.1:{}\r\n{}\r\n",
        port(&d),
        "X-A: b\r\n".repeat(MAX_HEAD / 8 + 1)
    );
    let r = exchange(&d, many.as_bytes());
    assert!(r.starts_with("HTTP/1.1 431"), "{r}");
    // a request line without end, sent as one stream of bytes
    let r = exchange(&d, &vec![b'G'; 3 * MAX_HEAD]);
    assert!(r.starts_with("HTTP/1.1 431"), "{r}");
    let r = get(&d, "/", "Content-Length: 5\r\n");
    assert!(r.starts_with("HTTP/1.1 413"), "{r}");
    let r = exchange(&d, b"POST / HTTP/1.1\r\n\r\n");
    assert!(r.starts_with("HTTP/1.1 405"), "{r}");
    // just under the limit is served
    let ok = get(
        &d,
        &keyed(&d),
        &format!("X-Pad: {}\r\n", "a".repeat(MAX_HEAD - 200)),
    );
    assert!(ok.starts_with("HTTP/1.1 200"), "{ok}");
}

#[test]
fn connection_cap_holds() {
    let d = WebDisplay::start(0).unwrap();
    let c = session(&d);
    let idle: Vec<TcpStream> = (0..MAX_CONNECTIONS)
        .map(|_| TcpStream::connect(("127.0.0.1", port(&d))).unwrap())
        .collect();
    // let the server accept them all
    std::thread::sleep(Duration::from_millis(300));
    let r = get(&d, "/", &c);
    assert!(r.starts_with("HTTP/1.1 503"), "{r}");
    drop(idle);
    // the slots come back once those clients leave
    let deadline = Instant::now() + Duration::from_secs(3);
    loop {
        let r = get(&d, "/", &c);
        if r.starts_with("HTTP/1.1 200") {
            break;
        }
        assert!(Instant::now() < deadline, "still refused: {r}");
        std::thread::sleep(Duration::from_millis(50));
    }
}

#[test]
fn idle_clients_are_cut_off() {
    let d = WebDisplay::start(0).unwrap();
    let mut s = TcpStream::connect(("127.0.0.1", port(&d))).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
    // a slow client: half a request line, then nothing
    s.write_all(b"GET /pat").unwrap();
    let t = Instant::now();
    let mut out = Vec::new();
    let _ = s.read_to_end(&mut out);
    assert!(t.elapsed() < Duration::from_secs(10), "{:?}", t.elapsed());
    assert!(out.is_empty(), "{}", String::from_utf8_lossy(&out));
}

#[test]
fn foreign_host_and_origin_are_refused() {
    let d = WebDisplay::start(0).unwrap();
    let p = port(&d);
    let c = session(&d);
    // even with the session: the Host and Origin checks come first
    for host in [
        "evil.example".to_string(),
        format!("evil.example:{p}"),
        format!("127.0.0.1:{}", p.wrapping_add(1)),
        "127.0.0.1".to_string(),
    ] {
        let r = exchange(
            &d,
            format!("GET / HTTP/1.1\r\nHost: {host}\r\n{c}\r\n").as_bytes(),
        );
        assert!(
            r.starts_with("HTTP/1.1 403") && r.contains("Host:"),
            "{host}: {r}"
        );
    }
    let r = exchange(&d, format!("GET / HTTP/1.1\r\n{c}\r\n").as_bytes());
    assert!(r.starts_with("HTTP/1.1 403"), "no Host: {r}");
    let r = exchange(
        &d,
        format!("GET / HTTP/1.1\r\nHost: localhost:{p}\r\n{c}\r\n").as_bytes(),
    );
    assert!(r.starts_with("HTTP/1.1 200"), "{r}");
    let r = get(&d, "/", &format!("Origin: http://evil.example\r\n{c}"));
    assert!(r.starts_with("HTTP/1.1 403") && r.contains("Origin"), "{r}");
    let r = get(&d, "/", &format!("Origin: http://127.0.0.1:{p}\r\n{c}"));
    assert!(r.starts_with("HTTP/1.1 200"), "{r}");
}

/// Another local process (it can connect to the port, but has neither the key nor the
/// session): `403` on every route, nothing in any reply that would let it in, and the run
/// stops if it presents a key it read elsewhere before the browser does.
#[test]
fn no_route_without_the_key_or_session() {
    let mut d = WebDisplay::from_spec(&DeviceSpec::parse("web,wait=5,timeout=5")).unwrap();
    let seq = d.post([0.3, 0.2, 0.1]);
    let url = d.url();
    let key = url.rsplit("key=").next().unwrap().to_string();
    assert_eq!(key.len(), 32);
    // another run's key differs
    let other = WebDisplay::start(0).unwrap();
    assert_ne!(keyed(&other), keyed(&d));
    let wrong = format!("{:032x}", u128::from_str_radix(&key, 16).unwrap() ^ 1);
    let name = d.cookie_name();
    let forged = format!("Cookie: {name}={wrong}\r\n");
    let outsider = |path: &str, extra: &str| {
        let r = get(&d, path, extra);
        assert!(r.starts_with("HTTP/1.1 403"), "{path} {extra}: {r}");
        assert!(
            !r.contains(&key) && !r.contains("Set-Cookie"),
            "{path}: {r}"
        );
        r
    };
    for path in [
        "/".to_string(),
        "/index.html".to_string(),
        "/patch".to_string(),
        format!("/shown?seq={seq}"),
        "/favicon.ico".to_string(),
        "/nope".to_string(),
        format!("/?key={wrong}"),
        format!("/?key={key}x"),
        format!("/?xkey={key}"),
        format!("/patch?key={key}"),
        format!("/shown?seq={seq}&key={key}"),
    ] {
        outsider(&path, "");
        outsider(&path, &forged);
        assert!(!d.wait_shown(seq, Duration::from_millis(10)), "{path}");
    }
    // the browser opens the link: the page and the session
    let c = session(&d);
    assert!(!c.contains(&key));
    let r = get(&d, "/patch", &c);
    assert!(
        r.starts_with("HTTP/1.1 200") && r.contains("rgb(77,51,26)"),
        "{r}"
    );
    // the page never carries the session or the key
    let page = get(&d, "/", &c);
    let s = c.trim_end().rsplit('=').next().unwrap();
    assert!(!page.contains(s) && !page.contains(&key), "{page}");
    // the session of one run does not open another
    let r = get(&other, "/patch", &c);
    assert!(r.starts_with("HTTP/1.1 403"), "{r}");
    let r = get(&d, &format!("/shown?seq={seq}"), &c);
    assert!(r.starts_with("HTTP/1.1 204"), "{r}");
    assert!(d.wait_shown(seq, Duration::from_millis(20)));
    // someone else presents the key (read from a browser's command line, say): refused,
    // and the run stops at its next patch instead of being driven by two clients
    outsider(&keyed(&d), "");
    let e = d.show([0.0; 3]).unwrap_err().to_string();
    assert!(e.contains("opened by a second client"), "{e}");
}
