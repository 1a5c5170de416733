//! AFL target: `woodpile_fuzz::fuzz_lattice` (docs/fuzzing.md).

fn main() {
    afl::fuzz!(|data: &[u8]| woodpile_fuzz::fuzz_lattice(data));
}
