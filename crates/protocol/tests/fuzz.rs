//! The protocol on arbitrary and on well-formed input: parsers never panic, every command and
//! reply survives `write → parse`, and replies stay within `MAX_REPLY`.
//!
//! The fuzzing is proptest (random bytes, random token soups built from the grammar's own
//! words, and mutations of valid lines), which runs under plain `cargo test` with no nightly
//! toolchain or cargo-fuzz.

use proptest::prelude::*;
use specpoly_core::light::channels::{Curve, Goal};
use specpoly_core::{
    DefaultSpectrum, GamutMap, Illuminant, Observer, PaperSpectrum, Transfer, Xyy, Xyz,
};
use specpoly_protocol::{
    write_reflect, write_reflect_hex, ChannelCommand, Channels, ColourReport, Command,
    CurveSummary, ErrorCode, Fault, Gamut, LineReader, MixReport, Reflectance, Reply, StateReport,
    MAX_LINE, MAX_REPLY,
};

fn line_of(c: &Command) -> String {
    let mut s = String::new();
    c.write(&mut s).unwrap();
    s
}

fn reply_of(r: &Reply) -> String {
    let mut s = String::new();
    r.write(&mut s).unwrap();
    s
}

/// Feeds bytes to a reader, collecting what it reports per line.
fn feed(bytes: &[u8]) -> Vec<Result<String, Fault>> {
    let mut r = LineReader::<MAX_LINE>::new();
    let mut out = Vec::new();
    for b in bytes {
        if let Some(l) = r.push(*b) {
            out.push(l.map(str::to_owned));
        }
    }
    out
}

const WORDS: &[&str] = &[
    "hello",
    "state",
    "cal",
    "trc",
    "map",
    "observer",
    "xyz",
    "xyy",
    "refl",
    "paper",
    "default",
    "D65",
    "FL11",
    "a",
    "*",
    "r",
    "g",
    "b",
    "rgb",
    "linear",
    "srgb",
    "gamma",
    "table",
    "clip",
    "desaturate",
    "1931",
    "1964",
    "0",
    "1",
    "-1",
    "0.5",
    "1e39",
    "nan",
    "2.2",
    "0.3127",
    "1e-45",
    "0x3f000000",
    "0x7fc00000",
    "0xffffffff",
    "0x",
    "ok",
    "err",
    "colour",
    "xyz=1,2,3",
    "duty=1,2,3",
    "max=65535",
    "gamut=in",
    "=",
    ",",
    "at=3",
    "channel",
    "curve",
    "clear",
    "xy",
    "cct",
    "duv",
    "lum",
    "fade",
    "5",
    "4000",
    "mix",
    "light=0.5,0.25,1",
    "steps=3",
];

/// A coefficient word as `core`'s `str::parse::<f32>` reads it (correctly rounded; an independent
/// reader of the same decimal grammar), with the protocol's rules around it: at most 40 bytes,
/// no `inf`/`nan` words, the compact form `0x` + 8 hexadecimal digits is an f32's bits, a value
/// beyond f32 is `out-of-range`.
fn std_reads(w: &str) -> Result<f32, ErrorCode> {
    if w.len() > 40 {
        return Err(ErrorCode::BadNumber);
    }
    if let Some(h) = w.strip_prefix("0x") {
        if h.len() != 8 || !h.bytes().all(|c| c.is_ascii_hexdigit()) {
            return Err(ErrorCode::BadNumber);
        }
        let v = f32::from_bits(u32::from_str_radix(h, 16).map_err(|_| ErrorCode::BadNumber)?);
        return if v.is_finite() {
            Ok(v)
        } else {
            Err(ErrorCode::OutOfRange)
        };
    }
    if !w
        .bytes()
        .all(|c| c.is_ascii_digit() || b"+-.eE".contains(&c))
    {
        return Err(ErrorCode::BadNumber);
    }
    match w.parse::<f32>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(ErrorCode::OutOfRange),
        Err(_) => Err(ErrorCode::BadNumber),
    }
}

