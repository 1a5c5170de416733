"""Claims of the Python package, each against the Rust library or the command line's own files.

Runs are kept short (0.2 ms of the paper's impact) so the suite takes seconds; a tolerance is
stated where one is used, and results that must be identical are compared exactly.
"""

import concurrent.futures
import json

import numpy as np
import pandas as pd
import pytest

import woodpile
from woodpile import Scenario, WoodpileError

SHORT = {"run.duration_s": 2e-4}


def short(name="paper-impact-80mm"):
    return Scenario.builtin(name).replace(**SHORT)


def test_scenario_dict_and_toml_round_trip():
    """to_dict → from_dict and to_toml → from_toml give the same complete scenario."""
    s = Scenario.builtin("paper-blast-optimized")
    assert Scenario.from_dict(s.to_dict()) == s
    assert Scenario.from_toml(s.to_toml()) == s
    assert s.to_dict()["excitation"]["kind"] == "blast"


def test_replace_sets_dotted_keys_and_drops_their_alternative():
    s = Scenario.builtin("paper-impact-80mm").replace(
        **{"chain.rods_mm": [80, 40, 20], "excitation.velocity_m_s": 2.0}
    )
    d = s.to_dict()
    assert d["chain"]["rods_mm"] == [80, 40, 20]
    assert d["excitation"]["velocity_m_s"] == 2.0
    assert "drop_height_m" not in d["excitation"]


def test_errors_name_the_key_the_value_and_what_is_valid():
    with pytest.raises(WoodpileError) as info:
        Scenario.builtin("paper-impact-80mm").replace(**{"excitation.velocity_m_s": -1.0})
    message, field, value, reason = info.value.args
    assert field == "excitation.velocity_m_s"
    assert value.startswith("-1")
    assert "> 0" in reason and field in message
    with pytest.raises(WoodpileError):
        Scenario.from_toml("[chain]\nrods_mm = [25]\n")  # not a Table 1 length
    with pytest.raises(WoodpileError):
        Scenario.builtin("no-such-scenario")


def test_simulate_gives_arrays_of_the_documented_shapes():
    run = woodpile.simulate(short())
    n = 20
    s = len(run.time_s)
    assert s == 201  # 0.2 ms at 1 µs
    assert run.forces_n.shape == (s, n + 1)
    assert run.energy_j.shape == (s, n + 1)
    assert run.displacements_m.shape == (s, n)
    assert run.velocities_m_s.shape == (s, n)
    # Energy is conserved to the integrator's accuracy (docs/physics.md §7: ~5e-8).
    total = run.energy_j.sum(axis=1) + run.wall_energy_j
    assert np.max(np.abs(total / total[0] - 1)) < 1e-6
    df = run.to_pandas()
    assert df.index.name == "time_s" and "contact_20_n" in df and "element_20_m_s" in df


def test_summary_and_saved_directory_are_the_command_lines(tmp_path):
    """run.summary has exactly summary.json's keys and values; load_run reads the files back."""
    run = woodpile.simulate(short())
    out = run.save(tmp_path / "run")
    on_disk = json.loads((out / "summary.json").read_text())
    assert set(run.summary) == set(on_disk)
    assert run.summary["transmitted_peak_force_n"] == on_disk["transmitted_peak_force_n"]
    back = woodpile.load_run(out)
    assert np.array_equal(back.forces_n, run.forces_n)
    assert np.array_equal(back.time_s, run.time_s)
    assert back.scenario == run.scenario
    with pytest.raises(WoodpileError, match="overwrite=True"):
        run.save(tmp_path / "run")  # an earlier run is replaced only with overwrite=True
    run.save(tmp_path / "run", overwrite=True)


def test_evaluate_equals_single_runs_exactly():
    scenarios = [short(), short("paper-impact-20mm")]
    table = woodpile.evaluate(scenarios)
    for s, (_, row) in zip(scenarios, table.iterrows()):
        single = woodpile.simulate(s).summary
        assert row["transmitted_peak_force_n"] == single["transmitted_peak_force_n"]
        assert row["incident_peak_force_n"] == single["incident_peak_force_n"]
        assert pd.isna(row["error"])


