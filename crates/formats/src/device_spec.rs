//! The one parser of device strings on the command line: `KIND[:ARG][,KEY[=VALUE]]...`, as in
//! `--display web:8080,wait=60`, `--display led:/dev/ttyACM0,timeout=2`,
//! `--display sim:crt,noise=0.001`, `--instrument serial:/dev/ttyUSB0,baud=9600`.
//!
//! The kind ends at the first `:` or `,`; the argument runs from that `:` to the first `,`;
//! options are split at `,`, trimmed, empty ones skipped, and split at the first `=` (a bare
//! `KEY` has the empty value). Each device then reads the options it knows with
//! [`DeviceSpec::seconds`], [`DeviceSpec::number`] and reports the others with
//! [`DeviceSpec::unknown`], so every device words its errors the same way.

use crate::{Error, Result};
use std::time::Duration;

/// A parsed `KIND[:ARG][,KEY[=VALUE]]...`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DeviceSpec<'a> {
    /// The whole text, for messages.
    pub text: &'a str,
    /// What comes before the first `:` or `,`.
    pub kind: &'a str,
    /// What comes between the `:` and the first `,` (trimmed), if there is a `:`.
    pub arg: Option<&'a str>,
    /// `(KEY, VALUE)` pairs in order; `VALUE` is empty for a bare `KEY`.
    pub options: Vec<(&'a str, &'a str)>,
}

impl<'a> DeviceSpec<'a> {
    /// Splits `text` (never fails: each device judges its own parts).
    pub fn parse(text: &'a str) -> Self {
        let mut parts = text.split(',');
        let head = parts.next().unwrap_or("");
        let (kind, arg) = match head.split_once(':') {
            Some((k, a)) => (k.trim(), Some(a.trim())),
            None => (head.trim(), None),
        };
        let options = parts
            .map(str::trim)
            .filter(|p| !p.is_empty())
            .map(|p| p.split_once('=').unwrap_or((p, "")))
            .collect();
        Self {
            text,
            kind,
            arg,
            options,
        }
    }

    /// The argument, or a usage error saying what it should be (`example`, e.g.
    /// `led:/dev/ttyACM0`).
    pub fn required_arg(&self, what: &str, example: &str) -> Result<&'a str> {
        match self.arg {
            Some(a) if !a.is_empty() => Ok(a),
            _ => Err(Error::DeviceArgument {
                spec: self.text.to_string(),
                what: what.to_string(),
                example: example.to_string(),
            }),
        }
    }

    /// An error about option `key=value` ([`Error::DeviceOption`]), as any error type it
    /// converts into (so a device's parser returns it as its own error).
    pub fn bad(&self, key: &str, value: &str, why: &str) -> Error {
        Error::DeviceOption {
            spec: self.text.to_string(),
            key: key.to_string(),
            value: value.to_string(),
            why: why.to_string(),
        }
    }

    /// An error for an unknown option ([`Error::UnknownDeviceOption`]); `known` lists the valid
    /// keys. As any error type it converts into, like [`DeviceSpec::bad`].
    pub fn unknown(&self, key: &str, known: &str) -> Error {
        Error::UnknownDeviceOption {
            spec: self.text.to_string(),
            key: key.to_string(),
            known: known.to_string(),
        }
    }

    /// A finite number.
    pub fn number(&self, key: &str, value: &str) -> Result<f64> {
        value
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| self.bad(key, value, "not a number"))
    }

    /// A finite number ≥ 0.
    pub fn non_negative(&self, key: &str, value: &str) -> Result<f64> {
        let x = self.number(key, value)?;
        if x < 0.0 {
            return Err(self.bad(key, value, "must be ≥ 0"));
        }
        Ok(x)
    }

    /// A duration in seconds, > 0 and at most [`MAX_SECONDS`] (a day: longer waits are typos).
    pub fn seconds(&self, key: &str, value: &str) -> Result<Duration> {
        value
            .parse::<f64>()
            .ok()
            .filter(|s| *s > 0.0 && *s <= MAX_SECONDS)
            .and_then(|s| Duration::try_from_secs_f64(s).ok())
            .ok_or_else(|| self.bad(key, value, "expected seconds in (0, 86400]"))
    }

    /// An integer of type `T`.
    pub fn integer<T: std::str::FromStr>(&self, key: &str, value: &str) -> Result<T> {
        value
            .parse()
            .map_err(|_| self.bad(key, value, "not a whole number in range"))
    }
}

/// The longest wait or timeout a device option accepts (s).
pub const MAX_SECONDS: f64 = 86_400.0;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splits_kind_arg_and_options() {
        let s = DeviceSpec::parse("serial:/dev/ttyUSB0, baud=9600,,retries=2,srgb");
        assert_eq!(s.kind, "serial");
        assert_eq!(s.arg, Some("/dev/ttyUSB0"));
        assert_eq!(
            s.options,
            vec![("baud", "9600"), ("retries", "2"), ("srgb", "")]
        );
        let w = DeviceSpec::parse("web,wait=5");
        assert_eq!((w.kind, w.arg), ("web", None));
        assert_eq!(w.options, vec![("wait", "5")]);
        assert!(w.seconds("wait", "0").is_err());
        assert!(w.seconds("wait", "inf").is_err());
        assert!(w.seconds("wait", "1e20").is_err());
        assert!(w.seconds("wait", "NaN").is_err());
        assert_eq!(
            w.seconds("wait", "1.5").unwrap(),
            Duration::from_millis(1500)
        );
        assert!(DeviceSpec::parse("led:")
            .required_arg("a port", "led:PORT")
            .is_err());
    }
}