/// Coefficient words: mostly what hosts send (the protocol's shortest decimals, longer ones,
/// signs, exponents, the hex form), some malformed.
fn coefficient_word() -> impl Strategy<Value = String> {
    prop_oneof![
        8 => "-?0\\.[0-9]{1,10}",
        4 => "[+-]?[0-9]{1,11}(\\.[0-9]{0,11})?",
        2 => "[+-]?[0-9]{0,22}\\.?[0-9]{0,24}([eE][+-]?[0-9]{1,3})?",
        1 => any::<u32>().prop_map(|b| format!("0x{b:08x}")),
        1 => "[0-9.eEx+*-]{1,6}",
    ]
}

fn spectrum_default(seed: f32) -> DefaultSpectrum {
    let mut s = DefaultSpectrum::ZERO;
    for k in 0..4 {
        for sp in 0..8 {
            s.coefficients_mut()[k][sp] = seed * (0.3 + 0.05 * sp as f32) / (1.0 + k as f32);
        }
    }
    s
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..3000)) {
        for line in feed(&bytes) {
            match line {
                Ok(l) => {
                    prop_assert!(l.len() <= MAX_LINE);
                    let _ = Command::parse(&l);
                    let _ = Reply::parse(&l);
                }
                Err(f) => prop_assert!(matches!(f.code, ErrorCode::TooLong | ErrorCode::BadByte)),
            }
        }
    }

    #[test]
    fn arbitrary_strings_never_panic(s in "\\PC{0,400}") {
        let _ = Command::parse(&s);
        let _ = Reply::parse(&s);
    }

    #[test]
    fn token_soup_never_panics(idx in proptest::collection::vec(0..WORDS.len(), 0..80)) {
        let line: Vec<&str> = idx.iter().map(|i| WORDS[*i]).collect();
        let line = line.join(" ");
        let _ = Command::parse(&line);
        let _ = Reply::parse(&line);
    }

    #[test]
    fn mutated_valid_lines_never_panic(cut in 0usize..400, byte in any::<u8>(), pos in 0usize..400) {
        let valid = [
            line_of(&Command::Calibrate { xy: [[0.64, 0.33], [0.3, 0.6], [0.15, 0.06]], luminance: [21.0, 72.0, 7.0] }),
            line_of(&Command::Reflect { illuminant: Illuminant::FL11, product: Reflectance::Default(spectrum_default(0.7)), factors: 1, hex: false }),
            line_of(&Command::Reflect { illuminant: Illuminant::FL11, product: Reflectance::Default(spectrum_default(0.7)), factors: 1, hex: true }),
            reply_of(&Reply::Colour(ColourReport { xyz: Xyz::new(1.0, 2.0, 3.0), led: Xyz::new(1.0, 2.0, 3.0), linear: [0.1, 0.2, 0.3], duty: [1, 2, 3], max: 65535, gamut: Gamut::In, hex: false })),
            reply_of(&Reply::Colour(ColourReport { xyz: Xyz::new(1.0, 2.0, 3.0), led: Xyz::new(1.0, 2.0, 3.0), linear: [0.1, 0.2, 0.3], duty: [1, 2, 3], max: 65535, gamut: Gamut::In, hex: true })),
        ];
        for v in valid {
            let mut b = v.into_bytes();
            let p = pos % (b.len() + 1);
            b.insert(p, byte);
            b.truncate(cut.max(1));
            if let Ok(s) = String::from_utf8(b) {
                let _ = Command::parse(&s);
                let _ = Reply::parse(&s);
            }
        }
    }

    #[test]
    fn tables_must_run_from_0_to_1(steps in proptest::collection::vec(0f32..0.5, 1..63), first in prop_oneof![Just(0f32), 0f32..0.5], last in prop_oneof![Just(1f32), 0.5f32..2.0]) {
        let mut v = vec![first];
        for s in &steps {
            v.push((v[v.len() - 1] + s).min(last));
        }
        v.push(last);
        let line = format!("trc rgb table {}", v.iter().map(|x| format!("{x:e}")).collect::<Vec<_>>().join(" "));
        let n = v.len();
        match Command::parse(&line) {
            Ok(Command::Transfer { curve: Transfer::Table(t), .. }) => {
                prop_assert!(first == 0.0 && last == 1.0, "{}", line);
                prop_assert_eq!(t.as_slice(), v.as_slice());
                // and it writes back as the same line
                let c = Command::parse(&line).unwrap();
                prop_assert_eq!(Command::parse(&line_of(&c)), Ok(c));
            }
            Err(f) => {
                prop_assert_eq!(f.code, ErrorCode::BadCurve);
                let at = if first != 0.0 { 3 } else { 2 + n };
                prop_assert!(last != 1.0 || first != 0.0, "{}: {:?}", line, f);
                prop_assert_eq!(f.at, Some(at as u16), "{}", line);
            }
            other => prop_assert!(false, "{}: {:?}", line, other),
        }
    }

    #[test]
    fn hex_refl_lines_read_as_their_decimal_twins(c in proptest::array::uniform32(any::<u32>()), n in 1usize..=4, paper in any::<bool>()) {
        // any finite coefficients: the compact form and shortest decimals name the same f32s
        let f = |i: usize| {
            let v = f32::from_bits(c[i % 32]);
            if v.is_finite() { v } else { 0.5 }
        };
        let mut d = DefaultSpectrum::ZERO;
        let mut p = PaperSpectrum::ZERO;
        for i in 0..32 {
            d.coefficients_mut()[i % 4][i / 4] = f(i);
            p.coefficients_mut()[i % 4][(i / 4) % 2] = f(i + 7);
        }
        let r = if paper { Reflectance::Paper(p) } else { Reflectance::Default(d) };
        // MAX_LINE holds two default factors (or four of the paper's) in either form
        let factors = vec![r; if paper { n } else { n.min(2) }];
        let (mut dec, mut hex) = (String::new(), String::new());
        write_reflect(&mut dec, Illuminant::D65, &factors).unwrap();
        write_reflect_hex(&mut hex, Illuminant::D65, &factors).unwrap();
        prop_assert!(hex.len() <= MAX_LINE);
        let (a, mut b) = (Command::parse(&dec), Command::parse(&hex));
        // the hex line says so (its reply's numbers are hex too); otherwise the same command
        if let Ok(Command::Reflect { hex, .. }) = &mut b {
            prop_assert!(*hex);
            *hex = false;
        }
        // accepted, or refused because the product overflows f32 (`not-finite`)
        prop_assert!(
            a.is_ok() || matches!(&a, Err(f) if f.code == ErrorCode::NotFinite),
            "{:?}",
            a
        );
        // the same either way, bit for bit (NaN products compare unequal as values)
        prop_assert_eq!(std::format!("{a:?}"), std::format!("{b:?}"));
    }

    #[test]
    fn refl_coefficients_read_as_std_parses_them(
        words in proptest::collection::vec(coefficient_word(), 8),
        seps in proptest::collection::vec(prop_oneof![Just(" "), Just("  "), Just("\t"), Just(" \r ")], 8),
    ) {
        // the firmware reads each coefficient as it finds the word (one pass over the bytes):
        // every value is std's, bit for bit, and the first word std refuses is the one named
        let mut line = String::from("refl paper D65");
        for (w, sep) in words.iter().zip(&seps) {
            line.push_str(sep);
            line.push_str(w);
        }
        let want: Result<Vec<f32>, Fault> = words
            .iter()
            .enumerate()
            .map(|(i, w)| {
                // `*` where a coefficient should be: the factor is cut short
                let r = if w == "*" { Err(ErrorCode::WrongCount) } else { std_reads(w) };
                r.map_err(|code| Fault { code, at: Some(3 + i as u16) })
            })
            .collect();
        match (Command::parse(&line), want) {
            (Ok(Command::Reflect { product: Reflectance::Paper(p), factors: 1, .. }), Ok(v)) => {
                for (i, v) in v.iter().enumerate() {
                    let got = p.coefficients()[i % 4][i / 4];
                    prop_assert_eq!(got.to_bits(), v.to_bits(), "{} in {:?}", words[i], line);
                }
            }
            (Err(f), Err(want)) => prop_assert_eq!(f, want, "{:?}", line),
            (got, want) => prop_assert!(false, "{:?}: {:?}, want {:?}", line, got, want),
        }
    }

    #[test]
    fn colour_commands_round_trip(x in -1e6f32..1e6, y in -1e6f32..1e6, z in -1e6f32..1e6) {
        let c = Command::Xyz(Xyz::new(x, y, z));
        prop_assert_eq!(Command::parse(&line_of(&c)), Ok(c));
    }

    #[test]
    fn colour_replies_round_trip(v in proptest::array::uniform9(any::<f32>()), d in proptest::array::uniform3(any::<u16>()), m in any::<u16>(), g in 0..3u8, hex in any::<bool>()) {
        prop_assume!(v.iter().all(|x| x.is_finite()));
        let r = Reply::Colour(ColourReport {
            xyz: Xyz::new(v[0], v[1], v[2]),
            led: Xyz::new(v[3], v[4], v[5]),
            linear: [v[6], v[7], v[8]],
            duty: d,
            max: m,
            gamut: [Gamut::In, Gamut::Out(GamutMap::Clip), Gamut::Out(GamutMap::Desaturate)][g as usize],
            hex,
        });
        let s = reply_of(&r);
        prop_assert!(s.len() <= MAX_REPLY, "{} bytes", s.len());
        prop_assert_eq!(Reply::parse(&s), Ok(r));
    }

    #[test]
    fn mix_replies_round_trip(v in proptest::array::uniform9(any::<f32>()), d in proptest::array::uniform6(any::<u16>()), n in 3..=6u8, m in any::<u16>(), k in any::<u16>()) {
        prop_assume!(v.iter().all(|x| x.is_finite()));
        let mut r = MixReport {
            xy: [v[0], v[1]],
            lum: v[2],
            light: [v[3], v[4], v[5], v[6], v[7], v[8]],
            duty: d,
            n,
            max: m,
            steps: k,
        };
        for i in n as usize..6 {
            r.light[i] = 0.0;
            r.duty[i] = 0;
        }
        let r = Reply::Mix(r);
        let s = reply_of(&r);
        prop_assert!(s.len() <= MAX_REPLY, "{} bytes", s.len());
        prop_assert_eq!(Reply::parse(&s), Ok(r));
    }

    #[test]
    fn state_replies_round_trip(v in proptest::array::uniform9(any::<f32>()), gm in any::<f32>()) {
        prop_assume!(v.iter().all(|x| x.is_finite()) && gm.is_finite());
        let r = Reply::State(StateReport {
            protocol: 1,
            primaries: [[v[0], v[1], v[2]], [v[3], v[4], v[5]], [v[6], v[7], v[8]]],
            trc: [CurveSummary::Gamma(gm), CurveSummary::Table(64), CurveSummary::Srgb],
            map: GamutMap::Desaturate,
            observer: Observer::Cie1964,
            lut: 17,
            duty: [65535; 3],
            max: 65535,
        });
        let s = reply_of(&r);
        prop_assert!(s.len() <= MAX_REPLY, "{} bytes", s.len());
        prop_assert_eq!(Reply::parse(&s), Ok(r));
    }
}

