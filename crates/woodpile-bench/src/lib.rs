//! # woodpile-bench
//!
//! Criterion benchmarks of the woodpile engine, in `benches/`:
//!
//! - `cargo bench --manifest-path crates/woodpile-bench/Cargo.toml --bench impact`: one 20-rod resonant impact run with the
//!   paper's RK4 and with cheaper accurate settings;
//! - `cargo bench --manifest-path crates/woodpile-bench/Cargo.toml --bench optimize`: GA evaluations per second on 1 and 2
//!   threads;
//! - `cargo bench --manifest-path crates/woodpile-bench/Cargo.toml --bench lattice`: woodpile
//!   lattices, cost per step against contacts and elements, runs per second on 1 and 2 threads.
//!
//! The package is separate from `woodpile` so that `cargo test` never builds criterion; this
//! library is empty. Figures and how to read them: `bench/README.md`.
