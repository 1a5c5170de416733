"""Claims: ``woodpile.fit`` reads the CLI's fit file and returns the estimates as a DataFrame.

Noise-free signals simulated at restitution 0.85 and impact speed 1.98 m/s are fitted from 0.8
and 2.0 m/s back to the truth within 1e-6 relative (the data are the model itself: only the
optimiser's stopping test, 1e-10, limits it), with finite 95 % intervals around them; a bound with
lower >= upper raises ``ScenarioError`` naming the key as written in the fit file.
"""

from pathlib import Path

import pandas as pd
import pytest

import woodpile
from woodpile import ScenarioError

MODEL = """[chain]
rods_mm = [80, 40, 20]
[excitation]
velocity_m_s = 2.0
[damping]
contact = "restitution"
restitution = 0.8
[run]
duration_s = 3e-4
"""

FIT = """scenario = "model.toml"
[[data]]
file = "measured.csv"
signals = {{ wall_n = "contact_3_n" }}
[fit]
parameters = [
  {{ key = "damping.restitution", bounds = {restitution} }},
  {{ key = "excitation.velocity_m_s", bounds = [1.5, 2.5] }},
]
starts = 1
"""


def measured(tmp_path: Path) -> None:
    truth = woodpile.Scenario.from_toml(MODEL).replace(
        **{"damping.restitution": 0.85, "excitation.velocity_m_s": 1.98}
    )
    run = woodpile.simulate(truth)
    pd.DataFrame({"time_s": run.time_s, "wall_n": run.forces_n[:, 3]}).to_csv(
        tmp_path / "measured.csv", index=False
    )
    (tmp_path / "model.toml").write_text(MODEL)


def test_fit_recovers_the_truth_as_a_dataframe(tmp_path: Path) -> None:
    measured(tmp_path)
    (tmp_path / "fit.toml").write_text(FIT.format(restitution="[0.6, 1.0]"))
    result = woodpile.fit(tmp_path / "fit.toml", tmp_path / "out")
    est = result.estimates
    assert list(est.index) == ["damping.restitution", "excitation.velocity_m_s"]
    for key, truth in [("damping.restitution", 0.85), ("excitation.velocity_m_s", 1.98)]:
        assert abs(est.loc[key, "estimate"] / truth - 1) < 1e-6
        # Noise-free: the interval is a rounding error wide, so only its order is checked.
        assert est.loc[key, "ci95_low"] <= est.loc[key, "estimate"] <= est.loc[key, "ci95_high"]
    assert result.correlation.shape == (2, 2)
    assert set(result.residuals["signal"]) == {"wall_n"}
    assert (tmp_path / "out" / "fitted.toml").is_file()


def test_bounds_in_the_wrong_order_name_the_key(tmp_path: Path) -> None:
    measured(tmp_path)
    (tmp_path / "fit.toml").write_text(FIT.format(restitution="[1.0, 0.6]"))
    with pytest.raises(ScenarioError) as e:
        woodpile.fit(tmp_path / "fit.toml")
    assert e.value.field == "fit.parameters[0].bounds"