def test_figures_of_merit_only_runs_take_simd_lanes_and_give_the_same_numbers():
    # sample_interval_s = duration_s: the runs advance together in SIMD lanes (woodpile::lanes),
    # which must report exactly what each run reports alone, with several rod counts, resonator
    # counts and a failing design in the batch.
    base = short()
    duration = base.to_dict()["run"]["duration_s"]
    scenarios = [
        base.replace(**{"chain.rods_mm": rods, "run.sample_interval_s": duration, "run.peak_tolerance": 1e-5})
        for rods in ([80, 40, 20], [20] * 6, [50, 30, 70, 40, 60, 20], [80] * 3, [30, 60])
    ]
    too_coarse = base.replace(**{"run.time_step_s": 1e-4, "run.sample_interval_s": duration})
    table = woodpile.evaluate(scenarios + [too_coarse])
    for s, (_, row) in zip(scenarios, table.iterrows()):
        single = woodpile.simulate(s).summary
        for key in ("transmitted_peak_force_n", "incident_peak_force_n", "rhs_evaluations"):
            if key in single:
                assert row[key] == single[key], key
        assert pd.isna(row["error"])
    assert "time_step" in table["error"].iloc[-1]


def test_a_failing_scenario_gives_an_error_row_not_an_exception():
    bad = short().replace(**{"run.time_step_s": 1e-4, "run.sample_interval_s": 1e-4})
    table = woodpile.evaluate([short(), bad])
    assert pd.isna(table["error"][0])
    assert isinstance(table["error"][1], str) and "time_step" in table["error"][1]


def _comparable(df):
    return df.drop(columns=["wall_time_s"])


def test_sweep_is_the_cartesian_product_and_executors_agree():
    grid = {"excitation.velocity_m_s": [1.0, 2.0, 3.0], "chain.rods_mm": [[80] * 4, [20] * 4]}
    local = woodpile.sweep(short(), grid)
    assert len(local) == 6
    assert list(local.columns[:2]) == list(grid)
    assert local["excitation.velocity_m_s"].tolist() == [1.0, 1.0, 2.0, 2.0, 3.0, 3.0]
    # The incident peak grows with the impact speed (Hertz: F ∝ v^{6/5}).
    four_80 = local[local["chain.rods_mm"].apply(lambda r: r[0] == 80)]
    assert four_80["incident_peak_force_n"].is_monotonic_increasing
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        threaded = woodpile.sweep(short(), grid, executor=pool)
    with concurrent.futures.ProcessPoolExecutor(2) as pool:
        processes = woodpile.sweep(short(), grid, executor=pool)
    assert _comparable(threaded).equals(_comparable(local))
    assert _comparable(processes).equals(_comparable(local))


def test_dask_local_cluster_gives_the_local_results():
    distributed = pytest.importorskip("dask.distributed")
    grid = {"excitation.velocity_m_s": [0.5, 1.0, 1.5, 2.0]}
    local = woodpile.sweep(short(), grid)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            remote = woodpile.sweep(short(), grid, executor=client)
    assert _comparable(remote).equals(_comparable(local))


def test_cells_and_band_gaps():
    """Table 1's 80 mm cell (f1 = 2.74 kHz, docs/physics.md §3) and its band structure: the
    effective mass is the total mass at 0 Hz, and the first gap opens below the first resonance."""
    c = woodpile.cells(80)
    assert abs(c["local_resonances_hz"][0] - 2740) < 10
    re, im = woodpile.effective_mass(c, [0.0, 1000.0])
    assert abs(re[0] - 1.0) < 1e-12 and im[0] == 0.0
    bands = woodpile.band_gaps(c, beta=1.7e9, precompression_n=10.0)
    first_gap = bands["gaps_hz"][0]
    assert first_gap[0] < c["local_resonances_hz"][0] < first_gap[1]
    derived = woodpile.cells(45, diameter_mm=6.0, material="steel")
    assert derived["primary_mass_kg"] > 0 and len(derived["resonator_masses_kg"]) >= 1
    f, a = woodpile.spectrum(np.sin(2 * np.pi * 1000 * np.arange(1000) * 1e-5), 1e-5, scaling="amplitude")
    assert abs(f[np.argmax(a)] - 1000) < 1e-9 and abs(a.max() - 1) < 1e-9


