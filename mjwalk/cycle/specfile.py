"""Where a cycle file's keys are and the checks that name them: the line of every key and
table header (found by scanning the TOML text, which tomllib does not report), a checker whose
errors start ``<file>:<line>:`` and name the key, and the size limits of a cycle file's texts
and lists (read before anything prints or uses them). :mod:`mjwalk.cycle.spec` reads the file
through these."""

from __future__ import annotations

import difflib
import math
import re
from pathlib import Path

from mjwalk.errors import CycleSpecError

#: Longest a task's ``duration`` and the durations of a cycle together may be, seconds. An
#: assembly cycle's tasks last seconds to minutes (the station cycle of agethen2018 about 40 s);
#: an hour bounds the simulated timeline at 108 000 frames at 30 fps (about 60 MB of poses),
#: where ``duration = 1e12`` asked for petabytes.
MAX_CYCLE_SECONDS = 3600.0
#: Shortest takt a cycle file may give, seconds (besides its waits, which every cycle spends in
#: full): the shortest task, a pick of a part 25 cm from the hand, takes 1.2 s for the reference
#: adult (MTM-1 reach case C 0.46 s, the pick's default hold 0.4 s, the return, case E, 0.37 s:
#: :mod:`mjwalk.cycle.handling`) and 1.0 s for a brisk operator (pace 1.2); below that no cycle
#: fits its takt, and ``takt = 1e-9`` (a unit slip) reported 100 % of cycles over takt.
MIN_TAKT_SECONDS = 1.0

#: Longest name, site, route, part or other label in a cycle file, characters: MJCF names and
#: report labels are identifiers and short phrases, and each is printed in the report's tables,
#: CSV rows and plot titles (a 1 MB name took 77 s and 0.93 GB for one 4.8 s cycle).
MAX_LABEL_CHARS = 256
#: Longest file path (``scene``, the models), characters: Linux's PATH_MAX.
MAX_PATH_CHARS = 4096
#: Most tasks (and entries of any list) a cycle file may have: an hour-long cycle
#: (:data:`MAX_CYCLE_SECONDS`) of one-second tasks.
MAX_TASKS = 3600
PATH_KEYS = ("scene", "step", "reach", "reach_right")

TOP_KEYS = (
    "name", "scene", "start", "takt", "humanoid", "models", "walking", "population", "task",
    "reference",
)  # fmt: skip
#: Keys of the optional [reference] table: its source, then route label -> metres tables.
REFERENCE_KEYS = ("source", "median", "iqr", "planner_median", "planner_iqr")
TABLE_KEYS = {
    "humanoid": ("stature",),
    "models": ("step", "reach", "reach_right"),
    "walking": ("radius",),
}
ALL_TASK_KEYS = ("kind", "site", "hand", "duration", "route", "part", "mass", "coupling")

HEADER_RE = re.compile(r"^\s*(\[\[|\[)\s*([^\[\]]+?)\s*(\]\]|\])\s*(#.*)?$")
KEY_RE = re.compile(
    r"""^\s*((?:"[^"]*"|'[^']*'|[A-Za-z0-9_-]+)(?:\s*\.\s*(?:"[^"]*"|'[^']*'|[A-Za-z0-9_-]+))*)\s*="""
)


