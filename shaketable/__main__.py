"""``python -m shaketable``: the same as the ``shaketable`` command."""

import sys

from shaketable.cli import main

sys.exit(main())
