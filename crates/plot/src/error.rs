//! What can go wrong drawing a plot: a `--size` that is not one or out of range, a legend too
//! big for the figure, and failures of the drawing backend or the PNG encoder. Messages are one
//! line; which errors are the user's mistake (exit 2) is decided by the CLI.

use crate::size::Size;

/// An error of `specpoly-plot`.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A `--size` that is not `WIDTHxHEIGHT` with sides in range.
    #[error("`{text}`: {why}")]
    BadSize {
        /// The size as given.
        text: String,
        /// What is wrong.
        why: String,
    },
    /// A size outside one command's limits.
    #[error("--size `{size}`: between {min} and {max}")]
    SizeOutOfRange {
        /// The size given.
        size: Size,
        /// The smallest accepted.
        min: Size,
        /// The largest accepted.
        max: Size,
    },
    /// More legend entries than fit the figure in readable type.
    #[error("{entries} legend entries do not fit a {width}x{height} figure in readable type (≥ {min_text_px} px): use --size {width}x{need_height} or larger, or plot fewer spectra")]
    LegendTooBig {
        /// The number of entries.
        entries: usize,
        /// The figure's width (px).
        width: u32,
        /// The figure's height (px).
        height: u32,
        /// The smallest text drawn ([`crate::MIN_TEXT_PX`]).
        min_text_px: f64,
        /// The height that holds the legend (px).
        need_height: f64,
    },
    /// The drawing backend failed.
    #[error("drawing the figure: {0}")]
    Draw(String),
    /// Drawing text on an image failed.
    #[error("drawing text: {0}")]
    Text(String),
    /// The PNG encoder failed.
    #[error("PNG encoding: {0}")]
    Png(#[source] png::EncodingError),
}

/// The result type of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;
