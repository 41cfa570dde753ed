//! On-target tests and measurements, under QEMU with semihosting: exits 0 when every check
//! passes, 1 otherwise. Logs through defmt (decoded on the host by the tests), for the host tests
//! and docs/performance.md:
//!
//! - `check NAME ok|FAIL`;
//! - `insns PRESET WHAT N`: instructions per call (meaningful under `-icount shift=0`);
//!   `insns mix N solve|step I` for mixing N channels;
//! - `colour I duty R G B`: duties of a fixed set of colours on an sRGB-curve LED (compared
//!   between the libm and the `fast-math` builds on the host);
//! - `stack BYTES`: the deepest stack use (painted);
//! - `selftest: pass|fail`.
#![no_std]
#![no_main]
#![deny(unsafe_code)]

use core::fmt::Write as _;
use cortex_m_rt::entry;
use cortex_m_semihosting::debug;
use heapless::String;
#[cfg(feature = "mixing")]
use specpoly_core::light::channels::{Channel, Curve, Goal};
use specpoly_core::{
    DefaultSpectrum, Illuminant, Layout, Moments, Observer, PaperSpectrum, Spectrum, Xyy,
};
use specpoly_device::Controller;
use specpoly_firmware::boards::mps2::{icount::Counter, stack};
#[cfg(feature = "mixing")]
use specpoly_protocol::DeviceMixer;
use specpoly_protocol::{
    write_reflect, write_reflect_hex, Command, Gamut, LineReader, Reflectance, Reply, MAX_LINE,
    MAX_REPLY,
};

/// A smooth test reflectance: a sigmoid-like ramp, as Chebyshev coefficients per span.
fn ramp<const S: usize, L: Layout<S>>(level: f32) -> Spectrum<S, 4, L> {
    let mut s = Spectrum::<S, 4, L>::ZERO;
    for sp in 0..S {
        let c = s.coefficients_mut();
        c[0][sp] = level * (0.2 + 0.6 * sp as f32 / S as f32);
        c[1][sp] = 0.05 * level;
        c[2][sp] = -0.01;
        c[3][sp] = 0.002;
    }
    s
}

#[cfg(feature = "mixing")]
/// Six LED channels as `x, y, Y` at full drive (red, green, blue, a 4000 K white, amber, a
/// warm white; typical of the sets in data/leds/).
const CHANNELS: [[f32; 3]; 6] = [
    [0.69, 0.30, 0.25],
    [0.17, 0.72, 0.9],
    [0.14, 0.05, 0.1],
    [0.38, 0.38, 1.0],
    [0.58, 0.42, 0.5],
    [0.46, 0.41, 0.9],
];

/// Instructions per mix solve (3–6 channels) and per fade step; the solved chromaticity
/// (feature `mixing`).
#[cfg(feature = "mixing")]
fn mix(checks: &mut Checks, counter: &mut Counter) {
    let mut worst = 0.0f32;
    for n in 3..=6 {
        let mut m = DeviceMixer::new();
        for (i, [x, y, big_y]) in CHANNELS.iter().take(n).enumerate() {
            let xyz = [x / y * big_y, *big_y, (1.0 - x - y) / y * big_y];
            let c = Channel::new(xyz, 1.0, Curve::Gamma(2.2));
            let _ = m.channels.set(i, c);
        }
        let goal = Goal::Cct {
            cct: 4000.0,
            duv: 0.0,
            lum: 0.5,
        };
        let Some(p) = goal.point() else {
            checks.check("mix-target", false);
            return;
        };
        let insns = counter.insns_per_call(20, || {
            core::hint::black_box(m.channels.solve(core::hint::black_box(p)).ok());
        });
        defmt::info!("insns mix {} solve {}", n, insns);
        // a whole fade step: the next point, its solve, curves and quantisation
        m.fade_ms = 0;
        let _ = m.target(goal, u16::MAX);
        m.fade_ms = 600_000;
        let _ = m.target(
            Goal::Cct {
                cct: 6500.0,
                duv: 0.0,
                lum: 1.0,
            },
            u16::MAX,
        );
        let insns = counter.insns_per_call(20, || {
            core::hint::black_box(m.step(u16::MAX));
        });
        defmt::info!("insns mix {} step {}", n, insns);
        // the light the fractions make has the target's chromaticity
        if let Ok(d) = m.channels.solve(p) {
            let mut xyz = [0.0f32; 3];
            for (i, c) in m.channels.list().iter().enumerate() {
                for k in 0..3 {
                    xyz[k] += d[i] * c.xyz[k];
                }
            }
            let s = xyz[0] + xyz[1] + xyz[2];
            let t = p.xy();
            worst = worst.max((xyz[0] / s - t[0]).abs().max((xyz[1] / s - t[1]).abs()));
        } else {
            worst = f32::INFINITY;
        }
    }
    checks.check("mix-chromaticity", worst < 1e-5);
}

