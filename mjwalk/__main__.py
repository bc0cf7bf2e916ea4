"""``python -m mjwalk`` runs the command line."""

import sys

from mjwalk.cli import main

sys.exit(main())
