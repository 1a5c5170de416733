#!/usr/bin/env python3
"""The docs' playground against the command line, in headless Chromium.

Serves a built site (`mkdocs build`) on 127.0.0.1, opens `playground/#scenario=<TOML>` for an
impact, a blast and a damped chain, and checks that every figure the page shows in a
`data-value` attribute (`incident_peak_force_n`, `transmitted_peak_force_n`,
`transmission_ratio`) equals `woodpile simulate`'s summary.json for the same TOML exactly (the
library computes alike on both: docs/playground/index.md); that a scenario the command line
refuses shows the command line's message in the page. Exit 1 on any mismatch. (The page's speed
and its screenshot: bench/playground.mjs, on the real clock.)

Usage: python3 scripts/playground_check.py --site SITE_DIR --woodpile target/debug/woodpile
"""

from __future__ import annotations

import argparse
import functools
import html.parser
import http.server
import json
import subprocess
import sys
import tempfile
import threading
import urllib.parse
from pathlib import Path

SCENARIOS = {
    "impact": """[chain]
rods_mm = [80, 70, 60, 50, 40, 30, 20]
[excitation]
kind = "impact"
velocity_m_s = 1.98
[run]
duration_s = 1e-3
peak_tolerance = 1e-5
""",
    "blast": """[chain]
rods_mm = [80, 80, 70, 60, 50, 40, 30, 20]
[excitation]
kind = "blast"
peak_force_n = 200.0
duration_s = 2.0e-4
[run]
duration_s = 1e-3
peak_tolerance = 1e-5
""",
    "damped": """[chain]
rods_mm = [40, 40, 40, 40, 40, 40]
[excitation]
kind = "impact"
[damping]
contact = "restitution"
restitution = 0.9
resonator_ratio = 0.01
[preload]
gravity_m_s2 = 9.81
[run]
duration_s = 1e-3
peak_tolerance = 1e-5
""",
}
BAD = "[chain]\nrods_mm = [80, 45]\n"
FIGURES = ("incident_peak_force_n", "transmitted_peak_force_n", "transmission_ratio")
CHROMIUM_FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
# The pages run on virtual time: the DOM is dumped once the run is done, however long it took.
VIRTUAL_TIME = ["--virtual-time-budget=60000"]


class Elements(html.parser.HTMLParser):
    """Every element with an id: its attributes and its text."""

    def __init__(self) -> None:
        super().__init__()
        self.attrs: dict[str, dict[str, str | None]] = {}
        self.text: dict[str, str] = {}
        self._open: list[str | None] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        found = dict(attrs)
        ident = found.get("id")
        if ident:
            self.attrs[ident] = found
            self.text.setdefault(ident, "")
        if tag not in ("input", "br", "link", "meta", "img", "hr"):
            self._open.append(ident)

    def handle_endtag(self, tag: str) -> None:
        if self._open:
            self._open.pop()

    def handle_data(self, data: str) -> None:
        for ident in self._open:
            if ident:
                self.text[ident] += data


def serve(site: Path) -> tuple[http.server.ThreadingHTTPServer, int]:
    handler = functools.partial(QuietHandler, directory=str(site))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server, server.server_address[1]


class QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, format: str, *args: object) -> None:
        pass


def page(chromium: str, url: str, scratch: Path, extra: list[str]) -> Elements:
    profile = tempfile.mkdtemp(dir=scratch)
    command = [chromium, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", *extra, url]
    done = subprocess.run(command, capture_output=True, text=True, timeout=180, check=True)
    elements = Elements()
    elements.feed(done.stdout)
    return elements


def native(woodpile: str, toml: str, scratch: Path, name: str) -> tuple[dict, str]:
    """The command line's summary.json of `toml` (empty on a refusal) and its error line."""
    file = scratch / f"{name}.toml"
    file.write_text(toml)
    out = scratch / f"run-{name}"
    done = subprocess.run(
        [woodpile, "simulate", str(file), "--out", str(out), "--quiet"],
        capture_output=True,
        text=True,
    )
    if done.returncode != 0:
        return {}, done.stderr.strip().splitlines()[0]
    return json.loads((out / "summary.json").read_text()), ""


def url_of(port: int, toml: str) -> str:
    return f"http://127.0.0.1:{port}/playground/#scenario={urllib.parse.quote(toml, safe='')}"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--site", required=True, type=Path, help="a built site (mkdocs build)")
    parser.add_argument("--woodpile", required=True, help="the woodpile command")
    parser.add_argument("--chromium", default="chromium", help="headless Chromium (default chromium)")
    args = parser.parse_args()
    if not (args.site / "playground" / "woodpile.wasm").is_file():
        print(f"error: {args.site}/playground/woodpile.wasm missing: build the site first", file=sys.stderr)
        return 2
    server, port = serve(args.site)
    failures = 0
    with tempfile.TemporaryDirectory(prefix="woodpile-playground-") as tmp:
        scratch = Path(tmp)
        for name, toml in SCENARIOS.items():
            summary, _ = native(args.woodpile, toml, scratch, name)
            shown = page(args.chromium, url_of(port, toml), scratch, ["--dump-dom", *VIRTUAL_TIME])
            for key in FIGURES:
                value = shown.attrs.get(key, {}).get("data-value")
                expected = summary[key]
                same = (value is None and expected is None) or (
                    value is not None and expected is not None and float(value) == expected
                )
                print(f"{name:8} {key:26} page {value} command line {expected!r} {'equal' if same else 'DIFFERENT'}")
                failures += not same
        _, message = native(args.woodpile, BAD, scratch, "bad")
        shown = page(args.chromium, url_of(port, BAD), scratch, ["--dump-dom", *VIRTUAL_TIME])
        text = shown.text.get("error", "").strip()
        visible = "hidden" not in shown.attrs.get("error", {})
        same = visible and text == message
        print(f"refusal  page {text!r}\n         command line {message!r} {'equal' if same else 'DIFFERENT'}")
        failures += not same
    server.shutdown()
    print("playground: " + ("all equal" if failures == 0 else f"{failures} differences"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