#[test]
fn every_command_round_trips() {
    let table = Transfer::table(&[0.0, 0.01, 0.2, 0.55, 1.0]).unwrap();
    let commands = [
        Command::Hello,
        Command::State,
        Command::Save,
        Command::Load,
        Command::Calibrate {
            xy: [[0.7, 0.29], [0.17, 0.7], [0.135, 0.04]],
            luminance: [2.5, 7.25, 1.0],
        },
        Command::Transfer {
            channels: Channels::All,
            curve: Transfer::Srgb,
        },
        Command::Transfer {
            channels: Channels::Green,
            curve: Transfer::Gamma(2.2),
        },
        Command::Transfer {
            channels: Channels::Blue,
            curve: table,
        },
        Command::Map(GamutMap::Desaturate),
        Command::Observer(Observer::Cie1964),
        Command::Xyz(Xyz::new(41.24, 21.26, 1.93)),
        Command::Xyy(Xyy {
            x: 0.3127,
            y: 0.329,
            big_y: 50.0,
        }),
        Command::Reflect {
            illuminant: Illuminant::D65,
            product: Reflectance::Paper(PaperSpectrum::constant(0.5)),
            factors: 1,
            hex: false,
        },
        Command::Reflect {
            illuminant: Illuminant::FL2,
            product: Reflectance::Paper(PaperSpectrum::constant(0.25)),
            factors: 1,
            hex: true,
        },
        Command::Reflect {
            illuminant: Illuminant::A,
            product: Reflectance::Default(spectrum_default(-0.3)),
            factors: 1,
            hex: false,
        },
        Command::Channel(ChannelCommand::Set {
            index: 5,
            xyz: [0.95, 1.0, 0.85],
            cost: 0.003,
        }),
        Command::Channel(ChannelCommand::Curve {
            index: 0,
            curve: Curve::Gamma(2.2),
        }),
        Command::Channel(ChannelCommand::Clear),
        Command::Mix(Goal::Xy {
            xy: [0.3127, 0.329],
            lum: 0.5,
        }),
        Command::Mix(Goal::Cct {
            cct: 4000.0,
            duv: -0.006,
            lum: 1.0,
        }),
        Command::Fade(600_000),
    ];
    for c in commands {
        let l = line_of(&c);
        assert!(l.len() <= MAX_LINE);
        assert_eq!(Command::parse(&l), Ok(c), "{l}");
    }
}

