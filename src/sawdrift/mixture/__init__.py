"""Two-species mixtures on the wave-driven plane: segregation of positions, a slow model of
touching chains, and sorting times.

* :mod:`.segregation`: how sorted a line of particles is (best-interface purity, its index and
  the Lacey index), from positions;
* :mod:`.chains`: each bead's steady speed under tangential and normal loads, and chains of
  touching beads moving at a common speed in slow time (events: contacts, merges, splits);
* :mod:`.sort`: ensembles of random placements run with the slow model (``sawdrift sort``).
"""
