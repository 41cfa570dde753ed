//! Settings kept in flash across resets: one settings record ([`crate::settings`]) in a `sequential-storage` map
//! (key [`KEY`]) over any `embedded-storage` NOR flash. The crate gives wear levelling (new
//! records are appended; a page is erased only when the range is full) and power-fail safety
//! (every item carries a CRC-32; an item whose write was interrupted is skipped, so a `load`
//! after a power cut returns the last complete record).
//!
//! `sequential-storage` is async; our flashes are not (QEMU's RAM-backed one and the STM32's
//! flash controller both finish before returning), so [`Blocking`] lifts a blocking
//! `embedded_storage::nor_flash::NorFlash` to the async traits and every call is driven to
//! completion with `embassy_futures::block_on` (it completes on the first poll).
//!
//! [`handle`] answers the `save` and `load` commands; the firmware calls [`Store::load`] at
//! start-up and logs why it used the defaults.

use crate::mix;
use crate::settings::{self, Record, RecordError, RECORD_MAX};
use crate::Controller;
use core::ops::Range;
use embassy_futures::block_on;
use embedded_storage::nor_flash as blocking;
use embedded_storage_async::nor_flash::{ErrorType, NorFlash, ReadNorFlash};
use sequential_storage::cache::{Cache, Uncached};
use sequential_storage::map::{MapConfig, MapStorage, SerializationError, Value};
use sequential_storage::Error;
use specpoly_protocol::{Command, ErrorCode, Fault, Reply};

/// The map key of the settings record.
pub const KEY: u8 = 1;

/// Bytes of the work buffer: key + largest record, rounded up to 16-byte flash words.
pub const BUFFER: usize = (1 + RECORD_MAX + 15) & !15;

/// A work buffer aligned for flashes that need aligned sources.
#[repr(align(4))]
pub struct Buffer(pub [u8; BUFFER]);

impl Buffer {
    /// A zeroed buffer.
    pub const fn new() -> Self {
        Self([0; BUFFER])
    }
}

impl Default for Buffer {
    fn default() -> Self {
        Self::new()
    }
}

/// Why `load` gave no settings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LoadError {
    /// Nothing was ever saved (the range is erased).
    NotSaved,
    /// The range holds data but no intact record (an interrupted write, bit errors).
    Corrupted,
    /// The newest record is of another format version.
    Format(u8),
    /// The newest record passed its CRC but its fields are out of range.
    Invalid,
    /// The flash reported an error.
    Storage,
    /// The record reads but does not apply (primaries that span no colour space, an observer
    /// this build lacks).
    NotApplicable,
}

impl LoadError {
    /// A short name for logs.
    pub fn name(self) -> &'static str {
        match self {
            LoadError::NotSaved => "not saved",
            LoadError::Corrupted => "corrupted",
            LoadError::Format(_) => "old format",
            LoadError::Invalid => "invalid",
            LoadError::Storage => "flash error",
            LoadError::NotApplicable => "not applicable",
        }
    }
}

/// Why `save` failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SaveError {
    /// The flash reported an error, or the range is damaged beyond repair.
    Storage,
}

/// The range given to [`Store::new`] is not whole erase pages, or fewer than two.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BadRange;

/// What the store writes: the settings record or the mixer's, borrowed. One type for both, so
/// `sequential-storage`'s writer is compiled once (≈ 1 KiB of flash each). Written from the
/// borrowed record; read back as bytes (`fetch_item::<&[u8]>`) and decoded by
/// [`settings::read`] or [`mix::read`], so no owned copy of the settings is ever built.
#[derive(Clone, Copy, Debug)]
pub enum Item<'a> {
    /// The calibration record ([`settings`], key [`KEY`]).
    Settings(Record<'a>),
    /// The mixer's record ([`mix`], key [`mix::KEY`]).
    Mix(mix::Record<'a>),
}

impl<'a> Value<'a> for Item<'_> {
    fn serialize_into(&self, buffer: &mut [u8]) -> Result<usize, SerializationError> {
        match self {
            Item::Settings(r) => r.encode(buffer),
            Item::Mix(r) => r.encode(buffer),
        }
        .ok_or(SerializationError::BufferTooSmall)
    }

    fn deserialize_from(_: &'a [u8]) -> Result<(Self, usize), SerializationError> {
        Err(SerializationError::InvalidData)
    }
}

