//! Claim: a run directory reads back to exactly what was written: the samples of every contact
//! force, layer energy, wall energy, input work and dissipated energy, bit for bit (`.npy` stores
//! f64 as is; the CSV fallback writes shortest round-trip digits), and the element labels and
//! unit cells from the typed `run.json`. A run written before the dissipated energy existed (no
//! `dissipated_j.npy`, no `dissipated_j` column) still reads, with zero dissipation.

use std::path::Path;
use woodpile::{simulate, Trajectory};
use woodpile_io::rundir::{read_run_info, read_trajectory, write_run, RunRecord};
use woodpile_io::scenario::{resolve, Scenario};

#[test]
fn written_run_reads_back_exactly() {
    let scenario =
        Scenario::parse("[chain]\nrods_mm = [80, 40, 20]\n[run]\nduration_s = 1e-4\n[damping]\ncontact = \"restitution\"\nrestitution = 0.8\n").unwrap();
    let resolved = resolve(&scenario, Path::new(".")).unwrap();
    let mut t = Trajectory::default();
    let summary = simulate(
        &resolved.chain,
        &resolved.excitation,
        &resolved.settings,
        &mut t,
    )
    .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let record = RunRecord {
        name: "roundtrip",
        file: None,
        scenario: &scenario,
        resolved: &resolved,
        summary: &summary,
        trajectory: &t,
    };
    write_run(dir.path(), &record).unwrap();
    let back = read_trajectory(dir.path(), 3).unwrap();
    assert_eq!(back.times_s, t.times_s);
    assert_eq!(back.contact_forces_n, t.contact_forces_n);
    assert_eq!(back.layer_energies_j, t.layer_energies_j);
    assert_eq!(back.wall_energy_j, t.wall_energy_j);
    assert_eq!(back.input_work_j, t.input_work_j);
    assert_eq!(back.dissipated_j, t.dissipated_j);
    assert!(
        t.dissipated_j.last().unwrap() > &0.0,
        "the damped run dissipates"
    );
    let energy_csv = std::fs::read_to_string(dir.path().join("energy.csv")).unwrap();
    assert!(energy_csv
        .lines()
        .next()
        .unwrap()
        .ends_with(",total_j,input_work_j,dissipated_j"));
    let info = read_run_info(dir.path()).unwrap();
    assert_eq!(info.labels, ["80mm", "40mm", "20mm"]);
    let cells: Vec<_> = resolved
        .chain
        .elements()
        .iter()
        .map(|e| e.cell.clone())
        .collect();
    assert_eq!(info.cells, cells);

    // An older run without dissipated_j.npy reads zero dissipation; without the .npy files the
    // CSV files are read: the same samples.
    std::fs::remove_file(dir.path().join("dissipated_j.npy")).unwrap();
    let old = read_trajectory(dir.path(), 3).unwrap();
    assert_eq!(old.dissipated_j, vec![0.0; t.len()]);
    std::fs::remove_file(dir.path().join("time_s.npy")).unwrap();
    let csv = read_trajectory(dir.path(), 3).unwrap();
    assert_eq!(csv.dissipated_j, t.dissipated_j);
    assert_eq!(csv.input_work_j, t.input_work_j);
    // An older run: no dissipated_j column.
    let old: String = energy_csv
        .lines()
        .map(|l| l.rsplit_once(',').unwrap().0.to_string() + "\n")
        .collect();
    std::fs::write(dir.path().join("energy.csv"), old).unwrap();
    let old = read_trajectory(dir.path(), 3).unwrap();
    assert_eq!(old.dissipated_j, vec![0.0; t.len()]);
    assert_eq!(old.input_work_j, t.input_work_j);
}
