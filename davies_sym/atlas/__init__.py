"""Atlas of one-degree-of-freedom planetary gear trains (``derive atlas``): every
non-isomorphic train of N links, its rotation and displacement graphs, a train file for
each, and the search for tooth numbers over all of them (``derive search --atlas``).

- `davies_sym.atlas.graphs`: a train as a graph (links, axes, gear pairs) -> `TrainGraph`
- `davies_sym.atlas.canonical`: canonical codes of trains and of their rotation graphs
- `davies_sym.atlas.enumeration`: every non-isomorphic train of N links -> `Atlas`
- `davies_sym.atlas.realisation`: a graph drawn as a train (main axis or frame, suns,
  rings, planet gears)
- `davies_sym.atlas.train_file`: the train file of a drawn graph (symbolic radii or tooth
  numbers, housing or frame, ports and states)
- `davies_sym.atlas.choices`: the held / input / output choices whose speed ratio the
  gears set
- `davies_sym.atlas.atlas_entries`: one entry per displacement graph (codes, drawing, choices)
- `davies_sym.atlas.recognition`: where a train written by hand lies in the atlas
- `davies_sym.atlas.drawing`: SVG of a graph and of its train's layout
- `davies_sym.atlas.atlas_report`: the atlas as text
- `davies_sym.atlas.search`: the tooth-number search over every train of the atlas

The commands that read these (``derive atlas``, ``derive search --atlas``) are in
`davies_sym.cli`.
"""
