"""Other tools' published CPU times for the free runs validation reports (`validation.run_free`), shown beside ours."""

# Scene name -> (tool, CPU seconds for the same 10 s free run from rest under gravity, as its authors report it).
FREE_RUN_PEERS: dict[str, tuple[str, float]] = {
    # IFToMM A04, Bricard's mechanism: OpenSim's re-implementation (RehabEngGroup/MBSbenchmarksInOpenSim,
    # src/A04-BricardsMechanism).
    "iftomm-a04": ("OpenSim", 0.258),
}