class KeyLines:
    """Line numbers of TOML keys and table headers, found by scanning the text.

    ``tomllib`` keeps no positions, so this scans line by line: ``[table]`` and ``[[array]]``
    headers set the current table (the n-th ``[[task]]`` is table ``("task", n)``) and each
    ``key =`` line is recorded under it. Multi-line strings are skipped.

    Args:
        text: the TOML file's text.
    """

    def __init__(self, text: str):
        self.headers: dict[tuple[str, int | None], int] = {}
        self.keys: dict[tuple[str, int | None, str], int] = {}
        counts: dict[str, int] = {}
        table: tuple[str, int | None] = ("", None)
        in_string = None
        for lineno, raw in enumerate(text.splitlines(), start=1):
            if in_string is not None:
                if raw.count(in_string) % 2 == 1:
                    in_string = None
                continue
            m = HEADER_RE.match(raw)
            if m:
                name = unquote(m.group(2))
                if m.group(1) == "[[":
                    idx = counts.get(name, 0)
                    counts[name] = idx + 1
                    table = (name, idx)
                else:
                    table = (name, None)
                self.headers.setdefault(table, lineno)
                continue
            m = KEY_RE.match(raw)
            if m:
                parts = [unquote(p) for p in re.split(r"\s*\.\s*", m.group(1))]
                if table == ("", None) and len(parts) > 1:  # humanoid.stature = 1.7
                    self.keys.setdefault((parts[0], None, parts[-1]), lineno)
                    self.headers.setdefault((parts[0], None), lineno)
                self.keys.setdefault((*table, parts[0]), lineno)
                rest = raw[m.end() :]
                for quote in ('"""', "'''"):
                    if rest.count(quote) % 2 == 1:
                        in_string = quote
                        break

    def line(self, table: str = "", index: int | None = None, key: str | None = None) -> int:
        """Line of ``key`` in ``table`` (``index``-th of an array of tables); falls back to the
        table's header, then to the array's ``key = [...]`` line, then to line 1.

        Args:
            table: the table's name ("" for the top level).
            index: the table's index in an array of tables, None for a plain table.
            key: the key; None: the table's own line.

        Returns:
            The line number (from 1).
        """
        if key is not None and (table, index, key) in self.keys:
            return self.keys[(table, index, key)]
        if (table, index) in self.headers:
            return self.headers[(table, index)]
        if table and ("", None, table) in self.keys:  # task = [{...}, ...] written inline
            return self.keys[("", None, table)]
        return 1


def unquote(s: str) -> str:
    """``s`` stripped of whitespace and of one pair of matching quotes around it.

    Args:
        s: a TOML key or header name as written.

    Returns:
        The bare name.
    """
    s = s.strip()
    if len(s) >= 2 and s[0] == s[-1] and s[0] in "\"'":
        return s[1:-1]
    return s


class Checker:
    """Raises CycleSpecErrors that name the file, the key and its line.

    Args:
        path: the spec file.
        lines: the lines of its keys.
    """

    def __init__(self, path: Path, lines: KeyLines):
        self.path = path
        self.lines = lines

    def fail(
        self, msg: str, table: str = "", index: int | None = None, key: str | None = None
    ) -> CycleSpecError:
        """The error ``<file>:<line>: msg`` for ``key`` of ``table`` (its ``path``, ``line`` and
        ``key`` attributes set).

        Args:
            msg: what is wrong.
            table: the key's table ("" for the top level).
            index: the table's index in an array of tables, None otherwise.
            key: the key; None: the table's line.

        Returns:
            The :class:`~mjwalk.errors.CycleSpecError` to raise.
        """
        line = self.lines.line(table, index, key)
        exc = CycleSpecError(f"{self.path}:{line}: {msg}")
        exc.path, exc.line, exc.key = self.path, line, key
        return exc

    def where(self, table: str, index: int | None) -> str:
        """Where a key is, for a message.

        Args:
            table: the key's table ("" for the top level).
            index: the table's index in an array of tables (a task's), None otherwise.

        Returns:
            "at the top level", "in [table]" or "in task <index + 1>".
        """
        if table == "":
            return "at the top level"
        if index is None:
            return f"in [{table}]"
        return f"in task {index + 1}"

    def keys(
        self, data: dict, allowed: tuple[str, ...], table: str = "", index: int | None = None
    ) -> None:
        """Raise naming the first key of ``data`` not in ``allowed`` (with the closest valid key).

        Args:
            data: the table read from the file.
            allowed: its valid keys.
            table: the table's name ("" for the top level).
            index: the table's index in an array of tables, None otherwise.
        """
        for key in data:
            if key not in allowed:
                close = difflib.get_close_matches(key, allowed, n=1, cutoff=0.5)
                hint = f"; did you mean {close[0]!r}?" if close else ""
                raise self.fail(
                    f"unknown key {key!r} {self.where(table, index)}{hint} "
                    f"(valid keys: {', '.join(allowed)})",
                    table,
                    index,
                    key,
                )

    def string(self, data: dict, key: str, table: str = "", index: int | None = None) -> str:
        """The non-empty string at ``data[key]``, stripped; raise naming the key otherwise.

        Args:
            data: the table read from the file.
            key: the key.
            table: the table's name ("" for the top level).
            index: the table's index in an array of tables, None otherwise.

        Returns:
            The string.
        """
        value = data[key]
        if not isinstance(value, str) or not value.strip():
            raise self.fail(
                f"key {key!r} {self.where(table, index)} must be a non-empty string, got {value!r}",
                table,
                index,
                key,
            )
        return value.strip()

    def number(
        self,
        data: dict,
        key: str,
        lo: float,
        hi: float,
        unit: str,
        table: str = "",
        index: int | None = None,
    ) -> float:
        """The finite number at ``data[key]`` within ``lo`` to ``hi``; raise naming the key
        otherwise (a bool is not a number).

        Args:
            data: the table read from the file.
            key: the key.
            lo: the smallest value allowed.
            hi: the largest value allowed (``inf``: no bound).
            unit: the value's unit, for the message ("m", "s", "kg").
            table: the table's name ("" for the top level).
            index: the table's index in an array of tables, None otherwise.

        Returns:
            The value as a float.
        """
        value = data[key]
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.fail(
                f"key {key!r} {self.where(table, index)} must be a number ({unit}), got {value!r}",
                table,
                index,
                key,
            )
        value = float(value)
        if not math.isfinite(value) or not lo <= value <= hi:
            rng = f"at least {lo:g}" if math.isinf(hi) else f"between {lo:g} and {hi:g}"
            raise self.fail(
                f"key {key!r} {self.where(table, index)} must be {rng} {unit}, got {value:g}",
                table,
                index,
                key,
            )
        return value

    def file(self, data: dict, key: str, base: Path, table: str = "") -> Path:
        """The existing file named by the string at ``data[key]``, relative to ``base``; raise
        naming the key when it is missing or a folder.

        Args:
            data: the table read from the file.
            key: the key.
            base: the folder relative paths start from (the spec file's).
            table: the table's name ("" for the top level).

        Returns:
            The resolved (absolute) path.
        """
        rel = self.string(data, key, table)
        resolved = (base / rel).resolve()
        if resolved.is_dir():
            raise self.fail(
                f"key {key!r} {self.where(table, None)}: {rel!r} is a folder, not a file "
                f"({resolved})",
                table,
                None,
                key,
            )
        if not resolved.is_file():
            raise self.fail(
                f"key {key!r} {self.where(table, None)}: file {rel!r} not found "
                f"(looked for {resolved})",
                table,
                None,
                key,
            )
        return resolved