/// The settings store over flash `F` (async NOR flash; see [`Blocking`]).
pub struct Store<F: NorFlash> {
    map: MapStorage<u8, F, Cache<Uncached, Uncached, Uncached, u8>>,
    range: Range<u32>,
}

impl<F: NorFlash> Store<F> {
    /// A store on `range` of `flash`: at least two whole erase pages.
    pub fn new(flash: F, range: Range<u32>) -> Result<Self, BadRange> {
        let config = MapConfig::try_new(range.clone()).map_err(|_| BadRange)?;
        Ok(Self {
            map: MapStorage::new(flash, config, Cache::new_uncached()),
            range,
        })
    }

    /// Appends `settings` as the newest record. A range the crate finds corrupted beyond its
    /// own repair (bytes that were never its pages) is erased once and the save retried.
    pub fn save(&mut self, record: &Record, buffer: &mut Buffer) -> Result<(), SaveError> {
        let item = Item::Settings(*record);
        match block_on(self.map.store_item(&mut buffer.0, &KEY, &item)) {
            Err(Error::Corrupted { .. }) => {
                block_on(self.map.erase_all()).map_err(|_| SaveError::Storage)?;
                block_on(self.map.store_item(&mut buffer.0, &KEY, &item))
                    .map_err(|_| SaveError::Storage)
            }
            r => r.map_err(|_| SaveError::Storage),
        }
    }

    /// The newest intact record's bytes (in `buffer`), checked with [`settings::read`].
    pub fn load<'b>(&mut self, buffer: &'b mut Buffer) -> Result<&'b [u8], LoadError> {
        match block_on(self.map.fetch_item::<&[u8]>(&mut buffer.0, &KEY)) {
            Ok(Some(bytes)) => match settings::read(bytes, None) {
                Ok(_) => Ok(bytes),
                Err(RecordError::Format(v)) => Err(LoadError::Format(v)),
                Err(RecordError::Invalid) => Err(LoadError::Invalid),
            },
            Ok(None) => match self.blank() {
                Ok(true) => Err(LoadError::NotSaved),
                Ok(false) => Err(LoadError::Corrupted),
                Err(e) => Err(e),
            },
            Err(Error::Corrupted { .. }) => Err(LoadError::Corrupted),
            Err(_) => Err(LoadError::Storage),
        }
    }

    /// Appends the mixer's record (after [`Store::save`], which repairs the range if need be).
    pub fn save_mix(&mut self, record: &mix::Record, buffer: &mut Buffer) -> Result<(), SaveError> {
        block_on(
            self.map
                .store_item(&mut buffer.0, &mix::KEY, &Item::Mix(*record)),
        )
        .map_err(|_| SaveError::Storage)
    }

    /// The newest intact mixer record's bytes (in `buffer`); `None` when none was saved.
    pub fn load_mix<'b>(&mut self, buffer: &'b mut Buffer) -> Result<Option<&'b [u8]>, LoadError> {
        match block_on(self.map.fetch_item::<&[u8]>(&mut buffer.0, &mix::KEY)) {
            Ok(v) => Ok(v),
            Err(Error::Corrupted { .. }) => Err(LoadError::Corrupted),
            Err(_) => Err(LoadError::Storage),
        }
    }

    /// Whether the whole range is erased (`0xFF`).
    fn blank(&mut self) -> Result<bool, LoadError> {
        let mut chunk = [0u8; 16];
        let step = chunk.len().max(F::READ_SIZE) as u32;
        let mut at = self.range.start;
        while at < self.range.end {
            let n = step.min(self.range.end - at) as usize;
            block_on(self.map.flash().read(at, &mut chunk[..n])).map_err(|_| LoadError::Storage)?;
            if chunk[..n].iter().any(|b| *b != 0xFF) {
                return Ok(false);
            }
            at += n as u32;
        }
        Ok(true)
    }

    /// The flash (for tests that damage it).
    pub fn flash(&mut self) -> &mut F {
        self.map.flash()
    }
}

