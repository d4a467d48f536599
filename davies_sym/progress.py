"""What a command tells on standard error while it works, the one display of every
command: a line per step (``derive atlas: reading the motions``) and, over the tasks of
a fan-out (`davies_sym.fan_out`), a tqdm bar on a terminal or a line per finished task
elsewhere.  Quiet leaves steps and bar out; notes (a refused file, a warning) are always
shown."""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

#: A step reported to the user; the stages take one and know nothing of the display.
Progress = Callable[[str], None]


def silent(text: str) -> None:
    """Progress nobody reads (a worker process: its finished task is the progress)."""


class Tally:
    """The count of finished tasks of one fan-out: the bar advances, or, without one, a
    line ``[done/total] what finished`` is a step."""

    def __init__(self, total: int, say: Progress, bar: Any = None) -> None:
        self.total, self.done, self._say, self._bar = total, 0, say, bar

    def finished(self, line: str | None = None) -> None:
        """One more task done; ``line`` says what it gave (None: nothing worth a line)."""
        self.done += 1
        if self._bar is not None:
            self._bar.update(1)
        elif line is not None:
            self._say(f"[{self.done}/{self.total}] {line}")


class Display:
    """The progress of the command ``command`` (its name starts every line), called with
    each step's text; it keeps the last step, which an internal error names as where it
    happened."""

    def __init__(self, command: str, quiet: bool = False) -> None:
        self.command, self.quiet = command, quiet
        self.last: str | None = None
        self._bar: Any = None

    def __call__(self, text: str) -> None:
        self.last = text
        if self.quiet:
            return
        if self._bar is not None:
            self._bar.set_description_str(f"{self.command}: {text}")
        else:
            print(f"{self.command}: {text}", file=sys.stderr, flush=True)

    def note(self, line: str) -> None:
        """A line always shown (quiet or not), above the bar when there is one."""
        if self._bar is not None:
            self._bar.write(line, file=sys.stderr)
        else:
            print(line, file=sys.stderr, flush=True)

    @contextmanager
    def tally(self, total: int, unit: str) -> Iterator[Tally]:
        """A bar over ``total`` tasks (named ``unit``) while the block runs, on a terminal
        and when there are several; otherwise the tasks count as lines."""
        if self.quiet or total < 2 or not sys.stderr.isatty():
            yield Tally(total, self)
            return
        from tqdm import tqdm

        self._bar = tqdm(total=total, unit=unit, file=sys.stderr)
        try:
            yield Tally(total, self, self._bar)
        finally:
            self._bar.close()
            self._bar = None


@contextmanager
def tally(progress: Progress, total: int, unit: str) -> Iterator[Tally]:
    """The tally of ``total`` tasks for whatever reports ``progress``: the display's bar,
    or lines through any other callable."""
    if isinstance(progress, Display):
        with progress.tally(total, unit) as counted:
            yield counted
    else:
        yield Tally(total, progress)


def note(progress: Progress, line: str) -> None:
    """``line`` shown whatever the quiet setting (on standard error where ``progress``
    is not a display)."""
    if isinstance(progress, Display):
        progress.note(line)
    else:
        print(line, file=sys.stderr, flush=True)
