//! The parsers' fuzz targets: one function per parser of users' files and devices' replies,
//! each taking arbitrary bytes. A target returns normally for every input, malformed or not;
//! it panics only when the parser panics or breaks one of the invariants checked here:
//!
//! - what the project writes, its own readers accept, and read back equal (CSV
//!   [`specpoly_formats::csv::format`], `.ti3` [`specpoly_formats::cgats::write_ti3`], calibration TOML,
//!   protocol lines [`specpoly_protocol::Command::write`] and [`specpoly_protocol::Reply::write`]);
//! - no accepted value is non-finite;
//! - errors are one line (messages end up on one stderr line).
//!
//! `fuzz/` (cargo-fuzz, nightly) runs them under libFuzzer; `crates/cli/tests/fuzz_corpora.rs`
//! replays every saved corpus and an `arbitrary`-style random run on stable, in `cargo test`
//! (docs/reliability.md, "Fuzzing"). The firmware's command handler has its own target in
//! `firmware/src/fuzz.rs` (it is not a dependency of the host).

/// A fuzz target: arbitrary bytes in, a panic only on a bug.
pub type Target = fn(&[u8]);

/// The targets by name, as `fuzz/fuzz_targets/NAME.rs` and the corpora `fuzz/corpus/NAME/`
/// call them.
pub const TARGETS: [(&str, Target); 15] = [
    ("csv", csv),
    ("cgats", cgats),
    ("scene_toml", scene_toml),
    ("calibration_toml", calibration_toml),
    ("display_toml", display_toml),
    ("protocol_line", protocol_line),
    ("pr655_reply", pr655_reply),
    ("argyll_ti3", argyll_ti3),
    ("obj_mesh", obj_mesh),
    ("ply_mesh", ply_mesh),
    ("gltf", gltf),
    ("ccss", ccss),
    ("ccmx", ccmx),
    ("spectral_ti3", spectral_ti3),
    ("calibration_blob", calibration_blob),
];

fn one_line(e: &dyn std::fmt::Display) {
    let s = e.to_string();
    assert!(!s.contains('\n'), "a multi-line error: {s:?}");
}

fn text(data: &[u8]) -> String {
    specpoly_formats::read::decode(data.to_vec())
}

/// Spectral CSV ([`specpoly_formats::csv::parse`]): an accepted table is finite, and formatting it
/// gives a file that reads back equal.
pub fn csv(data: &[u8]) {
    let text = text(data);
    match specpoly_formats::csv::parse(&text, "fuzz.csv") {
        Err(e) => one_line(&e),
        Ok(t) => {
            assert!(t.wavelengths.iter().all(|w| w.is_finite()));
            assert!(t.wavelengths.windows(2).all(|w| w[0] < w[1]));
            for (_, v) in &t.columns {
                assert_eq!(v.len(), t.wavelengths.len());
                assert!(v.iter().all(|x| x.is_finite()));
            }
            let again = specpoly_formats::csv::format(&t);
            match specpoly_formats::csv::parse(&again, "again.csv") {
                Ok(u) => assert_eq!(u, t, "{again}"),
                Err(e) => panic!("the formatted table does not read back: {e}\n{again}"),
            }
        }
    }
}

/// CGATS ([`specpoly_formats::cgats::parse`], [`specpoly_formats::cgats::read_ti3`],
/// [`specpoly_formats::ti1::read_ti1`]): a `.ti3` that reads and is written again reads back.
pub fn cgats(data: &[u8]) {
    let text = text(data);
    if let Err(e) = specpoly_formats::cgats::parse(&text, "fuzz.ti3") {
        one_line(&e);
    }
    if let Err(e) = specpoly_formats::ti1::read_ti1(&text, "fuzz.ti1") {
        one_line(&e);
    }
    ti3_roundtrip(&text);
}

