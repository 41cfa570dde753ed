//! Every function is total: extreme and non-finite inputs and corrupted mixer states give a
//! documented status (a panic would abort this test process: `extern "C"` does not unwind),
//! and results written with `SP_STATUS_OK` are finite and in range.

use specpoly_c::cct::{sp_cct_to_xy, sp_xy_to_cct, SpCct, SpXy};
use specpoly_c::display::{
    sp_display_drive, sp_display_forward, sp_display_inverse, SpDisplay, SpDrive, SpEncoded, SpXyz,
};
use specpoly_c::mix::{
    sp_mix_step, sp_mix_target_cct, sp_mix_target_xy, SpChannel, SpMixResult, SpMixStep, SpMixer,
    SpPoint,
};
use specpoly_c::SpStatus;

/// Values at and past every edge the functions check.
const EDGES: [f32; 16] = [
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    0.0,
    -0.0,
    1e-45,
    -1.0,
    0.05,
    0.3,
    1.0,
    999.0,
    1000.0,
    25_000.0,
    25_001.0,
    f32::MAX,
    f32::MIN,
];

fn all_finite(v: &[f32]) -> bool {
    v.iter().all(|x| x.is_finite())
}

#[test]
fn cct_and_xy_conversions_are_total() {
    for a in EDGES {
        for b in EDGES {
            let mut xy = SpXy::default();
            // SAFETY: a valid output pointer.
            let s = unsafe { sp_cct_to_xy(a, b, &mut xy) };
            match s {
                SpStatus::Ok => assert!(
                    xy.x > 0.0 && xy.y > 0.0 && xy.x + xy.y < 1.0,
                    "{a} {b}: {xy:?}"
                ),
                SpStatus::NotFinite | SpStatus::Domain => {}
                s => panic!("sp_cct_to_xy({a}, {b}): {s:?}"),
            }
            let mut c = SpCct::default();
            // SAFETY: a valid output pointer.
            let s = unsafe { sp_xy_to_cct(a as f64, b as f64, &mut c) };
            match s {
                SpStatus::Ok => assert!(c.cct.is_finite() && c.duv.abs() <= 0.05),
                SpStatus::NotFinite | SpStatus::Domain | SpStatus::NoCct => {}
                s => panic!("sp_xy_to_cct({a}, {b}): {s:?}"),
            }
        }
    }
}

fn mixer(n: u32) -> SpMixer {
    let xyz = [
        [0.65, 0.30, 0.0],
        [0.25, 0.70, 0.10],
        [0.18, 0.08, 0.95],
        [0.95, 1.0, 0.85],
        [0.40, 0.45, 0.05],
        [0.10, 0.30, 0.60],
    ];
    let mut m = SpMixer {
        count: n,
        ..Default::default()
    };
    for (c, xyz) in m.channels.iter_mut().zip(xyz) {
        *c = SpChannel {
            xyz,
            cost: 1.0,
            gamma: 2.2,
        };
    }
    m
}

#[test]
fn mixing_is_total_over_edge_targets_and_corrupted_states() {
    let mut states = Vec::new();
    for n in 0..=8 {
        states.push(mixer(n));
    }
    for v in EDGES {
        let mut m = mixer(6);
        m.channels[5].xyz[1] = v;
        states.push(m);
        let mut m = mixer(4);
        m.channels[0].gamma = v;
        m.channels[1].cost = v;
        states.push(m);
        let mut m = mixer(5);
        m.fade_ms = 300;
        m.from = SpPoint {
            u: 0.2,
            v: 0.45,
            lum: v,
        };
        m.to = SpPoint {
            u: v,
            v: 0.47,
            lum: 0.5,
        };
        (m.step, m.steps) = (3, 7);
        states.push(m);
    }
    let mut m = mixer(3);
    (m.step, m.steps) = (9, 2);
    states.push(m);
    for state in &states {
        for (a, b, lum) in [
            (0.3127, 0.329, 0.5),
            (0.08, 0.85, 1.0),
            (4000.0, 0.0, 1.0),
            (f32::NAN, 0.3, 0.2),
            (0.3, 0.3, f32::INFINITY),
            (0.3, 0.3, -0.0),
            (25_000.0, 0.05, 1.0),
        ] {
            for goal in 0..2 {
                let mut m = *state;
                let mut r = SpMixResult::default();
                // SAFETY: valid pointers.
                let s = unsafe {
                    if goal == 0 {
                        sp_mix_target_xy(&mut m, a, b, lum, 65535, &mut r)
                    } else {
                        sp_mix_target_cct(&mut m, a, b, lum, 4095, &mut r)
                    }
                };
                match s {
                    SpStatus::Ok => assert!(all_finite(&r.light)),
                    SpStatus::NotFinite
                    | SpStatus::Domain
                    | SpStatus::Channels
                    | SpStatus::OutOfGamut => {
                        // Debug, not ==: NaN fields are unequal to themselves
                        assert_eq!(
                            format!("{m:?}"),
                            format!("{state:?}"),
                            "unchanged on an error"
                        )
                    }
                    s => panic!("{s:?}"),
                }
                // step whatever state the target left, to the end
                for _ in 0..40 {
                    let mut st = SpMixStep::default();
                    // SAFETY: valid pointers.
                    match unsafe { sp_mix_step(&mut m, 1000, &mut st) } {
                        SpStatus::Ok => assert!(st.duty.iter().all(|d| *d <= 1000)),
                        SpStatus::FadeDone => break,
                        SpStatus::NotFinite
                        | SpStatus::Domain
                        | SpStatus::Channels
                        | SpStatus::OutOfGamut => break,
                        s => panic!("{s:?}"),
                    }
                }
            }
        }
    }
}

