"""Claims: ``woodpile.sensitivity`` computes SALib's Sobol' estimators.

(1) On the same Saltelli matrix and outputs (the Ishigami function on woodpile's design, N = 512,
with and without groups), woodpile's S1 and ST equal SALib's ``sobol.analyze``
(``calc_second_order=False``) to 1e-10 absolute: the same formulas in another summation order,
indices of order 1 (rounding ~1e-15). The bootstrap intervals use other random resamples than
SALib's, so they are only asserted to agree within a factor 1.5 (both estimate the same spread from
100 resamples, each to about ±10 %).
(2) A study of a three-rod chain with two parameters returns the Saltelli matrix (N·(G + 2) rows
in SALib's layout: row AB_g differs from A only in group g's columns) and indices equal to
SALib's on its own ``attrs["outputs"]``, to 1e-10.
(3) Bad input raises ``ScenarioError`` naming the key: ``base_samples`` of 0 or not a power of
two, a scenario without ``[uncertainty]``; a study over 1e6 elements raises ``LimitError`` naming
``allow_large=True``.
"""

import math

import numpy as np
import pytest
from SALib.analyze import sobol as salib_sobol

import woodpile
from woodpile import ScenarioError, Scenario
from woodpile.sobol import saltelli_unit_cube, sobol_indices


def ishigami(x: np.ndarray) -> np.ndarray:
    return np.sin(x[:, 0]) + 7.0 * np.sin(x[:, 1]) ** 2 + 0.1 * x[:, 2] ** 4 * np.sin(x[:, 0])


@pytest.mark.parametrize("group_of", [[0, 1, 2], [0, 1, 0]])
def test_estimators_equal_salib(group_of: list[int]) -> None:
    n = 512
    u = np.array(saltelli_unit_cube(n, group_of, seed=3))
    groups = max(group_of) + 1
    assert u.shape == (n * (groups + 2), 3)
    y = ishigami(-math.pi + 2 * math.pi * u)
    ours = sobol_indices(y.tolist(), n, groups)
    problem = {"num_vars": 3, "names": ["x1", "x2", "x3"], "bounds": [[-math.pi, math.pi]] * 3}
    if groups < 3:
        problem["groups"] = [f"g{g}" for g in group_of]
    theirs = salib_sobol.analyze(problem, y, calc_second_order=False, seed=1)
    np.testing.assert_allclose(ours["S1"], theirs["S1"], rtol=0, atol=1e-10)
    np.testing.assert_allclose(ours["ST"], theirs["ST"], rtol=0, atol=1e-10)
    for key in ["S1_conf", "ST_conf"]:
        ratio = np.asarray(ours[key]) / np.asarray(theirs[key])
        assert np.all((ratio > 1 / 1.5) & (ratio < 1.5)), (key, ratio)


CHAIN = """[chain]
elements = [
  { kind = "rod", length_mm = 40.0 },
  { kind = "rod", length_mm = 60.0 },
  { kind = "rod", length_mm = 20.0 },
]
[run]
duration_s = 2e-4
[uncertainty]
rod_length_mm = { sd = 0.5 }
impact_velocity_m_s = { uniform = [1.8, 2.2] }
"""


def test_chain_study_matches_salib_on_its_outputs() -> None:
    n = 16
    df = woodpile.sensitivity(Scenario.from_toml(CHAIN), n, seed=2)
    assert list(df.columns) == woodpile.INDEX_COLUMNS
    samples, outputs = df.attrs["samples"], df.attrs["outputs"]
    cols = ["rod_length_mm[1]", "rod_length_mm[2]", "rod_length_mm[3]", "impact_velocity_m_s"]
    assert list(samples.columns) == cols
    assert samples.shape == (n * 4, 4) and len(outputs) == n * 4
    x = samples.to_numpy()
    for k in range(n):
        a, ab0, ab1, b = x[4 * k : 4 * k + 4]
        assert np.array_equal(ab0[:3], b[:3]) and ab0[3] == a[3]
        assert np.array_equal(ab1[:3], a[:3]) and ab1[3] == b[3]
    assert df.attrs["parameters"] == ["rod_length_mm", "impact_velocity_m_s"]
    problem = {
        "num_vars": 4,
        "names": cols,
        "bounds": [[0, 1]] * 4,
        "groups": ["rod_length_mm"] * 3 + ["impact_velocity_m_s"],
    }
    for figure in ["transmitted_peak_force_n", "incident_peak_force_n"]:
        theirs = salib_sobol.analyze(problem, outputs[figure].to_numpy(), calc_second_order=False)
        ours = df[df["figure"] == figure]
        assert list(ours["parameter"]) == ["rod_length_mm", "impact_velocity_m_s"]
        np.testing.assert_allclose(ours["S1"], theirs["S1"], rtol=0, atol=1e-10)
        np.testing.assert_allclose(ours["ST"], theirs["ST"], rtol=0, atol=1e-10)


@pytest.mark.parametrize("n", [0, 48])
def test_base_samples_refused(n: int) -> None:
    with pytest.raises(ScenarioError) as e:
        woodpile.sensitivity(Scenario.from_toml(CHAIN), n)
    assert e.value.field == "base_samples" and e.value.value == str(n)
    assert "power of two" in str(e.value.reason)


def test_no_uncertainty_refused() -> None:
    with pytest.raises(ScenarioError) as e:
        woodpile.sensitivity(Scenario.from_toml("[chain]\nrods_mm = [80, 40]\n"), 16)
    assert e.value.field == "uncertainty"


def test_oversized_study_refused_before_any_run() -> None:
    # 131072 × (2 + 2) runs × 3 elements: over the 1e6-element limit.
    with pytest.raises(woodpile.LimitError) as e:
        woodpile.sensitivity(Scenario.from_toml(CHAIN), 131072)
    assert "allow_large=True" in str(e.value)
