//! # specpoly-protocol
//!
//! The RGB-LED controller's line protocol, shared by the host CLI (`specpoly led`) and the
//! firmware (`specpoly-firmware`), so both sides read and write the same grammar. Pure: no I/O,
//! no allocation, `no_std`; every parser returns a value or a [`Fault`] for any input and never
//! panics (fuzzed in `tests/fuzz.rs`). The grammar and its versioning are documented in
//! `firmware/PROTOCOL.md`.
//!
//! - [`LineReader`] assembles bounded lines from bytes;
//! - [`Command`] is a request (host → controller), [`Reply`] an answer (controller → host);
//! - [`lut`]: the drive-correction table's upload (`lut begin|row|end|off`);
//! - [`mix`]: the multi-channel mixing commands and the one place they are answered;
//! - [`number`] reads and writes decimals without `core`'s large float tables.
//!
//! Layers (no module cycles): [`number`] and [`fault`]; a private grammar layer (a line's
//! words, number words, curve and gamut-map names); [`lut`] and [`mix`]'s commands and
//! report; [`command`] and [`reply`], which hold them; [`mix::answer`] (in `mix/answer.rs`),
//! which takes a command and makes a reply.
//!
//! `duplicates --repo protocol` lists two same-shape pairs, kept: the reply reader's `Keys`
//! fields and their `match` of key names (one line per key, what the grammar is), and the
//! `map`/`observer` arms of the command parser (a word matched against two names each).
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod command;
pub mod fault;
mod grammar;
pub mod line;
pub mod lut;
pub mod mix;
pub mod number;
pub mod reply;
pub mod target;

pub use command::{write_reflect, write_reflect_hex, Channels, Command, Reflectance};
pub use fault::{ErrorCode, Fault};
pub use line::LineReader;
pub use lut::LutCommand;
pub use mix::{ChannelCommand, DeviceMixer, MixReport, MIX_CHANNELS};
pub use reply::{ColourReport, CurveSummary, Gamut, Reply, StateReport};

/// Protocol version, reported by `hello` and `state`. Incremented when a command or reply
/// changes meaning; new reply keys do not change it (readers ignore unknown keys).
pub const PROTOCOL_VERSION: u16 = 1;

/// Longest line accepted, in bytes, without its `\n`: two default-preset factors at full
/// precision (2 × 32 numbers of ≤ 15 characters) fit.
pub const MAX_LINE: usize = 1024;

/// Most factors in one `refl` product.
pub const MAX_FACTORS: usize = 4;

/// Longest reply line, in bytes, without its `\n`.
pub const MAX_REPLY: usize = 320;