def test_default_spectrum_of_a_pulse_does_not_depend_on_the_record_length():
    """Claim: woodpile.spectrum's default (the Fourier-transform magnitude) gives the same values
    for a 50 µs half-sine pulse recorded for 2 ms and for 4 ms, at the frequencies both records
    share (every other bin of the longer one). Tolerance 1e-9 relative: the two sums hold the same
    nonzero samples, so only rounding differs. A bad scaling name is refused naming the field."""
    dt = 1e-6
    def pulse(duration_s):
        t = np.arange(round(duration_s / dt)) * dt
        return np.where(t < 50e-6, 100.0 * np.sin(np.pi * t / 50e-6), 0.0)
    f2, a2 = woodpile.spectrum(pulse(2e-3), dt)
    f4, a4 = woodpile.spectrum(pulse(4e-3), dt)
    assert np.allclose(f4[::2][: len(f2)], f2, rtol=0, atol=1e-6)
    assert np.allclose(a4[::2][: len(a2)], a2, rtol=1e-9, atol=1e-12 * a2.max())
    with pytest.raises(woodpile.WoodpileError) as e:
        woodpile.spectrum(pulse(2e-3), dt, scaling="power")
    assert e.value.args[1] == "scaling" and "fourier" in e.value.args[3]


SMALL_GA = {
    "design": {"positions": 5, "catalogue_mm": [20, 40, 60, 80]},
    "run": {"duration_s": 3e-4},
    "ga": {"population": 8, "generations": 3, "seed": 7},
}


def _history_without_time(df):
    return df.drop(columns=["elapsed_s"])


def test_ask_tell_reproduces_the_command_lines_ga():
    """The ask/tell loop (local, thread pool, Dask) gives the generations of BreederGa::run, the
    command line's code path: same best design and the same history, bit for bit."""
    reference = woodpile.BreederGA(SMALL_GA)
    reference.run_to_end()
    local = woodpile.optimize(SMALL_GA)
    assert local.best == reference.best
    assert _history_without_time(local.history).equals(_history_without_time(reference.history()))
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        threaded = woodpile.optimize(SMALL_GA, executor=pool)
    assert _history_without_time(threaded.history).equals(_history_without_time(reference.history()))
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            remote = woodpile.optimize(SMALL_GA, executor=client)
    assert remote.best == reference.best
    assert _history_without_time(remote.history).equals(_history_without_time(reference.history()))
    assert local.scenario.to_dict()["chain"]["rods_mm"] == [int(l.rstrip("m")) for l in local.best["labels"]]


SCREENED_GA = {
    "design": {"positions": 5, "catalogue_mm": [20, 40, 60, 80]},
    "run": {"duration_s": 3e-4, "peak_tolerance": 1e-4},
    "ga": {"population": 8, "generations": 3, "seed": 7, "screen_peak_tolerance": 1e-2},
}


def test_screened_ask_tell_reproduces_the_command_line_and_the_unscreened_choices():
    """With screening, workers return screened values and tell() simulates the contested
    designs here: the history is BreederGa::run's, bit for bit, and the best design and its
    value are those of the unscreened GA."""
    reference = woodpile.BreederGA(SCREENED_GA)
    reference.run_to_end()
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        threaded = woodpile.optimize(SCREENED_GA, executor=pool)
    assert threaded.best == reference.best
    assert _history_without_time(threaded.history).equals(_history_without_time(reference.history()))
    assert threaded.history["screenings"].iloc[-1] > 0
    unscreened = {**SCREENED_GA, "ga": {k: v for k, v in SCREENED_GA["ga"].items() if k != "screen_peak_tolerance"}}
    plain = woodpile.optimize(unscreened)
    assert threaded.best == plain.best
    assert threaded.history["best"].equals(plain.history["best"])
    assert threaded.history["evaluations"].iloc[-1] < plain.history["evaluations"].iloc[-1]


