"""Joint-space planning: the planning problem from a package, RRT-Connect, shortcutting, time parameterisation, fake execution, trajectory files."""
