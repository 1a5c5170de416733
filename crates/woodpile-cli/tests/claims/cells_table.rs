//! Claim: `woodpile cells` prints the Table 1 catalogue with the numbers of docs/physics.md §3: total
//! masses, local resonances f_j and free-cell resonances F_j (the negative-mass band edges) to
//! 0.01 kHz, as computed by the library's UnitCell.

use crate::common;

#[test]
fn cells_prints_model_md_table() {
    let dir = tempfile::tempdir().unwrap();
    let out = common::run_in(dir.path(), &["cells"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let row = |rod: &str| {
        text.lines()
            .find(|l| l.split_whitespace().next() == Some(rod))
            .unwrap_or_else(|| panic!("no row {rod} in\n{text}"))
            .to_string()
    };
    for (rod, expected) in [
        ("20", &["0.866", "38.76", "55.45"][..]),
        ("40", &["1.732", "10.59", "15.23"][..]),
        ("50", &["2.165", "6.14", "35.65", "9.89", "48.52"][..]),
        ("80", &["3.464", "2.74", "15.65", "3.92", "20.33"][..]),
    ] {
        let r = row(rod);
        for e in expected {
            assert!(r.contains(e), "row {rod} lacks {e}: {r}");
        }
    }
}
