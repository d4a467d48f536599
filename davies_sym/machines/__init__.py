"""General machines by Davies' method (Laus ch. 4): linkages with joint friction.

The stage reads a machine file (`machine_loader`), builds the unit motion and action screws of
its joints (`joints`), assembles the network matrices from the coupling graph
(`network`), and either derives closed forms per friction mode (`closed_form`,
`cycle`) or solves positions and tasks numerically (`numeric`, `task`).
"""
