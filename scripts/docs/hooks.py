"""MkDocs hooks of the documentation site (mkdocs.yml `hooks:`).

- Generated reference: a page holding a marker `<!-- generated: NAME -->` gets NAME's Markdown
  from scripts/docs/reference.py (`scenario-keys`: the key table; `cli`: clap's --help).
- Executed tutorials: the `woodpile` command (reference.woodpile_binary) is put first on PATH and
  the build runs in a fresh scratch directory, so the tutorials' shell and Python blocks write
  their runs there and never into the checkout.
- The playground (docs/playground/): its WebAssembly module, woodpile's library built for
  `wasm32-unknown-unknown` from crates/woodpile-wasm, is built before the pages and copied next to
  the page after them (`playground/woodpile.wasm`).
- Math: `$...$` and `$$...$$` (pymdownx.arithmatex, generic) are converted to MathML at build
  time (latex2mathml), which browsers render natively: no script, no fonts, no network.
"""

from __future__ import annotations

import html
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

_HERE = str(Path(__file__).resolve().parent)
sys.path.insert(0, _HERE)
import reference  # noqa: E402

_STATE: dict[str, Any] = {}
_MARKER = re.compile(r"<!-- generated: ([a-z-]+) -->")


def on_config(config: Any) -> Any:
    binary = reference.woodpile_binary()
    _STATE["binary"] = binary
    os.environ["PATH"] = f"{binary.parent}{os.pathsep}{os.environ.get('PATH', '')}"
    os.environ.setdefault("MPLBACKEND", "Agg")
    # The build runs in a scratch directory (on_pre_build): snippets are read from the checkout.
    config["mdx_configs"].setdefault("pymdownx.snippets", {})["base_path"] = [str(reference.ROOT)]
    return config


def _playground_module() -> Path:
    """Builds the playground's module (release, wasm32-unknown-unknown) and returns its path."""
    target = "wasm32-unknown-unknown"
    command = ["cargo", "build", "--release", "--quiet", "--target", target, "-p", "woodpile-wasm"]
    try:
        subprocess.run(command, cwd=reference.ROOT, check=True)
    except (OSError, subprocess.CalledProcessError) as e:
        raise RuntimeError(
            f"building the playground's WebAssembly module failed ({e}); it needs the Rust target "
            f"{target}: rustup target add {target}"
        ) from e
    # (A relative CARGO_TARGET_DIR is cargo's, relative to the checkout.)
    target_dir = reference.ROOT / os.environ.get("CARGO_TARGET_DIR", "target")
    return target_dir / target / "release" / "woodpile_wasm.wasm"


def on_pre_build(config: Any) -> None:
    _STATE["playground"] = _playground_module()
    if _HERE not in sys.path:  # mkdocs restores sys.path after loading the hooks
        sys.path.append(_HERE)  # the tutorials' `from figure import show`
    _STATE["cwd"] = os.getcwd()
    _STATE["scratch"] = tempfile.TemporaryDirectory(prefix="woodpile-docs-")
    os.chdir(_STATE["scratch"].name)


def _restore() -> None:
    if "cwd" in _STATE:
        os.chdir(_STATE.pop("cwd"))
    if "scratch" in _STATE:
        _STATE.pop("scratch").cleanup()


def on_post_build(config: Any) -> None:
    _restore()
    playground = Path(config["site_dir"]) / "playground"
    playground.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(_STATE.pop("playground"), playground / "woodpile.wasm")


def on_build_error(error: Exception) -> None:
    _restore()


def _generated(name: str) -> str:
    if name == "scenario-keys":
        return reference.scenario_keys_markdown()
    if name == "lattice-keys":
        return reference.lattice_keys_markdown()
    if name == "cli":
        return reference.cli_markdown(_STATE["binary"])
    raise ValueError(f"unknown generated section {name!r} (scenario-keys, lattice-keys, cli)")


def on_page_markdown(markdown: str, page: Any, config: Any, files: Any) -> str:
    return _MARKER.sub(lambda m: _generated(m.group(1)), markdown)


_INLINE = re.compile(r'<span class="arithmatex">\\\((.*?)\\\)</span>', re.S)
_BLOCK = re.compile(r'<div class="arithmatex">\\\[(.*?)\\\]</div>', re.S)


def _mathml(tex: str, display: str) -> str:
    from latex2mathml.converter import convert

    return convert(html.unescape(tex).strip(), display=display)


_ROLE = re.compile(r":(?:class|func|meth|mod|attr|data|exc):<code>(~?)([\w.]+)</code>")


def _role(m: re.Match[str]) -> str:
    """A Sphinx cross-reference role of a docstring (`:class:`~woodpile.X``) as code: the last
    name with `~`, the whole path without, as Sphinx shows them."""
    name = m.group(2).rsplit(".", 1)[-1] if m.group(1) else m.group(2)
    return f"<code>{name}</code>"


def on_page_content(content: str, page: Any, config: Any, files: Any) -> str:
    content = _ROLE.sub(_role, content)
    content = _BLOCK.sub(lambda m: f'<div class="math">{_mathml(m.group(1), "block")}</div>', content)
    return _INLINE.sub(lambda m: _mathml(m.group(1), "inline"), content)
