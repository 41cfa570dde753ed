//! The fuzz targets on stable, in the normal `cargo test`: every target of
//! [`specpoly::fuzz::TARGETS`] over its saved libFuzzer corpus (`fuzz/corpus/NAME/`, found and
//! minimised by `cargo +nightly fuzz`, docs/reliability.md), then a proptest run of mutated
//! corpus inputs. A target panics on a parser panic or on a broken invariant (what the project
//! writes its readers accept, nothing accepted is non-finite, errors are one line), so this
//! fails on any regression of a crash the fuzzer found. (The firmware's target replays its
//! corpus in the firmware's own unit tests, `firmware/src/fuzz.rs`.)

use proptest::prelude::*;
use std::path::{Path, PathBuf};

fn corpus(target: &str) -> Vec<Vec<u8>> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fuzz/corpus")
        .join(target);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    files.iter().map(|f| std::fs::read(f).unwrap()).collect()
}

/// Every target's corpus, read once.
fn corpora() -> &'static [Vec<Vec<u8>>] {
    static ALL: std::sync::OnceLock<Vec<Vec<Vec<u8>>>> = std::sync::OnceLock::new();
    ALL.get_or_init(|| {
        specpoly::fuzz::TARGETS
            .iter()
            .map(|(n, _)| corpus(n))
            .collect()
    })
}

#[test]
fn every_target_has_a_corpus_and_replays_it() {
    for (name, target) in specpoly::fuzz::TARGETS {
        let inputs = corpus(name);
        assert!(!inputs.is_empty(), "{name}: empty corpus");
        assert!(
            inputs.len() <= 200,
            "{name}: {} files, keep ≤ 200 (cargo fuzz cmin)",
            inputs.len()
        );
        for (i, input) in inputs.iter().enumerate() {
            let r = std::panic::catch_unwind(|| target(input));
            assert!(
                r.is_ok(),
                "{name}: corpus input {i} fails: {:?}",
                String::from_utf8_lossy(input)
            );
        }
    }
}

/// One mutation of an input: overwrite, insert or delete a byte, or insert a token that the
/// parsers treat specially.
#[derive(Clone, Debug)]
enum Edit {
    Set(usize, u8),
    Insert(usize, &'static str),
    Delete(usize),
}

const TOKENS: [&str; 16] = [
    ",",
    ";",
    "\t",
    "\"",
    "\n",
    "\r\n",
    "#",
    " nan",
    " inf",
    "1e39",
    "3.4e38",
    "-1e-45",
    "=",
    "[",
    "\u{feff}",
    "\u{1b}[31m",
];

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Edit::Set(i, b)),
        (any::<usize>(), prop::sample::select(TOKENS.to_vec()))
            .prop_map(|(i, t)| Edit::Insert(i, t)),
        any::<usize>().prop_map(Edit::Delete),
    ]
}

fn apply(mut v: Vec<u8>, edits: &[Edit]) -> Vec<u8> {
    for e in edits {
        match *e {
            Edit::Set(i, b) if !v.is_empty() => {
                let n = v.len();
                v[i % n] = b;
            }
            Edit::Insert(i, t) => {
                let at = i % (v.len() + 1);
                v.splice(at..at, t.bytes());
            }
            Edit::Delete(i) if !v.is_empty() => {
                let n = v.len();
                v.remove(i % n);
            }
            _ => {}
        }
    }
    v
}

proptest! {
    // 4 000 mutated inputs per target (with the corpora ≈ 1.2 s for all fifteen in a test
    // build); the libFuzzer campaigns run millions (docs/reliability.md).
    #![proptest_config(ProptestConfig { cases: 4000, failure_persistence: None, ..ProptestConfig::default() })]
    #[test]
    fn mutated_corpus_inputs_keep_the_invariants(
        pick in any::<usize>(),
        edits in prop::collection::vec(edit(), 1..12),
    ) {
        for (k, (name, target)) in specpoly::fuzz::TARGETS.into_iter().enumerate() {
            let inputs = &corpora()[k];
            let input = apply(inputs[pick % inputs.len()].clone(), &edits);
            let r = std::panic::catch_unwind(|| target(&input));
            prop_assert!(r.is_ok(), "{}: fails on {:?}", name, String::from_utf8_lossy(&input));
        }
    }
}
