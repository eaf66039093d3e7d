"""MJCF fragments composed by sim_origami.mjcf (a data folder, importable for importlib.resources)."""