#[test]
fn products_are_folded_with_the_reduced_product() {
    let a = spectrum_default(0.9);
    let b = spectrum_default(0.4);
    let c = spectrum_default(-0.2);
    let factors = [
        Reflectance::Default(a),
        Reflectance::Default(b),
        Reflectance::Default(c),
    ];
    let mut line = String::new();
    write_reflect(&mut line, Illuminant::FL2, &factors).unwrap();
    assert!(line.len() <= MAX_LINE, "{}", line.len());
    match Command::parse(&line) {
        Ok(Command::Reflect {
            illuminant,
            product: Reflectance::Default(p),
            factors,
            ..
        }) => {
            assert_eq!(illuminant, Illuminant::FL2);
            assert_eq!(factors, 3);
            assert_eq!(p, a.mul(&b).mul(&c));
        }
        other => panic!("{other:?}"),
    }
    // mixed presets cannot be written
    let mixed = [
        Reflectance::Default(a),
        Reflectance::Paper(PaperSpectrum::constant(1.0)),
    ];
    assert!(write_reflect(&mut String::new(), Illuminant::D65, &mixed).is_err());
}

#[test]
fn bad_lines_name_the_word_at_fault() {
    let cases: &[(&str, ErrorCode, Option<u16>)] = &[
        ("", ErrorCode::UnknownCommand, Some(0)),
        ("blink", ErrorCode::UnknownCommand, Some(0)),
        ("xyz 1 2", ErrorCode::MissingArgument, Some(3)),
        ("xyz 1 2 3 4", ErrorCode::ExtraArgument, Some(4)),
        ("save now", ErrorCode::ExtraArgument, Some(1)),
        ("load 1", ErrorCode::ExtraArgument, Some(1)),
        ("xyz 1 two 3", ErrorCode::BadNumber, Some(2)),
        ("xyz 1 2 1e40", ErrorCode::OutOfRange, Some(3)),
        ("xyy 0.3 0 10", ErrorCode::OutOfRange, Some(2)),
        ("map vivid", ErrorCode::UnknownName, Some(1)),
        ("observer 2000", ErrorCode::UnknownName, Some(1)),
        ("trc x srgb", ErrorCode::UnknownName, Some(1)),
        ("trc r gamma 0", ErrorCode::OutOfRange, Some(3)),
        ("trc r table 0 0.5 0.4", ErrorCode::BadCurve, Some(2)),
        ("trc r table 0", ErrorCode::BadCurve, Some(2)),
        ("trc r table 0.1 0.5 1", ErrorCode::BadCurve, Some(3)),
        ("trc g table 0 0.5 0.9", ErrorCode::BadCurve, Some(5)),
        ("trc b table 0 1.5", ErrorCode::BadCurve, Some(4)),
        ("trc b table 1 1", ErrorCode::BadCurve, Some(3)),
        ("refl paper D99 1 2", ErrorCode::UnknownName, Some(2)),
        ("refl rgb D65 1", ErrorCode::UnknownName, Some(1)),
        ("refl paper D65 1 2 3", ErrorCode::WrongCount, Some(6)),
        (
            "refl paper D65 1 2 3 4 5 6 7 8 9",
            ErrorCode::WrongCount,
            Some(11),
        ),
        (
            "refl paper D65 1 2 3 4 5 6 7 8 *",
            ErrorCode::WrongCount,
            Some(12),
        ),
        (
            "refl paper D65 1 2 3 * 5 6 7 8",
            ErrorCode::WrongCount,
            Some(6),
        ),
        (
            "cal 0.64 0.33 1 0.3 0.6 1 0.15 0.06",
            ErrorCode::MissingArgument,
            Some(9),
        ),
        (
            "cal 0.64 0.33 -1 0.3 0.6 1 0.15 0.06 1",
            ErrorCode::OutOfRange,
            Some(3),
        ),
    ];
    for (line, code, at) in cases {
        assert_eq!(
            Command::parse(line),
            Err(Fault {
                code: *code,
                at: *at
            }),
            "{line:?}"
        );
    }
    // more than MAX_FACTORS factors
    let one = "0.5 0 0 0 0.5 0 0 0";
    let five = [one; 5].join(" * ");
    assert_eq!(
        Command::parse(&format!("refl paper D65 {five}")).map_err(|f| f.code),
        Err(ErrorCode::WrongCount)
    );
}

