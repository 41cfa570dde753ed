//! The calibration blob: its checksum is CRC-32 (the catalogue's check value), a display
//! survives the round trip, and every cut, every flipped bit and every foreign header is
//! refused with its error, never a panic or a read past the slice.

use specpoly_core::blob::{self, Parts, MAX_BYTES};
use specpoly_core::{Error, Transfer, Xyz};

/// A panel with one curve of each kind.
fn parts() -> Parts {
    Parts {
        primaries: [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]],
        luminance: [21.26, 71.52, 7.22],
        black: Xyz::new(0.05, 0.05, 0.06),
        transfer: [
            Transfer::Srgb,
            Transfer::Gamma(2.2),
            Transfer::table(&[0.0, 0.1, 0.3, 0.6, 1.0]).unwrap(),
        ],
    }
}

fn bytes(p: &Parts) -> Vec<u8> {
    let mut buf = [0u8; MAX_BYTES];
    let n = blob::write_parts(p, &mut buf).unwrap();
    buf[..n].to_vec()
}

/// The CRC-32 check value of the catalogue of parametrised CRCs (Greg Cook, "CRC-32/ISO-HDLC":
/// check = 0xCBF43926 for the ASCII bytes "123456789").
#[test]
fn the_checksum_is_crc32() {
    assert_eq!(blob::crc32(b"123456789"), 0xCBF4_3926);
    assert_eq!(blob::crc32(b""), 0);
}

#[test]
fn a_display_survives_the_blob() {
    let p = parts();
    let b = bytes(&p);
    assert_eq!(b.len(), 12 + 48 + 8 + 12 + 28 + 4);
    assert_eq!(&b[..4], b"SPCB");
    assert_eq!(blob::parts(&b).unwrap(), p);
    // trailing bytes (a larger flash region) are allowed
    let mut longer = b.clone();
    longer.extend([0xFF; 100]);
    assert_eq!(blob::parts(&longer).unwrap(), p);
    // a display written through its own primaries comes back within f32 rounding
    let d = p.clone().display().unwrap();
    let back = blob::read(&{
        let mut buf = [0u8; MAX_BYTES];
        let n = blob::write(&d, &mut buf).unwrap();
        buf[..n].to_vec()
    })
    .unwrap();
    for rgb in [[1.0, 1.0, 1.0], [0.2, 0.7, 0.4], [0.0, 0.0, 1.0]] {
        let (a, b) = (d.device_to_xyz(rgb), back.device_to_xyz(rgb));
        for (x, y) in a.to_array().iter().zip(b.to_array()) {
            assert!(
                (x - y).abs() <= 1e-5 * x.abs().max(1.0),
                "{rgb:?}: {a:?} {b:?}"
            );
        }
    }
    // the largest blob: three tables of 64 points
    let t: Vec<f32> = (0..64).map(|i| i as f32 / 63.0).collect();
    let mut big = p;
    big.transfer = [0, 1, 2].map(|_| Transfer::table(&t).unwrap());
    assert_eq!(bytes(&big).len(), MAX_BYTES);
    let mut short = [0u8; MAX_BYTES - 1];
    assert_eq!(blob::write_parts(&big, &mut short), Err(Error::Capacity));
}

#[test]
fn cut_corrupted_and_foreign_blobs_are_refused() {
    let b = bytes(&parts());
    for n in 0..b.len() {
        let e = blob::parts(&b[..n]).unwrap_err();
        assert_eq!(e, Error::BlobTruncated, "cut at {n}");
    }
    for bit in 0..8 * b.len() {
        let mut c = b.clone();
        c[bit / 8] ^= 1 << (bit % 8);
        let e = blob::parts(&c).unwrap_err();
        let want: &[Error] = match bit / 8 {
            // magic, version, flags: not ours; length: longer than the slice, or not the
            // checksummed length
            0..8 => &[Error::BlobVersion],
            8..12 => &[
                Error::BlobTruncated,
                Error::BlobVersion,
                Error::BlobChecksum,
            ],
            _ => &[Error::BlobChecksum],
        };
        assert!(want.contains(&e), "bit {bit}: {e:?}");
    }
    let mut v2 = b.clone();
    v2[4] = 2;
    let n = v2.len();
    let crc = blob::crc32(&v2[..n - 4]).to_le_bytes();
    v2[n - 4..].copy_from_slice(&crc);
    assert_eq!(blob::parts(&v2), Err(Error::BlobVersion));
    assert_eq!(blob::parts(b"not a blob"), Err(Error::BlobVersion));
}

/// A blob whose checksum is right but whose fields are not a display: the core's errors.
#[test]
fn well_formed_blobs_of_bad_displays_give_the_cores_errors() {
    let reseal = |mut b: Vec<u8>| {
        let n = b.len();
        let crc = blob::crc32(&b[..n - 4]).to_le_bytes();
        b[n - 4..].copy_from_slice(&crc);
        b
    };
    let b = bytes(&parts());
    let mut nan = b.clone();
    nan[12..16].copy_from_slice(&f32::NAN.to_le_bytes());
    assert!(matches!(blob::read(&reseal(nan)), Err(Error::NonFinite(_))));
    let mut flat = b.clone();
    flat[16..20].copy_from_slice(&0.0f32.to_le_bytes());
    assert_eq!(blob::read(&reseal(flat)).unwrap_err(), Error::Singular);
    let mut kind = b.clone();
    kind[60..64].copy_from_slice(&7u32.to_le_bytes());
    assert_eq!(blob::read(&reseal(kind)).unwrap_err(), Error::BlobVersion);
    // a table of 6 points where 5 are written: the fields overrun the blob
    let at = 60 + 8 + 12;
    let mut over = b.clone();
    over[at + 4..at + 8].copy_from_slice(&6u32.to_le_bytes());
    assert_eq!(blob::read(&reseal(over)).unwrap_err(), Error::BlobTruncated);
    let mut falling = b;
    falling[at + 8 + 4..at + 8 + 8].copy_from_slice(&(-1.0f32).to_le_bytes());
    assert_eq!(
        blob::read(&reseal(falling)).unwrap_err(),
        Error::NotIncreasing(1)
    );
}
