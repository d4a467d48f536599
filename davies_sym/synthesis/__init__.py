"""Design synthesis: the tooth numbers of a train for target speed ratios, ranked by the
closed-form efficiency (``derive search``).

- `davies_sym.synthesis.problem`: the search asked for, read and checked -> `SearchProblem`
- `davies_sym.synthesis.enumeration`: every design whose ratios can reach their targets,
  by exact-bound pruning, never the blind product of the ranges
- `davies_sym.synthesis.planet_sets`: the planet sets of a train and their assembly and
  tip-clearance conditions
- `davies_sym.synthesis.rules`: the feasibility rules, one documented function each
- `davies_sym.synthesis.ranking`: efficiency through the generated formulas, score, Pareto front
- `davies_sym.synthesis.search`: the whole search -> `SearchResult`
- `davies_sym.synthesis.best_design`: the chosen design as a train file with numbers

The ``derive search`` command that reads these is `davies_sym.cli.search_command`.
"""
