//! The controller: protocol commands in, replies and duties out, on the same core as the host.
//!
//! State: the LED's calibration (Cowan's model: primaries' chromaticities and luminances,
//! per-channel transfer curves), the gamut map, the observer and the last target colour. The
//! lights' moments are compiled in ([`crate::lights`]). A colour goes
//!
//! `reflectance(s) ─mul─▶ product ─· moments(observer, illuminant)─▶ XYZ ─Display─▶ duties`
//!
//! with XYZ relative to a white of `Y = 100` (the light's perfect reflector, or the LED's full
//! white for `xyz`/`xyy`), scaled to the LED's white luminance ([`Display::encode_relative`]).
//! No chromatic adaptation: under illuminant A a white paper is shown as A's colour.
//! Out-of-gamut targets are mapped with [`GamutMap`] and the reply says so.

use core::mem::MaybeUninit;

use crate::{
    lights,
    settings::{self, Record},
};
use specpoly_core::{
    display::{D65_XY, SRGB_PRIMARIES},
    Display, GamutMap, Illuminant, Observer, Transfer, Xyz,
};
#[cfg(feature = "mixing")]
use specpoly_protocol::{mix, DeviceMixer, MIX_CHANNELS};
use specpoly_protocol::{
    ColourReport, Command, CurveSummary, ErrorCode, Fault, Reflectance, Reply, StateReport,
    PROTOCOL_VERSION,
};

/// Parses a line (the protocol's [`Command::parse`]) in a frame of its own: its work space
/// (a 64-point table, the factors of a product) is gone before the command runs.
#[inline(never)]
pub fn parse(line: &str) -> Result<Command, Fault> {
    Command::parse(line)
}

pub use specpoly_protocol::target::{check_target, MAX_TARGET, NEGATIVE_TOLERANCE};

/// The LED colour controller.
pub struct Controller {
    xy: [[f32; 2]; 3],
    luminance: [f32; 3],
    display: Display,
    map: GamutMap,
    observer: Observer,
    target: Xyz,
    duty: [u16; 3],
    max: u16,
    /// The multi-channel mixer (`channel`, `xy`, `cct`, `fade`: [`crate::mix`]; feature
    /// `mixing`).
    #[cfg(feature = "mixing")]
    pub mixer: DeviceMixer,
    /// The drive-correction table in flash ([`crate::lut`]).
    #[cfg(feature = "lut")]
    pub lut: crate::lut::Lut,
}

impl Controller {
    /// A controller for PWM channels of full-scale duty `max`, calibrated by default as an
    /// ideal linear LED with the Rec. 709 primaries and a D65 white (`Y` shares 0.2126, 0.7152,
    /// 0.0722), clipping, CIE 1931 observer, off.
    pub fn new(max: u16) -> Self {
        // sRGB's matrices (Rec. 709 primaries, D65 white) with linear curves
        let display = match Display::from_primaries_white(SRGB_PRIMARIES, D65_XY, 1.0, linear()) {
            Ok(d) => d,
            // constant, valid primaries (as `Display::srgb`, unit-tested in the core)
            Err(_) => unreachable!("sRGB primaries are valid"),
        };
        let (_, luminance) = display.primaries();
        Self {
            xy: SRGB_PRIMARIES,
            luminance,
            display,
            map: GamutMap::Clip,
            observer: Observer::Cie1931,
            target: Xyz::default(),
            duty: [0; 3],
            max,
            #[cfg(feature = "mixing")]
            mixer: DeviceMixer::new(),
            #[cfg(feature = "lut")]
            lut: crate::lut::Lut::new(),
        }
    }

    /// The table's flash region ([`crate::lut`]); the table stored there applies when it was
    /// made for the current calibration.
    #[cfg(feature = "lut")]
    pub fn attach_lut(&mut self, region: &'static mut dyn crate::lut::Region) {
        self.lut.attach(region);
        self.refresh_lut();
    }

    /// Whether the stored table applies to the current calibration (after `cal`, `trc`, a
    /// loaded record, an upload).
    fn refresh_lut(&mut self) {
        #[cfg(feature = "lut")]
        {
            let key = self.calibration_key();
            self.lut.refresh(key);
        }
    }

    /// The key of the current primaries and curves
    /// ([`specpoly_core::drive_table::calibration_key`]).
    #[cfg(feature = "lut")]
    fn calibration_key(&self) -> u32 {
        specpoly_core::drive_table::calibration_key(
            self.xy,
            self.luminance,
            self.display.transfer(),
        )
    }

