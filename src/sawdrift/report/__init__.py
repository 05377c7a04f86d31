"""Reports read results and tables: phase diagrams, comparisons, validation, benchmarks."""