fn ti3_roundtrip(text: &str) {
    use specpoly_formats::cgats::{read_ti3, write_ti3, Ti3Info};
    match read_ti3(text, "fuzz.ti3") {
        Err(e) => one_line(&e),
        Ok(t) => {
            for m in &t.measurements {
                assert!(m.device.iter().chain(&m.xyz).all(|v| v.is_finite()));
            }
            let info = Ti3Info {
                descriptor: "fuzz".into(),
                ..Ti3Info::default()
            };
            // The writer may refuse (out-of-range values); what it writes must read back.
            if let Ok(out) = write_ti3(&t.measurements, &info) {
                let back = read_ti3(&out, "again.ti3")
                    .unwrap_or_else(|e| panic!("a written .ti3 does not read back: {e}\n{out}"));
                assert_eq!(back.measurements.len(), t.measurements.len());
            }
        }
    }
}

/// ArgyllCMS's `dispread` output as `calibrate run --instrument argyll` reads it: a `.ti3`
/// after [`specpoly_calibrate::instrument::argyll::strip_noise`].
pub fn argyll_ti3(data: &[u8]) {
    let text = specpoly_calibrate::instrument::argyll::strip_noise(&text(data));
    ti3_roundtrip(&text);
}

/// A scene file ([`specpoly_render::scene_file::SceneFile`]): parsed, resolved (built-in spectra
/// only, no base folder) and one pixel traced at the smallest size, within the render budget.
pub fn scene_toml(data: &[u8]) {
    use specpoly_render::scene_file::SceneFile;
    let text = text(data);
    let file = match SceneFile::parse(&text, "fuzz.toml") {
        Ok(f) => f,
        Err(e) => return one_line(&crate::error::CliError::from(e)),
    };
    let mut scene = match file.resolve("fuzz.toml") {
        Ok(s) => s,
        Err(e) => return one_line(&crate::error::CliError::from(e)),
    };
    scene.render.width = 1;
    scene.render.height = 1;
    scene.render.samples = 1;
    scene.render.spp = scene.render.spp.min(2);
    if let Err(e) = specpoly_render::render(&scene, specpoly_spectra::repr::Repr::Rgb, None) {
        one_line(&crate::error::CliError::from(e));
    }
}

/// A calibration file ([`specpoly_display::calibration::Calibration::from_toml`]): one that reads is
/// written ([`specpoly_display::calibration::Calibration::to_toml`]) and reads back equal.
pub fn calibration_toml(data: &[u8]) {
    use specpoly_display::calibration::Calibration;
    let text = text(data);
    match Calibration::from_toml(&text, "fuzz.toml") {
        Err(e) => one_line(&crate::error::CliError::from(e)),
        Ok(c) => {
            let out = c.to_toml().expect("a calibration that reads is written");
            let back = Calibration::from_toml(&out, "again.toml")
                .unwrap_or_else(|e| panic!("a written calibration does not read back: {e}\n{out}"));
            assert_eq!(back.to_toml().ok(), Some(out));
        }
    }
}

/// A display file ([`specpoly_display::spec::parse`]): primaries, luminances, transfer curves.
pub fn display_toml(data: &[u8]) {
    if let Err(e) = specpoly_display::spec::parse(&text(data), "fuzz.toml") {
        one_line(&crate::error::CliError::from(e));
    }
}

/// The LED protocol: a line through the fixed-size [`specpoly_protocol::LineReader`], then
/// [`specpoly_protocol::Command::parse`] and [`specpoly_protocol::Reply::parse`]; an accepted
/// command or reply is written and parses back equal.
pub fn protocol_line(data: &[u8]) {
    use specpoly_protocol::{Command, LineReader, Reply, MAX_LINE};
    let mut reader = LineReader::<MAX_LINE>::new();
    let mut lines: Vec<String> = Vec::new();
    for &b in data.iter().chain(b"\n") {
        if let Some(Ok(line)) = reader.push(b) {
            lines.push(line.to_string());
        }
    }
    for line in &lines {
        if let Ok(cmd) = Command::parse(line) {
            let mut s = String::new();
            cmd.write(&mut s).expect("write to a String");
            let again = Command::parse(&s);
            // `refl` is written as its product (one factor): compare the written forms.
            let mut t = String::new();
            match again {
                Ok(c) => c.write(&mut t).expect("write to a String"),
                Err(f) => panic!("`{line}` → `{s}` does not parse back: {f:?}"),
            }
            assert_eq!(s, t, "`{line}`");
        }
        if let Ok(reply) = Reply::parse(line) {
            let mut s = String::new();
            reply.write(&mut s).expect("write to a String");
            assert!(
                !s.starts_with("ok") || !(s.contains("nan") || s.contains("inf")),
                "`{line}` → `{s}`"
            );
            assert_eq!(Reply::parse(&s), Ok(reply), "`{line}` → `{s}`");
        }
    }
}

