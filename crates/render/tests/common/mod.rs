//! Helpers the test modules share.

/// The shipped displays' fits (one copy, in the calibrate crate's tests).
#[path = "../../../calibrate/tests/common/displays.rs"]
pub mod displays;
pub mod scenes;

/// Base64 (RFC 4648), for `data:` URIs in the glTF files the tests write (a dozen lines: no
/// crate for them).
pub fn b64(data: &[u8]) -> String {
    const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in data.chunks(3) {
        let n = (c[0] as u32) << 16
            | (*c.get(1).unwrap_or(&0) as u32) << 8
            | *c.get(2).unwrap_or(&0) as u32;
        for k in 0..4 {
            if k <= c.len() {
                s.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}
