"""Design synthesis: the tooth numbers of a train for target speed ratios, ranked by the
closed-form efficiency (``derive search``).

- `davies_sym.synthesis.problem`: the search asked for, read and checked -> `SearchProblem`
- `davies_sym.synthesis.design_enumeration`: every design whose ratios can reach their targets,
  by exact-bound pruning, never the blind product of the ranges
- `davies_sym.synthesis.planet_sets`: the planet sets of a train and their assembly and
  tip-clearance conditions
- `davies_sym.synthesis.rules`: the feasibility rules, one documented function each
- `davies_sym.synthesis.formulas`: the closed forms of each state (ratio, formula module),
  derived once per state through the one fan-out
- `davies_sym.synthesis.exact_values`: exact ratios of integer designs
- `davies_sym.synthesis.feasible_designs`: the exact rules a design meets before it is scored
- `davies_sym.synthesis.box_bounds`: rigorous ranges of a rational function over boxes of
  tooth numbers
- `davies_sym.synthesis.best_first`: branch and bound over boxes of tooth numbers, its
  work bounded
- `davies_sym.synthesis.bounded_search`: the best designs of a search found best-first
  (``derive search --atlas``)
- `davies_sym.synthesis.tooth_search`: the whole search -> `SearchResult`
- `davies_sym.synthesis.best_design`: the chosen design as a train file with numbers
- `davies_sym.synthesis.search_report`: the search's text and Pareto figure
- `davies_sym.synthesis.shift_kinematics`: the main-axis members' speeds of a train of
  several degrees of freedom, exact linear forms in its free shaft speeds
- `davies_sym.synthesis.shift_elements`: brakes and clutches, those that lock the same
  degree of freedom counted once, and the ratio of the gear a set of them engages
- `davies_sym.synthesis.shift_schedules`: the shift schemes (elements and schedule)
  that give a ratio table

The ``derive search`` command that reads these is `davies_sym.cli.search_command`.
"""