/// A PR-655 reply line ([`specpoly_calibrate::instrument::serial::parse_reply`] and
/// [`specpoly_calibrate::instrument::serial::find_reply`]): an accepted successful reading is
/// finite.
pub fn pr655_reply(data: &[u8]) {
    use specpoly_calibrate::instrument::serial::{find_reply, parse_reply};
    // The instrument link reads lines of at most a few hundred bytes.
    let text = text(&data[..data.len().min(4096)]);
    for line in text.lines() {
        for r in [parse_reply(line), find_reply(line)].into_iter().flatten() {
            if r.status == 0 {
                assert!(r.values.iter().all(|v| v.is_finite()), "{line}");
            }
        }
    }
}

/// A mesh read by `load` (given the placement and the soup to fill) from bytes: either a
/// one-line error, or triangles whose vertices are finite and within
/// [`specpoly_render::mesh::MAX_COORDINATE`], whose BVH builds, and which rays from six sides
/// cross at finite distances.
fn mesh(
    load: impl FnOnce(
        &specpoly_render::mesh::ObjPlacement<'_>,
        &mut specpoly_render::mesh::TriangleSoup,
    ) -> specpoly_render::Result<usize>,
) {
    use specpoly_render::geometry::{Ray, V3};
    use specpoly_render::mesh::{ObjPlacement, TriangleSoup, MAX_COORDINATE};
    let map = std::collections::BTreeMap::new();
    let place = ObjPlacement {
        scale: 1.0,
        translate: V3::new(0.0, 0.0, 0.0),
        default: 0,
        map: &map,
    };
    let mut soup = TriangleSoup::default();
    match load(&place, &mut soup) {
        Err(e) => one_line(&crate::error::CliError::from(e)),
        Ok(n) => {
            assert_eq!(n, soup.tris.len());
            let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
            for v in soup.tris.iter().flatten() {
                for (k, c) in [v.x, v.y, v.z].into_iter().enumerate() {
                    assert!(c.is_finite() && c.abs() <= MAX_COORDINATE, "{v:?}");
                    lo[k] = lo[k].min(c);
                    hi[k] = hi[k].max(c);
                }
            }
            let tris = soup.build();
            if tris.is_empty() {
                return;
            }
            let c = V3::from_array([0, 1, 2].map(|k| lo[k] * 0.5 + hi[k] * 0.5));
            let r = [0, 1, 2]
                .map(|k| hi[k] - lo[k])
                .into_iter()
                .fold(1.0f32, f32::max);
            for k in 0..6 {
                let mut a = [0.0; 3];
                a[k / 2] = if k % 2 == 0 { 1.0 } else { -1.0 };
                let d = V3::from_array(a);
                let ray = Ray {
                    origin: c - d * (2.0 * r),
                    dir: d,
                };
                if let Some((t, n, _)) = tris.intersect(&ray, f32::INFINITY) {
                    assert!(t.is_finite() && t >= 0.0, "t = {t}");
                    assert!(
                        n.x.is_finite() && n.y.is_finite() && n.z.is_finite(),
                        "{n:?}"
                    );
                }
            }
        }
    }
}

/// An OBJ mesh ([`specpoly_render::mesh::parse_obj`], `tobj` underneath): see [`mesh`]. Every
/// `mtllib` reads the same bytes as its material library, so one input exercises the `.mtl`
/// check and parser too.
pub fn obj_mesh(data: &[u8]) {
    use specpoly_render::mesh::{parse_obj, MtlSource};
    let path = std::path::Path::new("fuzz.obj");
    mesh(|place, soup| parse_obj(path, data, MtlSource::Bytes(data), place, soup));
}