    /// The drive step for `target`: the core's matrix-model step, corrected by the table
    /// when one applies ([`specpoly_core::drive_table::corrected`]). Without a table the
    /// kernel's result is returned as it is made (no copy, no frame for the correction: 70
    /// instructions of a colour's ≈ 1 500 on the Cortex-M4).
    fn drive(&mut self, target: Xyz) -> specpoly_core::Drive {
        #[cfg(feature = "lut")]
        if self.lut.applied() > 0 {
            return self.drive_corrected(target);
        }
        specpoly_kernels::drive(&self.display, target, self.map, self.max)
    }

    /// [`Self::drive`] when a table applies.
    #[cfg(feature = "lut")]
    #[inline(never)]
    fn drive_corrected(&mut self, target: Xyz) -> specpoly_core::Drive {
        let plain = specpoly_kernels::drive(&self.display, target, self.map, self.max);
        match self.lut.nodes() {
            Some(mut nodes) => specpoly_core::drive_table::corrected(&mut nodes, plain, self.max),
            None => plain,
        }
    }

    /// [`Controller::new`] into `slot` (a static): built in a frame of its own, which is gone
    /// when the caller goes on, so the caller's frame never holds a controller.
    #[inline(never)]
    pub fn init(slot: &mut MaybeUninit<Controller>, max: u16) -> &mut Controller {
        slot.write(Self::new(max))
    }

    /// The duties the LED should show now.
    pub fn duty(&self) -> [u16; 3] {
        self.duty
    }

    /// The full-scale duty.
    pub fn max(&self) -> u16 {
        self.max
    }

    /// One fade step of the mixer (the next point solved): `(step, steps, duties)`, or `None`
    /// when no fade is under way ([`crate::fade`]).
    #[cfg(feature = "mixing")]
    pub fn fade_step(&mut self) -> Option<(u16, u16, [u16; MIX_CHANNELS])> {
        self.mixer.step(self.max)
    }

    /// The mixed channels' duties shown now (solved again: not kept in RAM).
    #[cfg(feature = "mixing")]
    pub fn mix_duty(&self) -> [u16; MIX_CHANNELS] {
        self.mixer.duty(self.max)
    }

    /// The calibrated display model.
    pub fn display(&self) -> &Display {
        &self.display
    }

    /// Handles one parsed line (or its parse fault) and returns the reply. Not inlined: its
    /// temporaries are not wanted in the frames of callers that go deeper (`store::handle`).
    #[inline(never)]
    pub fn handle(&mut self, parsed: Result<Command, Fault>) -> Reply {
        let cmd = match parsed {
            Ok(c) => c,
            Err(f) => return Reply::Error(f),
        };
        match cmd {
            Command::Hello => Reply::hello(self.max),
            Command::State => Reply::State(self.state()),
            // new matrices in place (no second display copying three 64-point curves)
            Command::Calibrate { xy, luminance } => match self.display.set_primaries(xy, luminance)
            {
                Ok(()) => {
                    self.xy = xy;
                    self.luminance = luminance;
                    self.refresh_lut();
                    self.colour(self.target);
                    Reply::Done("cal")
                }
                Err(_) => Reply::Error(Fault::new(ErrorCode::Singular)),
            },
            Command::Transfer { channels, curve } => {
                // the curves are independent of the matrices: set in place
                for (i, c) in self.display.transfer_mut().iter_mut().enumerate() {
                    if channels.includes(i) {
                        *c = curve.clone();
                    }
                }
                self.refresh_lut();
                self.colour(self.target);
                Reply::Done("trc")
            }
            Command::Map(m) => {
                self.map = m;
                self.colour(self.target);
                Reply::Done("map")
            }
            Command::Observer(o) if lights::has_observer(o) => {
                self.observer = o;
                Reply::Done("observer")
            }
            // not built in (feature `observer-1964`)
            Command::Observer(_) => Reply::Error(Fault::at(ErrorCode::UnknownName, 1)),
            Command::Xyz(v) => self.show(v, false),
            Command::Xyy(v) => self.show(v.to_xyz(), false),
            Command::Reflect {
                illuminant,
                product,
                hex,
                ..
            } => {
                let xyz = self.reflectance_xyz(illuminant, &product);
                self.show(xyz, hex)
            }
            // answered with the flash by `store::handle`; a controller alone has no storage
            Command::Save | Command::Load => Reply::Error(Fault::new(ErrorCode::Storage)),
            // the shared answer of the mixing commands (the host's simulated controller too)
            #[cfg(feature = "mixing")]
            Command::Channel(_) | Command::Mix(_) | Command::Fade(_) => {
                mix::answer(&mut self.mixer, &cmd, self.max)
                    .unwrap_or(Reply::Error(Fault::new(ErrorCode::UnknownCommand)))
            }
            // not built in (the parser without `mix` never makes them)
            #[cfg(not(feature = "mixing"))]
            Command::Channel(_) | Command::Mix(_) | Command::Fade(_) => {
                Reply::Error(Fault::new(ErrorCode::UnknownCommand))
            }
            #[cfg(feature = "lut")]
            Command::Lut(c) => {
                let key = self.calibration_key();
                let reply = self.lut.command(&c, key);
                self.colour(self.target);
                reply
            }
            // built without the table (feature `lut`)
            #[cfg(not(feature = "lut"))]
            Command::Lut(_) => Reply::Error(Fault::at(ErrorCode::UnknownCommand, 0)),
        }
    }

