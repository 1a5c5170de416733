"""Claims: Ctrl-C reaches Rust. ``simulate``, ``evaluate`` and a sweep raise ``KeyboardInterrupt``
less than 2 s after SIGINT while their work would take far longer, and the next call runs
normally; the command line's up-front limits hold in Python too (``simulate`` raises
``LimitError`` naming ``allow_long``; in ``evaluate`` such a run is an error row).

Each case runs in a child Python (the signal must reach its main thread) that starts the work,
reports ``started`` and, on ``KeyboardInterrupt``, tries a short run and reports ``interrupted``.
Tolerance: 2 s from the signal to the child's report, against work of tens of seconds (the
library polls the stop request after every step; Python's handlers are checked every 50 ms).
"""

import os
import signal
import subprocess
import sys
import time

import pytest

import woodpile
from woodpile import LimitError

# 1 s of simulated time at the paper's 0.1 µs step: 10 million steps of 20 rods.
# The child installs Python's Ctrl-C handler itself, as an interactive Python has it: a runner
# that starts the tests with SIGINT ignored (nohup, a background job) would otherwise pass that
# on to the child, and Python installs no handler for an ignored signal.
CHILD = """
import signal, sys, woodpile
signal.signal(signal.SIGINT, signal.default_int_handler)
s = woodpile.Scenario.builtin("paper-impact-optimized").replace(**{{
    "run.duration_s": 1.0, "run.sample_interval_s": 1.0}})
short = s.replace(**{{"run.duration_s": 1e-4, "run.sample_interval_s": 1e-4}})
print("started", flush=True)
try:
    {work}
    print("finished", flush=True)
except KeyboardInterrupt:
    after = woodpile.simulate(short)
    print("interrupted", after.summary["transmitted_peak_force_n"] >= 0.0, flush=True)
"""

WORK = {
    "simulate": "woodpile.simulate(s)",
    "evaluate": "woodpile.evaluate([s] * 8)",
    "sweep": 'woodpile.sweep(s, {"excitation.velocity_m_s": [1.0, 2.0, 3.0, 4.0]})',
}


@pytest.mark.skipif(os.name != "posix", reason="sends SIGINT")
@pytest.mark.parametrize("work", sorted(WORK))
def test_ctrl_c_interrupts_within_two_seconds(work: str) -> None:
    child = subprocess.Popen(
        [sys.executable, "-c", CHILD.format(work=WORK[work])],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    assert child.stdout is not None
    assert child.stdout.readline().strip() == "started"
    time.sleep(1.0)  # well inside the work
    sent = time.monotonic()
    child.send_signal(signal.SIGINT)
    report = child.stdout.readline().strip()
    seconds = time.monotonic() - sent
    child.wait(timeout=60)
    assert report == "interrupted True", child.stderr.read() if child.stderr else report
    assert seconds < 2.0, f"{work}: KeyboardInterrupt {seconds:.2f} s after SIGINT"


def test_an_endless_run_is_refused_by_the_step_limit() -> None:
    s = woodpile.Scenario.builtin("paper-impact-80mm").replace(
        **{"run.duration_s": 10.0, "run.time_step_s": 1e-9, "run.sample_interval_s": 10.0}
    )
    with pytest.raises(LimitError) as e:
        woodpile.simulate(s)
    assert e.value.field == "run.duration_s / run.time_step_s"
    assert "allow_long=True" in str(e.value)


def test_an_endless_run_in_a_study_is_an_error_row() -> None:
    endless = woodpile.Scenario.builtin("paper-impact-80mm").replace(
        **{"run.duration_s": 10.0, "run.time_step_s": 1e-9, "run.sample_interval_s": 10.0}
    )
    short = endless.replace(**{"run.duration_s": 1e-4, "run.time_step_s": 1e-7, "run.sample_interval_s": 1e-4})
    table = woodpile.evaluate([endless, short])
    assert "run.duration_s / run.time_step_s" in table["error"][0]
    assert table["error"].isna().tolist() == [False, True]
