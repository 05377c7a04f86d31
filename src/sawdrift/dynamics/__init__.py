"""Dynamics: a run assembled from parts (docs/architecture.md).

* :mod:`.drives` - the substrate's motion, one module per drive (the travelling wave's local orbit
  of any phase, a substrate at rest);
* :mod:`.assembly` - what a run computes, decided once from the scene: scheme, engine, slots, the
  drive and the step; the same decisions print as ``--explain``;
* :mod:`.adams_bashforth` - compliant models (paper eq. 5), Adams-Bashforth orders 1-4, the loop
  generated per contact kernel and drive;
* :mod:`.rigid` - the material point: unilateral contact, Coulomb friction, located events, the
  scheme generated per drive;
* :mod:`.stepper` - one integration advanced in segments (and warm starts for continuation);
* :mod:`.evidence`, :mod:`.window` - what the loops observe (statistics, the event log) and the
  measuring window read from it; :mod:`.synchrony` and :mod:`.lyapunov` - the window's lift-off
  synchrony and its chaos (largest Lyapunov exponent);
* :mod:`.steady` - settling to the steady drift; :mod:`.integrate` - a scene integrated to its
  measured window (the Result is built by :mod:`sawdrift.result.runner`).
"""
