//! Every command in the README and `docs/*.md` runs as written: the fenced `sh` blocks are
//! extracted and each command is run by `sh -c`, in order, in a fresh temporary copy of the
//! repository per markdown file (so files one command writes are there for the next command of
//! the same file, no file depends on another's, and nothing lands in the tree), with
//! the `specpoly` under test first on `PATH`. A command must exit 0; all failures are listed
//! at once.
//!
//! The convention for blocks (docs/reliability.md, "Commands in the docs"):
//!
//! - ` ```sh ` (or `bash`, `shell`, `console`) blocks are commands; a synopsis with
//!   `[OPTIONS]` placeholders goes in a ` ```text ` block instead.
//! - `# …` after a command is a comment; a line ending in `\` continues on the next.
//! - An HTML comment on the line before the fence changes how the block runs (it is not shown
//!   on GitHub):
//!   - `<!-- docs-test: skip REASON -->`: the block needs what CI has not (a real serial
//!     instrument, a screen); the reason is required. Keep these few.
//!   - `<!-- docs-test: fake-led PORT -->`: `PORT` is replaced by a pseudo-terminal on which a
//!     fake LED controller answers as the firmware does (the host's [`specpoly_led::Model`]).

use crate::common::pty;

use pty::{Answer, FakePort};
use serialport::TTYPort;
use specpoly_core::{Display, GamutMap, Observer, Transfer, Xyz};
use specpoly_led::{MixModel, Model};
use specpoly_protocol::{Command, CurveSummary, Reply, StateReport};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use std::time::Instant;

/// A fenced command block.
#[derive(Debug)]
struct Block {
    file: String,
    line: usize,
    directive: Option<String>,
    commands: Vec<(usize, String)>,
}

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The command blocks of one markdown file.
fn blocks(file: &str, text: &str) -> Vec<Block> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let l = lines[i].trim_start();
        let Some(lang) = l.strip_prefix("```") else {
            i += 1;
            continue;
        };
        let is_shell = matches!(lang.trim(), "sh" | "bash" | "shell" | "console");
        let directive = lines[..i]
            .iter()
            .rev()
            .find(|l| !l.trim().is_empty())
            .and_then(|l| l.trim().strip_prefix("<!-- docs-test:"))
            .and_then(|l| l.strip_suffix("-->"))
            .map(|d| d.trim().to_string());
        let start = i + 1;
        i += 1;
        while i < lines.len() && !lines[i].trim_start().starts_with("```") {
            i += 1;
        }
        if !is_shell {
            i += 1;
            continue;
        }
        let mut commands = Vec::new();
        let mut pending: Option<(usize, String)> = None;
        for (k, raw) in lines[start..i.min(lines.len())].iter().enumerate() {
            let code = strip_comment(raw);
            let (text, more) = match code.trim_end().strip_suffix('\\') {
                Some(t) => (t.to_string(), true),
                None => (code.trim_end().to_string(), false),
            };
            let entry = pending.get_or_insert((start + k + 1, String::new()));
            entry.1.push_str(text.trim());
            entry.1.push(' ');
            if !more {
                let (n, c) = pending.take().unwrap();
                if !c.trim().is_empty() {
                    commands.push((n, c.trim().to_string()));
                }
            }
        }
        out.push(Block {
            file: file.to_string(),
            line: start,
            directive,
            commands,
        });
        i += 1;
    }
    out
}

/// The line without a `# comment` (a `#` after whitespace, outside quotes: `FILE#COLUMN`
/// stays).
fn strip_comment(line: &str) -> String {
    let mut quote: Option<char> = None;
    let mut prev = ' ';
    for (i, c) in line.char_indices() {
        match quote {
            Some(q) if c == q => quote = None,
            Some(_) => {}
            None if c == '"' || c == '\'' => quote = Some(c),
            None if c == '#' && prev.is_whitespace() => return line[..i].to_string(),
            None => {}
        }
        prev = c;
    }
    line.to_string()
}

fn all_blocks() -> Vec<Block> {
    let mut files = vec![repo().join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(repo().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    files.extend(docs);
    files
        .iter()
        .flat_map(|f| {
            let name = f.strip_prefix(repo()).unwrap_or(f).display().to_string();
            blocks(&name, &std::fs::read_to_string(f).unwrap())
        })
        .collect()
}

fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let name = e.file_name();
        if [".git", "target", "fuzz"].iter().any(|s| name == *s) {
            continue;
        }
        let ty = e.file_type().unwrap();
        if ty.is_dir() {
            copy_tree(&e.path(), &to.join(&name));
        } else if ty.is_file() {
            std::fs::copy(e.path(), to.join(&name)).unwrap();
        }
    }
}

/// A fake LED controller on a pseudo-terminal, answering as the firmware does (Rec. 709
/// primaries, linear curves, 65 535 ticks), until dropped.
fn fake_led() -> FakePort {
    pty::spawn(serve)
}

