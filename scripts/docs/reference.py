"""The generated reference pages, from the code: the scenario key table (woodpile-io's `keys()`,
read through the Python package), the command line's `--help` (clap) and the keys a scenario
file holds. Used by the site's build hook (scripts/docs/hooks.py) and by the package's test that
the key page lists every key `woodpile scenario NAME` writes (python/tests/test_docs.py)."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path
from typing import Any, Iterable

ROOT = Path(__file__).resolve().parents[2]


def _cell(text: str) -> str:
    """Text for a Markdown table cell (pipes escaped, no line breaks)."""
    return text.replace("|", "\\|").replace("\n", " ")


def _default(key: Any) -> str:
    if key.default_rule:
        return _cell(key.default_rule)
    if key.default is None:
        return ""
    if isinstance(key.default, bool):
        return f"`{str(key.default).lower()}`"
    if isinstance(key.default, str):
        return f'`"{key.default}"`'
    return f"`{key.default:g}`"


def scenario_keys_markdown() -> str:
    """Every key of the scenario file, one table per top-level table, in the order of the file."""
    import woodpile

    return _keys_markdown(woodpile.scenario_keys(), "")


def lattice_keys_markdown() -> str:
    """Every key of a lattice scenario's `[lattice]`, `[excitation]` and `[wall]`, one table each."""
    import woodpile

    return _keys_markdown(woodpile.lattice_keys(), "#")


def _keys_markdown(keys: Iterable[Any], deeper: str) -> str:
    """Keys as one Markdown table per top-level table (headings `##`, or deeper)."""
    sections: dict[str, list[Any]] = {}
    for key in keys:
        sections.setdefault(key.name.split(".")[0].split("[")[0], []).append(key)
    out = []
    for section, keys in sections.items():
        out.append(f"##{deeper} `[{section}]`\n")
        out.append("| key | type [unit] | default | what it is; valid values |")
        out.append("| --- | --- | --- | --- |")
        for k in keys:
            valid = k.valid
            if k.choices:
                valid = ", ".join(f'`"{c}"`' for c in k.choices) + (f"; {valid}" if valid else "")
            doc = k.doc
            if k.alternatives:
                doc += " (replaces " + ", ".join(f"`{a}`" for a in k.alternatives) + ")"
            if valid:
                doc += f". Valid: {valid}"
            ty = k.type + (f" [{k.unit}]" if k.unit else "")
            out.append(f"| `{k.name}` | {_cell(ty)} | {_default(k)} | {_cell(doc)} |")
        out.append("")
    return "\n".join(out)


def scenario_key_names(document: dict[str, Any]) -> set[str]:
    """The dotted keys a scenario document (a parsed scenario file, `Scenario.to_dict()`)
    holds, named as the key table names them: a table's keys as `TABLE.KEY`, the keys of an
    array of tables' entries as `LIST[].KEY`."""
    names: set[str] = set()

    def walk(prefix: str, value: Any) -> None:
        if isinstance(value, dict):
            for k, v in value.items():
                name = f"{prefix}.{k}" if prefix else k
                names.add(name)
                walk(name, v)
        elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
            for v in value:
                walk(prefix + "[]", v)

    walk("", document)
    return names


def woodpile_binary() -> Path:
    """The `woodpile` command the build runs: $WOODPILE_BIN, else `woodpile` on PATH, else the
    release build, else the debug build of this checkout."""
    if os.environ.get("WOODPILE_BIN"):
        return Path(os.environ["WOODPILE_BIN"]).resolve()
    on_path = shutil.which("woodpile")
    if on_path:
        return Path(on_path)
    for profile in ("release", "debug"):
        candidate = ROOT / "target" / profile / "woodpile"
        if candidate.is_file():
            return candidate
    raise RuntimeError(
        "the docs build runs the woodpile command: build it first "
        "(cargo build --release -p woodpile-cli) or set WOODPILE_BIN"
    )


def _help(binary: Path, args: Iterable[str]) -> str:
    return subprocess.run(
        [str(binary), *args, "--help"], check=True, capture_output=True, text=True
    ).stdout.rstrip()


def subcommands(binary: Path) -> list[str]:
    """The subcommands `woodpile --help` lists (its `Commands:` section, `help` left out)."""
    text = _help(binary, [])
    block = text.split("Commands:", 1)[1].split("\n\n", 1)[0]
    names = [m.group(1) for m in re.finditer(r"^  (\S+)", block, flags=re.M)]
    return [n for n in names if n != "help"]


def cli_markdown(binary: Path) -> str:
    """`woodpile --help` and every subcommand's `--help`, verbatim."""
    out = ["## `woodpile`\n", "```text", _help(binary, []), "```\n"]
    for name in subcommands(binary):
        out += [f"## `woodpile {name}`\n", "```text", _help(binary, [name]), "```\n"]
    return "\n".join(out)
