"""``python -m hyperrotor.cli``: the ``hyperrotor`` command, through its launcher (its handling of signals after the
command; this module's import has imported the package already)."""
import sys

from _hyperrotor_launch import main

sys.exit(main())