def test_checkpoint_resume_and_pickle_are_exact(tmp_path):
    import pickle

    full = woodpile.optimize(SMALL_GA)
    ga = woodpile.BreederGA(SMALL_GA)
    designs = ga.ask()
    ga.tell(designs, ga.evaluate(designs))  # generation 0 only
    ga.save(tmp_path / "cp.json")
    clone = pickle.loads(pickle.dumps(ga))
    assert clone.generation == 0
    resumed = woodpile.optimize(SMALL_GA, checkpoint=tmp_path / "cp.json")
    assert _history_without_time(resumed.history).equals(_history_without_time(full.history))
    assert resumed.best == full.best
    with pytest.raises(RuntimeError, match="without a pending ask"):
        ga.tell([[0, 0, 0, 0, 0]], [1.0])


def test_figures_draw_from_a_run_and_a_result(tmp_path):
    """Force map, energy map, spectra and convergence draw and save (Agg backend)."""
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    from woodpile import plot

    run = woodpile.simulate(short().replace(**{"run.duration_s": 5e-4}))
    ax = plot.force_map(run)
    assert ax.collections and ax.get_xlabel() == "time [ms]"
    # The energy map is normalised by the impact's energy: its first column sums to ~100 %.
    ax = plot.energy_map(run)
    first_column = ax.collections[0].get_array().reshape(21, -1)[:, 0]
    assert abs(first_column.sum() - 100) < 1e-6
    plot.spectra(run)
    plot.convergence(woodpile.optimize(SMALL_GA)).figure.savefig(tmp_path / "c.png")
    assert (tmp_path / "c.png").stat().st_size > 1000


def test_transmission_matches_the_command_lines_record():
    """woodpile.transmission gives the spectrum and the record `woodpile transmission` writes; for
    the built-in 80 mm chain the second predicted gap's lower edge (13.35 kHz) is measured within
    2 % (docs/physics.md §15 reports +0.03 % for the report's case)."""
    s = Scenario.builtin("transmission-80mm")
    table, record = woodpile.transmission(s)
    assert table.index.name == "frequency_hz"
    assert abs(len(table) - 2990) <= 1  # 100 Hz to 30 kHz in the default 10 Hz bins
    assert record["preload_n"] == 10.0
    edge = min(record["edges"], key=lambda e: abs(e["predicted_hz"] - 13351))
    assert abs(edge["relative_error"]) < 0.02, edge
    with pytest.raises(WoodpileError) as info:
        woodpile.transmission(short())
    assert info.value.args[1] == "preload.force_n"


def test_transmission_damping_is_a_keyword_refused_for_a_damped_chain():
    """``damping_time_s`` is ``--damping-time-s``: the built-in transmission chain has its own
    damping, so a measurement damping is refused naming the keyword; an invalid resolution names
    ``resolution_hz`` (the keyword), not the library's ``transmission.resolution_hz``."""
    s = Scenario.builtin("transmission-80mm")
    with pytest.raises(WoodpileError) as info:
        woodpile.transmission(s, damping_time_s=0.05)
    assert info.value.field == "damping_time_s"
    with pytest.raises(WoodpileError) as info:
        woodpile.transmission(s, resolution_hz=-1.0)
    assert info.value.field == "resolution_hz"


def test_the_chain_actuator_rest_position_is_a_float_under_a_displacement_drive_only(tmp_path):
    """``Run.actuator_rest_m`` (``summary.json``'s ``actuator_rest_m``) is a displacement drive's
    tip at rest, u* [m], downward: a float, the same read back from the directory, above the top
    element's static displacement x₁ (the first sample; the run starts from the static state) by
    the tip's Hertz overlap under the 2 N preload, so u* > x₁ > 0. None for an impact."""
    text = """[chain]
rods_mm = [80, 40, 20]
[excitation]
kind = "drive"
drive = "displacement"
signal = "harmonic"
amplitude = 1e-7
frequency_hz = 5e3
[preload]
force_n = 2.0
[run]
duration_s = 2e-5
"""
    run = woodpile.simulate(Scenario(text))
    u = run.actuator_rest_m
    assert isinstance(u, float) and np.isfinite(u)
    top = float(run.displacements_m[0, 0])
    assert u > top > 0.0, f"u* = {u} m, the top element at {top} m"
    assert woodpile.load_run(run.save(tmp_path / "run")).actuator_rest_m == u
    assert woodpile.simulate(short()).actuator_rest_m is None
