//! Errors talking to the LED controller.

use specpoly_protocol::Fault;

/// A failure of the link or of the controller.
#[derive(Debug, thiserror::Error)]
pub enum LedError {
    /// The serial port could not be opened.
    #[error("{port}: cannot open the serial port: {source}")]
    Open {
        /// The port.
        port: String,
        /// Why.
        source: serialport::Error,
    },
    /// Reading or writing the port failed.
    #[error("{port}: {source}")]
    Io {
        /// The port.
        port: String,
        /// Why.
        source: std::io::Error,
    },
    /// No complete reply within the timeout.
    #[error("{port}: no reply to `{command}` within {ms} ms (is the controller running?)")]
    Timeout {
        /// The port.
        port: String,
        /// The command sent (first 40 bytes).
        command: String,
        /// The timeout.
        ms: u128,
    },
    /// The port closed (the device went away).
    #[error("{port}: the device closed the connection")]
    Closed {
        /// The port.
        port: String,
    },
    /// A reply that is not the protocol's.
    #[error(
        "{port}: unreadable reply to `{command}`: `{}`",
        specpoly_formats::escape::one_line(reply)
    )]
    BadReply {
        /// The port.
        port: String,
        /// The command sent (first 40 bytes).
        command: String,
        /// What came back (first 80 bytes).
        reply: String,
    },
    /// The controller answered `err`.
    #[error("the controller rejected `{command}`: {fault}")]
    Rejected {
        /// The command sent (first 40 bytes).
        command: String,
        /// Its answer.
        fault: Fault,
    },
    /// A controller of another protocol version.
    #[error("{port}: the controller speaks protocol {found}, this host speaks {expected}")]
    Version {
        /// The port.
        port: String,
        /// The device's version.
        found: u16,
        /// Ours.
        expected: u16,
    },
    /// A command longer than the protocol allows.
    #[error("command of {len} bytes exceeds the protocol's {max}-byte line")]
    TooLong {
        /// Its length.
        len: usize,
        /// The limit.
        max: usize,
    },
}
