"""The documentation site's generated reference says what the code does.

Claim 1: the scenario-key page lists every key that `woodpile scenario NAME` writes, for every
built-in NAME. The page is generated from the key table (scripts/docs/reference.py); a key the
emitted files hold but the table lacks would be undocumented. The built-in scenarios' TOML
are read through the extension, which completes them with woodpile-io's code, as `woodpile
scenario NAME` does.

Claim 2: the output-file page (docs/reference/outputs.md) names every file a run directory holds,
for an impact (the case with the most files: the striker's).
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import woodpile

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts" / "docs"))
import reference  # noqa: E402


def test_key_page_lists_every_key_of_every_builtin_scenario() -> None:
    page = reference.scenario_keys_markdown()
    listed = set(re.findall(r"^\| `([^`]+)` \|", page, flags=re.M))
    assert len(listed) == len(woodpile.scenario_keys())
    names = woodpile.builtin_scenarios()
    assert len(names) >= 10
    for name in names:
        written = reference.scenario_key_names(woodpile.Scenario.builtin(name).to_dict())
        missing = sorted(written - listed)
        assert not missing, f"{name}: keys written but not on the key page: {missing}"


def test_outputs_page_names_every_file_of_a_run_directory(tmp_path: Path) -> None:
    page = (ROOT / "docs" / "reference" / "outputs.md").read_text()
    scenario = woodpile.Scenario.builtin("paper-impact-80mm").replace(**{"run.duration_s": 1e-4})
    directory = woodpile.simulate(scenario).save(tmp_path / "run")
    files = sorted(p.name for p in directory.iterdir())
    assert "striker.npy" in files and "summary.json" in files
    unnamed = [f for f in files if f"`{f}`" not in page]
    assert not unnamed, f"files of a run directory not on docs/reference/outputs.md: {unnamed}"
