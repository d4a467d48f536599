"""Topology stage: a train file as the user writes it -> a validated, immutable `Train`.

It owns the language (`.schema`, one table the loader, the validator and the
documentation read), the YAML reading with the line of every entry (`.yaml_source`),
the expression grammar (`.expressions`: user text is parsed, never evaluated), the
symbols and their assumptions (`.symbols`), the coupling kinds as data
(`.couplings`: revolute, mesh, prismatic, explicit screws; their friction laws of
Laus Table 2), the model (`.model`) and operating states (`.states`: brakes and
clutches join links, free members leave).  Every problem is collected with its file,
line and entry and raised once.
"""