struct Checks {
    failed: u32,
}

impl Checks {
    fn check(&mut self, name: &str, ok: bool) {
        defmt::info!("check {} {}", name, if ok { "ok" } else { "FAIL" });
        if !ok {
            self.failed += 1;
        }
    }
}

fn handle(c: &mut Controller, line: &str) -> Reply {
    c.handle(Command::parse(line))
}

#[entry]
fn main() -> ! {
    stack::paint();
    let mut checks = Checks { failed: 0 };
    let Some(p) = cortex_m::Peripherals::take() else {
        defmt::info!("selftest: no peripherals");
        debug::exit(debug::EXIT_FAILURE);
        loop {
            cortex_m::asm::wfi();
        }
    };
    let mut counter = Counter::new(p.SYST);
    let mut c = Controller::new(u16::MAX);

    // 1. colour results
    let w = c.display().white();
    let mut line: String<MAX_LINE> = String::new();
    let _ = write!(line, "xyz {} 100 {}", w.x * 100.0 / w.y, w.z * 100.0 / w.y);
    let white_ok = matches!(handle(&mut c, &line),
        Reply::Colour(r) if r.gamut == Gamut::In && r.duty.iter().all(|d| *d >= 65534));
    checks.check("white-at-full-duty", white_ok);

    let mut worst = 0.0f32;
    for (x, y, big_y) in [(0.3127, 0.329, 50.0), (0.4, 0.4, 30.0), (0.25, 0.3, 10.0)] {
        let t = Xyy { x, y, big_y }.to_xyz();
        let r = c.colour(t);
        for (a, b) in r.led.to_array().iter().zip(t.to_array()) {
            worst = worst.max((a - b).abs());
        }
    }
    checks.check("in-gamut-emitted-within-quantisation", worst < 0.01);

    let out = matches!(handle(&mut c, "xyy 0.08 0.85 50"),
        Reply::Colour(r) if r.gamut != Gamut::In);
    checks.check("out-of-gamut-reported", out);

    let one = DefaultSpectrum::constant(1.0);
    let d65 = c.reflectance_xyz(Illuminant::D65, &Reflectance::Default(one));
    checks.check(
        "perfect-reflector-is-d65-white",
        (d65.x - 95.04).abs() < 0.05
            && (d65.y - 100.0).abs() < 1e-3
            && (d65.z - 108.88).abs() < 0.05,
    );

    let half = Reflectance::Paper(PaperSpectrum::constant(0.5));
    line.clear();
    let _ = write_reflect(&mut line, Illuminant::A, &[half, half]);
    let quarter = matches!(handle(&mut c, &line),
        Reply::Colour(r) if (r.xyz.y - 25.0).abs() < 1e-3);
    checks.check("product-of-halves-is-a-quarter", quarter);

    // 2. fuzz: random bytes never panic and every reply fits
    let mut reader = LineReader::<MAX_LINE>::new();
    let mut out: String<MAX_REPLY> = String::new();
    let mut seed = 0x2545_F491u32;
    let mut replies = 0u32;
    let mut fits = true;
    let words: [&[u8]; 8] = [
        b"refl ",
        b"default ",
        b"D65 ",
        b"0.5 ",
        b"* ",
        b"xyz ",
        b"\n",
        b"trc r table ",
    ];
    for i in 0..60_000u32 {
        seed ^= seed << 13;
        seed ^= seed >> 17;
        seed ^= seed << 5;
        // half raw bytes, half grammar words, so parsing goes deep
        let chunk: &[u8] = if i % 2 == 0 {
            &[(seed & 0xff) as u8]
        } else {
            words[(seed % 8) as usize]
        };
        for b in chunk {
            if let Some(l) = reader.push(*b) {
                let r = match l {
                    Ok(l) => c.handle(Command::parse(l)),
                    Err(f) => Reply::Error(f),
                };
                out.clear();
                fits &= r.write(&mut out).is_ok();
                replies += 1;
            }
        }
    }
    checks.check("fuzz-replies-fit", fits && replies > 100);

    // 3. instruction counts (under -icount shift=0)
    let cal = counter.insns_per_call(10, || cortex_m::asm::delay(100_000));
    defmt::info!("insns calibration delay-100000 {}", cal);
    let n = 20;
    let ill = Illuminant::D65.tabulated();
    let m_paper = Moments::new(Observer::Cie1931, &ill);
    let m_default = Moments::new(Observer::Cie1931, &ill);
    let rp: PaperSpectrum = ramp(0.9);
    let rd: DefaultSpectrum = ramp(0.9);
    let disp = c.display().clone();
    let insns = counter.insns_per_call(2, || {
        core::hint::black_box(Moments::<2, 4, specpoly_core::Paper>::new(
            Observer::Cie1931,
            &ill,
        ));
    });
    defmt::info!("insns paper moments {}", insns);
    let insns = counter.insns_per_call(2, || {
        core::hint::black_box(Moments::<8, 4>::new(Observer::Cie1931, &ill));
    });
    defmt::info!("insns default moments {}", insns);
    // the kernels as the controller runs them: through `Reflectance`, compiled in
    // `specpoly-kernels` (built for speed; this crate is built for size, docs/performance.md)
    let (fp, fd) = (Reflectance::Paper(rp), Reflectance::Default(rd));
    let insns = counter.insns_per_call(n * 50, || {
        core::hint::black_box(core::hint::black_box(&fp).mul(core::hint::black_box(&fp)));
    });
    defmt::info!("insns paper mul {}", insns);
    let insns = counter.insns_per_call(n * 50, || {
        core::hint::black_box(core::hint::black_box(&fd).mul(core::hint::black_box(&fd)));
    });
    defmt::info!("insns default mul {}", insns);
    let insns = counter.insns_per_call(n * 50, || {
        core::hint::black_box(core::hint::black_box(&fp).xyz(&m_paper, &m_default));
    });
    defmt::info!("insns paper xyz {}", insns);
    let insns = counter.insns_per_call(n * 50, || {
        core::hint::black_box(core::hint::black_box(&fd).xyz(&m_paper, &m_default));
    });
    defmt::info!("insns default xyz {}", insns);
    let target = m_default.xyz(&rd);
    for (name, curve) in [("linear", "trc rgb linear"), ("srgb", "trc rgb srgb")] {
        let _ = handle(&mut c, curve);
        let d = c.display().clone();
        let insns = counter.insns_per_call(n * 50, || {
            core::hint::black_box(
                d.encode_relative(core::hint::black_box(target), specpoly_core::GamutMap::Clip),
            );
        });
        defmt::info!("insns {} encode {}", name, insns);
    }
    let _ = disp;
    // the wire's numbers: a 9-digit decimal read, a float written (shortest round trip)
    let insns = counter.insns_per_call(n * 50, || {
        let _ = core::hint::black_box(specpoly_protocol::number::parse_f32(core::hint::black_box(
            "0.123456789",
        )));
    });
    defmt::info!("insns number parse-9-digits {}", insns);
    let insns = counter.insns_per_call(n * 50, || {
        let _ = core::hint::black_box(specpoly_protocol::number::parse_f32(core::hint::black_box(
            "0.25",
        )));
    });
    defmt::info!("insns number parse-short {}", insns);
    let insns = counter.insns_per_call(n * 50, || {
        let mut s: String<24> = String::new();
        let _ = specpoly_protocol::number::write_f32(&mut s, core::hint::black_box(1.0 / 3.0));
        core::hint::black_box(&s);
    });
    defmt::info!("insns number format {}", insns);
    // whole colour computations: reflectance (cached moments) → XYZ → duties, on a linear
    // (PWM) curve, then (below) on the sRGB curve
    let _ = handle(&mut c, "trc rgb linear");
    let r = Reflectance::Default(rd);
    let insns = counter.insns_per_call(n * 10, || {
        let xyz = c.reflectance_xyz(Illuminant::D65, core::hint::black_box(&r));
        core::hint::black_box(c.colour(xyz));
    });
    defmt::info!("insns default colour-linear {}", insns);
    for (preset, r) in [
        ("paper", Reflectance::Paper(rp)),
        ("default", Reflectance::Default(rd)),
    ] {
        let _ = handle(&mut c, "trc rgb srgb");
        let _ = c.reflectance_xyz(Illuminant::D65, &r); // fill the moments cache
        let insns = counter.insns_per_call(n * 10, || {
            let xyz = c.reflectance_xyz(Illuminant::D65, core::hint::black_box(&r));
            core::hint::black_box(c.colour(xyz));
        });
        defmt::info!("insns {} colour {}", preset, insns);
        // a whole line: parse (two factors), compute, format the reply
        line.clear();
        let _ = write_reflect(&mut line, Illuminant::D65, &[r, r]);
        let insns = counter.insns_per_call(n, || {
            let reply = c.handle(Command::parse(core::hint::black_box(&line)));
            out.clear();
            let _ = reply.write(&mut out);
        });
        defmt::info!("insns {} line-2-factors {}", preset, insns);
        let decimal = c.handle(Command::parse(&line));
        // the same line with the coefficients in the compact hex form (`0x` + f32 bits)
        line.clear();
        let _ = write_reflect_hex(&mut line, Illuminant::D65, &[r, r]);
        let insns = counter.insns_per_call(n, || {
            let reply = c.handle(Command::parse(core::hint::black_box(&line)));
            out.clear();
            let _ = reply.write(&mut out);
        });
        defmt::info!("insns {} line-2-factors-hex {}", preset, insns);
        // where a hex line's instructions go: parsing, answering, writing the reply
        let insns = counter.insns_per_call(n, || {
            let _ = core::hint::black_box(Command::parse(core::hint::black_box(&line)));
        });
        defmt::info!("insns {} line-hex-parse {}", preset, insns);
        let cmd = Command::parse(&line);
        let insns = counter.insns_per_call(n, || {
            core::hint::black_box(c.handle(core::hint::black_box(cmd.clone())));
        });
        defmt::info!("insns {} line-handle {}", preset, insns);
        let reply = c.handle(cmd.clone());
        let insns = counter.insns_per_call(n, || {
            out.clear();
            let _ = core::hint::black_box(&reply).write(&mut out);
        });
        defmt::info!("insns {} line-reply {}", preset, insns);
        // the same colour, its numbers in the hex form
        let same = match (c.handle(Command::parse(&line)), &decimal) {
            (Reply::Colour(h), Reply::Colour(d)) => {
                h.hex && !d.hex && Reply::Colour(h) != decimal && {
                    let mut h = h;
                    h.hex = false;
                    h == *d
                }
            }
            _ => false,
        };
        checks.check("hex-line-answers-as-decimal", same);
    }

    // 4. mixing 3–6 channels (xy/CCT targets solved on the device) and fade steps
    #[cfg(feature = "mixing")]
    mix(&mut checks, &mut counter);

    // 5. colours on an sRGB-curve LED, for the libm / fast-math comparison on the host
    let _ = handle(&mut c, "trc rgb srgb");
    let mut i = 0;
    for x in [0.25f32, 0.3, 0.35, 0.4, 0.45] {
        for y in [0.25f32, 0.3, 0.35, 0.4] {
            for big_y in [5.0f32, 20.0, 60.0] {
                let r = c.colour(Xyy { x, y, big_y }.to_xyz());
                defmt::info!(
                    "colour {} duty {} {} {}",
                    i,
                    r.duty[0],
                    r.duty[1],
                    r.duty[2]
                );
                i += 1;
            }
        }
    }

    defmt::info!("stack {}", stack::high_water());
    if checks.failed == 0 {
        defmt::info!("selftest: pass");
        debug::exit(debug::EXIT_SUCCESS);
    } else {
        defmt::info!("selftest: fail ({} checks)", checks.failed);
        debug::exit(debug::EXIT_FAILURE);
    }
    loop {
        cortex_m::asm::wfi();
    }
}
