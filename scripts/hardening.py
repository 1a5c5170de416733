#!/usr/bin/env python3
"""Runs the bad-input and interruption cases that woodpile must survive, against the command line
and the Python package, and prints one line per case: its exit status (or exception), seconds,
and the verdict. A case passes when nothing panics (exit 101, "panicked at"), nothing hangs (over
its time limit), the exit status is the one stated, and the message names the key, option or
file it is about. Exit status: the number of failed cases (0: all passed).

    python3 scripts/hardening.py [--woodpile target/release/woodpile] [--only SUBSTRING]

Needs the built binary (`cargo build --release -p woodpile-cli`) and, for the Python cases,
the package installed in the interpreter that runs this script.
"""

from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import tempfile
import textwrap
import time
from dataclasses import dataclass, field
from pathlib import Path


@dataclass
class Case:
    name: str
    argv: list[str]                       # after the binary; or a shell line when shell=True
    codes: tuple[int, ...]                # accepted exit statuses
    needles: tuple[str, ...] = ()         # each must appear in stderr (or stdout)
    absent: tuple[str, ...] = ()          # none may appear in the output
    files: dict[str, str] = field(default_factory=dict)
    shell: bool = False
    timeout_s: float = 60.0
    interrupt_after_s: float | None = None  # send SIGINT then; the exit must follow within 2 s


SHORT = "[chain]\nrods_mm = [40, 30, 20]\n[run]\nduration_s = 2e-4\n"


def drive(extra: str) -> str:
    return (
        "[chain]\nrods_mm = [40, 30, 20]\n[preload]\nforce_n = 10.0\n[excitation]\n"
        'kind = "drive"\ndrive = "force"\nsignal = "harmonic"\n' + extra + "[run]\nduration_s = 2e-4\n"
    )


def lattice(layers: str = '{ rods = 3 },', extra: str = "") -> str:
    return (
        "[lattice]\nlayers = [\n"
        '  { rods = 3, pitch_mm = 20.0, length_mm = 80.0, diameter_mm = 5.0, material = "fused-quartz" },\n'
        "  " + layers + "\n]\nrod = { fe_elements = 2 }\n" + extra + "[run]\nduration_s = 2e-4\n"
    )


def blast(extra: str) -> str:
    return (
        '[chain]\nrods_mm = [40, 30, 20]\n[excitation]\nkind = "blast"\nprofile = "friedlander"\n'
        + extra + "[run]\nduration_s = 2e-4\n"
    )


SCATTERED = SHORT + "[uncertainty]\nimpact_velocity_m_s = { uniform = [1.8, 2.2] }\n"
MO = ('[design]\npositions = 4\ncatalogue_mm = [20, 40, 60]\n[run]\nduration_s = 3e-4\npeak_tolerance = 1e-4\n'
      '[ga]\nobjectives = ["transmitted-force", "total-mass"]\npopulation = 8\ngenerations = 2\n')
FIT_FILES = {"model.toml": "[chain]\nrods_mm = [80, 40]\n[run]\nduration_s = 1e-4\n",
             "m.csv": "time_s,sensor_n\n0,0\n1e-6,0.5\n2e-6,1.0\n3e-6,1.5\n"}


def fit_file(extra: str) -> str:
    return ('scenario = "model.toml"\n[[data]]\nfile = "m.csv"\nsignals = { sensor_n = "contact_2_n" }\n[fit]\n'
            'parameters = [{ key = "excitation.velocity_m_s", bounds = [1.5, 2.5] }]\n' + extra)


