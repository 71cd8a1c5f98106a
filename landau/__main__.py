"""``python -m landau``: the command line (same as the ``landau`` script)."""

import sys

from landau.cli import main

sys.exit(main())
