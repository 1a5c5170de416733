//! AFL target: `woodpile_fuzz::fuzz_optimize_config` (docs/fuzzing.md).

fn main() {
    afl::fuzz!(|data: &[u8]| woodpile_fuzz::fuzz_optimize_config(data));
}
