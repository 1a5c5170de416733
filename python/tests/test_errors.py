"""Claims about errors: every failure is a ``WoodpileError`` subclass whose ``field``, ``value``
and ``reason`` are attributes (never a message to parse), worded in Python's terms.

Runs are 0.2 ms of the paper's impact, as in test_api.py. Values are compared exactly: they are
the text of the value as the user gave it, not a computed number.
"""

import concurrent.futures
import pickle

import pytest

import woodpile
from woodpile import Scenario
from woodpile.errors import (
    FileError,
    OverwriteError,
    RunError,
    ScenarioError,
    StateError,
    WoodpileError,
)

SHORT = {"run.duration_s": 2e-4}


def short():
    return Scenario.builtin("paper-impact-80mm").replace(**SHORT)


def _snapshot(directory):
    """Every path under ``directory`` with its bytes and modification time."""
    return {
        str(p.relative_to(directory)): (p.read_bytes() if p.is_file() else None, p.stat().st_mtime_ns)
        for p in sorted(directory.rglob("*"))
    }


def test_a_bad_scenario_value_raises_scenario_error_with_its_dotted_key_and_value():
    """The field is the dotted key as written (an element's index included), the value the text
    the user gave, and the class is also a ValueError for code that catches that."""
    with pytest.raises(ScenarioError) as info:
        short().replace(**{"excitation.velocity_m_s": -1.0})
    e = info.value
    assert isinstance(e, WoodpileError) and isinstance(e, ValueError)
    assert e.field == "excitation.velocity_m_s"
    assert e.value == "-1.0"
    assert "> 0" in e.reason
    assert e.field in str(e) and e.args == (str(e), e.field, e.value, e.reason)
    with pytest.raises(ScenarioError) as info:
        short().replace(**{"chain.elements": [{"rod_mm": 80, "diameter_mm": -2}]})
    assert info.value.field == "chain.elements[0].diameter_mm"
    assert info.value.value == "-2"


def test_writing_into_a_foreign_directory_raises_overwrite_error_and_touches_nothing(tmp_path):
    """A non-empty directory that holds no earlier run is refused, with or without
    overwrite=True (which would not help, so the reason does not offer it); its files, and the
    directory around it, are left exactly as they were (bytes and modification times)."""
    run = woodpile.simulate(short())
    target = tmp_path / "mine"
    (target / "sub").mkdir(parents=True)
    (target / "notes.txt").write_text("my notes\n")
    (target / "sub" / "data.csv").write_text("1,2\n")
    before, around = _snapshot(target), sorted(p.name for p in tmp_path.iterdir())
    for overwrite in (False, True):
        with pytest.raises(OverwriteError) as info:
            run.save(target, overwrite=overwrite)
        e = info.value
        assert isinstance(e, FileExistsError)  # and so an OSError, as before the classes
        assert e.field == "directory" and e.value == str(target)
        assert "overwrite=True" not in e.reason and "--" not in str(e)
        assert _snapshot(target) == before
        assert sorted(p.name for p in tmp_path.iterdir()) == around


def test_an_earlier_run_is_replaced_only_with_overwrite_true_in_pythons_words(tmp_path):
    """The refusal names the keyword argument, never the command line's flag."""
    run = woodpile.simulate(short())
    out = run.save(tmp_path / "run")
    with pytest.raises(OverwriteError) as info:
        run.save(out)
    assert "overwrite=True" in info.value.reason and "overwrite=True" in str(info.value)
    assert "--" not in str(info.value)
    assert info.value.field == "directory" and info.value.value == str(out)
    assert run.save(out, overwrite=True) == out


def test_a_numerical_failure_raises_run_error():
    """An impact far beyond what the contact can take fails in the run, not in the input
    checks: RunError (a RuntimeError), not about one key."""
    with pytest.raises(RunError) as info:
        woodpile.simulate(short().replace(**{"excitation.velocity_m_s": 1e3}))
    assert isinstance(info.value, RuntimeError)
    assert info.value.field is None and "contact" in str(info.value)


def test_load_run_of_a_missing_directory_names_the_argument(tmp_path):
    """load_run's argument is `directory`, not the command line's RUN_DIR."""
    missing = tmp_path / "none"
    with pytest.raises(ScenarioError) as info:
        woodpile.load_run(missing)
    assert info.value.field == "directory" and info.value.value == str(missing)
    assert "RUN_DIR" not in str(info.value)


def test_an_error_raised_in_a_worker_process_arrives_with_its_attributes():
    """Executors pickle exceptions between processes: class and attributes survive."""
    with concurrent.futures.ProcessPoolExecutor(1) as pool:
        future = pool.submit(Scenario.builtin, "no-such-scenario")
        with pytest.raises(ScenarioError) as info:
            future.result()
    assert info.value.value == "no-such-scenario"
    assert "paper-impact-80mm" in info.value.reason
    for cls in (FileError, OverwriteError, RunError, StateError):
        e = pickle.loads(pickle.dumps(cls("message", "field", "value", "reason")))
        assert type(e) is cls and (e.field, e.value, e.reason, str(e)) == ("field", "value", "reason", "message")


SMALL_GA = {
    "design": {"positions": 5, "catalogue_mm": [20, 40, 60, 80]},
    "run": {"duration_s": 3e-4},
    "ga": {"population": 8, "generations": 3, "seed": 7},
}


def test_the_ga_used_out_of_order_raises_state_error_and_bad_values_scenario_error(tmp_path):
    """tell() without ask(), best or save() before the first generation: StateError (a
    RuntimeError, as before). Objectives that do not match the designs: ScenarioError naming
    `objectives`; the pending ask() survives it."""
    ga = woodpile.BreederGA(SMALL_GA)
    with pytest.raises(StateError):
        ga.tell([[0, 0, 0, 0, 0]], [1.0])
    with pytest.raises(StateError):
        ga.best
    with pytest.raises(StateError) as info:
        ga.save(tmp_path / "cp.json")
    assert isinstance(info.value, RuntimeError) and info.value.field == "checkpoint"
    designs = ga.ask()
    with pytest.raises(ScenarioError) as info:
        ga.tell(designs, [1.0])
    assert info.value.field == "objectives"
    ga.tell(designs, ga.evaluate(designs))
    assert ga.generation == 0


def test_breeder_ga_refuses_a_pareto_study_naming_the_algorithm():
    """Several objectives ask for NSGA-II, which BreederGA does not run (woodpile.optimize does,
    returning a ParetoResult): ScenarioError on `ga.algorithm`, before any simulation; an unknown
    objective of the config names its list entry."""
    study = {**SMALL_GA, "ga": {"objectives": ["transmitted-force", "total-mass"], "population": 8}}
    with pytest.raises(ScenarioError) as info:
        woodpile.BreederGA(study)
    assert info.value.field == "ga.algorithm" and info.value.value == "nsga2"
    unknown = {**SMALL_GA, "ga": {"objectives": ["transmitted-force", "weight"]}}
    with pytest.raises(ScenarioError) as info:
        woodpile.optimize(unknown)
    assert info.value.field == "ga.objectives[1]" and info.value.value == "weight"