    /// The settings `save` keeps (calibration, curves, gamut map, observer), borrowed.
    pub fn record(&self) -> Record<'_> {
        Record {
            xy: self.xy,
            luminance: self.luminance,
            trc: self.display.transfer(),
            map: self.map,
            observer: self.observer,
        }
    }

    /// Applies a saved record ([`settings::read`]) and re-drives the last colour; refuses
    /// (and changes nothing) a record that does not read, primaries that span no colour space,
    /// or an observer this build lacks. The record is checked whole first, then the primaries
    /// are set and the curves read straight into the display (no copy of the curves).
    pub fn apply_record(&mut self, bytes: &[u8]) -> Result<(), ErrorCode> {
        let h = settings::read(bytes, None).map_err(|_| ErrorCode::NotSaved)?;
        if !lights::has_observer(h.observer) {
            return Err(ErrorCode::UnknownName);
        }
        self.display
            .set_primaries(h.xy, h.luminance)
            .map_err(|_| ErrorCode::Singular)?;
        // checked above: reads again without error
        let _ = settings::read(bytes, Some(self.display.transfer_mut()));
        self.xy = h.xy;
        self.luminance = h.luminance;
        self.map = h.map;
        self.observer = h.observer;
        self.refresh_lut();
        self.colour(self.target);
        Ok(())
    }

    /// XYZ (perfect white `Y = 100`) of a reflectance under a built-in light, with the current
    /// observer: three dot products against the light's moments ([`crate::lights`]).
    pub fn reflectance_xyz(&self, illuminant: Illuminant, r: &Reflectance) -> Xyz {
        let o = self.observer;
        r.xyz(lights::paper(o, illuminant), lights::default(o, illuminant))
    }

    /// Shows `target` (white `Y = 100`): the core's drive step ([`Display::drive`]: gamut
    /// mapping, transfer curves, quantisation, and the XYZ the LED then emits at those duties),
    /// corrected by the drive table when one applies ([`crate::lut`]).
    pub fn colour(&mut self, target: Xyz) -> ColourReport {
        let drive = self.drive(target);
        self.target = target;
        self.duty = drive.level;
        ColourReport::of(target, &drive, self.map, self.max)
    }

    /// The reply to a colour command: the colour report, or an error (and nothing changes:
    /// target and duties stay): `err out-of-range` for a target that is no colour
    /// ([`check_target`]: a negative or absurdly large X, Y or Z), `err not-finite` when any
    /// number of the target or the report would not be a finite f32 (e.g.
    /// `xyy 0.5 1e-45 3.4e38`, whose X and Z overflow). The one place where colour replies are
    /// made, so no `ok` reply carries `nan` or `inf`. `hex`: the numbers in the compact form (a
    /// `refl` line written in it).
    fn show(&mut self, target: Xyz, hex: bool) -> Reply {
        if let Err(code) = check_target(target) {
            return Reply::Error(Fault::new(code));
        }
        let drive = self.drive(target);
        let report = ColourReport {
            hex,
            ..ColourReport::of(target, &drive, self.map, self.max)
        };
        if !report.is_finite() {
            return Reply::Error(Fault::new(ErrorCode::NotFinite));
        }
        self.target = target;
        self.duty = drive.level;
        Reply::Colour(report)
    }

    fn state(&self) -> StateReport {
        let mut primaries = [[0.0; 3]; 3];
        for i in 0..3 {
            primaries[i] = [self.xy[i][0], self.xy[i][1], self.luminance[i]];
        }
        let t = self.display.transfer();
        StateReport {
            protocol: PROTOCOL_VERSION,
            primaries,
            trc: [
                CurveSummary::of(&t[0]),
                CurveSummary::of(&t[1]),
                CurveSummary::of(&t[2]),
            ],
            map: self.map,
            observer: self.observer,
            #[cfg(feature = "lut")]
            lut: self.lut.applied(),
            #[cfg(not(feature = "lut"))]
            lut: 0,
            duty: self.duty,
            max: self.max,
        }
    }
}

