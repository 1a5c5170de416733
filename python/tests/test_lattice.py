"""Claims of lattices in Python (docs/physics.md §16): ``woodpile.Scenario`` reads a
``[lattice]`` scenario and ``woodpile.simulate`` runs it on the command line's code path (the same
run directory, byte for byte), the contacts table names every contact as ``run.json`` does, a
centred strike gives mirror-equal forces, and bad input raises ``woodpile.errors`` classes naming
the key.

Lattices are kept small (3 × 3 rods, 2 elements per half rod, 0.1 ms) so the suite takes seconds.
"""

import filecmp
import json
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

import woodpile
from woodpile.errors import InaccurateRunError, OverwriteError, ScenarioError, StateError

REPO = Path(__file__).resolve().parents[2]

LATTICE = """description = "three layers of three quartz rods"
[lattice]
layers = [
  { rods = 3, pitch_mm = 20.0, length_mm = 80.0, diameter_mm = 5.0, material = "fused-quartz" },
  { rods = 3 },
  { rods = 3 },
]
rod = { fe_elements = 2 }
[excitation]
kind = "impact"
at_mm = [0.0, 0.0]
[run]
duration_s = 1e-4
"""


def _cli():
    """The `woodpile` binary: $WOODPILE_BIN, else the one `cargo test` / `cargo build` left in
    target/ (CI runs `cargo test --workspace` before pytest)."""
    candidates = [os.environ.get("WOODPILE_BIN")]
    candidates += [str(REPO / "target" / p / "woodpile") for p in ("debug", "release")]
    candidates += [shutil.which("woodpile")]
    for c in candidates:
        if c and Path(c).is_file():
            return c
    pytest.skip("no woodpile binary: run `cargo build -p woodpile-cli` (CI builds it before pytest)")


def test_a_lattice_text_makes_a_lattice_scenario_with_every_default_written():
    """Scenario() of a [lattice] text is a lattice's scenario (one Scenario class, ``is_lattice``);
    completion fills the lower layers from the layer above and the defaults (8 elements unless
    given, 90° crossings)."""
    s = woodpile.Scenario(LATTICE)
    assert type(s) is woodpile.Scenario and s.is_lattice
    d = s.to_dict()
    assert [layer["length_mm"] for layer in d["lattice"]["layers"]] == [80.0, 80.0, 80.0]
    assert [layer.get("angle_deg") for layer in d["lattice"]["layers"]] == [None, 90.0, 90.0]
    assert d["lattice"]["rod"] == {"fe_elements": 2}
    assert woodpile.Scenario.from_dict(d) == s
    assert not woodpile.Scenario.builtin("paper-impact-80mm").is_lattice


