//! The 3D LUT export's figures on every shipped display (data/ti3), for docs/calibration.md:
//! the default model fitted on each `.ti3`; an sRGB → display `.cube` (white adapted, clip) at
//! each size, timed; applied by Debian's `ffmpeg` (`lut3d`, tetrahedral) and OpenColorIO's
//! `ocioconvert --lut` to a 16-bit image of in-gamut source colours (Halton, off every node);
//! the model's prediction of what the display shows against the colour the source asks for
//! (`palette`'s CIEDE2000, CIELAB relative to the display's white): mean / max ΔE00.
//!
//! Run: `cargo run -p specpoly-calibrate --example lut3d_figures [SIZES] [COLOURS] [SOURCE]`
//! (defaults `17,33,65`, `1000`, `srgb`; `exact` after them builds without the node fit).

#[path = "../tests/common/displays.rs"]
mod displays;
#[path = "../tests/common/lut3d_consumers.rs"]
mod lc;

use specpoly_display::lut3d::file::{self, Format};
use specpoly_display::lut3d::source::SourceSpace;
use specpoly_display::lut3d::{build, Options, Target};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let sizes: Vec<usize> = args
        .get(1)
        .map_or("17,33,65", |s| s.as_str())
        .split(',')
        .map(|s| s.parse().unwrap())
        .collect();
    let count: usize = args.get(2).map_or(1000, |s| s.parse().unwrap());
    let source = SourceSpace::from_name(args.get(3).map_or("srgb", |s| s.as_str())).unwrap();
    let refine = args.get(4).map(|s| s.as_str()) != Some("exact");
    let dir = tempfile::tempdir().unwrap();
    println!("| display | size | build (s) | nodes out of gamut | ffmpeg mean / max | OpenColorIO mean / max | colours |");
    println!("|---|---:|---:|---:|---|---|---:|");
    for name in displays::shipped() {
        let cal = displays::fitted(&name);
        let model = cal.model();
        let opts0 = Options {
            source,
            refine,
            ..Options::default()
        };
        let target = Target::new(model, source, opts0.white).unwrap();
        let cols = lc::in_gamut_colours(model, &target, count);
        let image = dir.path().join("colours.ppm");
        lc::write_ppm16(&image, &cols.iter().map(|c| c.0).collect::<Vec<_>>(), 40);
        for &size in &sizes {
            let opts = Options { size, ..opts0 };
            let t0 = std::time::Instant::now();
            let lut = build(model, &name, &opts).unwrap();
            let secs = t0.elapsed().as_secs_f64();
            let cube = dir.path().join("display.cube");
            std::fs::write(&cube, file::write(&lut, Format::Cube, source)).unwrap();
            let stats = |devices: Vec<[f64; 3]>| {
                let de: Vec<f64> = cols
                    .iter()
                    .zip(&devices)
                    .map(|((_, want), d)| {
                        displays::de00(lc::shown(model, *d), *want, target.white())
                    })
                    .collect();
                lc::mean_max(&de)
            };
            let (fm, fx) = stats(lc::ffmpeg_apply(&cube, &image, cols.len()));
            let (om, ox) = stats(lc::ocio_apply(&cube, &image, cols.len()));
            let st = lut.stats();
            println!(
                "| {} | {size}³ | {secs:.1} | {} of {} | {fm:.3} / {fx:.3} | {om:.3} / {ox:.3} | {} |",
                name.trim_end_matches(".ti3"),
                st.out_of_gamut,
                st.nodes,
                cols.len()
            );
        }
    }
}
