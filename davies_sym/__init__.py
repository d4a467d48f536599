"""davies_sym: closed-form mechanical efficiency of gear trains by Davies' method.

The package is a pipeline; each stage is a subpackage that hands the next a frozen result:

- `davies_sym.topology`: the YAML language, loading, validation -> `Train`
- `davies_sym.geometry`: axes, pitch points, geometric constraints -> ``Layout``
- `davies_sym.network`: coupling graph, screws, M_N, A_N, D_A, null spaces -> `Analysis`
- `davies_sym.efficiency`: virtual power, turning conditions, variants, losses -> `VariantSet`
- `davies_sym.emit`: text, JSON, LaTeX, formula modules, figures
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

from davies_sym.efficiency.turning_conditions import TurningCondition
from davies_sym.efficiency.variant import Variant
from davies_sym.efficiency.variants import VariantSet, derive_variants
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
from davies_sym.network.analysis import Analysis, analyse
from davies_sym.network.sign_condition import SignCondition
from davies_sym.topology.catalog_files import catalog_file, catalog_names
from davies_sym.topology.loader import load, loads
from davies_sym.topology.model import Gear, Link, Ports, State, Train
from davies_sym.topology.states import train_in_state

#: Every variant of a train's efficiency (Laus Tables 5 and 6); ``derive(train).evaluate(values, input)``.
derive = derive_variants

__version__ = "0.1.0"

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
    "Ports",
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
    "derive_variants",
    "load",
    "loads",
    "train_in_state",
]
