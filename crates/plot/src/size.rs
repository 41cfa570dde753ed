//! An image size on the command line, `WIDTHxHEIGHT` (`--size` of `render` and `plot`).

use crate::{Error, Result};
use std::fmt;
use std::str::FromStr;

/// An image size, `WIDTHxHEIGHT`, each side 1 to [`Size::MAX`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Size {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl Size {
    /// The largest side accepted.
    pub const MAX: u32 = 16384;

    /// A usage error unless both sides lie within `min ..= max` (`--size`'s own limits for one
    /// command).
    pub fn check(self, min: Size, max: Size) -> Result<Self> {
        if (min.width..=max.width).contains(&self.width)
            && (min.height..=max.height).contains(&self.height)
        {
            Ok(self)
        } else {
            Err(Error::SizeOutOfRange {
                size: self,
                min,
                max,
            })
        }
    }
}

impl fmt::Display for Size {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}x{}", self.width, self.height)
    }
}

impl FromStr for Size {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        let bad = || Error::BadSize {
            text: s.to_string(),
            why: "expected WIDTHxHEIGHT, e.g. 512x512".into(),
        };
        let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
        let (width, height): (u32, u32) =
            (w.parse().map_err(|_| bad())?, h.parse().map_err(|_| bad())?);
        if width == 0 || height == 0 || width > Self::MAX || height > Self::MAX {
            return Err(Error::BadSize {
                text: s.to_string(),
                why: format!("each side must be 1..{}", Self::MAX),
            });
        }
        Ok(Size { width, height })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_checks() {
        assert_eq!(
            "800x600".parse::<Size>().unwrap(),
            Size {
                width: 800,
                height: 600
            }
        );
        assert!("12".parse::<Size>().is_err());
        assert!("0x5".parse::<Size>().is_err());
        assert!("20000x5".parse::<Size>().is_err());
        let s = Size {
            width: 100,
            height: 100,
        };
        assert!(s.check(s, s).is_ok());
        assert!(s
            .check(
                Size {
                    width: 200,
                    height: 1
                },
                s
            )
            .is_err());
    }
}
