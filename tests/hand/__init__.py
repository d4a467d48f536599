"""Hand-written helpers for the tests: exact arithmetic with one square root, and the
LaTeX round trip of emitted formulas."""
