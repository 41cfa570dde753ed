//! `specpoly accuracy`: the report through the real binary, and the acceptance target — the
//! default preset reaches mean ≤ 0.1 and max ≤ 0.5 ΔE00 on the validation set (spectra and
//! lights it was not tuned on), for both observers.

use specpoly_core::Observer;
use specpoly_paper::accuracy::{self, Method};
use specpoly_spectra::repr::Repr;
use std::process::Command;

#[test]
fn default_meets_the_target_on_the_validation_set() {
    let patches = accuracy::colorchecker().unwrap();
    let val = accuracy::validation_set();
    let tune = accuracy::tuning_set();
    // no spectrum and no light in common
    assert!(val.patches.iter().all(|p| !tune.patches.contains(p)));
    assert!(val
        .illuminants
        .iter()
        .all(|i| !tune.illuminants.contains(i)));
    for obs in Observer::CLASSIC {
        let s = accuracy::evaluate(&[Method::Repr(Repr::DEFAULT)], obs, &val, &patches).unwrap();
        let st = accuracy::stats(&s[0], |_| true);
        eprintln!(
            "validation {obs:?}: n {} mean {:.4} max {:.4}",
            st.n, st.mean, st.max
        );
        assert_eq!(st.n, 4 * (12 + 66 + 220));
        assert!(st.mean <= 0.1 && st.max <= 0.5, "{st:?}");
    }
    let pooled = accuracy::default_validation().unwrap();
    assert!(pooled.mean <= accuracy::TARGET_MEAN && pooled.max <= accuracy::TARGET_MAX);
}

#[test]
fn report_through_the_binary() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("accuracy.md");
    let r = Command::new(env!("CARGO_BIN_EXE_specpoly"))
        .args(["accuracy", "-o", out.to_str().unwrap(), "--json"])
        .output()
        .unwrap();
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    // --json: each method's figures as numbers, the same method list as the document
    let v: serde_json::Value = serde_json::from_slice(&r.stdout).expect("JSON on stdout");
    let methods = v["methods"].as_array().unwrap();
    assert_eq!(methods.len(), accuracy::methods().len());
    for m in methods {
        for obs in ["cie1964", "cie1931"] {
            assert!(m[obs]["mean"].as_f64().unwrap() >= 0.0, "{m}");
        }
    }
    let doc = std::fs::read_to_string(&out).unwrap();
    for needle in [
        "## Every representation",
        "| **poly** (default, 8x3) | 32 |",
        "| `sampled:32` | 32 |",
        "| `paper` | 8 |",
        "| `rgb` | 3 |",
        "paper path (light + CMFs fitted)",
        "## Tuning and validation",
        "1931",
        "1964",
        "meets the target",
    ] {
        assert!(doc.contains(needle), "missing `{needle}`");
    }
    assert!(!doc.contains("MISSES"));
    // polynomials beat sampling at equal size: the equal-size table's rows
    let row = |label: &str| {
        doc.lines()
            .find(|l| l.starts_with(label))
            .unwrap_or_else(|| panic!("{label}"))
            .split('|')
            .map(str::trim)
            .filter_map(|c| c.parse::<f64>().ok())
            .collect::<Vec<f64>>()
    };
    for size in ["| 8 |", "| 16 |", "| 32 |"] {
        let v = row(size); // values, poly mean, poly max, sampled mean, sampled max
        assert!(v[1] < v[3] && v[2] < v[4], "{size} {v:?}");
    }
}