def check_lengths(check: Checker, data: dict) -> None:
    """Raise naming the key of the first string (value or key) longer than
    :data:`MAX_LABEL_CHARS` (:data:`MAX_PATH_CHARS` for file paths) and of a list longer than
    :data:`MAX_TASKS`: before anything else reads or prints them.

    Args:
        check: the spec file's checker.
        data: the file's parsed TOML.
    """

    def visit(value, table: str, index: int | None, key: str) -> None:
        if isinstance(value, str):
            limit = MAX_PATH_CHARS if key in PATH_KEYS else MAX_LABEL_CHARS
            if len(value) > limit:
                what = "a file path" if key in PATH_KEYS else "a name, key or label"
                raise check.fail(
                    f"key {short(key)!r} {check.where(table, index)}: a text of {len(value)} "
                    f"characters; {what} may have at most {limit}",
                    table,
                    index,
                    key,
                )
        elif isinstance(value, list):
            if len(value) > MAX_TASKS:
                raise check.fail(
                    f"key {short(key)!r} {check.where(table, index)} has {len(value)} entries, "
                    f"more than {MAX_TASKS}",
                    table,
                    index,
                    key,
                )
            for v in value:
                visit(v, table, index, key)
        elif isinstance(value, dict):
            for k, v in value.items():
                visit(k, table, index, key)  # a key is text too, named by its table
                visit(v, table, index, k if len(k) <= MAX_LABEL_CHARS else key)

    for key, value in data.items():
        visit(key, "", None, "(a top-level key)")
        if key == "task" and isinstance(value, list):
            if len(value) > MAX_TASKS:
                raise check.fail(
                    f"{len(value)} tasks, more than the {MAX_TASKS} a cycle may have", "task"
                )
            for i, task in enumerate(value):
                if isinstance(task, dict):
                    for k, v in task.items():
                        visit(k, "task", i, "(a key)")
                        visit(v, "task", i, k)
        elif isinstance(value, dict):
            for k, v in value.items():
                visit(k, key, None, "(a key)")
                visit(v, key, None, k)
        else:
            visit(value, "", None, key)


def short(text: str) -> str:
    """``text`` cut to 60 characters for a message.

    Args:
        text: any text.

    Returns:
        ``text`` itself up to 60 characters, else its first 40 and its length.
    """
    return text if len(text) <= 60 else f"{text[:40]}...({len(text)} characters)"
