"""Topology stage: a train file as the user writes it -> a validated, immutable :class:`Train`.

It owns the language (:mod:`.schema`, one table the loader, the validator and the
documentation read), the YAML reading with the line of every entry (:mod:`.yaml_source`),
the expression grammar (:mod:`.expressions`: user text is parsed, never evaluated), the
symbols and their assumptions (:mod:`.symbols`), the coupling kinds as data
(:mod:`.couplings`: revolute, mesh, prismatic, explicit screws; their friction laws of
Laus Table 2), the model (:mod:`.model`) and operating states (:mod:`.states`: brakes and
clutches join links, free members leave).  Every problem is collected with its file,
line and entry and raised once.
"""
