"""davies_sym: closed-form mechanical efficiency of gear trains by Davies' method.

The package is a pipeline; each stage is a subpackage that hands the next a frozen result:

- `davies_sym.topology`: the YAML language, loading, validation -> `Train`
- `davies_sym.geometry`: axes, pitch points, geometric constraints -> ``Layout``
- `davies_sym.network`: coupling graph, screws, M_N, A_N, D_A, null spaces -> `Analysis`
- `davies_sym.efficiency`: virtual power, turning conditions, variants, losses -> `VariantSet`
- `davies_sym.emit`: text, JSON, LaTeX, formula modules, figures
- `davies_sym.calibration`: loss parameters fitted to measurements
- `davies_sym.synthesis`: tooth numbers for target ratios, ranked by efficiency (``derive search``)
- `davies_sym.cli`: the ``derive`` command

`davies_sym.algebra` holds the exact algebra the stages share (flint polynomials,
fraction-free elimination, square roots, signs, Plücker coordinates).

Example (run by the tests, from the root of a checkout):

```python
import davies_sym

train = davies_sym.load("catalog/simple_pair.yaml")
davies_sym.analyse(train).efficiency  # r1*(r2 - zeta_C)/(r2*(r1 + zeta_C)), Laus eq. (136)
variants = davies_sym.derive(train)  # every variant with its turning conditions
variants.evaluate({"r1": 20, "r2": 50, "eta_C": "0.98"}, "A")  # 49/50, exact
```
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from davies_sym.errors import (
    DaviesError,
    DerivationError,
    DesignError,
    GeometryError,
    InputError,
    MobilityError,
    NotCoveredError,
    TopologyError,
    TopologySyntaxError,
)

if TYPE_CHECKING:
    from davies_sym.efficiency.power_flow_regions import OperatingPoint, SeveralInputs
    from davies_sym.efficiency.several_inputs import derive_several_inputs
    from davies_sym.efficiency.turning_conditions import TurningCondition
    from davies_sym.efficiency.variant_result import Variant
    from davies_sym.efficiency.variants import VariantSet, derive_variants
    from davies_sym.network.analysis import Analysis, analyse
    from davies_sym.network.sign_condition import SignCondition
    from davies_sym.topology.catalog_files import catalog_file, catalog_names
    from davies_sym.topology.loader import load, loads
    from davies_sym.topology.model import Gear, Link, Ports, State, Train
    from davies_sym.topology.states import train_in_state

    derive = derive_variants

__version__ = "0.1.0"

#: Where each public name lives.  They are imported on first use (PEP 562), so that
#: ``import davies_sym.cli`` for ``derive --help`` does not load sympy and flint.
_LAZY = {
    "OperatingPoint": "davies_sym.efficiency.power_flow_regions",
    "SeveralInputs": "davies_sym.efficiency.power_flow_regions",
    "derive_several_inputs": "davies_sym.efficiency.several_inputs",
    "TurningCondition": "davies_sym.efficiency.turning_conditions",
    "Variant": "davies_sym.efficiency.variant_result",
    "VariantSet": "davies_sym.efficiency.variants",
    "derive_variants": "davies_sym.efficiency.variants",
    "Analysis": "davies_sym.network.analysis",
    "analyse": "davies_sym.network.analysis",
    "SignCondition": "davies_sym.network.sign_condition",
    "catalog_file": "davies_sym.topology.catalog_files",
    "catalog_names": "davies_sym.topology.catalog_files",
    "load": "davies_sym.topology.loader",
    "loads": "davies_sym.topology.loader",
    "Gear": "davies_sym.topology.model",
    "Link": "davies_sym.topology.model",
    "Ports": "davies_sym.topology.model",
    "State": "davies_sym.topology.model",
    "Train": "davies_sym.topology.model",
    "train_in_state": "davies_sym.topology.states",
}
#: Every variant of a train's efficiency (Laus Tables 5 and 6); ``derive(train).evaluate(values, input)``.
_ALIASES = {"derive": "derive_variants"}


def __getattr__(name: str) -> Any:
    target = _ALIASES.get(name, name)
    module = _LAZY.get(target)
    if module is None:
        raise AttributeError(f"module 'davies_sym' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), target)
    globals()[name] = value  # later look-ups are plain attribute reads
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_LAZY, *_ALIASES})


__all__ = [
    "Analysis",
    "DaviesError",
    "DerivationError",
    "DesignError",
    "Gear",
    "GeometryError",
    "InputError",
    "Link",
    "MobilityError",
    "NotCoveredError",
    "OperatingPoint",
    "Ports",
    "SeveralInputs",
    "SignCondition",
    "State",
    "TopologyError",
    "TopologySyntaxError",
    "Train",
    "TurningCondition",
    "Variant",
    "VariantSet",
    "analyse",
    "catalog_file",
    "catalog_names",
    "derive",
    "derive_several_inputs",
    "derive_variants",
    "load",
    "loads",
    "train_in_state",
]
