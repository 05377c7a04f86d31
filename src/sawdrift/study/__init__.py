"""Studies over many scenes: sweeps on serial, process or dask executors, resumable tables."""
