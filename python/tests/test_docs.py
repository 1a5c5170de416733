"""The documentation site's generated reference says what the code does.

Claim 1: the scenario-key page lists every key that `woodpile scenario NAME` writes, for every
built-in NAME. The page is generated from the key table (scripts/docs/reference.py); a key the
emitted files hold but the table lacks would be undocumented. The built-in scenarios' TOML
are read through the extension, which completes them with woodpile-io's code, as `woodpile
scenario NAME` does.

Claim 2: the output-file page (docs/reference/outputs.md) names every file a run directory holds,
every key of its summary.json and every column of its CSV files (a numbered column by its first
number: `contact_0_n`), for a preloaded impact with damping (the case with the most of them: the
striker's files, the static forces and the dissipated energy); and its lattice section names
every file, summary key and CSV column of a damped lattice run under a displacement drive.
"""

from __future__ import annotations

import json
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


def test_key_page_lists_every_lattice_key() -> None:
    page = reference.lattice_keys_markdown()
    listed = set(re.findall(r"^\| `([^`]+)` \|", page, flags=re.M))
    keys = {k.name for k in woodpile.lattice_keys()}
    assert listed == keys
    assert {"lattice.layers[].lengths_mm", "lattice.layers[].offsets_mm", "lattice.rod.modes"} <= keys


def test_outputs_page_names_every_file_of_a_run_directory(tmp_path: Path) -> None:
    page = (ROOT / "docs" / "reference" / "outputs.md").read_text()
    scenario = woodpile.Scenario.builtin("lab-impact-40mm").replace(
        **{"run.duration_s": 1e-4, "preload.force_n": 5.0}
    )
    directory = woodpile.simulate(scenario).save(tmp_path / "run")
    files = sorted(p.name for p in directory.iterdir())
    assert "striker.npy" in files and "summary.json" in files
    unnamed = [f for f in files if f"`{f}`" not in page]
    assert not unnamed, f"files of a run directory not on docs/reference/outputs.md: {unnamed}"

    summary = json.loads((directory / "summary.json").read_text())
    assert "static_contact_forces_n" in summary
    keys = list(summary) + [k for v in summary.values() if isinstance(v, dict) for k in v]
    unnamed = [k for k in keys if f"`{k}`" not in page]
    assert not unnamed, f"summary.json keys not on docs/reference/outputs.md: {unnamed}"

    columns: set[str] = set()
    for csv in directory.glob("*.csv"):
        header = csv.read_text().splitlines()[0].split(",")
        first: dict[tuple[str, str], int] = {}
        for name in header:
            m = re.fullmatch(r"([a-z]+)_(\d+)_([a-z_]+)", name)
            if m:
                key = (m.group(1), m.group(3))
                first[key] = min(first.get(key, int(m.group(2))), int(m.group(2)))
            else:
                columns.add(name)
        columns |= {f"{a}_{i}_{b}" for (a, b), i in first.items()}
    unnamed = sorted(c for c in columns if c not in page)
    assert not unnamed, f"CSV columns not on docs/reference/outputs.md: {unnamed}"


def test_outputs_page_names_every_file_of_a_lattice_run(tmp_path: Path) -> None:
    """The lattice section of the output-file page names every file of a damped lattice run
    under a displacement drive (the case with the most files: the actuator's column, the contacts'
    dissipated energies) and every column of its CSV files, a numbered column by its first
    numbers (`contact_0_n`, `layer_1_rod_1_j`)."""
    page = (ROOT / "docs" / "reference" / "outputs.md").read_text()
    section = page.split("## A lattice run directory", 1)[1].split("\n## ", 1)[0]
    scenario = woodpile.Scenario(
        """[lattice]
layers = [{ rods = 2, pitch_mm = 20.0, length_mm = 40.0 }, { rods = 2 }]
rod = { fe_elements = 2 }
[excitation]
kind = "drive"
drive = "displacement"
signal = "harmonic"
amplitude = 1e-7
frequency_hz = 1e4
[damping]
modal_ratio = 0.01
[preload]
force_n = 2.0
[run]
duration_s = 5e-5
"""
    )
    directory = woodpile.simulate(scenario).save(tmp_path / "lat")
    files = sorted(p.name for p in directory.iterdir())
    assert "contact_dissipated_j.npy" in files and "contact_energy_j.npy" in files
    unnamed = [f for f in files if f"`{f}`" not in section]
    assert not unnamed, f"files of a lattice run not in the lattice section of outputs.md: {unnamed}"
    summary = json.loads((directory / "summary.json").read_text())
    keys = list(summary) + [k for v in summary.values() if isinstance(v, dict) for k in v]
    unnamed = [k for k in keys if f"`{k}`" not in section]
    assert not unnamed, f"lattice summary.json keys not in outputs.md: {unnamed}"
    first: dict[str, tuple[tuple[int, ...], str]] = {}
    for csv in directory.glob("*.csv"):
        for name in csv.read_text().splitlines()[0].split(","):
            numbers = tuple(int(n) for n in re.findall(r"\d+", name))
            shape = re.sub(r"\d+", "#", name)
            if shape not in first or numbers < first[shape][0]:
                first[shape] = (numbers, name)
    unnamed = sorted(name for _, name in first.values() if name not in section)
    assert not unnamed, f"lattice CSV columns not in outputs.md: {unnamed}"
