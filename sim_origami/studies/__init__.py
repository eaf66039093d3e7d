"""Studies built on the harness: questions asked of the models beyond the three-way check (Poisson's ratios of
metamaterials, fabrication errors, run time against error). Scripts and the `bench` command use them; the
validation layers below never import them."""
