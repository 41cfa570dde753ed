//! `specpoly light --tm30 / --cvg / --report` through the real binary, on a shipped LED
//! (`data/leds/rgbwa.csv#white`): the hue bins, the 99 samples and the graphic's points against
//! colour-science 0.4.7 and the design intents against luxpy 1.12.5 (the light is
//! `rgbwa:0/0/0/1/0` of `crates/core/tests/data/light_references*.csv`), the SVG's 16 arrows
//! parsed back, the HTML report rendered by headless Chromium with each arrow's colour found
//! at the tip the reference figures give, and clean failures that leave no file.

use crate::common::calibrate_run::{chromium, chromium_args};
use crate::common::cli;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const LED: &str = "data/leds/rgbwa.csv#white";
const REF_NAME: &str = "rgbwa:0/0/0/1/0";

fn specpoly(args: &[&str]) -> (i32, String, String) {
    cli::run_in(cli::ROOT, args).parts()
}

/// The reference row of `file` (in `crates/core/tests/data/`) for the LED: header → value.
fn reference(file: &str) -> std::collections::HashMap<String, String> {
    let p = format!("{}/../core/tests/data/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(p).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<&str> = lines
        .find(|l| l.starts_with(&format!("{REF_NAME},")))
        .unwrap()
        .split(',')
        .collect();
    head.iter()
        .zip(row)
        .map(|(h, v)| (h.to_string(), v.to_string()))
        .collect()
}

fn num(m: &std::collections::HashMap<String, String>, k: &str) -> f64 {
    m[k].parse().unwrap()
}

/// colour-science's graphic points of bin `j` (0-based): the reference mean over its radius,
/// and the test mean over the same radius.
fn cs_points(t: &std::collections::HashMap<String, String>, j: usize) -> ([f64; 2], [f64; 2]) {
    let h = j + 1;
    let (ra, rb) = (
        num(t, &format!("ref_a_h{h}")),
        num(t, &format!("ref_b_h{h}")),
    );
    let (ta, tb) = (
        num(t, &format!("test_a_h{h}")),
        num(t, &format!("test_b_h{h}")),
    );
    let r = ra.hypot(rb);
    ([ra / r, rb / r], [ta / r, tb / r])
}

#[test]
fn tm30_json_matches_colour_science_and_luxpy() {
    let (code, out, err) = specpoly(&["light", LED, "--tm30", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let cs = reference("light_references.csv");
    let tm = reference("light_references_tm30.csv");
    let lux = reference("light_references_annex_e.csv");
    let t = &v["tm30"];
    // the light's own keys are there too
    assert_eq!(v["rf"], t["rf"]);
    assert!((t["rf"].as_f64().unwrap() - num(&cs, "rf")).abs() < 0.05);
    assert!((t["rg"].as_f64().unwrap() - num(&cs, "rg")).abs() < 0.05);
    let bins = t["bins"].as_array().unwrap();
    assert_eq!(bins.len(), 16);
    for (j, b) in bins.iter().enumerate() {
        let h = j + 1;
        let f = |k: &str| b[k].as_f64().unwrap();
        assert_eq!(b["bin"], h);
        assert!(
            (f("rf") - num(&cs, &format!("rf_h{h}"))).abs() < 0.1,
            "bin {h}"
        );
        assert!((f("rcs_percent") / 100.0 - num(&cs, &format!("rcs_h{h}"))).abs() < 0.005);
        assert!((f("rhs") - num(&cs, &format!("rhs_h{h}"))).abs() < 0.005);
        let (r, p) = cs_points(&tm, j);
        for k in 0..2 {
            assert!((b["cvg_reference"][k].as_f64().unwrap() - r[k]).abs() < 2e-4);
            assert!((b["cvg_test"][k].as_f64().unwrap() - p[k]).abs() < 2e-4);
        }
    }
    let ces = t["ces"].as_array().unwrap();
    assert_eq!(ces.len(), 99);
    for (i, c) in ces.iter().enumerate() {
        let n = i + 1;
        assert_eq!(c["ces"], n);
        assert_eq!(c["bin"].as_f64().unwrap(), num(&tm, &format!("bin_ces{n}")));
        assert!((c["rf"].as_f64().unwrap() - num(&tm, &format!("rf_ces{n}"))).abs() < 0.1);
    }
    let d = &t["design_intents"];
    for k in ["preference", "vividness", "fidelity"] {
        assert_eq!(d[k].as_str().unwrap(), lux[k], "{k}");
    }
    // the text form has a row a bin and a sample
    let (code, out, err) = specpoly(&["light", LED, "--tm30"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains(&format!(
        "design intents (Annex E): {} {} {}",
        lux["preference"], lux["vividness"], lux["fidelity"]
    )));
    assert_eq!(
        out.lines().filter(|l| !l.starts_with('#')).count(),
        2 + 17 + 100
    );
}

/// A `points` attribute as pixel pairs.
fn points(s: &str) -> Vec<(f64, f64)> {
    s.split_whitespace()
        .map(|p| {
            let (x, y) = p.split_once(',').unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect()
}

/// The graphic's geometry read from its SVG: the black reference circle's centre and radius.
fn circle(svg: &roxmltree::Document) -> (f64, f64, f64) {
    let c = svg
        .descendants()
        .find(|n| n.has_tag_name("circle") && n.attribute("stroke") == Some("#000000"))
        .expect("the reference circle");
    let a = |k| c.attribute(k).unwrap().parse::<f64>().unwrap();
    (a("cx"), a("cy"), a("r"))
}

const ARROWS: [&str; 16] = [
    "#E62828", "#E74B4B", "#FB812E", "#FFB529", "#CBCA46", "#7EB94C", "#41C06D", "#009C7C",
    "#16BCB0", "#00A4BF", "#0085C3", "#3B62AA", "#4568AE", "#6A4E85", "#9D69A1", "#A74F81",
];

#[test]
fn cvg_svg_has_16_arrows_where_the_numbers_say() {
    let dir = tempfile::tempdir().unwrap();
    let svg_path = dir.path().join("cvg.svg");
    let png_path = dir.path().join("cvg.png");
    let (code, _, err) = specpoly(&["light", LED, "--cvg", svg_path.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&svg_path).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let (cx, cy, r) = circle(&doc);
    let tm = reference("light_references_tm30.csv");
    let mut worst = 0.0f64;
    for (j, colour) in ARROWS.iter().enumerate() {
        let shaft: Vec<_> = doc
            .descendants()
            .filter(|n| n.has_tag_name("polyline") && n.attribute("stroke") == Some(colour))
            .collect();
        let head: Vec<_> = doc
            .descendants()
            .filter(|n| n.has_tag_name("polygon") && n.attribute("fill") == Some(colour))
            .collect();
        assert_eq!((shaft.len(), head.len()), (1, 1), "bin {}", j + 1);
        let tail = points(shaft[0].attribute("points").unwrap())[0];
        let apex = points(head[0].attribute("points").unwrap())[0];
        let (want_tail, want_tip) = cs_points(&tm, j);
        let px = |p: [f64; 2]| (cx + p[0] * r, cy - p[1] * r);
        for (got, want) in [(tail, px(want_tail)), (apex, px(want_tip))] {
            let d = (got.0 - want.0).hypot(got.1 - want.1);
            worst = worst.max(d);
        }
    }
    println!("worst arrow end off by {worst:.2} px (r = {r} px a unit)");
    // whole pixels, and the circle's radius rounded to one
    assert!(worst <= 1.5, "{worst}");
    // the PNG of the same graphic
    let (code, _, err) = specpoly(&["light", LED, "--cvg", png_path.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let d = png::Decoder::new(std::fs::File::open(&png_path).unwrap());
    let info = d.read_info().unwrap().info().clone();
    assert_eq!((info.width, info.height), (600, 600));
}

/// Runs Chromium on `page` as the brief of the test says, returns the screenshot's RGB pixels
/// and width.
fn screenshot(page: &Path, dir: &Path, (w, h): (u32, u32)) -> (Vec<[u8; 3]>, u32) {
    let shot = dir.join("shot.png");
    let mut args = chromium_args(&dir.join("profile"));
    args.retain(|a| !a.starts_with("--window-size"));
    args.extend([
        format!("--window-size={w},{h}"),
        format!("--screenshot={}", shot.display()),
        format!("file://{}", page.display()),
    ]);
    let mut c = Command::new(chromium())
        .args(&args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("start chromium");
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        if let Some(st) = c.try_wait().unwrap() {
            assert!(st.success(), "chromium failed: {st}");
            break;
        }
        if Instant::now() > deadline {
            let _ = c.kill();
            let _ = c.wait();
            panic!("chromium did not finish within 60 s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    rgb_pixels(&shot)
}

fn rgb_pixels(png_file: &Path) -> (Vec<[u8; 3]>, u32) {
    let d = png::Decoder::new(std::fs::File::open(png_file).expect("a screenshot"));
    let mut r = d.read_info().unwrap();
    let mut buf = vec![0; r.output_buffer_size()];
    let info = r.next_frame(&mut buf).unwrap();
    let ch = info.color_type.samples();
    let px = buf[..info.buffer_size()]
        .chunks(ch)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    (px, info.width)
}

fn hex(s: &str) -> [u8; 3] {
    let v = |i: usize| u8::from_str_radix(&s[i..i + 2], 16).unwrap();
    [v(1), v(3), v(5)]
}

/// The page's size, and where the graphic's unit circle is on the page: its centre and
/// radius, from `div#cvg`'s placement and the black circle of the SVG inside it.
fn page_geometry(html: &str) -> ((u32, u32), (f64, f64, f64)) {
    let opt = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..Default::default()
    };
    let doc = roxmltree::Document::parse_with_options(html, opt).unwrap();
    let style = |id: &str| -> Vec<f64> {
        let n = doc
            .descendants()
            .find(|n| n.attribute("id") == Some(id))
            .unwrap();
        n.attribute("style")
            .unwrap()
            .split(';')
            .filter_map(|kv| kv.split_once(':'))
            .map(|(_, v)| v.trim().trim_end_matches("px").parse().unwrap())
            .collect()
    };
    let page = style("page");
    let b = style("cvg");
    let svg = doc
        .descendants()
        .find(|n| n.attribute("id") == Some("cvg"))
        .unwrap();
    let c = svg
        .descendants()
        .find(|n| n.has_tag_name("circle") && n.attribute("stroke") == Some("#000000"))
        .unwrap();
    let a = |k| c.attribute(k).unwrap().parse::<f64>().unwrap();
    (
        (page[0] as u32, page[1] as u32),
        (b[0] + a("cx"), b[1] + a("cy"), a("r")),
    )
}

/// Each arrow's colour at its tip as colour-science's figures give it (within 6 px back along
/// the arrow from the tip toward its tail: the head's point is anti-aliased into the test
/// polygon), the reference circle black where it should be, and no arrow colour at the centre.
fn check_arrows(px: &[[u8; 3]], width: u32, (cx, cy, r): (f64, f64, f64)) {
    let tm = reference("light_references_tm30.csv");
    let at = |x: f64, y: f64| px[y.round() as usize * width as usize + x.round() as usize];
    let near = |x: f64, y: f64, c: [u8; 3], radius: i32| {
        (-radius..=radius).any(|dy| {
            (-radius..=radius).any(|dx| {
                let p = at(x + dx as f64, y + dy as f64);
                (0..3).all(|k| (p[k] as i32 - c[k] as i32).abs() <= 3)
            })
        })
    };
    for (j, colour) in ARROWS.iter().enumerate() {
        let (tail, tip) = cs_points(&tm, j);
        let (x, y) = (cx + tip[0] * r, cy - tip[1] * r);
        let (dx, dy) = ((tail[0] - tip[0]) * r, (tip[1] - tail[1]) * r);
        let len = dx.hypot(dy);
        assert!(len > 6.0, "bin {}: arrow of {len:.1} px", j + 1);
        let found = (0..=6).any(|t| {
            let k = t as f64 / len;
            near(x + k * dx, y + k * dy, hex(colour), 1)
        });
        assert!(
            found,
            "bin {}: no {colour} at the tip ({x:.1}, {y:.1}): {:?}",
            j + 1,
            at(x, y)
        );
    }
    // the reference circle, at four points between the bins' arrows
    for deg in [11.25f64, 101.25, 191.25, 281.25] {
        let (x, y) = (
            cx + r * deg.to_radians().cos(),
            cy - r * deg.to_radians().sin(),
        );
        assert!(near(x, y, [0, 0, 0], 1), "circle at {deg}°: {:?}", at(x, y));
    }
    for c in ARROWS {
        assert!(!near(cx, cy, hex(c), 3));
    }
}

#[test]
fn report_html_renders_in_chromium_with_the_arrows_where_the_numbers_say() {
    let dir = tempfile::tempdir().unwrap();
    let page = dir.path().join("report.html");
    let (code, _, err) = specpoly(&["light", LED, "--report", page.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let html = std::fs::read_to_string(&page).unwrap();
    let (size, geometry) = page_geometry(&html);
    let (px, width) = screenshot(&page, dir.path(), size);
    assert_eq!(width, size.0);
    check_arrows(&px, width, geometry);
    // the 16 bins' and 99 samples' bars are there
    for id in ["rcs-16", "rhs-16", "rfh-16", "rfces-99"] {
        assert!(html.contains(&format!("id=\"{id}\"")), "{id}");
    }
}

#[test]
fn report_png_is_the_page_rendered_by_chromium() {
    let dir = tempfile::tempdir().unwrap();
    let png_path = dir.path().join("report.png");
    let (code, _, err) = specpoly(&["light", LED, "--report", png_path.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let html_path = dir.path().join("report.html");
    let (code, _, err) = specpoly(&["light", LED, "--report", html_path.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let (size, geometry) = page_geometry(&std::fs::read_to_string(&html_path).unwrap());
    let (px, width) = rgb_pixels(&png_path);
    assert_eq!((width, px.len() as u32 / width), size);
    check_arrows(&px, width, geometry);
}

#[test]
fn bad_input_is_one_line_and_leaves_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r.html");
    let o = out.to_str().unwrap();
    let svg = dir.path().join("r.svg").to_str().unwrap().to_string();
    // a red LED has no CCT: no TM-30
    for args in [
        vec!["light", "data/leds/rgb.csv#red", "--report", o],
        vec!["light", "data/leds/rgb.csv#red", "--tm30"],
        vec!["light", "data/leds/rgb.csv#red", "--cvg", &svg],
    ] {
        let (code, out_text, err) = specpoly(&args);
        assert_eq!(code, 1, "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains("correlated colour temperature"), "{err}");
        assert!(out_text.is_empty());
    }
    assert!(!out.exists());
    // an unwritable path: nothing written anywhere
    let bad = dir.path().join("no/such/folder/r.html");
    let (code, _, err) = specpoly(&["light", LED, "--report", bad.to_str().unwrap()]);
    assert_eq!(code, 1, "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    // a wrong extension is a usage error
    let (code, _, err) = specpoly(&["light", LED, "--report", "r.pdf"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains(".html or .png"), "{err}");
    let (code, _, err) = specpoly(&["light", LED, "--cvg", "r.html"]);
    assert_eq!(code, 2, "{err}");
    let png = dir.path().join("same.png");
    let p = png.to_str().unwrap();
    let (code, _, err) = specpoly(&["light", LED, "--cvg", p, "--report", p]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("same file"), "{err}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}
