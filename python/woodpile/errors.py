"""The exceptions of woodpile: one class per kind of failure, each carrying attributes.

Every error woodpile raises is a :class:`WoodpileError`. Where it is about one value, ``field``
names it (a scenario's dotted key as written, e.g. ``"excitation.velocity_m_s"``, or an
argument's name such as ``"directory"``), ``value`` is the value as given (as text) and
``reason`` says what would be valid; they are None where an error is not about one value.
``str(e)`` is the whole message. The extension (``woodpile._core``) raises these classes with
the attributes set, so nothing needs to parse a message::

    try:
        scenario.replace(**{"excitation.velocity_m_s": -1.0})
    except woodpile.ScenarioError as e:
        e.field, e.value, e.reason   # "excitation.velocity_m_s", "-1", "must be a finite number > 0"

Each class also derives from the built-in exception that code written before the classes
existed catches: :class:`ScenarioError` is a :class:`ValueError`, :class:`FileError` an
:class:`OSError`, :class:`OverwriteError` a :class:`FileExistsError` (so also an
:class:`OSError`), :class:`RunError` and
:class:`StateError` :class:`RuntimeError`\\ s. ``args`` is ``(message, field, value, reason)``.
"""

from __future__ import annotations

__all__ = [
    "WoodpileError",
    "ScenarioError",
    "FileError",
    "OverwriteError",
    "RunError",
    "InaccurateRunError",
    "LimitError",
    "InterruptedRunError",
    "StateError",
]


class WoodpileError(Exception):
    """Any error of woodpile, with the ``field``, ``value`` and ``reason`` it is about.

    Args:
        message: The whole message (what ``str()`` gives).
        field: The scenario's dotted key or the argument's name; None if not about one value.
        value: The value as given, as text; None if not about one value.
        reason: What would be valid, or why it failed; None if the message says it all.
    """

    field: str | None
    value: str | None
    reason: str | None

    def __init__(
        self,
        message: str,
        field: str | None = None,
        value: str | None = None,
        reason: str | None = None,
    ) -> None:
        # One argument for the built-in bases (OSError reads several as errno, strerror, …).
        super().__init__(message)
        self.args = (message, field, value, reason)
        self.field = field
        self.value = value
        self.reason = reason

    def __str__(self) -> str:
        return str(self.args[0])


class ScenarioError(WoodpileError, ValueError):
    """A scenario, problem config, checkpoint or argument value is not valid, or a file's
    content is not what it should be (a TOML syntax error, a malformed blast table)."""


class FileError(WoodpileError, OSError):
    """A file or directory could not be read or written; ``value`` is its path and ``reason``
    the operating system's message."""


class OverwriteError(WoodpileError, FileExistsError):
    """The output directory exists and may not be written: ``field`` is ``"directory"``,
    ``value`` its path. A directory holding an earlier run is replaced only with
    ``overwrite=True``; any other non-empty directory is refused and left untouched."""


class RunError(WoodpileError, RuntimeError):
    """A run failed numerically (a blow-up, too many steps, a load beyond a contact's range);
    the message says at which time and contact, and what to change."""


class InaccurateRunError(RunError):
    """A run whose energy balance does not close to the stated accuracy: its numbers would not
    mean what they say."""


class LimitError(ScenarioError):
    """A run beyond an up-front limit (integration steps, the run directory's size, worker
    threads): ``field`` names the key that leads there, ``reason`` the limit and how to stay
    within it."""


class InterruptedRunError(WoodpileError):
    """The work was interrupted after saving what lets it continue; ``reason`` says what was
    saved."""


class StateError(WoodpileError, RuntimeError):
    """A call the object's state does not allow yet, e.g. ``BreederGA.tell()`` without a pending
    ``ask()``, or ``best`` before the first generation."""


def _check_count(name: str, value: object, valid: str, bound: int = 2**64) -> None:
    """Refuses a keyword argument that must be a non-negative integer below ``bound`` (or None)
    with a :class:`ScenarioError` naming it, rather than the extension's bare ``OverflowError``
    or ``TypeError``."""
    ok = value is None or (isinstance(value, int) and not isinstance(value, bool) and 0 <= value < bound)
    if not ok:
        raise ScenarioError(f"invalid {name} = {value!r}: must be {valid}", name, repr(value), valid)