#[test]
fn the_drive_step_is_total() {
    let good = SpDisplay {
        primaries: [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]],
        luminance: [21.26, 71.52, 7.22],
        black: [0.0; 3],
        gamma: [0.0, 2.2, 1.0],
        ..SpDisplay::default()
    };
    for (i, v) in EDGES.into_iter().enumerate() {
        let mut bad = [good; 6];
        bad[0].primaries[1][1] = v;
        bad[1].luminance[2] = v;
        bad[2].black[0] = v;
        bad[3].gamma[1] = v;
        // a table: of 0 to 65 points, one of them an edge value
        bad[4].table_len[2] = [0, 1, 2, 3, 64, 65, u32::MAX][i % 7];
        bad[4].table[2] = core::array::from_fn(|k| k as f32 / 63.0);
        bad[5].table_len[0] = 4;
        bad[5].table[0][..4].copy_from_slice(&[0.0, 0.2, v, 1.0]);
        for d in bad.iter().chain([&good]) {
            for t in [[v, 50.0, 50.0], [20.0, 21.0, 23.0], [v, v, v]] {
                for map in [-1, 0, 1, 2] {
                    let mut r = SpDrive::default();
                    let t = SpXyz {
                        x: t[0],
                        y: t[1],
                        z: t[2],
                    };
                    // SAFETY: valid pointers.
                    let s = unsafe { sp_display_drive(d, &t, map, 255, &mut r) };
                    match s {
                        SpStatus::Ok => {
                            assert!(r.level.iter().all(|l| *l <= 255));
                            assert!(r.linear.iter().all(|l| (0.0..=1.0).contains(l)));
                        }
                        SpStatus::NotFinite
                        | SpStatus::Domain
                        | SpStatus::Singular
                        | SpStatus::Size => {}
                        s => panic!("{s:?}"),
                    }
                    let mut e = SpEncoded::default();
                    // SAFETY: valid pointers.
                    let s = unsafe { sp_display_inverse(d, &t, map, &mut e) };
                    match s {
                        SpStatus::Ok => {
                            assert!(e.device.iter().all(|l| (0.0..=1.0).contains(l)));
                            assert!(e.linear.iter().all(|l| (0.0..=1.0).contains(l)));
                        }
                        SpStatus::NotFinite
                        | SpStatus::Domain
                        | SpStatus::Singular
                        | SpStatus::Size => {}
                        s => panic!("{s:?}"),
                    }
                }
                let mut x = SpXyz::default();
                // SAFETY: `t` is 3 floats; valid pointers.
                let s = unsafe { sp_display_forward(d, t.as_ptr(), &mut x) };
                match s {
                    SpStatus::Ok => assert!(x.x.is_finite() && x.y.is_finite() && x.z.is_finite()),
                    SpStatus::NotFinite
                    | SpStatus::Domain
                    | SpStatus::Singular
                    | SpStatus::Size => {}
                    s => panic!("{s:?}"),
                }
            }
        }
    }
}