CLI_CASES = [
    Case("stdout full: scenario", ["scenario paper-impact-80mm > /dev/full"], (2,), ("standard output",), shell=True),
    Case("stdout full: scenarios", ["scenarios > /dev/full"], (2,), ("standard output",), shell=True),
    Case("stdout full: cells", ["cells > /dev/full"], (2,), ("standard output",), shell=True),
    Case("stdout full: simulate", ["simulate s.toml --out o > /dev/full"], (2,), ("standard output",), files={"s.toml": SHORT}, shell=True),
    # The scenario fits the pipe's buffer (written before head closes it: exit 0); the cell
    # table of many rods does not (exit 141, quietly).
    Case("closed pipe: scenario | head -c 10", ["scenario paper-impact-80mm | head -c 10 > /dev/null; exit ${PIPESTATUS[0]}"], (0, 141), shell=True),
    Case("closed pipe: simulate | head -c 10", ["simulate s.toml --out o | head -c 10 > /dev/null; exit ${PIPESTATUS[0]}"], (0, 141), files={"s.toml": SHORT}, shell=True),
    Case("positions = 100000", ["optimize", "c.toml", "--out", "o"], (2,), ("design.positions", "--allow-large"), files={"c.toml": "[design]\npositions = 100000\n"}),
    Case("population = 100000000", ["optimize", "c.toml", "--out", "o"], (2,), ("ga.population", "--allow-large"), files={"c.toml": "[ga]\npopulation = 100000000\n"}),
    Case("SIGINT during a long generation", ["optimize", "c.toml", "--out", "o", "--threads", "1"], (130,), ("interrupted",),
         files={"c.toml": '[run]\nintegrator = "rk4"\ntime_step_s = 1e-7\nduration_s = 2e-2\n[ga]\npopulation = 200\n'}, interrupt_after_s=2.0),
    Case("SIGINT during a long simulate", ["simulate", "s.toml", "--out", "o"], (130,), ("interrupted",),
         files={"s.toml": '[chain]\nrods_mm = [80, 80, 80, 80, 80]\n[run]\nduration_s = 10.0\nsample_interval_s = 10.0\n'}, interrupt_after_s=2.0),
    Case("drive amplitude 0", ["simulate", "s.toml", "--out", "o"], (0, 1, 2), ("amplitude",), absent=("ratio 6.0000",),
         files={"s.toml": drive("amplitude = 0.0\nfrequency_hz = 1000.0\n")}),
    Case("drive at 1 GHz", ["simulate", "s.toml", "--out", "o"], (0, 2), ("frequency_hz",),
         files={"s.toml": drive("amplitude = 0.1\nfrequency_hz = 1e9\n")}),
    Case("ramp longer than the run", ["simulate", "s.toml", "--out", "o"], (0, 2), ("ramp_s",),
         files={"s.toml": drive("amplitude = 0.1\nfrequency_hz = 1000.0\nramp_s = 1.0\n")}),
    Case("blast decay 1e300", ["simulate", "s.toml", "--out", "o"], (0, 1, 2), ("decay",),
         files={"s.toml": blast("peak_force_n = 100.0\nduration_s = 2e-4\ndecay = 1e300\n")}),
    Case("blast 1e300 N", ["simulate", "s.toml", "--out", "o"], (1, 2), ("load",), absent=("reduce run.time_step_s",),
         files={"s.toml": blast("peak_force_n = 1e300\nduration_s = 2e-4\n")}),
    Case("blast 1e9 N", ["simulate", "s.toml", "--out", "o"], (1, 2), ("load",), absent=("reduce run.time_step_s",),
         files={"s.toml": blast("peak_force_n = 1e9\nduration_s = 2e-4\n")}),
    Case("force drive 1e300 N", ["simulate", "s.toml", "--out", "o"], (1, 2), ("excitation.amplitude",),
         absent=("reduce run.time_step_s",),
         files={"s.toml": "[chain]\nrods_mm = [40, 30, 20]\n[excitation]\nkind = \"drive\"\ndrive = \"force\"\n"
                "signal = \"harmonic\"\namplitude = 1e300\nfrequency_hz = 1000.0\n[run]\nduration_s = 1e-4\n"}),
    Case("gravity 1e300 m/s2", ["simulate", "s.toml", "--out", "o"], (1, 2), ("gravity_m_s2",),
         absent=("reduce run.time_step_s",),
         files={"s.toml": "[chain]\nrods_mm = [40, 30, 20]\n[preload]\ngravity_m_s2 = 1e300\n[run]\nduration_s = 1e-4\n"}),
    Case("drop from 1e300 m", ["simulate", "s.toml", "--out", "o"], (1, 2), ("drop_height_m",),
         files={"s.toml": "[chain]\nrods_mm = [40, 30, 20]\n[excitation]\ndrop_height_m = 1e300\n"}),
    Case("duration 1e300 s", ["simulate", "s.toml", "--out", "o"], (2,), ("run.duration_s",),
         files={"s.toml": "[chain]\nrods_mm = [40, 30, 20]\n[run]\nduration_s = 1e300\n"}),
    Case("cells --rod 1e9", ["cells", "--rod", "1e9"], (2,), ("--rod",)),
    Case("cells --rod 0.001", ["cells", "--rod", "0.001"], (2,), ("--rod",), absent=("--modes",)),
    Case("cells --modes 2 without --rod", ["cells", "--modes", "2"], (2,), ("--rod",)),
    Case("cap radius 1e300 mm", ["simulate", "s.toml", "--out", "o"], (0, 1, 2), ("cap_radius_mm",),
         files={"s.toml": "[chain]\nrods_mm = [40, 30, 20]\n[wall]\ncap_radius_mm = 1e300\n[run]\nduration_s = 2e-4\n"}),
    Case("max_total_mass_g = 1", ["optimize", "c.toml", "--out", "o"], (2,), ("max_total_mass_g", " g"), absent=("_kg",),
         files={"c.toml": "[design.constraints]\nmax_total_mass_g = 1.0\n"}),
    Case("max_total_mass_g = nan", ["optimize", "c.toml", "--out", "o"], (2,), ("max_total_mass_g",), absent=("_kg",),
         files={"c.toml": "[design.constraints]\nmax_total_mass_g = nan\n"}),
    Case("positions = { min = 9, max = 4 }", ["optimize", "c.toml", "--out", "o"], (2,), ("design.positions.max", "min = 9"),
         files={"c.toml": "[design]\npositions = { min = 9, max = 4 }\n"}),
    Case("positions range: mass no design of min layers meets", ["optimize", "c.toml", "--out", "o"], (2,), ("max_total_mass_g", "8 layers"),
         files={"c.toml": "[design]\npositions = { min = 8, max = 24 }\n[design.constraints]\nmax_total_mass_g = 5.0\n"}),
    Case("negative --seed", ["optimize", "--scenario", "paper-impact", "--out", "o", "--seed", "-1"], (2,), ("--seed",), absent=("'-- -1'",)),
    Case("negative --threads", ["optimize", "--scenario", "paper-impact", "--out", "o", "--threads", "-1"], (2,), ("--threads",), absent=("'-- -1'",)),
    Case("negative --resolution-hz", ["transmission", "--scenario", "transmission-80mm", "--out", "o", "--resolution-hz", "-1"], (2,), ("--resolution-hz",), absent=("'-- -1'",)),
    Case("transmission --threshold-db 10", ["transmission", "--scenario", "transmission-80mm", "--out", "o", "--threshold-db", "10"], (2,), ("--threshold-db",)),
    Case("peak_tolerance = 1e-15", ["simulate", "s.toml", "--out", "o"], (2,), ("run.peak_tolerance",),
         files={"s.toml": "[chain]\nrods_mm = [40, 30, 20]\n[run]\npeak_tolerance = 1e-15\n"}),
    Case("duplicate resonator damping", ["simulate", "s.toml", "--out", "o"], (2,), ("damping.resonators",),
         files={"s.toml": "[chain]\nrods_mm = [40, 30, 20]\n[damping]\nresonators = [{ element = 1, resonator = 1, ratio = 0.1 }, { element = 1, resonator = 1, ratio = 0.2 }]\n"}),
    Case("lattice: supports = []", ["simulate", "s.toml", "--out", "o"], (2,), ("wall.supports",), absent=("transmitted",),
         files={"s.toml": lattice(extra='[wall]\nsupports = []\n')}),
    Case("lattice: length -80 mm", ["simulate", "s.toml", "--out", "o"], (2,), ("lattice.layers[1].length_mm", "-80"),
         files={"s.toml": lattice('{ rods = 3, length_mm = -80.0 },')}),
    Case("lattice: parallel layers", ["simulate", "s.toml", "--out", "o"], (2,), ("lattice.layers[1].angle_deg",),
         files={"s.toml": lattice('{ rods = 3, angle_deg = 180.0 },')}),
    Case("lattice: impact off the top layer", ["simulate", "s.toml", "--out", "o"], (2,), ("excitation.at_mm",),
         files={"s.toml": lattice(extra='[excitation]\nat_mm = [500.0, 0.0]\n')}),
    Case("lattice: at_mm = [1, 0, 0]", ["simulate", "s.toml", "--out", "o"], (2,), ("at_mm", "[x, y]"),
         files={"s.toml": lattice(extra='[excitation]\nat_mm = [1.0, 0.0, 0.0]\n')}),
    Case("lattice: two supports at one point", ["simulate", "s.toml", "--out", "o"], (2,), ("wall.supports[1]",),
         files={"s.toml": lattice(extra='[wall]\nsupports = [{ x_mm = 0.0, y_mm = 0.0 }, { x_mm = 0.0, y_mm = 0.0 }]\n')}),
    Case("lattice: rods 1e9 mm long", ["simulate", "s.toml", "--out", "o"], (2,), ("lattice.layers[0].length_mm",),
         files={"s.toml": lattice().replace("length_mm = 80.0", "length_mm = 1e9")}),
    Case("lattice: displacement drive", ["simulate", "s.toml", "--out", "o"], (0, 2), ("excitation",),
         files={"s.toml": lattice(extra='[excitation]\nkind = "drive"\ndrive = "displacement"\nsignal = "harmonic"\namplitude = 1e-7\nfrequency_hz = 2000.0\nramp_s = 1e-4\n')}),
    Case("SIGINT during a long lattice simulate", ["simulate", "s.toml", "--out", "o"], (130,), ("interrupted",),
         files={"s.toml": lattice().replace("duration_s = 2e-4", "duration_s = 10.0\nsample_interval_s = 10.0")}, interrupt_after_s=2.0),
    Case("lattice study: objective pressure", ["optimize", "c.toml", "--out", "o"], (2,), ("ga.objectives[0]",),
         files={"c.toml": lattice() + '[design]\nlength_mm = [60.0, 80.0]\n[ga]\nobjectives = ["pressure"]\n'}),
    # Studies and fits: sizes refused up front, lattices named, directories kept, nonsense refused.
    Case("--samples 1000000000", ["simulate", "s.toml", "--samples", "1000000000", "--out", "o"], (2,), ("--samples", "--allow-large"),
         files={"s.toml": SCATTERED}, timeout_s=10.0),
    Case("fit starts = 1000000000", ["fit", "f.toml", "--out", "o"], (2,), ("fit.starts", "--allow-large"),
         files={**FIT_FILES, "f.toml": fit_file("starts = 1000000000\n")}, timeout_s=10.0),
    Case("fit max_evaluations = 0", ["fit", "f.toml", "--out", "o"], (2,), ("fit.max_evaluations",),
         files={**FIT_FILES, "f.toml": fit_file("max_evaluations = 0\n")}),
    Case("fit to rounding noise", ["fit", "f.toml", "--out", "o"], (2,), ("data[0].signals.sensor_n", "rounding noise"),
         files={**FIT_FILES, "m.csv": "time_s,sensor_n\n0,1e-12\n1e-6,-2e-12\n", "f.toml": fit_file("starts = 1\n")}),
    Case("SIGINT during a long fit", ["fit", "f.toml", "--out", "o", "--threads", "1"], (130,), ("interrupted",),
         files={**FIT_FILES, "f.toml": fit_file("starts = 5000\n")}, interrupt_after_s=2.0),
    Case("sensitivity --base-samples 1", ["sensitivity", "s.toml", "--base-samples", "1", "--out", "o"], (2,), ("--base-samples", "at least 8"),
         files={"s.toml": SCATTERED}),
    Case("sensitivity --base-samples 2^22", ["sensitivity", "s.toml", "--base-samples", "4194304", "--out", "o"], (2,), ("--base-samples", "--allow-large"),
         absent=("uncertainty.samples",), files={"s.toml": SCATTERED}, timeout_s=10.0),
    Case("[uncertainty] rod_length_mm = { sd = 1e6 }", ["simulate", "s.toml", "--samples", "16", "--out", "o"], (2,), ("uncertainty.rod_length_mm", "row 1 of samples.csv"),
         files={"s.toml": '[chain]\nelements = [{ kind = "rod", length_mm = 40 }, { kind = "rod", length_mm = 30 }]\n[run]\nduration_s = 2e-4\n[uncertainty]\nrod_length_mm = { sd = 1e6 }\n'}),
    Case("[uncertainty] negative speed range", ["sensitivity", "s.toml", "--base-samples", "8", "--out", "o"], (2,), ("uncertainty.impact_velocity_m_s",),
         files={"s.toml": SHORT + "[uncertainty]\nimpact_velocity_m_s = { uniform = [-2.0, -1.0] }\n"}),
    Case("fit CSV with a column twice", ["fit", "f.toml", "--out", "o"], (2,), ("m.csv, line 1", "twice"),
         files={**FIT_FILES, "m.csv": "time_s,sensor_n,sensor_n\n0,0,1\n1e-6,0.5,1\n", "f.toml": fit_file("starts = 1\n")}),
    Case("fit CSV with a ragged row", ["fit", "f.toml", "--out", "o"], (2,), ("m.csv, line 3", "fields"),
         files={**FIT_FILES, "m.csv": "time_s,sensor_n\n0,0\n1e-6,0.5,7\n2e-6,1\n", "f.toml": fit_file("starts = 1\n")}),
    Case("fit parameters = []", ["fit", "f.toml", "--out", "o"], (2,), ("fit.parameters",),
         files={**FIT_FILES, "f.toml": fit_file("starts = 1\n").replace('[{ key = "excitation.velocity_m_s", bounds = [1.5, 2.5] }]', "[]")}),
    Case("fit of a record up to 1e6 s", ["fit", "f.toml", "--out", "o"], (2,), ("data", "steps"), absent=("every start point",),
         files={**FIT_FILES, "m.csv": "time_s,sensor_n\n0,0\n1e6,1\n", "f.toml": fit_file("starts = 1\n")}),
    Case("fit time_shift_s bounds of ±1000 s", ["fit", "f.toml", "--out", "o"], (2,), ("fit.time_shift_s.bounds",), absent=("every start point",),
         files={**FIT_FILES, "f.toml": fit_file("starts = 1\ntime_shift_s = { bounds = [-1000.0, 1000.0] }\n")}),
    Case("fit chain.elements[99] of a rods_mm chain", ["fit", "f.toml", "--out", "o"], (2,), ("chain.elements[99].diameter_mm", "rods_mm"), absent=("0 entries",),
         files={**FIT_FILES, "f.toml": fit_file("starts = 1\n").replace("excitation.velocity_m_s", "chain.elements[99].diameter_mm")}),
    Case("--samples -3", ["simulate", "s.toml", "--samples", "-3", "--out", "o"], (2,), ("--samples",), absent=("'-- -3'",), files={"s.toml": SCATTERED}),
    Case("--base-samples -4", ["sensitivity", "s.toml", "--base-samples", "-4", "--out", "o"], (2,), ("--base-samples",), absent=("'-- -4'",), files={"s.toml": SCATTERED}),
    Case("empty [uncertainty] with --samples", ["simulate", "s.toml", "--samples", "4", "--out", "o"], (2,), ("uncertainty", "scattered parameter"),
         files={"s.toml": SHORT + "[uncertainty]\n"}),
    *[Case(f"lattice given to {label}", argv, (2,), (f"{label} supports chains only", "[lattice]"), absent=("unknown field",),
           files={"l.toml": lattice(), **FIT_FILES, "f.toml": fit_file("starts = 1\n").replace("model.toml", "l.toml")})
      for label, argv in [("transmission", ["transmission", "l.toml", "--out", "o"]),
                          ("sensitivity", ["sensitivity", "l.toml", "--out", "o"]),
                          ("simulate --samples", ["simulate", "l.toml", "--samples", "4", "--out", "o"]),
                          ("fit", ["fit", "f.toml", "--out", "o"])]],
    Case("plot of a lattice study", ["optimize ls.toml --out lo --quiet && $W plot lo"], (0,), ("pareto_front",),
         files={"ls.toml": lattice() + '[design]\nlength_mm = [60.0, 80.0]\n[ga]\npopulation = 6\ngenerations = 2\n'}, shell=True),
    Case("plot of a pareto.csv with a NaN objective", ["optimize ls.toml --out lo --quiet && sed -i '2s/^[^,]*/NaN/' lo/pareto.csv && $W plot lo"], (2,),
         ("pareto.csv, line 2", "NaN"), files={"ls.toml": lattice() + '[design]\nlength_mm = [60.0, 80.0]\n[ga]\npopulation = 6\ngenerations = 2\n'}, shell=True),
    Case("plot of a samples study", ["simulate s.toml --samples 4 --out k --quiet && $W plot k"], (2,), ("samples study",), absent=("optimize",),
         files={"s.toml": SCATTERED}, shell=True),
    Case("plot of a sensitivity study", ["sensitivity s.toml --base-samples 8 --out k --quiet && $W plot k"], (0,), ("indices_",),
         files={"s.toml": SCATTERED}, shell=True),
    Case("--samples --out a folder holding a summary.json", ["--version > /dev/null; mkdir d && echo '{}' > d/summary.json && $W simulate s.toml --samples 4 --out d; c=$?; test \"$(cat d/summary.json)\" = '{}' && exit $c"], (2,),
         ("--out = d", "choose another --out"), absent=("remove", "delete", "--overwrite"), files={"s.toml": SCATTERED}, shell=True),
    Case("two sensitivity runs into one folder", ["--version > /dev/null; ($W sensitivity s.toml --base-samples 128 --out d --quiet & $W sensitivity s.toml --base-samples 128 --out d --quiet; wait) 2>&1; test -f d/summary.json"], (0,),
         absent=("--overwrite",), files={"s.toml": SCATTERED}, shell=True),
    Case("--resume of a finished NSGA-II run without history.csv", ["optimize mo.toml --out o --quiet && rm o/history.csv && $W optimize mo.toml --out o --resume --quiet && test -f o/history.csv"], (0,),
         files={"mo.toml": MO}, shell=True),
    Case("NSGA-II reference_point = [-1, -1]", ["optimize", "mo.toml", "--out", "o", "--quiet"], (0,), ("hypervolume is 0", "ga.reference_point"),
         files={"mo.toml": MO + "reference_point = [-1.0, -1.0]\n"}),
    Case("plot of a deleted run.json", ["simulate s.toml --out r --quiet && rm r/run.json && $W plot r"], (2,), ("run.json",), absent=("optimize output",),
         files={"s.toml": SHORT}, shell=True),
]

