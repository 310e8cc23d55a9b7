"""The preprint "5D-Euler Equations for Rotating Bodies": its printed formulas and their verification."""
