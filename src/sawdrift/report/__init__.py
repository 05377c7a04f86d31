"""Reports only draw: phase diagrams, comparisons, figures, the explorer page.

The benchmarks (``sawdrift.bench``) and the validation harness (``sawdrift.validation``) sit
beside this package and draw through it; it never imports them.
"""