/// A PLY mesh, ASCII or binary ([`specpoly_render::mesh_ply::parse_ply`], `ply-rs-bw`
/// underneath): see [`mesh`].
pub fn ply_mesh(data: &[u8]) {
    let path = std::path::Path::new("fuzz.ply");
    mesh(|place, soup| specpoly_render::mesh_ply::parse_ply(path, data, place, soup));
}

/// A glTF 2.0 file, JSON or binary ([`specpoly_render::mesh_gltf::GltfFile::from_bytes`],
/// external buffers refused): the scene it makes ([`specpoly_render::scene_gltf::scene_file_of`]:
/// materials, camera, lights) and its triangles as [`mesh`] checks them.
pub fn gltf(data: &[u8]) {
    use specpoly_render::mesh_gltf::{add_gltf, GltfFile};
    let path = std::path::Path::new("fuzz.glb");
    let file = match GltfFile::from_bytes(path, data.to_vec(), None) {
        Ok(f) => f,
        Err(e) => return one_line(&crate::error::CliError::from(e)),
    };
    if let Err(e) = specpoly_render::scene_gltf::scene_file_of(&file) {
        one_line(&crate::error::CliError::from(e));
    }
    mesh(|place, soup| add_gltf(&file, place, soup));
}

/// Bands read back from a written file: the same count, the ends within the six decimals
/// written (`SPECTRAL_START_NM "%f"`, as ArgyllCMS writes them).
fn same_bands(back: &specpoly_formats::spectral::Bands, b: &specpoly_formats::spectral::Bands) {
    assert_eq!(back.count, b.count);
    for (x, y) in [(back.start_nm, b.start_nm), (back.end_nm, b.end_nm)] {
        assert!((x - y).abs() <= 5e-7 + 1e-15 * y.abs(), "{back:?} vs {b:?}");
    }
}

/// A `.ccss` ([`specpoly_formats::ccss::read`]): an accepted file has at least
/// [`specpoly_formats::ccss::MIN_SAMPLES`] finite samples of its band count; written again
/// ([`specpoly_formats::ccss::write`]) it reads back with the same bands (to the six decimals
/// written) and samples (to the 7 significant digits written), and writing that gives the same
/// text.
pub fn ccss(data: &[u8]) {
    use specpoly_formats::ccss::{read, write, MIN_SAMPLES};
    match read(&text(data), "fuzz.ccss") {
        Err(e) => one_line(&e),
        Ok(c) => {
            let s = &c.samples;
            assert!(s.samples.len() >= MIN_SAMPLES);
            assert!(s
                .samples
                .iter()
                .all(|v| v.len() == s.bands.count && v.iter().all(|x| x.is_finite())));
            // the writer may refuse (no technology: the file gave only DISPLAY)
            if let Ok(out) = write(&c) {
                let back = read(&out, "again.ccss")
                    .unwrap_or_else(|e| panic!("a written .ccss does not read back: {e}\n{out}"));
                same_bands(&back.samples.bands, &s.bands);
                assert_eq!(back.samples.samples.len(), s.samples.len());
                for (a, b) in back
                    .samples
                    .samples
                    .iter()
                    .flatten()
                    .zip(s.samples.iter().flatten())
                {
                    assert!((a - b).abs() <= 1e-6 * b.abs().max(1e-300), "{a} vs {b}");
                }
                assert_eq!(write(&back).ok(), Some(out));
            }
        }
    }
}

