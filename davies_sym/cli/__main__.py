"""``python -m davies_sym.cli``: the ``derive`` command."""

import sys

from davies_sym.cli.command import main

sys.exit(main())
