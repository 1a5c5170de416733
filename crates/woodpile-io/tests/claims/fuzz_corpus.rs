//! Claim: every reader of user files (scenario, lattice, optimisation config, `.npy`, blast
//! table, checkpoint, fit file with its CSV, `[uncertainty]`) answers arbitrary bytes with a result or an error, never a panic: the fuzzing
//! corpus (`crates/woodpile-fuzz/corpus/`: the seeds and every input the fuzzer once found to
//! crash or hang, kept after the fix) replays cleanly, and so do 320 random mutations of it
//! (a random target and seed each, up to 8 byte edits; proptest shrinks a failure to the
//! smallest edit).
//!
//! This is the short run of CI; the long one is AFL++ over the same targets,
//! `bash crates/woodpile-fuzz/run.sh` (docs/fuzzing.md). No tolerance: a panic is a failure.

#[path = "../../../woodpile-fuzz/src/targets.rs"]
#[allow(dead_code)]
mod targets;

use proptest::prelude::*;
use std::path::PathBuf;

fn corpus(target: &str) -> Vec<Vec<u8>> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../woodpile-fuzz/corpus")
        .join(target);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.unwrap().path())
        .collect();
    files.sort();
    assert!(!files.is_empty(), "an empty corpus for {target}");
    files.iter().map(|f| std::fs::read(f).unwrap()).collect()
}

#[test]
fn the_corpus_replays_without_a_panic() {
    for (name, target) in targets::TARGETS {
        for input in corpus(name) {
            target(&input);
        }
    }
}

/// One byte edit at a relative position: replace, insert or delete.
#[derive(Debug, Clone)]
enum Edit {
    Replace(f64, u8),
    Insert(f64, u8),
    Delete(f64),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (0.0..1.0f64, any::<u8>()).prop_map(|(at, b)| Edit::Replace(at, b)),
        (0.0..1.0f64, any::<u8>()).prop_map(|(at, b)| Edit::Insert(at, b)),
        (0.0..1.0f64).prop_map(Edit::Delete),
    ]
}

fn mutated(mut bytes: Vec<u8>, edits: &[Edit]) -> Vec<u8> {
    for e in edits {
        let at = |x: f64, len: usize| ((x * len as f64) as usize).min(len.saturating_sub(1));
        match *e {
            Edit::Replace(x, b) if !bytes.is_empty() => {
                let i = at(x, bytes.len());
                bytes[i] = b;
            }
            Edit::Insert(x, b) => {
                let i = at(x, bytes.len() + 1);
                bytes.insert(i, b);
            }
            Edit::Delete(x) if !bytes.is_empty() => {
                let i = at(x, bytes.len());
                bytes.remove(i);
            }
            _ => {}
        }
    }
    bytes
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(320))]
    #[test]
    fn mutations_of_the_corpus_never_panic(
        target in 0..targets::TARGETS.len(),
        seed in any::<prop::sample::Index>(),
        edits in prop::collection::vec(edit(), 1..=8),
    ) {
        let (name, run) = targets::TARGETS[target];
        let inputs = corpus(name);
        let input = mutated(inputs[seed.index(inputs.len())].clone(), &edits);
        run(&input);
    }
}
