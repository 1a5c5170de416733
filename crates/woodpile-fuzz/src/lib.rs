//! Fuzz targets: every reader of user files, fed arbitrary bytes. A target may return any
//! error (that is the reader doing its job); it must not panic, hang or exhaust memory.
//!
//! `targets.rs` holds the targets; it is compiled here (one AFL binary per target, `src/bin/`)
//! and by woodpile-io's claims (`fuzz_corpus`), which replay the corpus and short mutations
//! of it on every `cargo test`.

#![allow(missing_docs)]

include!("targets.rs");