fn serve(port: TTYPort, stop: Arc<AtomicBool>) {
    let srgb = Display::srgb();
    let (mut xy, mut lum) = srgb.primaries();
    let mut map = GamutMap::Clip;
    let mut mix = MixModel::new(u16::MAX);
    pty::serve_lines(port, stop, |line| {
        if line.trim().is_empty() {
            return Answer::Nothing;
        }
        let t = [Transfer::Linear, Transfer::Linear, Transfer::Linear];
        let model = Model {
            display: Display::from_primaries(xy, lum, Xyz::default(), t).unwrap(),
            map,
            observer: Observer::Cie1931,
            max: u16::MAX,
        };
        let parsed = Command::parse(line);
        // the mixing commands (`channel`, `xy`, `cct`, `fade`) as the firmware's mixer
        let mixed = parsed.as_ref().ok().and_then(|c| mix.answer(c));
        let reply = match (mixed, parsed) {
            (Some(r), _) => r,
            (None, Err(f)) => Reply::Error(f),
            (None, Ok(c)) => match c {
                Command::Hello => Reply::hello(model.max),
                Command::State => Reply::State(StateReport {
                    protocol: 1,
                    primaries: [0, 1, 2].map(|i| [xy[i][0], xy[i][1], lum[i]]),
                    trc: [CurveSummary::Linear; 3],
                    map,
                    observer: model.observer,
                    lut: 0,
                    duty: [0; 3],
                    max: model.max,
                }),
                Command::Calibrate { xy: x, luminance } => {
                    xy = x;
                    lum = luminance;
                    Reply::Done("cal")
                }
                Command::Map(m) => {
                    map = m;
                    Reply::Done("map")
                }
                Command::Xyz(v) => model.answer(v),
                Command::Reflect {
                    illuminant,
                    product,
                    hex,
                    ..
                } => model.answer_in(model.reflectance_xyz(illuminant, &product), hex),
                Command::Transfer { .. } => Reply::Done("trc"),
                _ => Reply::Done("ok"),
            },
        };
        let mut s = String::new();
        reply.write(&mut s).unwrap();
        Answer::Line(s)
    })
}

#[test]
fn every_command_in_the_docs_runs_as_written() {
    let bin = PathBuf::from(env!("CARGO_BIN_EXE_specpoly"));
    let tmp = tempfile::tempdir().unwrap();
    let mut copies: Vec<String> = Vec::new();
    // `specpoly` on PATH; nothing else of the test's environment changes
    let path = format!(
        "{}:{}",
        bin.parent().unwrap().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let blocks = all_blocks();
    assert!(
        blocks.len() >= 5,
        "found only {} command blocks",
        blocks.len()
    );
    let mut failures = Vec::new();
    let mut skipped = Vec::new();
    let mut ran = 0;
    let t0 = Instant::now();
    for b in &blocks {
        // a fresh copy of the repository for each markdown file
        if !copies.contains(&b.file) {
            copies.push(b.file.clone());
            copy_tree(&repo(), &tmp.path().join(copies.len().to_string()));
        }
        let n = copies.iter().position(|f| *f == b.file).unwrap() + 1;
        let root = tmp.path().join(n.to_string());
        let mut replace: Option<(String, FakePort)> = None;
        match b.directive.as_deref() {
            None => {}
            Some(d) if d.starts_with("skip") => {
                let reason = d["skip".len()..].trim();
                assert!(
                    !reason.is_empty(),
                    "{}:{}: a skip needs a reason",
                    b.file,
                    b.line
                );
                skipped.push(format!("{}:{} ({reason})", b.file, b.line));
                continue;
            }
            Some(d) if d.starts_with("fake-led ") => {
                replace = Some((d["fake-led ".len()..].trim().to_string(), fake_led()));
            }
            Some(d) => panic!("{}:{}: unknown docs-test directive `{d}`", b.file, b.line),
        }
        for (line, cmd) in &b.commands {
            let run = match &replace {
                Some((port, fake)) => cmd.replace(port.as_str(), &fake.path),
                None => cmd.clone(),
            };
            let started = Instant::now();
            let out = std::process::Command::new("sh")
                .arg("-c")
                .arg(&run)
                .current_dir(&root)
                .env("PATH", &path)
                .stdin(std::process::Stdio::null())
                .output()
                .unwrap();
            ran += 1;
            let secs = started.elapsed().as_secs_f64();
            eprintln!("{}:{line}: {secs:.1} s: {cmd}", b.file);
            if !out.status.success() {
                failures.push(format!(
                    "{}:{line}: `{cmd}` → {}: {}",
                    b.file,
                    out.status,
                    String::from_utf8_lossy(&out.stderr).trim()
                ));
            }
        }
    }
    eprintln!(
        "{ran} commands in {:.1} s; skipped blocks: {}",
        t0.elapsed().as_secs_f64(),
        skipped.join(", ")
    );
    // the six that need hardware, a root install or minutes of rendering, and the two of the
    // Python package (a virtual environment and PyPI: test.sh builds and tests it)
    assert!(skipped.len() <= 8, "too many skipped blocks: {skipped:?}");
    assert!(
        failures.is_empty(),
        "{} doc commands fail:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn the_extractor_reads_continuations_comments_and_directives() {
    let md = "x\n<!-- docs-test: skip needs a PR-655 -->\n```sh\na b#c  # note\nd \\\n  e\n```\n```text\nnot [run]\n```\n";
    let b = blocks("t.md", md);
    assert_eq!(b.len(), 1);
    assert_eq!(b[0].directive.as_deref(), Some("skip needs a PR-655"));
    assert_eq!(
        b[0].commands,
        vec![(4, "a b#c".to_string()), (5, "d e".to_string())]
    );
}
