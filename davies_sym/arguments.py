"""Argument types the commands share (``derive``, ``derive atlas``, ``derive search
--atlas``): read by argparse before anything heavy is imported."""

from __future__ import annotations

import argparse
import os


def jobs(text: str) -> int:
    """``--jobs N``: a whole number of processes, at least 1, or ``auto`` (every core)."""
    if text == "auto":
        return os.cpu_count() or 1
    if not text.isdigit() or int(text) < 1:
        raise argparse.ArgumentTypeError(f"expected a number of processes (1, 2, ...) or auto, got {text!r}")
    return int(text)
