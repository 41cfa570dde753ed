//! The command handler's fuzz target: bytes as they arrive on the UART, through the same
//! [`LineReader`] and [`controller::parse`](crate::controller::parse) as the firmware, answered by one
//! [`Controller`]. It panics only if the controller does, or if an `ok` reply carries a number
//! that its own reader ([`Reply::parse`]) refuses or that is not finite (the `nan`/`inf`
//! replies). `fuzz/fuzz_targets/firmware_command.rs` runs it under libFuzzer; the
//! test below replays the saved corpus (`fuzz/corpus/firmware_command/`) on stable.
//! (`save`/`load` need the flash store and are answered by [`Controller::handle`]'s fallback.)

use crate::controller::Controller;
use core::fmt::Write;
use specpoly_protocol::{LineReader, Reply, MAX_LINE};

/// A `fmt::Write` into a fixed buffer that drops what does not fit (replies are bounded by
/// the protocol; a longer one would be a bug caught by the read-back below).
struct Buf {
    bytes: [u8; 2 * MAX_LINE],
    len: usize,
}

impl Write for Buf {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        let end = self.len + s.len();
        if end > self.bytes.len() {
            return Err(core::fmt::Error);
        }
        self.bytes[self.len..end].copy_from_slice(s.as_bytes());
        self.len = end;
        Ok(())
    }
}

/// Feeds `data` to a fresh controller, line by line, and checks every reply.
pub fn command_bytes(data: &[u8]) {
    let mut controller = Controller::new(u16::MAX);
    let mut lines = LineReader::<MAX_LINE>::new();
    for &b in data.iter().chain(b"\n") {
        let Some(line) = lines.push(b) else {
            continue;
        };
        let reply = match line {
            Ok(l) if l.trim_ascii().is_empty() => continue,
            Ok(l) => controller.handle(crate::controller::parse(l)),
            Err(f) => Reply::Error(f),
        };
        let mut buf = Buf {
            bytes: [0; 2 * MAX_LINE],
            len: 0,
        };
        assert!(reply.write(&mut buf).is_ok(), "a reply longer than 2 lines");
        let text = core::str::from_utf8(&buf.bytes[..buf.len]).expect("replies are ASCII");
        if let Reply::Colour(r) = &reply {
            assert!(r.is_finite(), "{text}");
        }
        if text.starts_with("ok") {
            assert!(!text.contains("nan") && !text.contains("inf"), "{text}");
            assert_eq!(Reply::parse(text), Ok(reply), "{text}");
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every saved input of the libFuzzer corpus, and a seeded run of mutated ones.
    #[test]
    fn the_fuzz_corpus_replays_without_a_failure() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../fuzz/corpus/firmware_command");
        let mut inputs: Vec<Vec<u8>> = std::fs::read_dir(&dir)
            .map(|d| {
                d.filter_map(|e| std::fs::read(e.ok()?.path()).ok())
                    .collect()
            })
            .unwrap_or_default();
        assert!(!inputs.is_empty(), "no corpus in {}", dir.display());
        inputs.sort();
        for input in &inputs {
            command_bytes(input);
        }
        // xorshift-mutated corpus entries: byte flips, insertions of protocol tokens
        let mut s: u64 = 0x2545_f491_4f6c_dd1d;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        const TOKENS: [&str; 10] = [
            " 3.4e38",
            " 1e-45",
            " -0",
            " nan",
            " inf",
            "\n",
            " 0.5",
            "xyy",
            "refl paper D65",
            " 1e38",
        ];
        for _ in 0..2000 {
            let mut v = inputs[next() as usize % inputs.len()].clone();
            for _ in 0..1 + next() % 4 {
                let at = next() as usize % (v.len() + 1);
                match next() % 3 {
                    0 if at < v.len() => v[at] = next() as u8,
                    1 if at < v.len() => {
                        v.remove(at);
                    }
                    _ => {
                        let t = TOKENS[next() as usize % TOKENS.len()];
                        v.splice(at..at, t.bytes());
                    }
                }
            }
            command_bytes(&v);
        }
    }
}
