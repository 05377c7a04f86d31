"""Two-species mixtures on the wave-driven plane: segregation of positions, a slow model of
touching chains, and sorting times.

* :mod:`.segregation`: how sorted a line of particles is (best-interface purity, its index and
  the Lacey index), from positions;
* :mod:`.curves`: each bead's steady speed under a tangential and a normal load (force-velocity
  curves over normal loads, cached on disk);
* :mod:`.chains`: chains of touching beads at a common speed, pair forces along the inclined
  contact normals, splits where a pair force would pull;
* :mod:`.events`: beads in lanes along the wave moved from contact to contact in slow time (1-D);
* :mod:`.plane`: beads on the plate in 2-D, sliding round each other (:mod:`.plane_curves`,
  :mod:`.plane_kernel` and :mod:`.plane_step`: its compiled parts);
* :mod:`.check`: chains placed by hand, in LAMMPS and in the slow model;
* :mod:`.sort`: ensembles of random placements run with the slow model (``sawdrift sort``).
"""