/// Three linear curves.
fn linear() -> [Transfer; 3] {
    [Transfer::Linear, Transfer::Linear, Transfer::Linear]
}

#[cfg(test)]
mod tests {
    use super::*;
    use specpoly_core::{DefaultSpectrum, Xyy};
    use specpoly_protocol::Gamut;

    fn run(c: &mut Controller, line: &str) -> Reply {
        c.handle(Command::parse(line))
    }

    #[test]
    fn the_default_led_shows_its_white_at_full_duty() {
        let mut c = Controller::new(65535);
        let w = c.display().white();
        let line = format!("xyz {} 100 {}", w.x * 100.0 / w.y, w.z * 100.0 / w.y);
        match run(&mut c, &line) {
            Reply::Colour(r) => {
                assert_eq!(r.gamut, Gamut::In);
                assert!(r.duty.iter().all(|d| *d >= 65534), "{:?}", r.duty);
                assert!((r.led.y - 100.0).abs() < 0.01);
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn in_gamut_colours_are_emitted_within_quantisation() {
        let mut c = Controller::new(65535);
        for (x, y, big_y) in [(0.3127, 0.329, 50.0), (0.4, 0.4, 30.0), (0.25, 0.3, 10.0)] {
            let t = Xyy { x, y, big_y }.to_xyz();
            let r = c.colour(t);
            assert_eq!(r.gamut, Gamut::In);
            for (a, b) in r.led.to_array().iter().zip(t.to_array()) {
                assert!((a - b).abs() < 0.01, "{:?} vs {t:?}", r.led);
            }
        }
    }

    #[test]
    fn out_of_gamut_targets_are_mapped_and_reported() {
        let mut c = Controller::new(255);
        match run(&mut c, "xyy 0.08 0.85 50") {
            Reply::Colour(r) => {
                assert_eq!(r.gamut, Gamut::Out(GamutMap::Clip));
                assert!(r.linear.iter().all(|v| (0.0..=1.0).contains(v)));
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(run(&mut c, "map desaturate"), Reply::Done("map"));
        match run(&mut c, "xyy 0.08 0.85 50") {
            Reply::Colour(r) => assert_eq!(r.gamut, Gamut::Out(GamutMap::Desaturate)),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn a_perfect_reflector_is_the_lights_white() {
        let mut c = Controller::new(65535);
        let one = DefaultSpectrum::constant(1.0);
        let xyz = c.reflectance_xyz(Illuminant::D65, &Reflectance::Default(one));
        // D65 under the 1931 observer: (95.04, 100, 108.88)
        assert!((xyz.x - 95.04).abs() < 0.05 && (xyz.y - 100.0).abs() < 1e-3);
        assert!((xyz.z - 108.88).abs() < 0.05, "{xyz:?}");
        let mut line = String::from("refl paper A");
        for i in 0..8 {
            line.push_str(if i % 4 == 0 { " 0.5" } else { " 0" });
        }
        line.push_str(" *");
        for i in 0..8 {
            line.push_str(if i % 4 == 0 { " 0.5" } else { " 0" });
        }
        match run(&mut c, &line) {
            // 0.5 · 0.5 = 0.25 of A's white
            Reply::Colour(r) => assert!((r.xyz.y - 25.0).abs() < 1e-3, "{r:?}"),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn settings_apply_to_another_controller() {
        let mut a = Controller::new(1000);
        for l in [
            "cal 0.7 0.29 2 0.17 0.7 7 0.135 0.04 1",
            "trc g gamma 2.2",
            "map desaturate",
        ] {
            assert!(matches!(run(&mut a, l), Reply::Done(_)), "{l}");
        }
        let mut buf = [0u8; crate::settings::RECORD_MAX];
        let n = a.record().encode(&mut buf).unwrap();
        let mut b = Controller::new(1000);
        run(&mut b, "xyz 20 20 20");
        b.apply_record(&buf[..n]).unwrap();
        run(&mut a, "xyz 20 20 20");
        assert_eq!(a.duty(), b.duty(), "re-driven with the loaded calibration");
        assert_eq!(run(&mut a, "state"), run(&mut b, "state"));
        let mut bad = a.record();
        bad.xy = [[0.3, 0.3]; 3];
        let n = bad.encode(&mut buf).unwrap();
        assert_eq!(b.apply_record(&buf[..n]), Err(ErrorCode::Singular));
        assert_eq!(b.apply_record(&buf[..n - 1]), Err(ErrorCode::NotSaved));
        assert_eq!(run(&mut a, "state"), run(&mut b, "state"), "unchanged");
        assert_eq!(
            run(&mut b, "save"),
            Reply::Error(Fault::new(ErrorCode::Storage))
        );
    }

    #[test]
    fn calibration_and_curves_change_the_duties() {
        let mut c = Controller::new(1000);
        run(&mut c, "xyz 20 20 20");
        let linear = c.duty();
        assert_eq!(run(&mut c, "trc rgb gamma 2.2"), Reply::Done("trc"));
        let gamma = c.duty();
        assert!(gamma.iter().zip(linear).all(|(g, l)| *g > l));
        assert_eq!(
            run(&mut c, "cal 0.3 0.3 1 0.3 0.3 1 0.3 0.3 1"),
            Reply::Error(Fault::new(ErrorCode::Singular))
        );
        assert_eq!(
            run(&mut c, "cal 0.7 0.29 2 0.17 0.7 7 0.135 0.04 1"),
            Reply::Done("cal")
        );
        match run(&mut c, "state") {
            Reply::State(s) => {
                assert_eq!(s.primaries[1], [0.17, 0.7, 7.0]);
                assert_eq!(s.trc, [CurveSummary::Gamma(2.2); 3]);
                assert_eq!(s.duty, c.duty());
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(
            run(&mut c, "bogus"),
            Reply::Error(Fault::at(ErrorCode::UnknownCommand, 0))
        );
    }

    /// A small xorshift generator: the firmware tests have no proptest.
    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }
        fn unit(&mut self) -> f32 {
            (self.next() >> 40) as f32 / (1u64 << 24) as f32
        }
        /// Any f32 magnitude from 1e-45 to 3.4e38 (log-uniform), either sign, or 0.
        fn wide(&mut self) -> f32 {
            match self.next() % 8 {
                0 => 0.0,
                1 => f32::MAX,
                2 => 1e-45,
                _ => {
                    let v = 10f32.powf(self.unit() * 83.5 - 45.0).min(f32::MAX);
                    if self.next() % 2 == 0 {
                        v
                    } else {
                        -v
                    }
                }
            }
        }
        /// In `(0, 1]`, sometimes tiny.
        fn positive_unit(&mut self) -> f32 {
            match self.next() % 4 {
                0 => 1e-45,
                1 => 1.0,
                _ => self.unit().max(1e-45),
            }
        }
    }

    /// A random command within the documented ranges (the parser accepts it).
    fn random_command(g: &mut Rng) -> String {
        match g.next() % 8 {
            0 | 1 => format!("xyz {:e} {:e} {:e}", g.wide(), g.wide(), g.wide()),
            2 | 3 => format!("xyy {:e} {:e} {:e}", g.unit(), g.positive_unit(), g.wide()),
            4 => {
                let n = if g.next() % 2 == 0 { 8 } else { 32 };
                let preset = if n == 8 { "paper" } else { "default" };
                let mut l = format!("refl {preset} D65");
                for _ in 0..n {
                    l.push_str(&format!(" {:e}", g.wide()));
                }
                l
            }
            5 => {
                let mut l = String::from("cal");
                for _ in 0..3 {
                    l.push_str(&format!(
                        " {:e} {:e} {:e}",
                        g.unit(),
                        g.positive_unit(),
                        g.wide().abs().max(1e-45)
                    ));
                }
                l
            }
            6 => format!("trc rgb gamma {:e}", 0.1 + 9.9 * g.unit()),
            _ => String::from(if g.next() % 2 == 0 {
                "map clip"
            } else {
                "map desaturate"
            }),
        }
    }

    #[test]
    fn every_ok_reply_reads_back_with_finite_numbers() {
        let mut c = Controller::new(65535);
        let mut g = Rng(0x9e37_79b9_7f4a_7c15);
        let mut lines = vec![String::from("xyy 0.5 1e-45 3.4e38")];
        lines.extend((0..20_000).map(|_| random_command(&mut g)));
        let mut refused = 0;
        for line in &lines {
            let parsed = Command::parse(line);
            assert!(parsed.is_ok(), "{line}: {parsed:?}");
            let reply = c.handle(parsed);
            let mut text = String::new();
            reply.write(&mut text).unwrap();
            if let Reply::Colour(r) = reply {
                assert!(r.is_finite(), "{line} → {text}");
            }
            if text.starts_with("ok") {
                assert!(
                    !text.contains("nan") && !text.contains("inf"),
                    "{line} → {text}"
                );
                assert_eq!(Reply::parse(&text), Ok(reply), "{line} → {text}");
            } else {
                assert!(
                    reply == Reply::Error(Fault::new(ErrorCode::NotFinite))
                        || reply == Reply::Error(Fault::new(ErrorCode::OutOfRange))
                        || reply == Reply::Error(Fault::new(ErrorCode::Singular)),
                    "{line} → {text}"
                );
                refused += usize::from(text == "err not-finite");
            }
        }
        assert!(refused > 0, "the extremes overflow somewhere");
    }

    #[test]
    fn a_colour_no_light_can_have_is_refused_never_amplified() {
        let mut c = Controller::new(65535);
        assert_eq!(run(&mut c, "map desaturate"), Reply::Done("map"));
        run(&mut c, "xyz 20 20 20");
        let duty = c.duty();
        let refused = Reply::Error(Fault::new(ErrorCode::OutOfRange));
        for line in [
            "xyz -1e30 1 1",
            "xyz -1 1 1",
            "xyz 1 -0.5 1",
            "xyz 0 -5 0",
            "xyz 50 50 -3",
            "xyz 1e30 1 1",
            "xyz 1 1 1e30",
            "xyz 1e6 1e6 1e6",
            "xyy 0.3 0.3 1e5",
        ] {
            assert_eq!(run(&mut c, line), refused, "{line}");
            assert_eq!(c.duty(), duty, "{line} changed the duties");
        }
        // colours, also out of gamut and at the limits, are shown; never brighter than asked
        // (desaturation keeps the luminance, clipped at the LED's white Y = 100)
        for line in [
            "xyz -0.0005 50 50",
            "xyz 1e-30 1 1",
            "xyz 9999 1 1",
            "xyz 1 1 9999",
            "xyz 1e4 1e4 1e4",
            "xyy 0.9 0.05 1",
            "xyy 0.08 0.85 50",
        ] {
            match run(&mut c, line) {
                Reply::Colour(r) => {
                    assert!(r.led.y <= r.xyz.y.min(100.0) + 0.01, "{line}: {r:?}")
                }
                other => panic!("{line}: {other:?}"),
            }
        }
        // a sweep of chromaticities far outside any gamut, at several luminances
        for k in 0..400 {
            let x = 10f32.powf(-6.0 + (k % 20) as f32 * 0.5);
            let z = 10f32.powf(-6.0 + (k / 20) as f32 * 0.5);
            for y in [0.0f32, 1.0, 30.0, 100.0, 5000.0] {
                match run(&mut c, &format!("xyz {x:e} {y:e} {z:e}")) {
                    Reply::Colour(r) => assert!(
                        r.led.y <= y.min(100.0) + 0.01,
                        "xyz {x:e} {y:e} {z:e}: {r:?}"
                    ),
                    // X or Z beyond MAX_TARGET
                    Reply::Error(f) => {
                        assert_eq!(f, Fault::new(ErrorCode::OutOfRange));
                        assert!(x > MAX_TARGET || z > MAX_TARGET, "{x} {y} {z}");
                    }
                    other => panic!("{other:?}"),
                }
            }
        }
    }

    #[test]
    fn an_overflowing_colour_is_refused_and_changes_nothing() {
        let mut c = Controller::new(65535);
        run(&mut c, "xyz 20 20 20");
        let duty = c.duty();
        assert_eq!(
            run(&mut c, "xyy 0.5 1e-45 3.4e38"),
            Reply::Error(Fault::new(ErrorCode::NotFinite))
        );
        assert_eq!(c.duty(), duty);
        assert_eq!(
            Reply::parse("err not-finite"),
            Ok(Reply::Error(Fault::new(ErrorCode::NotFinite)))
        );
    }
}
