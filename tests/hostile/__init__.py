"""Helpers of the security and hostile-input tests (black box: the ``derive`` command)."""