#[test]
fn the_line_reader_bounds_and_reports() {
    let mut bytes = vec![b'x'; MAX_LINE + 10];
    bytes.extend_from_slice(b"\nstate\r\nxy\x00z\nhello\n\n");
    let got = feed(&bytes);
    assert_eq!(
        got,
        vec![
            Err(Fault::new(ErrorCode::TooLong)),
            Ok("state".to_owned()),
            Err(Fault::new(ErrorCode::BadByte)),
            Ok("hello".to_owned()),
            Ok(String::new()),
        ]
    );
    // exactly MAX_LINE bytes is accepted
    let mut exact = vec![b' '; MAX_LINE];
    exact.push(b'\n');
    assert_eq!(feed(&exact), vec![Ok(" ".repeat(MAX_LINE))]);
}

#[test]
fn replies_parse_and_reject() {
    assert_eq!(
        Reply::parse("ok hello specpoly-led protocol=1 max_line=1024 max=65535 future=1"),
        Ok(Reply::Hello {
            protocol: 1,
            max_line: 1024,
            max: 65535
        })
    );
    assert_eq!(Reply::parse("ok cal"), Ok(Reply::Done("cal")));
    assert_eq!(Reply::parse("ok save"), Ok(Reply::Done("save")));
    assert_eq!(
        Reply::parse("err not-saved"),
        Ok(Reply::Error(Fault::new(ErrorCode::NotSaved)))
    );
    assert_eq!(
        Reply::parse("err bad-number at=2"),
        Ok(Reply::Error(Fault {
            code: ErrorCode::BadNumber,
            at: Some(2)
        }))
    );
    for bad in [
        "",
        "ok",
        "ok colour xyz=1,2",
        "ok colour xyz=1,2,3 led=1,2,3 linear=0,0,0 duty=1,2,3 max=9 gamut=maybe",
        "ok hello other-device protocol=1 max_line=1 max=1",
        "err no-such-code",
        "garbage",
    ] {
        assert_eq!(
            Reply::parse(bad),
            Err(Fault::new(ErrorCode::BadReply)),
            "{bad:?}"
        );
    }
}

/// Finite factors whose reduced product overflows f32 are refused (`not-finite`), so every
/// accepted `refl` writes back as numbers (found by `crates/cli/tests/fuzz_corpora.rs`).
#[test]
fn an_overflowing_product_is_not_finite() {
    let line = "refl paper A 0.5 0 3.4e38 0 0.5 0 0 0 * 0.9 0 0 0 0.9 0 0 0";
    assert_eq!(
        Command::parse(line).map_err(|f| f.code),
        Err(ErrorCode::NotFinite)
    );
    // The same factors at a tenth of the size are a product that is accepted.
    let fine = "refl paper A 0.5 0 3.4e37 0 0.5 0 0 0 * 0.9 0 0 0 0.9 0 0 0";
    assert!(Command::parse(fine).is_ok());
}
