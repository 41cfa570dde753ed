//! What a calibration fitted from a `.ti3` records about it, the same for every front end
//! (`specpoly calibrate fit`, the Python package): the file (as the user named it) and the
//! SHA-256 of its bytes, its `CREATED` and `TARGET_INSTRUMENT` keywords, a note when its
//! readings are normalised to white Y = 100 (with or without `LUMINANCE_XYZ_CDM2` to scale
//! them back), a note when it was measured through a video-LUT calibration, and that video LUT
//! itself (its `CAL` table), so the ICC profile carries it as its `vcgt`.

use specpoly_display::calibration::Calibration;
use specpoly_display::video_lut::VideoLut;
use specpoly_formats::cgats::Ti3;

/// Records `ti3`'s provenance in `cal` (see the module docs). `source` is the file as shown
/// to the user, `readings_sha256` the hex SHA-256 of its bytes. Fails only when the file's
/// `CAL` table is not a usable video LUT.
pub fn record(
    cal: &mut Calibration,
    ti3: &Ti3,
    source: &str,
    readings_sha256: String,
) -> Result<(), specpoly_display::Error> {
    let (_, prov) = cal.report_mut();
    prov.source = source.to_string();
    prov.readings_sha256 = readings_sha256;
    prov.measured = ti3.keyword("CREATED").unwrap_or_default().to_string();
    prov.instrument = ti3
        .keyword("TARGET_INSTRUMENT")
        .unwrap_or_default()
        .to_string();
    if ti3.normalized {
        prov.notes.push(match ti3.white_cdm2 {
            Some(w) => format!(
                "the source is normalised to white Y = 100 (NORMALIZED_TO_Y_100); scaled to cd/m² with LUMINANCE_XYZ_CDM2 (white Y = {:.3} cd/m²)",
                w[1]
            ),
            None => "the source is normalised to white Y = 100 and gives no absolute luminance: units are relative".into(),
        });
    }
    if ti3.video_lut_active() {
        prov.notes.push(format!(
            "measured through a video-LUT calibration (the source's CAL table, {} entries): this model holds only while that LUT is loaded",
            ti3.video_lut.as_ref().map_or(0, Vec::len)
        ));
    }
    if let Some(rows) = &ti3.video_lut {
        let lut = VideoLut::from_rows(rows, &format!("{source}: CAL table"))?;
        cal.set_video_lut(Some(lut))?;
    }
    Ok(())
}
