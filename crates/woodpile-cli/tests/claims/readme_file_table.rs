//! Claim: the README's table of a run directory lists every file a run writes (it missed
//! `dissipated_j.npy`): a damped impact run under gravity and a preload, which writes every
//! optional file, is listed file by file in the README's table rows (lines starting with `|`).

use crate::common;

#[test]
fn every_file_a_run_writes_is_in_the_readme_table() {
    let readme = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../README.md"),
    )
    .unwrap();
    let table: String = readme
        .lines()
        .filter(|l| l.starts_with("| `"))
        .collect::<Vec<_>>()
        .join("\n");
    let dir = tempfile::tempdir().unwrap();
    common::write(
        dir.path(),
        "s.toml",
        "[chain]\nrods_mm = [40, 40]\n[damping]\ncontact = \"restitution\"\nrestitution = 0.9\n[run]\nduration_s = 5e-5\n",
    );
    let o = common::run_in(dir.path(), &["simulate", "s.toml", "--out", "run", "-q"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mut files: Vec<String> = std::fs::read_dir(dir.path().join("run"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    assert!(files.contains(&"dissipated_j.npy".to_string()), "{files:?}");
    for f in &files {
        assert!(
            table.contains(&format!("`{f}`")),
            "README.md's run-directory table does not list {f} (the run wrote {files:?})"
        );
    }
}
