"""``python -m axlebox``: the ``axlebox`` command line."""
import sys

from axlebox.pipelines.cli import main

sys.exit(main())
