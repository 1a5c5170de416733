"""Claims about the package's records: one ``Run`` type for computed and loaded runs, the GA
history as typed records whose field names are the history table's columns, the public API of
the one-module package still importable from ``woodpile``, and key alternatives known to the
extension. Exact comparisons: the same numbers travel through files and the extension unchanged.
"""

import dataclasses

import numpy as np
import pytest

import woodpile
from woodpile import GenerationStats, Run, Scenario, StateError

SHORT = {"run.duration_s": 2e-4}


def test_computed_and_loaded_runs_are_one_type(tmp_path):
    """load_run gives the same Run type as simulate, with the same summary and arrays (bit for
    bit); only a computed run can be saved again."""
    run = woodpile.simulate(Scenario.builtin("paper-impact-80mm").replace(**SHORT))
    out = run.save(tmp_path / "run")
    back = woodpile.load_run(out)
    assert type(back) is Run and type(run) is Run
    assert run.directory is None and back.directory == out
    assert back.run_info is not None and back.run_info["scenario_name"] == "paper-impact-80mm"
    assert back.summary == run.summary
    for name in ("time_s", "forces_n", "energy_j", "displacements_m", "velocities_m_s",
                 "wall_energy_j", "input_work_j", "dissipated_j"):
        assert np.array_equal(getattr(back, name), getattr(run, name)), name
    assert back.to_pandas().equals(run.to_pandas())
    with pytest.raises(StateError):
        back.save(tmp_path / "again")


def test_ga_history_columns_are_the_record_fields():
    """The history DataFrame is built from GenerationStats records: its index and columns are
    the record's field names, in order, and each row holds the record's values exactly."""
    result = woodpile.optimize({
        "design": {"positions": 5, "catalogue_mm": [20, 40, 60, 80]},
        "run": {"duration_s": 3e-4},
        "ga": {"population": 8, "generations": 2, "seed": 7},
    })
    records = result.ga.generations()
    names = [f.name for f in dataclasses.fields(GenerationStats)]
    assert [result.history.index.name, *result.history.columns] == names
    assert len(records) == len(result.history) == 3  # generations 0, 1, 2
    for record, (generation, row) in zip(records, result.history.iterrows()):
        assert isinstance(record, GenerationStats)
        assert (generation, *row.tolist()) == dataclasses.astuple(record)


def test_the_public_api_of_the_single_module_is_still_there():
    """Every name the one-module package exported is importable from `woodpile`, plus the
    error classes; `LoadedRun` is now `Run`."""
    before = ["Scenario", "Run", "WoodpileError", "simulate", "load_run", "evaluate", "sweep",
              "builtin_scenarios", "cells", "effective_mass", "band_gaps", "spectrum",
              "transmission", "BreederGA", "optimize", "OptimizeResult", "SUMMARY_COLUMNS"]
    for name in before + ["ScenarioError", "FileError", "OverwriteError", "RunError",
                          "InaccurateRunError", "LimitError", "InterruptedRunError", "StateError"]:
        assert hasattr(woodpile, name), name
    assert woodpile.LoadedRun is Run
    assert issubclass(woodpile.ScenarioError, woodpile.WoodpileError)


def test_a_peak_tolerance_replaces_the_integrator_settings_and_back():
    """The keys that exclude each other come from the extension: setting run.peak_tolerance
    removes the integrator settings, and setting run.time_step_s removes the tolerance."""
    s = Scenario.builtin("paper-impact-80mm").replace(**{"run.peak_tolerance": 1e-4})
    run = s.to_dict()["run"]
    assert run["peak_tolerance"] == 1e-4
    assert not {"integrator", "time_step_s", "rtol", "atol"} & set(run)
    back = s.replace(**{"run.time_step_s": 1e-7}).to_dict()["run"]
    assert "peak_tolerance" not in back and back["time_step_s"] == 1e-7


def test_scenario_keys_carry_the_defaults_that_completion_writes():
    """The key table comes from the extension (woodpile-io's table, its defaults from
    woodpile::defaults): every key with a plain default that a minimal scenario's completion
    writes holds exactly that default (compared with ==: the same f64 crosses twice), and the
    table knows which keys replace each other."""
    keys = {k.name: k for k in woodpile.scenario_keys()}
    completed = Scenario.from_toml("[chain]\nrods_mm = [80, 40]\n").to_dict()
    checked = []
    for name, key in keys.items():
        if key.default is None or "[]" in name:
            continue
        node = completed
        for part in name.split("."):
            node = node.get(part) if isinstance(node, dict) else None
        if node is not None:
            assert node == key.default, name
            checked.append(name)
    assert "run.time_step_s" in checked and "excitation.striker.diameter_mm" in checked, checked
    assert "excitation.drop_height_m" in keys["excitation.velocity_m_s"].alternatives
    assert keys["run.integrator"].choices == ("rk4", "dopri5")
