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

use crate::lights;
use specpoly_core::{
    display::SRGB_PRIMARIES, Display, GamutMap, Illuminant, Observer, Transfer, Xyz,
};
use specpoly_protocol::{
    ColourReport, Command, CurveSummary, ErrorCode, Fault, Reflectance, Reply, StateReport,
    PROTOCOL_VERSION,
};

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
}

impl Controller {
    /// A controller for PWM channels of full-scale duty `max`, calibrated by default as an
    /// ideal linear LED with the Rec. 709 primaries and a D65 white (`Y` shares 0.2126, 0.7152,
    /// 0.0722), clipping, CIE 1931 observer, off.
    pub fn new(max: u16) -> Self {
        let srgb = Display::srgb();
        let (_, luminance) = srgb.primaries();
        let xy = SRGB_PRIMARIES;
        let t = [Transfer::Linear, Transfer::Linear, Transfer::Linear];
        let display = match Display::from_primaries(xy, luminance, Xyz::default(), t) {
            Ok(d) => d,
            // sRGB's primaries are valid (the core's unit tests)
            Err(_) => srgb,
        };
        Self {
            xy,
            luminance,
            display,
            map: GamutMap::Clip,
            observer: Observer::Cie1931,
            target: Xyz::default(),
            duty: [0; 3],
            max,
        }
    }

    /// The duties the LED should show now.
    pub fn duty(&self) -> [u16; 3] {
        self.duty
    }

    /// The calibrated display model.
    pub fn display(&self) -> &Display {
        &self.display
    }

    /// Handles one parsed line (or its parse fault) and returns the reply.
    pub fn handle(&mut self, parsed: Result<Command, Fault>) -> Reply {
        let cmd = match parsed {
            Ok(c) => c,
            Err(f) => return Reply::Error(f),
        };
        match cmd {
            Command::Hello => Reply::hello(self.max),
            Command::State => Reply::State(self.state()),
            Command::Calibrate { xy, luminance } => {
                let t = self.display.transfer().clone();
                match Display::from_primaries(xy, luminance, Xyz::default(), t) {
                    Ok(d) => {
                        self.xy = xy;
                        self.luminance = luminance;
                        self.display = d;
                        self.colour(self.target);
                        Reply::Done("cal")
                    }
                    Err(_) => Reply::Error(Fault::new(ErrorCode::Singular)),
                }
            }
            Command::Transfer { channels, curve } => {
                let mut t = self.display.transfer().clone();
                for (i, c) in t.iter_mut().enumerate() {
                    if channels.includes(i) {
                        *c = curve.clone();
                    }
                }
                match Display::from_primaries(self.xy, self.luminance, Xyz::default(), t) {
                    Ok(d) => {
                        self.display = d;
                        self.colour(self.target);
                        Reply::Done("trc")
                    }
                    Err(_) => Reply::Error(Fault::new(ErrorCode::Singular)),
                }
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
            Command::Xyz(v) => Reply::Colour(self.colour(v)),
            Command::Xyy(v) => Reply::Colour(self.colour(v.to_xyz())),
            Command::Reflect {
                illuminant,
                product,
                ..
            } => {
                let xyz = self.reflectance_xyz(illuminant, &product);
                Reply::Colour(self.colour(xyz))
            }
        }
    }

    /// XYZ (perfect white `Y = 100`) of a reflectance under a built-in light, with the current
    /// observer: three dot products against the light's moments ([`crate::lights`]).
    pub fn reflectance_xyz(&self, illuminant: Illuminant, r: &Reflectance) -> Xyz {
        let o = self.observer;
        match r {
            Reflectance::Paper(s) => lights::paper(o, illuminant).xyz(s),
            Reflectance::Default(s) => lights::default(o, illuminant).xyz(s),
        }
    }

    /// Shows `target` (white `Y = 100`): the core's drive step ([`Display::drive`]: gamut
    /// mapping, transfer curves, quantisation, and the XYZ the LED then emits at those duties).
    pub fn colour(&mut self, target: Xyz) -> ColourReport {
        let drive = self.display.drive(target, self.map, self.max);
        self.target = target;
        self.duty = drive.level;
        ColourReport::of(target, &drive, self.map, self.max)
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
            duty: self.duty,
            max: self.max,
        }
    }
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
}
