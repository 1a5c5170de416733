"""Claims: a Python argument of the wrong kind or out of range is refused up front, naming the
argument or the scenario key, as a ``TypeError`` (not a value of the expected kind) or a
``woodpile.errors.ScenarioError`` (a value out of range, with ``field`` set) — never a bare
``OverflowError`` from the conversion to Rust's unsigned integers, nor an ``AttributeError`` from
deep inside the package. And the size limits of the command line hold here too: a fit of a
billion starts raises ``LimitError`` naming ``allow_large=True`` before any run, and a lattice
scenario given to ``sensitivity`` is refused naming the ``lattice`` table. The estimators alone
(``saltelli_unit_cube``, ``sobol_indices``) name a negative count the same way.
"""

from pathlib import Path
from typing import Callable

import numpy as np
import pytest

import woodpile
from woodpile import LimitError, Scenario, ScenarioError
from woodpile.sobol import saltelli_unit_cube, sobol_indices

CHAIN = """[chain]
rods_mm = [40, 30, 20]
[run]
duration_s = 2e-4
[uncertainty]
impact_velocity_m_s = { uniform = [1.8, 2.2] }
"""


@pytest.mark.parametrize(
    "kwargs, field",
    [
        ({"base_samples": -4}, "base_samples"),
        ({"base_samples": 1}, "base_samples"),
        ({"seed": -1}, "seed"),
        ({"seed": 2**40}, "seed"),
        ({"threads": -1}, "threads"),
    ],
)
def test_sensitivity_out_of_range_arguments_are_named(kwargs: dict[str, int], field: str) -> None:
    with pytest.raises(ScenarioError) as e:
        woodpile.sensitivity(Scenario.from_toml(CHAIN), **kwargs)
    assert e.value.field == field


def test_sensitivity_of_a_file_name_is_a_type_error_naming_scenario() -> None:
    with pytest.raises(TypeError, match="scenario"):
        woodpile.sensitivity("file.toml")  # type: ignore[arg-type]


def test_sensitivity_of_a_lattice_names_the_lattice_table() -> None:
    lattice = Path(__file__).resolve().parents[2] / "examples" / "lattice.toml"
    with pytest.raises(ScenarioError) as e:
        woodpile.sensitivity(Scenario.load(lattice))
    assert e.value.field == "lattice"
    assert "[lattice]" in str(e.value)


def test_evaluate_of_none_names_the_entry() -> None:
    with pytest.raises(TypeError, match=r"scenarios\[1\]"):
        woodpile.evaluate([Scenario.from_toml(CHAIN), None])  # type: ignore[list-item]


def test_sweep_of_a_list_is_a_type_error_naming_grid() -> None:
    with pytest.raises(TypeError, match="grid"):
        woodpile.sweep(Scenario.from_toml(CHAIN), ["excitation.velocity_m_s"])  # type: ignore[arg-type]


def test_spectrum_of_a_two_dimensional_array_names_signal() -> None:
    with pytest.raises(ScenarioError) as e:
        woodpile.spectrum(np.zeros((16, 3)), 1e-6)
    assert e.value.field == "signal"


def test_nan_in_a_scenario_names_its_key() -> None:
    s = Scenario.from_toml(CHAIN)
    with pytest.raises(ScenarioError) as e:
        s.replace(**{"excitation.velocity_m_s": float("nan")})
    assert e.value.field == "excitation.velocity_m_s"
    d = s.to_dict()
    d["run"]["duration_s"] = np.float64("nan")
    with pytest.raises(ScenarioError) as e:
        Scenario.from_dict(d)
    assert e.value.field == "run.duration_s"


FIT = """scenario = "model.toml"
[[data]]
file = "m.csv"
signals = { sensor_n = "contact_2_n" }
[fit]
parameters = [{ key = "excitation.velocity_m_s", bounds = [1.5, 2.5] }]
starts = 1000000000
"""


def write_fit(tmp_path: Path) -> Path:
    (tmp_path / "model.toml").write_text("[chain]\nrods_mm = [80, 40]\n[run]\nduration_s = 1e-4\n")
    (tmp_path / "m.csv").write_text("time_s,sensor_n\n0,0\n1e-6,0.5\n2e-6,1.0\n3e-6,1.5\n")
    (tmp_path / "fit.toml").write_text(FIT)
    return tmp_path / "fit.toml"


def test_fit_negative_threads_is_named(tmp_path: Path) -> None:
    with pytest.raises(ScenarioError) as e:
        woodpile.fit(write_fit(tmp_path), threads=-1)
    assert e.value.field == "threads"


def test_fit_of_a_billion_starts_is_refused_before_any_run(tmp_path: Path) -> None:
    with pytest.raises(LimitError) as e:
        woodpile.fit(write_fit(tmp_path))
    assert "allow_large=True" in str(e.value)
    assert e.value.field == "fit.starts × fit.max_evaluations"


@pytest.mark.parametrize(
    "call, field",
    [
        (lambda: saltelli_unit_cube(-1, [0]), "base_samples"),
        (lambda: saltelli_unit_cube(8, [0], seed=-1), "seed"),
        (lambda: sobol_indices([1.0] * 24, -8, 1), "base_samples"),
        (lambda: sobol_indices([1.0] * 24, 8, 1, resamples=-1), "resamples"),
    ],
)
def test_the_estimators_name_a_negative_count(call: Callable[[], object], field: str) -> None:
    with pytest.raises(ScenarioError) as e:
        call()
    assert e.value.field == field