PY_PRELUDE = """
import pickle, sys, woodpile
s = woodpile.Scenario.builtin("paper-impact-80mm")
SCATTERED = "[chain]\\nrods_mm = [40, 30, 20]\\n[run]\\nduration_s = 2e-4\\n[uncertainty]\\nimpact_velocity_m_s = { uniform = [1.8, 2.2] }\\n"
"""

PY_CASES = [
    ("from_dict type error names the key", 'try:\n    s.replace(**{"excitation.velocity_m_s": "fast"})\nexcept woodpile.ScenarioError as e:\n    assert e.field == "excitation.velocity_m_s", e.field\n    print("ok")'),
    ("NumPy values are scenario values", 'import numpy as np\ns.replace(**{"chain.rods_mm": np.array([80, 40]), "excitation.velocity_m_s": np.float64(1.5)})\nprint("ok")'),
    ("simulate(None) is a TypeError", 'try:\n    woodpile.simulate(None)\nexcept TypeError:\n    print("ok")'),
    ("sweep over a string is refused by key", 'try:\n    woodpile.sweep(s, {"run.integrator": "rk4"})\nexcept woodpile.ScenarioError as e:\n    assert e.field == "run.integrator"; print("ok")'),
    ("sweep: a refused value is an error row", 't = woodpile.sweep(s.replace(**{"run.duration_s": 1e-4, "run.sample_interval_s": 1e-4}), {"excitation.velocity_m_s": [1.0, "fast"]})\nassert "excitation.velocity_m_s" in t["error"][1]; print("ok")'),
    ("optimize(seed=-1) names seed", 'try:\n    woodpile.optimize("paper-impact", seed=-1)\nexcept woodpile.ScenarioError as e:\n    assert e.field == "seed"; print("ok")'),
    ("errors pickle", 'try:\n    s.replace(**{"run.duration_s": "x"})\nexcept woodpile.ScenarioError as e:\n    b = pickle.loads(pickle.dumps(e)); assert b.field == e.field; print("ok")'),
    ("a lattice's bad key names it", 'try:\n    woodpile.Scenario(\'[lattice]\\nlayers = [{ rods = 0, pitch_mm = 20.0, length_mm = 80.0 }]\\n\')\nexcept woodpile.ScenarioError as e:\n    assert e.field == "lattice.layers[0].rods", e.field; print("ok")'),
    ("sensitivity(base_samples=-4) names it", 'u = woodpile.Scenario.from_toml(SCATTERED)\ntry:\n    woodpile.sensitivity(u, base_samples=-4)\nexcept woodpile.ScenarioError as e:\n    assert e.field == "base_samples"; print("ok")'),
    ("sensitivity(seed=-1) names it", 'u = woodpile.Scenario.from_toml(SCATTERED)\ntry:\n    woodpile.sensitivity(u, seed=-1)\nexcept woodpile.ScenarioError as e:\n    assert e.field == "seed"; print("ok")'),
    ("sensitivity(\"file.toml\") is a TypeError", 'try:\n    woodpile.sensitivity("file.toml")\nexcept TypeError as e:\n    assert "scenario" in str(e); print("ok")'),
    ("evaluate([None]) is a TypeError", 'try:\n    woodpile.evaluate([None])\nexcept TypeError as e:\n    assert "scenarios[0]" in str(e); print("ok")'),
    ("spectrum of a 2-D array names signal", 'import numpy as np\ntry:\n    woodpile.spectrum(np.zeros((8, 2)), 1e-6)\nexcept woodpile.ScenarioError as e:\n    assert e.field == "signal"; print("ok")'),
    ("sweep given a list is a TypeError", 'try:\n    woodpile.sweep(s, ["excitation.velocity_m_s"])\nexcept TypeError as e:\n    assert "grid" in str(e); print("ok")'),
    ("NaN in replace names the key", 'try:\n    s.replace(**{"excitation.velocity_m_s": float("nan")})\nexcept woodpile.ScenarioError as e:\n    assert e.field == "excitation.velocity_m_s"; print("ok")'),
    ("fit(threads=-1) names it", 'import pathlib, tempfile\nd = pathlib.Path(tempfile.mkdtemp())\n(d / "f.toml").write_text("x")\ntry:\n    woodpile.fit(d / "f.toml", threads=-1)\nexcept woodpile.ScenarioError as e:\n    assert e.field == "threads"; print("ok")'),
    ("10 s at 1 ns is refused", 'try:\n    woodpile.simulate(s.replace(**{"run.duration_s": 10.0, "run.time_step_s": 1e-9, "run.sample_interval_s": 10.0}))\nexcept woodpile.LimitError as e:\n    assert "allow_long" in str(e); print("ok")'),
]

