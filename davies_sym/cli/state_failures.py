"""The states of a file that did not derive, and the exit status they give."""

from __future__ import annotations


class StateFailures(list[str]):
    """One line per problem of the states that did not derive (the others did), and
    whether every one of them is a design the formulas do not cover (exit status 3,
    as for a file of one state) rather than a mistake in the file (exit status 2)."""

    def __init__(self) -> None:
        super().__init__()
        self.bad_input = False

    def add(self, lines: list[str], not_covered: bool) -> None:
        self.extend(lines)
        self.bad_input = self.bad_input or not not_covered

    @property
    def status(self) -> int:
        """0 when every state derived, else 2 or 3."""
        if not self:
            return 0
        return 2 if self.bad_input else 3
