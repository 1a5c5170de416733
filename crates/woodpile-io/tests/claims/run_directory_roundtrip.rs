//! Claim: a run directory reads back to exactly what was written: the samples of every contact
//! force, layer energy, wall energy and input work, bit for bit (`.npy` stores f64 as is), and
//! the element labels and unit cells from the typed `run.json`.

use std::path::Path;
use woodpile::{simulate, Trajectory};
use woodpile_io::rundir::{read_run_info, read_trajectory, write_run, RunRecord};
use woodpile_io::scenario::{resolve, Scenario};

#[test]
fn written_run_reads_back_exactly() {
    let scenario =
        Scenario::parse("[chain]\nrods_mm = [80, 40, 20]\n[run]\nduration_s = 1e-4\n").unwrap();
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
    let info = read_run_info(dir.path()).unwrap();
    assert_eq!(info.labels, ["80mm", "40mm", "20mm"]);
    let cells: Vec<_> = resolved
        .chain
        .elements()
        .iter()
        .map(|e| e.cell.clone())
        .collect();
    assert_eq!(info.cells, cells);
}
