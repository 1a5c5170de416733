//! AFL target: `woodpile_fuzz::fuzz_fit` (docs/fuzzing.md).

fn main() {
    afl::fuzz!(|data: &[u8]| woodpile_fuzz::fuzz_fit(data));
}
