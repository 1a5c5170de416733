"""Claims: the Python package takes the values a notebook has and refuses the rest by name.

NumPy scalars and arrays are scenario values (as the numbers they hold: the run equals the one
from plain floats, bit for bit); an object that is no scenario value is a ``ScenarioError`` naming
its dotted key; ``simulate`` of something that is no scenario is a ``TypeError``; a sweep over a
string (which Python would iterate letter by letter) is refused naming the key; a GA seed that is
no count names ``seed``; a run pickles (to come back from an executor) and keeps its numbers; a
sweep value the scenario refuses is a row whose ``error`` names the key, the other rows run.
"""

import numpy as np
import pytest

import woodpile
from woodpile import ScenarioError


def short(**changes: object) -> woodpile.Scenario:
    base = woodpile.Scenario.builtin("paper-impact-80mm")
    return base.replace(**{"run.duration_s": 2e-4, "run.sample_interval_s": 2e-4, **changes})


def test_numpy_scalars_and_arrays_are_scenario_values():
    plain = short(**{"chain.rods_mm": [80, 40, 20], "excitation.velocity_m_s": 1.5})
    numpy = short(**{"chain.rods_mm": np.array([80, 40, 20]), "excitation.velocity_m_s": np.float64(1.5)})
    assert numpy == plain
    a, b = woodpile.simulate(plain).summary, woodpile.simulate(numpy).summary
    assert a["transmitted_peak_force_n"] == b["transmitted_peak_force_n"]


def test_an_object_that_is_no_value_names_its_key():
    with pytest.raises(ScenarioError) as e:
        short(**{"excitation.velocity_m_s": object()})
    assert e.value.field == "excitation.velocity_m_s"
    assert "object" in str(e.value)


def test_simulate_of_no_scenario_is_a_type_error():
    with pytest.raises(TypeError, match="Scenario"):
        woodpile.simulate(None)  # type: ignore[arg-type]


def test_a_sweep_over_a_string_is_refused_by_key():
    with pytest.raises(ScenarioError) as e:
        woodpile.sweep(short(), {"run.integrator": "rk4"})  # type: ignore[dict-item]
    assert e.value.field == "run.integrator"


@pytest.mark.parametrize("seed", [-1, 2**64, 1.5])
def test_a_seed_that_is_no_count_names_the_argument(seed: object):
    with pytest.raises(ScenarioError) as e:
        woodpile.BreederGA("paper-impact", seed=seed)  # type: ignore[arg-type]
    assert e.value.field == "seed"


def test_a_run_pickles_with_its_arrays_summary_and_scenario(tmp_path):
    import pickle

    run = woodpile.simulate(short())
    back = pickle.loads(pickle.dumps(run))
    assert back.summary == run.summary
    assert np.array_equal(back.forces_n, run.forces_n)
    assert back.scenario == run.scenario
    with pytest.raises(woodpile.StateError):
        back.save(tmp_path / "never-written")
    assert not (tmp_path / "never-written").exists()


def test_a_sweep_value_the_scenario_refuses_is_an_error_row():
    table = woodpile.sweep(short(), {"excitation.velocity_m_s": [1.0, "fast", 2.0]})
    assert list(table["excitation.velocity_m_s"]) == [1.0, "fast", 2.0]
    assert table["error"].isna().tolist() == [True, False, True]
    assert "excitation.velocity_m_s" in table["error"][1]
    assert table["transmitted_peak_force_n"][2] > table["transmitted_peak_force_n"][0] > 0.0
