//! The drive-correction table a calibration with a channel-interaction lattice sends to the
//! controller (`specpoly_core::drive_table`): built here with the full model's exact inverse,
//! uploaded as `lut begin N`, `N²` `lut row` lines and `lut end CHECK` (firmware/PROTOCOL.md).
//!
//! The controller evaluates Cowan's matrix model from the `cal` and `trc` lines it was sent,
//! with black 0; [`controller_display`] rebuilds exactly that model (the lines carry the f32
//! values bit for bit), and the table corrects it toward the calibration's full model.

use rayon::prelude::*;
use specpoly_core::display_model::FULL;
use specpoly_core::drive_table::{self, Table};
use specpoly_core::{delta_e2000, Display, DisplayModel, Lab, Transfer, Xyz};
use specpoly_protocol::{Command, LutCommand};

/// The grid side sent by default: measured against the exact inverse on the shipped displays
/// (docs/calibration.md, "The full model on the controller"), 13 brings the worst (the
/// Surface) to a mean of 0.29 ΔE00 (9: 0.43, 17: 0.18; the matrix model alone 1.20) in
/// 13.2 KiB of controller flash and 3.5 s of upload at 115 200 baud.
pub const DEFAULT_GRID: usize = 13;

/// The table's interpolation error against the exact inverse, ΔE00 of the worst colour (a dense
/// sample off the nodes, every shipped display, `crates/cli/tests/led_table.rs`): measured 1.69 on the
/// Surface at [`DEFAULT_GRID`], held at 2.0. `led --check` and the QEMU test bound each
/// colour's emission by it.
pub const TABLE_DE: f64 = 2.0;

/// The bound on the mean over that sample, ΔE00: measured 0.295 (Surface), 0.096 (Lenovo),
/// ≤ 0.04 on the other displays.
pub const TABLE_MEAN_DE: f64 = 0.35;

/// A calibration's full model, the controller's matrix model and the table between them.
#[derive(Clone, Debug)]
pub struct Correction {
    /// The full model (matrix + interaction lattice).
    pub model: Box<DisplayModel<FULL>>,
    /// The controller's matrix model ([`controller_display`]).
    pub matrix: Display,
    /// The table sent.
    pub table: DriveTable,
}

impl Correction {
    /// The table of side `grid` for `model`; `None` when its primaries span no colour space.
    pub fn new(model: Box<DisplayModel<FULL>>, grid: usize) -> Option<Self> {
        let matrix = controller_display(model.display())?;
        let table = DriveTable::build(&model, &matrix, grid);
        Some(Self {
            model,
            matrix,
            table,
        })
    }

    /// What the full model emits at `duty` (of `max`) against the colour asked for, `target`
    /// (white `Y = 100`, the controller's: its matrix model's white), in ΔE00 relative to the
    /// full model's white; `None` when the exact inverse cannot reach the colour (outside the
    /// full model's gamut), where no table can do better.
    pub fn miss(&self, target: Xyz, duty: [u16; 3], max: u16) -> Option<f64> {
        let want = target.scale(self.matrix.white().y / 100.0);
        if !self.model.inverse(want).exact {
            return None;
        }
        let full = max.max(1) as f32;
        let got = self.model.device_to_xyz(duty.map(|d| d as f32 / full));
        let white = self.model.white();
        Some(delta_e2000(
            Lab::from_xyz(got, white),
            Lab::from_xyz(want, white),
        ))
    }
}

/// The controller's matrix model for a calibration's primaries and curves: what it builds
/// from the `cal` and `trc` lines (no black: the protocol has none).
pub fn controller_display(display: &Display) -> Option<Display> {
    let (xy, luminance) = display.primaries();
    let trc: [Transfer; 3] = display.transfer().clone();
    Display::from_primaries(xy, luminance, Xyz::default(), trc).ok()
}

/// A drive-correction table.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DriveTable {
    /// Nodes per side.
    pub grid: usize,
    /// `grid³` corrections, Q15, red slowest.
    pub nodes: Vec<[i16; 3]>,
}

impl DriveTable {
    /// The table of side `grid` correcting `matrix` (the controller's model) toward `model`:
    /// each node from the exact inverse (in parallel).
    pub fn build<const CAP: usize>(
        model: &DisplayModel<CAP>,
        matrix: &Display,
        grid: usize,
    ) -> Self {
        let nodes = (0..grid * grid * grid)
            .into_par_iter()
            .map(|i| drive_table::node(model, matrix, grid, i))
            .collect();
        Self { grid, nodes }
    }

    /// The core's view of it, for [`Display::drive_corrected`].
    pub fn table(&self) -> Option<Table<'_>> {
        Table::new(self.grid, &self.nodes)
    }

    /// The upload's checksum ([`drive_table::checksum`]).
    pub fn checksum(&self) -> u32 {
        drive_table::checksum(self.grid, self.nodes.iter().copied())
    }

    /// The upload as protocol commands: `lut begin`, one `lut row` per `(red, green)` pair
    /// (its `grid` nodes along blue), `lut end` with the checksum.
    pub fn commands(&self) -> Vec<Command> {
        let g = self.grid;
        let mut out = vec![Command::Lut(LutCommand::Begin(g as u8))];
        for (row, chunk) in self.nodes.chunks(g).enumerate() {
            let mut values = heapless::Vec::new();
            for v in chunk.iter().flatten() {
                // a row of at most GRID_MAX nodes fits the command's capacity
                let _ = values.push(*v);
            }
            out.push(Command::Lut(LutCommand::Row {
                row: row as u16,
                values,
            }));
        }
        out.push(Command::Lut(LutCommand::End(self.checksum())));
        out
    }
}
