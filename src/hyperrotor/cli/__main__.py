"""``python -m hyperrotor.cli``: the ``hyperrotor`` command."""
import sys

from hyperrotor.cli import main

sys.exit(main())
