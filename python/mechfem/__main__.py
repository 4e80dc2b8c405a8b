"""``python -m mechfem``: the ``mechfem`` command, for an environment whose scripts folder is not on the PATH."""

import sys

from mechfem.cli.command import main

sys.exit(main())
