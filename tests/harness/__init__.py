"""The black-box harness of the tests: ``derive`` run as a user runs it (in this process or in a
fresh one), the refusal contract of its answers to bad input, and edits of train files to feed it."""
