"""A planar four-bar linkage with its own closed form, registered as the sim_origami scene `four-bar`."""