/// A `.ccmx` ([`specpoly_formats::ccmx::read`]): an accepted matrix is finite; written again
/// ([`specpoly_formats::ccmx::write`], six decimals) it reads back within 5·10⁻⁷ of each entry,
/// and writing that gives the same text.
pub fn ccmx(data: &[u8]) {
    use specpoly_formats::ccmx::{read, write};
    match read(&text(data), "fuzz.ccmx") {
        Err(e) => one_line(&e),
        Ok(c) => {
            assert!(c.matrix.iter().flatten().all(|v| v.is_finite()));
            if let Ok(out) = write(&c) {
                let back = read(&out, "again.ccmx")
                    .unwrap_or_else(|e| panic!("a written .ccmx does not read back: {e}\n{out}"));
                for (a, b) in back.matrix.iter().flatten().zip(c.matrix.iter().flatten()) {
                    assert!((a - b).abs() <= 5e-7 + 1e-15 * b.abs(), "{a} vs {b}\n{out}");
                }
                assert_eq!(write(&back).ok(), Some(out));
            }
        }
    }
}

/// A spectral `.ti3` ([`specpoly_formats::cgats::read_ti3`] with `SPEC_…` fields): the spectra
/// are one per measurement, of the band count, finite; written again
/// ([`specpoly_formats::cgats::write_spectral_ti3`]) the file reads back with as many spectra
/// on the same bands.
pub fn spectral_ti3(data: &[u8]) {
    use specpoly_formats::cgats::{read_ti3, write_spectral_ti3, Ti3Info};
    let t = match read_ti3(&text(data), "fuzz.ti3") {
        Err(e) => return one_line(&e),
        Ok(t) => t,
    };
    let Some(s) = &t.spectra else {
        return;
    };
    assert_eq!(s.samples.len(), t.measurements.len());
    assert!(s
        .samples
        .iter()
        .all(|v| v.len() == s.bands.count && v.iter().all(|x| x.is_finite())));
    for absolute in [false, true] {
        let info = Ti3Info {
            descriptor: "fuzz".into(),
            absolute,
            ..Ti3Info::default()
        };
        if let Ok(out) = write_spectral_ti3(&t.measurements, s, &info) {
            let back = read_ti3(&out, "again.ti3").unwrap_or_else(|e| {
                panic!("a written spectral .ti3 does not read back: {e}\n{out}")
            });
            let b = back.spectra.expect("the written file has spectra");
            same_bands(&b.bands, &s.bands);
            assert_eq!(b.samples.len(), s.samples.len());
        }
    }
}

/// The C library's calibration blob ([`specpoly_core::blob::read`]), given both as the bytes
/// are and sealed: the input with its length field set and its CRC-32 appended, so mutations
/// reach the fields behind the checksum. A blob that reads is a display whose colours of
/// drives in `[0, 1]` are finite; its fields written again ([`specpoly_core::blob::write_parts`])
/// read back equal, and the display written ([`specpoly_core::blob::write`]) reads back.
pub fn calibration_blob(data: &[u8]) {
    use specpoly_core::blob::{crc32, parts, read, write, write_parts, MAX_BYTES};
    let mut sealed = data.to_vec();
    if sealed.len() >= 12 {
        let len = (sealed.len() + 4) as u32;
        sealed[8..12].copy_from_slice(&len.to_le_bytes());
        let crc = crc32(&sealed);
        sealed.extend_from_slice(&crc.to_le_bytes());
    }
    for bytes in [data, &sealed[..]] {
        let Ok(p) = parts(bytes) else {
            assert!(read(bytes).is_err());
            continue;
        };
        let mut buf = vec![0u8; MAX_BYTES];
        let n = write_parts(&p, &mut buf).expect("read fields are written");
        // (bytes compared: the fields may hold NaN, which no `==` equals)
        let again = parts(&buf[..n]).expect("written fields read back");
        let mut buf2 = vec![0u8; MAX_BYTES];
        let m = write_parts(&again, &mut buf2).expect("read fields are written");
        assert_eq!(buf[..n], buf2[..m]);
        let Ok(d) = p.display() else {
            continue;
        };
        for rgb in [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.5; 3],
            [1.0; 3],
        ] {
            let c = d.device_to_xyz(rgb);
            assert!(
                c.x.is_finite() && c.y.is_finite() && c.z.is_finite(),
                "{rgb:?} → {c:?}"
            );
        }
        let n = write(&d, &mut buf).expect("a display that reads is written");
        read(&buf[..n]).expect("a written display reads back");
    }
}