def test_the_python_run_directory_is_the_command_lines_byte_for_byte(tmp_path):
    """A lattice's Run.save writes what `woodpile simulate` writes for the same file: every file of
    the run directory equal byte for byte (run.json, CSV, NPY), and summary.json but for its
    ``wall_time_s`` (a clock reading)."""
    path = tmp_path / "lat.toml"
    path.write_text(LATTICE)
    done = subprocess.run(
        [_cli(), "simulate", str(path), "--out", str(tmp_path / "cli"), "--quiet"],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    run = woodpile.simulate(woodpile.Scenario.load(path))
    run.save(tmp_path / "py")
    files = sorted(p.name for p in (tmp_path / "cli").iterdir())
    assert files == sorted(p.name for p in (tmp_path / "py").iterdir())
    assert "supports.csv" in files and "forces_n.npy" in files
    match, mismatch, errors = filecmp.cmpfiles(tmp_path / "cli", tmp_path / "py", files, shallow=False)
    assert mismatch in ([], ["summary.json"]) and errors == [], (mismatch, errors)
    summaries = [json.loads((tmp_path / d / "summary.json").read_text()) for d in ("cli", "py")]
    for s in summaries:
        s.pop("wall_time_s")
    assert summaries[0] == summaries[1]
    back = woodpile.load_run(tmp_path / "cli")
    assert type(back) is type(run) is woodpile.Run and back.structure == "lattice"
    np.testing.assert_array_equal(back.forces_n, run.forces_n)
    np.testing.assert_array_equal(back.energy_j, run.energy_j)
    np.testing.assert_array_equal(back.wall_energy_j, run.wall_energy_j)
    assert back.supports == run.supports and back.rods_per_layer == [3, 3, 3]
    assert back.contacts.equals(run.contacts)
    with pytest.raises(OverwriteError):
        run.save(tmp_path / "py")


def test_contacts_table_supports_and_transmitted_force_agree():
    """The contacts table lists the striker's contact, the 9 + 9 crossings and 3 supports in
    output order with the documented columns; the supports are layer L + 1 = 4; the transmitted
    force is the sum of the supports' columns; the peaks of summary.json (tracked at every step's
    end) and the 1 µs samples' maxima (dense output) agree to 1e-3 of the largest force: measured,
    the peaks exceed the samples by up to 6e-4 of it (the grid misses a peak's instant) and a
    sample exceeds a step-end peak by up to 2e-5 of it (the interpolant between step ends)."""
    run = woodpile.simulate(woodpile.Scenario(LATTICE))
    c = run.contacts
    assert list(c.columns) == ["layer_above", "rod_above", "layer_below", "rod_below", "x_mm", "y_mm"]
    assert len(c) == 1 + 9 + 9 + 3 == run.forces_n.shape[1]
    assert (c.loc[0, "layer_above"], c.loc[0, "layer_below"], c.loc[0, "rod_below"]) == (0, 1, 2)
    assert run.supports == [19, 20, 21]
    assert list(c.loc[run.supports, "layer_below"]) == [4, 4, 4]
    assert list(c.loc[run.supports, "rod_below"]) == [1, 2, 3]
    np.testing.assert_array_equal(run.transmitted_n, run.forces_n[:, 19:22].sum(axis=1))
    peaks = run.contact_peak_forces_n
    scale = peaks.max()
    assert peaks.shape == (22,)
    np.testing.assert_allclose(peaks, run.forces_n.max(axis=0), rtol=0, atol=1e-3 * scale)
    assert abs(run.transmitted_n.max() - run.transmitted_peak_force_n) <= 1e-3 * scale
    assert run.energy_max_relative_error < 1e-4
    frame = run.to_pandas()
    np.testing.assert_array_equal(frame["transmitted_n"].to_numpy(), run.transmitted_n)


def test_a_chain_and_a_lattice_give_one_run(tmp_path):
    """A chain's and a lattice's runs are one ``Run`` with the same arrays: the chain's contacts
    are a path (contact c joins layer c to c + 1, the wall layer N + 1), its one support the wall,
    so ``transmitted_n`` is the wall's force column exactly; each body's energy and the supports'
    halves sum to the lattice's total energy E(t) as the core audits it (``energy.csv``'s
    ``total_j``, printed to round-trip precision) within 1e-12 of its largest value (rounding of
    a sum of 10 terms); the arrays only one structure has raise ``StateError`` naming them."""
    chain = woodpile.simulate(woodpile.Scenario("[chain]\nrods_mm = [80, 40, 20]\n[run]\nduration_s = 2e-4\n"))
    lattice = woodpile.simulate(woodpile.Scenario(LATTICE))
    assert type(chain) is type(lattice) is woodpile.Run
    assert (chain.structure, lattice.structure) == ("chain", "lattice")
    c = chain.contacts
    assert list(c["layer_above"]) == [0, 1, 2, 3] and list(c["layer_below"]) == [1, 2, 3, 4]
    assert chain.supports == [3]
    np.testing.assert_array_equal(chain.transmitted_n, chain.forces_n[:, 3])
    for run in (chain, lattice):
        assert run.energy_j.shape[0] == run.time_s.shape[0] == run.wall_energy_j.shape[0]
        assert run.summary["energy"]["max_relative_error"] == run.energy_max_relative_error
    table = np.loadtxt(lattice.save(tmp_path / "lat") / "energy.csv", delimiter=",", skiprows=1, ndmin=2)
    total = table[:, 1]
    assert np.abs(lattice.total_energy_j - total).max() <= 1e-12 * np.abs(total).max()
    with pytest.raises(StateError, match="displacements_m"):
        lattice.displacements_m
    with pytest.raises(StateError, match="contact_energy_j"):
        chain.contact_energy_j


def test_one_accuracy_rule_for_chains_in_python():
    """As ``woodpile simulate``, Python refuses a chain's run whose energy balance is off by more
    than 1e-2 (RK4 at Δt = 5 µs on five rods: 5e-2, measured by the command line's claim),
    raising ``InaccurateRunError`` with the reference energy in its words, and keeps it with
    ``allow_inaccurate=True`` (flagged in its summary)."""
    coarse = woodpile.Scenario(
        "[chain]\nrods_mm = [80, 40, 20, 30, 50]\n[run]\nduration_s = 2e-4\ntime_step_s = 5e-6\n"
    )
    with pytest.raises(InaccurateRunError, match="the larger of the initial energy and the largest work done"):
        woodpile.simulate(coarse)
    kept = woodpile.simulate(coarse, allow_inaccurate=True)
    assert kept.summary["energy_balance_ok"] is False and kept.energy_max_relative_error > 1e-2


def test_a_run_too_short_for_the_wave_says_so():
    """Over 5 µs the wave has not reached the supports (their force below a thousandth of the
    striker's): ``wave_arrived`` is False, so ``transmitted_peak_force_n`` means nothing; over
    the suite's 0.1 ms it is True."""
    short = woodpile.simulate(woodpile.Scenario(LATTICE.replace("duration_s = 1e-4", "duration_s = 5e-6")))
    assert short.wave_arrived is False
    assert woodpile.simulate(woodpile.Scenario(LATTICE)).wave_arrived is True


def test_a_centred_strike_gives_mirror_equal_forces():
    """Struck at the centre, the lattice is symmetric under x → −x: contact forces at mirrored
    crossings are equal to 1e-9 of the largest force (the claim core's lattice tests make to
    1e-12; here the contacts are matched by their coordinates read from the table, to 1e-9 mm),
    and the outer supports carry equal forces."""
    run = woodpile.simulate(woodpile.Scenario(LATTICE))
    c = run.contacts
    scale = np.abs(run.forces_n).max()
    for k in range(len(c)):
        x, y = c.loc[k, "x_mm"], c.loc[k, "y_mm"]
        same_pair = (c["layer_above"] == c.loc[k, "layer_above"]) & (c["layer_below"] == c.loc[k, "layer_below"])
        mirror = c[same_pair & np.isclose(c["x_mm"], -x, atol=1e-9) & np.isclose(c["y_mm"], y, atol=1e-9)]
        assert len(mirror) == 1, f"contact {k} at ({x}, {y}) has no mirror image"
        j = mirror.index[0]
        np.testing.assert_allclose(run.forces_n[:, k], run.forces_n[:, j], rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(run.support_forces_n[:, 0], run.support_forces_n[:, 2], rtol=0, atol=1e-9 * scale)


def test_bad_lattice_input_names_the_key():
    """An impact point off the top layer, layers that do not touch and a support outside every
    bottom rod raise ScenarioError with the dotted key, the value and what is valid."""
    off = LATTICE.replace("at_mm = [0.0, 0.0]", "at_mm = [0.0, 200.0]")
    with pytest.raises(ScenarioError) as e:
        woodpile.Scenario(off)
    assert e.value.field == "excitation.at_mm"
    apart = LATTICE.replace("{ rods = 3 },\n  { rods = 3 },", "{ rods = 2, pitch_mm = 100.0 },\n  { rods = 2 },")
    with pytest.raises(ScenarioError) as e:
        woodpile.Scenario(apart)
    assert e.value.field is not None and e.value.field.startswith("lattice.layers[1]")
    assert e.value.value is not None and e.value.reason
    outside = LATTICE + '[wall]\nsupports = [{ x_mm = 500.0, y_mm = 0.0 }]\n'
    with pytest.raises(ScenarioError) as e:
        woodpile.Scenario(outside)
    assert e.value.field == "wall.supports[0]"
    with pytest.raises(ScenarioError) as e:
        woodpile.Scenario(LATTICE).replace(**{"lattice.rod.fe_elements": "four"})
    assert e.value.field == "lattice.rod.fe_elements"


def test_a_lattice_run_pickles_with_its_arrays():
    """A lattice's Run pickles (to come back from an executor) with its arrays and contacts."""
    import pickle

    run = woodpile.simulate(woodpile.Scenario(LATTICE).replace(**{"run.duration_s": 2e-5}))
    back = pickle.loads(pickle.dumps(run))
    np.testing.assert_array_equal(back.forces_n, run.forces_n)
    assert back.contacts.equals(run.contacts) and back.scenario == run.scenario


STUDY = """[lattice]
layers = [
  { rods = 3, pitch_mm = 16.0, length_mm = 60.0, diameter_mm = 5.0, material = "fused-quartz" },
  { rods = 3 },
]
rod = { fe_elements = 2 }
[run]
duration_s = 1e-4
peak_tolerance = 1e-4
[design]
length_mm = { from_mm = 50.0, to_mm = 70.0, step_mm = 10.0 }
pitch_mm = [12.0, 16.0]
[ga]
population = 6
generations = 4
seed = 1
"""


def test_a_lattice_study_gives_the_command_lines_front(tmp_path):
    """woodpile.optimize of a lattice study and `woodpile optimize` give the same pareto.csv
    (every value exactly) and history (but wall time); each front scenario is a lattice's Scenario
    whose run gives its row's transmitted force and mass exactly."""
    import pandas as pd

    config = tmp_path / "study.toml"
    config.write_text(STUDY)
    out = tmp_path / "o"
    done = subprocess.run(
        [_cli(), "optimize", str(config), "--out", str(out), "--seed", "3", "--quiet"],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    result = woodpile.optimize(config, seed=3, checkpoint=tmp_path / "cp.json")
    assert isinstance(result, woodpile.ParetoResult)
    pd.testing.assert_frame_equal(result.front, pd.read_csv(out / "pareto.csv"), check_exact=True)
    cli_history = pd.read_csv(out / "history.csv").set_index("generation")
    pd.testing.assert_frame_equal(
        result.history.drop(columns=["elapsed_s"]), cli_history.drop(columns=["elapsed_s"]), check_exact=True
    )
    assert list(result.front.columns) == [
        "transmitted-force", "total-mass", "layer_1_length_mm", "layer_2_length_mm", "pitch_mm"
    ]
    scenario = result.scenarios[0]
    assert isinstance(scenario, woodpile.Scenario) and scenario.is_lattice
    run = woodpile.simulate(scenario)
    assert run.transmitted_peak_force_n == result.front["transmitted-force"].iloc[0]
    assert run.lattice_mass_kg == result.front["total-mass"].iloc[0]
    again = woodpile.optimize(config, seed=3, checkpoint=tmp_path / "cp.json")
    pd.testing.assert_frame_equal(again.front, result.front, check_exact=True)


def test_bad_lattice_study_input_names_the_keyword():
    """An objective a lattice study cannot minimise is refused naming the keyword argument."""
    with pytest.raises(ScenarioError) as e:
        woodpile.optimize({"lattice": {"layers": [{"rods": 1, "length_mm": 60.0}]}}, objectives=["layers"])
    assert e.value.field == "objectives[0]"


DRIVEN = LATTICE.replace(
    'kind = "impact"\nat_mm = [0.0, 0.0]',
    'kind = "drive"\ndrive = "displacement"\nsignal = "harmonic"\namplitude = 3e-7\nfrequency_hz = 1e4\n'
    'ramp_s = 3e-5\ntip = { kind = "cap", material = "steel", cap_radius_mm = 5.0 }\n'
    '[damping]\ncontact = "viscoelastic"\nviscous_time_s = 1e-7\n[preload]\nforce_n = 9.0',
)


def test_contact_energies_and_dissipation_over_time(tmp_path):
    """A displacement drive on the top-layer crossings (9 tips, layer 0 of the contacts), with
    viscoelastic contacts: ``contact_energy_j`` and ``contact_dissipated_j`` are (S, C) arrays in
    ``contacts`` order; the contacts' potentials never exceed the total energy (the rest is the
    rods' kinetic and strain energy); every contact's dissipated energy never falls (to 1e-18 J)
    and its last row is ``summary.json``'s per-contact total (within 1e-12 of their sum: the last
    sample is the final state, interpolated); a run read
    back from its directory has the same arrays, bit for bit."""
    run = woodpile.simulate(woodpile.Scenario(DRIVEN, name="driven"))
    s, c = run.forces_n.shape
    assert (run.contacts["layer_above"] == 0).sum() == 9
    assert run.contact_energy_j.shape == (s, c)
    assert run.contact_dissipated_j is not None and run.contact_dissipated_j.shape == (s, c)
    assert np.all(run.contact_energy_j.sum(axis=1) <= run.total_energy_j * (1 + 1e-12))
    assert run.contact_energy_j[:, :9].max() > 0.0, "the tips hold energy"
    assert np.all(np.diff(run.contact_dissipated_j, axis=0) >= -1e-18)
    totals = np.asarray(run.summary["contact_dissipated_j"])
    assert totals.sum() > 0.0
    assert np.abs(run.contact_dissipated_j[-1] - totals).max() <= 1e-12 * totals.sum()
    back = woodpile.load_run(run.save(tmp_path / "out"))
    assert np.array_equal(back.contact_energy_j, run.contact_energy_j)
    assert back.contact_dissipated_j is not None
    assert np.array_equal(back.contact_dissipated_j, run.contact_dissipated_j)
    lossless = woodpile.simulate(woodpile.Scenario(LATTICE))
    assert lossless.contact_dissipated_j is None


def test_a_bad_actuator_tip_names_the_key():
    """A free tip under a displacement drive raises ScenarioError naming ``excitation.tip.kind``."""
    with pytest.raises(ScenarioError) as e:
        woodpile.Scenario(DRIVEN.replace('tip = { kind = "cap", material = "steel", cap_radius_mm = 5.0 }', 'tip = { kind = "free" }'))
    assert e.value.field == "excitation.tip.kind"


def test_the_actuator_rest_position_is_a_float_under_a_displacement_drive_only(tmp_path):
    """A lattice run's ``actuator_rest_m`` (``summary.json``'s ``actuator_rest_m``) is the rigid
    actuator's static position u* [m], downward: a float under the displacement drive of 9 N on the
    9 top crossings, the same read back from the run's directory, and above every tip's point —
    each tip's Hertz overlap (F_i/β_i)^{2/3} (static force and β from the directory) is less than
    u*, the rest u* − δ_i = w_i > 0 being how far the preload pressed its point down. None under
    a force drive and an impact (no actuator)."""
    run = woodpile.simulate(woodpile.Scenario(DRIVEN, name="driven"))
    u = run.actuator_rest_m
    assert isinstance(u, float) and np.isfinite(u) and u > 0.0
    assert run.summary["actuator_rest_m"] == u
    back = woodpile.load_run(run.save(tmp_path / "out"))
    assert back.actuator_rest_m == u
    assert back.run_info is not None
    betas = np.asarray(back.run_info["contact_betas_n_per_m1_5"])[:9]
    forces = np.asarray(back.summary["static_contact_forces_n"])[:9]
    assert forces.min() > 0.0
    overlaps = (forces / betas) ** (2.0 / 3.0)
    assert np.all(overlaps < u), f"tips' overlaps {overlaps} against u* = {u}"
    force = DRIVEN.replace('drive = "displacement"', 'drive = "force"').replace(
        'tip = { kind = "cap", material = "steel", cap_radius_mm = 5.0 }\n', ""
    )
    forced = woodpile.simulate(woodpile.Scenario(force))
    assert "static_contact_forces_n" in forced.summary and forced.actuator_rest_m is None
    assert woodpile.simulate(woodpile.Scenario(LATTICE)).actuator_rest_m is None
