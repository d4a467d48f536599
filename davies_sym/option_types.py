"""Argument types the commands share (``derive``, ``derive atlas``, ``derive search
--atlas``): read by argparse before anything heavy is imported."""

from __future__ import annotations

import argparse
import os
import re
from typing import Any


def jobs(text: str) -> int:
    """``--jobs N``: a whole number of processes, at least 1, or ``auto`` (every core)."""
    if text == "auto":
        return os.cpu_count() or 1
    if not text.isdigit() or int(text) < 1:
        raise argparse.ArgumentTypeError(f"expected a number of processes (1, 2, ...) or auto, got {text!r}")
    return int(text)


def starts(text: str) -> int:
    """``--starts N``: a whole number of start points, 1 to 1024."""
    if not text.isdigit() or not 1 <= int(text) <= 1024:
        raise argparse.ArgumentTypeError(f"expected a number of start points from 1 to 1024, got {text!r}")
    return int(text)


class Parser(argparse.ArgumentParser):
    """An argument parser that reads a value beginning with a minus sign and a digit as a
    value, not an option: ``--target -22/25`` (a fraction), as it reads ``-0.88``.  No
    option of the commands begins with a digit, so nothing is lost."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        # argparse before 3.13 takes only integers and decimals for negative numbers.
        self._negative_number_matcher = re.compile(r"^-\.?\d")
