"""Dynamics: the wave kinematics once, and one integration scheme per module.

* :mod:`.wave` - substrate motion of paper eq. 1 and the start-up ramp;
* :mod:`.adams_bashforth` - compliant models (paper eq. 5), Adams-Bashforth orders 1-4;
* :mod:`.rigid` - the material point: unilateral contact, Coulomb friction, located events;
* :mod:`.runner` - assembles the slots a scene asks for and picks the scheme.
"""