PY_INTERRUPTS = {
    "Ctrl-C in simulate": 'woodpile.simulate(long)',
    "Ctrl-C in evaluate([s] * 3000)": 'woodpile.evaluate([long] * 3000)',
    "Ctrl-C in sensitivity(base_samples=4096)": 'woodpile.sensitivity(long.replace(**{"uncertainty.impact_velocity_m_s": {"uniform": [1.8, 2.2]}}), 4096)',
    "Ctrl-C in a 3000-point sweep": 'woodpile.sweep(long, {"excitation.velocity_m_s": [1.0 + i / 3000 for i in range(3000)]})',
}


def run_cli(case: Case, woodpile: str) -> tuple[str, str]:
    with tempfile.TemporaryDirectory() as d:
        for name, text in case.files.items():
            Path(d, name).write_text(text)
        env = dict(os.environ, W=woodpile)
        if case.shell:
            line = case.argv[0]
            cmd: list[str] | str = ["bash", "-c", f'W="{woodpile}"; "$W" {line}']
        else:
            cmd = [woodpile, *case.argv]
        started = time.monotonic()
        child = subprocess.Popen(cmd, cwd=d, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        limit = case.timeout_s
        if case.interrupt_after_s is not None:
            time.sleep(case.interrupt_after_s)
            sent = time.monotonic()
            child.send_signal(signal.SIGINT)
            limit = 2.0
            started = sent
        try:
            out, err = child.communicate(timeout=limit)
        except subprocess.TimeoutExpired:
            child.kill()
            child.communicate()
            return "-", "HANG"
        seconds = time.monotonic() - started
        text = out + err
        code = child.returncode
        status = f"exit {code} in {seconds:.2f} s"
        if code == 101 or "panicked at" in text:
            return status, "PANIC"
        if code not in case.codes:
            return status, f"WRONG EXIT (expected {case.codes}): {err.strip()[:160]}"
        missing = [n for n in case.needles if n not in text]
        if missing:
            return status, f"DOES NOT NAME {missing}: {text.strip()[:160]}"
        present = [a for a in case.absent if a in text]
        if present:
            return status, f"SAYS {present}: {text.strip()[:160]}"
        return status, "ok"


def run_py(name: str, body: str) -> tuple[str, str]:
    started = time.monotonic()
    try:
        done = subprocess.run([sys.executable, "-c", PY_PRELUDE + body], capture_output=True, text=True, timeout=120)
    except subprocess.TimeoutExpired:
        return "-", "HANG"
    status = f"{time.monotonic() - started:.2f} s"
    if "panicked at" in done.stderr or "PanicException" in done.stderr:
        return status, "PANIC"
    if done.stdout.strip() != "ok":
        return status, f"FAILED: {done.stderr.strip()[-200:]}"
    return status, "ok"


def run_py_interrupt(name: str, work: str) -> tuple[str, str]:
    body = textwrap.dedent(f"""
        long = s.replace(**{{"run.duration_s": 1.0, "run.sample_interval_s": 1.0}})
        print("started", flush=True)
        try:
            {work}
            print("finished", flush=True)
        except KeyboardInterrupt:
            print("interrupted", flush=True)
    """)
    child = subprocess.Popen([sys.executable, "-c", PY_PRELUDE + body], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert child.stdout is not None
    child.stdout.readline()
    time.sleep(1.5)
    sent = time.monotonic()
    child.send_signal(signal.SIGINT)
    try:
        out, err = child.communicate(timeout=10)
    except subprocess.TimeoutExpired:
        child.kill()
        return "-", "HANG"
    seconds = time.monotonic() - sent
    status = f"{seconds:.2f} s after SIGINT"
    if out.strip() != "interrupted":
        return status, f"FAILED: {out.strip()} {err.strip()[-200:]}"
    if seconds > 1.0:
        return status, "SLOW (over 1 s)"
    return status, "ok"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--woodpile", default=str(Path(__file__).resolve().parents[1] / "target/release/woodpile"))
    parser.add_argument("--only", default="")
    args = parser.parse_args()
    woodpile = str(Path(args.woodpile).resolve())
    rows: list[tuple[str, str, str]] = []
    for case in CLI_CASES:
        if args.only in case.name:
            rows.append(("cli: " + case.name, *run_cli(case, woodpile)))
            print(f"{rows[-1][0]:<48} {rows[-1][1]:<26} {rows[-1][2]}", flush=True)
    for name, body in PY_CASES:
        if args.only in name:
            rows.append(("python: " + name, *run_py(name, body)))
            print(f"{rows[-1][0]:<48} {rows[-1][1]:<26} {rows[-1][2]}", flush=True)
    for name, work in PY_INTERRUPTS.items():
        if args.only in name:
            rows.append(("python: " + name, *run_py_interrupt(name, work)))
            print(f"{rows[-1][0]:<48} {rows[-1][1]:<26} {rows[-1][2]}", flush=True)
    failed = [r for r in rows if r[2] != "ok"]
    print(f"\n{len(rows)} cases, {len(rows) - len(failed)} passed, {len(failed)} failed; "
          f"panics: {sum(r[2] == 'PANIC' for r in rows)}, hangs: {sum(r[2] == 'HANG' for r in rows)}")
    return len(failed)


if __name__ == "__main__":
    sys.exit(main())