pub use crate::controller::parse;

/// Answers a line: `save` and `load` with the store; every other command goes to the
/// controller. Not inlined: the caller's frame (the firmware's `main`, alive for ever) would
/// otherwise hold every command's temporaries at once.
#[inline(never)]
pub fn handle<F: NorFlash>(
    controller: &mut Controller,
    store: &mut Store<F>,
    buffer: &mut Buffer,
    line: &str,
) -> Reply {
    let parsed = parse(line);
    match parsed {
        Ok(Command::Save) => save(controller, store, buffer),
        Ok(Command::Load) => load(controller, store, buffer),
        other => controller.handle(other),
    }
}

/// `save`: both records. Not inlined: `sequential-storage`'s futures are large, and `handle`'s
/// frame is on every command's path.
#[inline(never)]
fn save<F: NorFlash>(controller: &Controller, store: &mut Store<F>, buffer: &mut Buffer) -> Reply {
    match store
        .save(&controller.record(), buffer)
        .and_then(|()| save_mix(controller, store, buffer))
    {
        Ok(()) => Reply::Done("save"),
        Err(SaveError::Storage) => Reply::Error(Fault::new(ErrorCode::Storage)),
    }
}

/// The mixer's record (nothing without feature `mixing`).
fn save_mix<F: NorFlash>(
    controller: &Controller,
    store: &mut Store<F>,
    buffer: &mut Buffer,
) -> Result<(), SaveError> {
    #[cfg(feature = "mixing")]
    return store.save_mix(&mix::Record(&controller.mixer), buffer);
    #[cfg(not(feature = "mixing"))]
    {
        let _ = (controller, store, buffer);
        Ok(())
    }
}

/// `load`: the calibration record, then the mixer's if one was saved. Not inlined (see
/// [`save`]).
#[inline(never)]
fn load<F: NorFlash>(
    controller: &mut Controller,
    store: &mut Store<F>,
    buffer: &mut Buffer,
) -> Reply {
    let r = restore(controller, store, buffer);
    #[cfg(feature = "mixing")]
    let r = r.and_then(|()| match restore_mix(controller, store, buffer) {
        Err(LoadError::NotSaved) => Ok(()),
        r => r,
    });
    match r {
        Ok(()) => Reply::Done("load"),
        Err(LoadError::Storage) => Reply::Error(Fault::new(ErrorCode::Storage)),
        Err(_) => Reply::Error(Fault::new(ErrorCode::NotSaved)),
    }
}

/// Applies the newest saved record to the controller (`load`, and every start); on an error
/// the controller is unchanged.
pub fn restore<F: NorFlash>(
    controller: &mut Controller,
    store: &mut Store<F>,
    buffer: &mut Buffer,
) -> Result<(), LoadError> {
    let bytes = store.load(buffer)?;
    controller
        .apply_record(bytes)
        .map_err(|_| LoadError::NotApplicable)
}

/// Applies the newest saved mixer record ([`crate::mix`]: channels, curves, fade time);
/// [`LoadError::NotSaved`] when there is none. On an error the mixer is unchanged.
#[cfg(feature = "mixing")]
pub fn restore_mix<F: NorFlash>(
    controller: &mut Controller,
    store: &mut Store<F>,
    buffer: &mut Buffer,
) -> Result<(), LoadError> {
    let bytes = store.load_mix(buffer)?.ok_or(LoadError::NotSaved)?;
    mix::read(bytes, &mut controller.mixer).map_err(|e| match e {
        RecordError::Format(v) => LoadError::Format(v),
        RecordError::Invalid => LoadError::Invalid,
    })
}

/// A blocking `embedded-storage` NOR flash seen through the async traits `sequential-storage`
/// takes. Hand-written (20 lines) rather than `embassy-embedded-hal`'s `BlockingAsync`, which
/// brings `embassy-sync` and `embassy-time` for this one adapter.
pub struct Blocking<F>(pub F);

impl<F: blocking::ErrorType> ErrorType for Blocking<F> {
    type Error = F::Error;
}

impl<F: blocking::ReadNorFlash> ReadNorFlash for Blocking<F> {
    const READ_SIZE: usize = F::READ_SIZE;

    async fn read(&mut self, offset: u32, bytes: &mut [u8]) -> Result<(), Self::Error> {
        self.0.read(offset, bytes)
    }

    fn capacity(&self) -> usize {
        self.0.capacity()
    }
}

impl<F: blocking::NorFlash> NorFlash for Blocking<F> {
    const WRITE_SIZE: usize = F::WRITE_SIZE;
    const ERASE_SIZE: usize = F::ERASE_SIZE;

    async fn erase(&mut self, from: u32, to: u32) -> Result<(), Self::Error> {
        self.0.erase(from, to)
    }

    async fn write(&mut self, offset: u32, bytes: &[u8]) -> Result<(), Self::Error> {
        self.0.write(offset, bytes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::{Header, FORMAT};
    use sequential_storage::mock_flash::{MockFlashBase, WriteCountCheck};
    use specpoly_core::{display::TABLE_MAX, GamutMap, Observer, Transfer};

    /// Owned settings for the tests: curves plus the record's other fields.
    #[derive(Clone, Debug, PartialEq)]
    struct Owned {
        trc: [Transfer; 3],
        header: Header,
    }

    impl Owned {
        fn record(&self) -> Record<'_> {
            let h = self.header;
            Record {
                xy: h.xy,
                luminance: h.luminance,
                trc: &self.trc,
                map: h.map,
                observer: h.observer,
            }
        }
    }

    /// Distinct settings for save number `i` (a gamma that says which).
    fn numbered(i: usize) -> Owned {
        Owned {
            trc: [
                Transfer::Gamma(1.0 + i as f32 / 64.0),
                Transfer::Srgb,
                Transfer::Linear,
            ],
            header: Header {
                xy: [[0.7, 0.29], [0.17, 0.7], [0.135, 0.04]],
                luminance: [2.5, 7.25, 1.0],
                map: GamutMap::Desaturate,
                observer: Observer::Cie1931,
            },
        }
    }

    fn largest() -> Owned {
        let table: [f32; TABLE_MAX] = core::array::from_fn(|i| (i as f32 / 63.0).powi(2));
        let t = Transfer::table(&table).unwrap();
        Owned {
            trc: [t.clone(), t.clone(), t],
            ..numbered(0)
        }
    }

    /// What `load` gives, read back into owned settings.
    fn load<F: NorFlash>(s: &mut Store<F>, buf: &mut Buffer) -> Result<Owned, LoadError> {
        let bytes = s.load(buf)?;
        let mut trc = [Transfer::Linear, Transfer::Linear, Transfer::Linear];
        let header = settings::read(bytes, Some(&mut trc)).map_err(|_| LoadError::Invalid)?;
        Ok(Owned { trc, header })
    }

    /// 4 pages of 2 KiB, 4-byte words (the QEMU RAM flash's word; STM32F4 sectors are larger).
    type Flash = MockFlashBase<4, 4, 512>;

    fn store(flash: Flash) -> Store<Flash> {
        Store::new(flash, Flash::FULL_FLASH_RANGE).unwrap()
    }

    #[test]
    fn saved_settings_load_back_and_blank_flash_says_so() {
        let mut buf = Buffer::new();
        let mut s = store(Flash::default());
        assert_eq!(load(&mut s, &mut buf), Err(LoadError::NotSaved));
        s.save(&largest().record(), &mut buf).unwrap();
        assert_eq!(load(&mut s, &mut buf), Ok(largest()));
        s.save(&numbered(3).record(), &mut buf).unwrap();
        assert_eq!(
            load(&mut s, &mut buf),
            Ok(numbered(3)),
            "the newest record wins"
        );
        assert!(Store::new(Flash::default(), 0..100).is_err());
    }

    #[test]
    fn many_saves_wear_level_over_the_pages() {
        let mut buf = Buffer::new();
        let mut s = store(Flash::default());
        let start = s.flash().stats_snapshot();
        for i in 0..300 {
            s.save(&numbered(i).record(), &mut buf).unwrap();
        }
        assert_eq!(load(&mut s, &mut buf), Ok(numbered(299)));
        let stats = start.compare_to(s.flash().stats_snapshot());
        // 300 records of 64 B in 8 KiB: the pages were recycled, each a few times only
        assert!(stats.erases >= 4 && stats.erases < 40, "{stats:?}");
    }

    #[test]
    fn old_formats_and_damaged_records_are_refused() {
        let mut buf = Buffer::new();
        // a record of format 0 (an older firmware), written through the map directly
        let mut s = store(Flash::default());
        let mut raw = [0u8; RECORD_MAX];
        let n = numbered(1).record().encode(&mut raw).unwrap();
        raw[0] = FORMAT - 1;
        block_on(s.map.store_item(&mut buf.0, &KEY, &&raw[..n])).unwrap();
        assert_eq!(load(&mut s, &mut buf), Err(LoadError::Format(FORMAT - 1)));

        // a record with a flipped bit: its CRC fails, it is skipped, and nothing else is there
        let mut s = store(Flash::default());
        s.save(&numbered(2).record(), &mut buf).unwrap();
        let n = numbered(2).record().encode(&mut raw).unwrap();
        let bytes = s.flash().as_bytes_mut();
        let at = bytes
            .windows(n)
            .position(|w| w == &raw[..n])
            .expect("the record is in flash");
        bytes[at + 5] ^= 0x10;
        assert_eq!(load(&mut s, &mut buf), Err(LoadError::Corrupted));
        // and the store still takes new records
        s.save(&numbered(4).record(), &mut buf).unwrap();
        assert_eq!(load(&mut s, &mut buf), Ok(numbered(4)));

        // bytes that were never the crate's pages: refused, then erased by the next save
        let mut s = store(Flash::default());
        s.flash().as_bytes_mut()[..256].fill(0x5A);
        assert_eq!(load(&mut s, &mut buf), Err(LoadError::Corrupted));
        s.save(&numbered(5).record(), &mut buf).unwrap();
        assert_eq!(load(&mut s, &mut buf), Ok(numbered(5)));
    }

    /// Power cut at every byte written or erased over a run of saves that wraps the pages: after
    /// the cut, `load` gives the last completed save or the interrupted one (never anything
    /// else, never a panic), and the store takes and returns a new record.
    #[test]
    fn a_save_interrupted_at_every_step_loses_at_most_that_save() {
        type Small = MockFlashBase<3, 4, 128>; // 3 pages of 512 B: wraps after ≈ 14 saves
        const SAVES: usize = 24;
        let mut buf = Buffer::new();
        let mut cuts = 0;
        for k in 0u32.. {
            let flash = Small::new(WriteCountCheck::Twice, Some(k), true);
            let mut s = Store::new(flash, Small::FULL_FLASH_RANGE).unwrap();
            let mut done = None;
            let mut cut = None;
            for i in 0..SAVES {
                match s.save(&numbered(i).record(), &mut buf) {
                    Ok(()) => done = Some(i),
                    Err(_) => {
                        cut = Some(i);
                        break;
                    }
                }
            }
            let Some(i) = cut else {
                break; // k is past the last byte of the run
            };
            cuts += 1;
            match load(&mut s, &mut buf) {
                Ok(got) => assert!(
                    got == numbered(i) || Some(&got) == done.map(numbered).as_ref(),
                    "cut at byte {k} in save {i}: loaded {got:?}"
                ),
                Err(LoadError::NotSaved | LoadError::Corrupted) => {
                    assert_eq!(done, None, "cut at byte {k} lost an earlier save")
                }
                Err(e) => panic!("cut at byte {k} in save {i}: {e:?}"),
            }
            s.save(&numbered(99).record(), &mut buf)
                .unwrap_or_else(|e| panic!("save after a cut at byte {k}: {e:?}"));
            assert_eq!(load(&mut s, &mut buf), Ok(numbered(99)), "cut at byte {k}");
        }
        assert!(cuts > 24 * 60, "{cuts} cut points");
    }
}
