# ruff: noqa: E501
"""Generated from the Scene schema by ``python -m sawdrift.scene.options``. Do not edit.

One row per scene field: (option name, dotted field, kind, choices, help).
"""

OPTIONS = (
    ('mu', 'material.mu', 'float', (), 'material.mu: Coulomb friction coefficient mu, in (0, 10]; scene default 0.1'),
    ('nu', 'material.nu', 'float', (), "material.nu: Poisson's ratio nu, in (-1, 0.5) (the substrate's, for r(nu)); scene default 0.3"),
    ('theta', 'material.theta', 'float', (), 'material.theta: theta = E*/(4 G*) of the contact, in (0, 10]; default (2 - nu)/(2 (1 - nu)) for identical materials'),
    ('restitution', 'material.restitution', 'float', (), 'material.restitution: coefficient of restitution e of a free normal impact, in [0, 1]: a normal damping that gives the rebound speed ratio e independent of impact speed (compliant models); default none, the undamped contact'),
    ('m-star', 'particle.m_star', 'float', (), 'particle.m_star: m* = a0 m f^2 / (M g) (paper eq. 4), > 0; in (0, inf); scene default 0.1'),
    ('gyration', 'particle.gyration', 'float', (), 'particle.gyration: kappa = I / (m R^2), in (0, 1]: 2/5 solid sphere, 2/3 thin shell; only with effects.rotation = true (another value without rotation is an error); scene default 0.4'),
    ('preload', 'particle.preload', 'float', (), 'particle.preload: F_ext / (m g). It enters the normalized equations only through M = m + F_ext/g in m*; kept for conversion from dimensional inputs; in [0, inf); scene default 0.0'),
    ('load', 'particle.load', 'float', (), "particle.load: constant external tangential force on the particle, in units of its static normal load M g, positive along +x (a motor's thrust, gravity along an incline); in [-100, 100]; scene default 0.0"),
    ('profile', 'particle.profile.shape', 'choice', ('sphere', 'cone', 'flat', 'power', 'table'), 'particle.profile.shape: one of sphere, cone, flat, power, table; scene default sphere'),
    ('profile-exponent', 'particle.profile.exponent', 'float', (), "particle.profile.exponent: p of N* = a*^p for shape 'power'; in [1, 10]"),
    ('amplitude', 'drive.amplitude', 'float', (), 'drive.amplitude: A* = A_y / a0, >= 0; in [0, inf); scene default 0.316'),
    ('horizontal-ratio', 'drive.horizontal_ratio', 'float', (), 'drive.horizontal_ratio: r = horizontal / vertical surface amplitude; default r(nu) (Rayleigh eq.); in [0, 100]'),
    ('ramp-periods', 'drive.ramp_periods', 'float', (), 'drive.ramp_periods: length of the smooth ramp R(t*) = sin^2(pi t* / (2 T_ramp)), periods; in [0, 1e+06]; scene default 5.0'),
    ('orbit', 'drive.orbit', 'choice', ('prograde', 'retrograde'), "drive.orbit: prograde: eq. 1 as printed with y* into the substrate (the crest moves with the wave, the paper's figures); retrograde: a Rayleigh wave on an isotropic half-space (the mirror x -> -x: every drift changes sign); one of prograde, retrograde; scene default prograde"),
    ('backward', 'drive.backward', 'float', (), 'drive.backward: amplitude ratio s of a second, counter-propagating wave (travelling to -x), in [0, 1]; 1: a standing wave; scene default 0.0'),
    ('backward-phase', 'drive.backward_phase', 'float', (), 'drive.backward_phase: phase psi of the counter-propagating wave, degrees; in [-3600, 3600]; scene default 0.0'),
    ('backward-phase-rate', 'drive.backward_phase_rate', 'float', (), 'drive.backward_phase_rate: change of backward_phase per wave period, degrees (a moving trap); in [-3600, 3600]; scene default 0.0'),
    ('position', 'drive.position', 'float', (), 'drive.position: where the particle sits, xi = X / wavelength: with two waves the local orbit depends on it; in [-1e+06, 1e+06]; scene default 0.0'),
    ('wavelength', 'drive.wavelength', 'float', (), "drive.wavelength: L* = wavelength / a0: given, the drive is evaluated at the particle's own position (phase 2 pi (t* -+ x*/L*), a direct run); default: at drive.position; in (0, 1e+15]"),
    ('phase', 'drive.phase', 'float', (), 'drive.phase: phase of u_x against u_y in degrees, u_x = r A* cos(2 pi t* + phase): 90 is the prograde orbit, -90 the retrograde one, 0 and 180 a linear vibration; default from orbit; phase + 180 mirrors x; in [-360, 360]'),
    ('order', 'numerics.order', 'int', (), "numerics.order: Adams-Bashforth order 1-4 (default 4: on the undamped normal oscillation its amplitude error per step is O((h omega)^6), AB3's is (3/8)(h omega)^4, which over thousands of periods changes the drift). The first order-1 steps use the lower orders (start-up from rest at the static compression, where the derivative history is exact); in [1, 4]; scene default 4"),
    ('steps-per-period', 'numerics.steps_per_period', 'int', (), 'numerics.steps_per_period: steps per wave period; default resolves sqrt(1.5/m*) and the wave; in [8, 1e+07]'),
    ('periods', 'numerics.periods', 'float', (), 'numerics.periods: simulated periods (with settle: the minimum); in (0, 1e+07]; scene default 60.0'),
    ('measure-periods', 'numerics.measure_periods', 'int', (), 'numerics.measure_periods: whole periods at the end over which the drift is measured; in [1, 1e+07]'),
    ('drift-tolerance', 'numerics.drift_tolerance', 'float', (), "numerics.drift_tolerance: |drift_ratio| below this is 'stick' (no steady drift); in [0, 1]; scene default 0.001"),
    ('settle', 'numerics.settle', 'bool', (), 'numerics.settle: run on, in chunks of measure_periods, until the drift has settled; default: on where the drift needs longer than periods/3 to relax (of order m*/mu periods: a heavy particle), else a fixed run of periods'),
    ('settle-tolerance', 'numerics.settle_tolerance', 'float', (), 'numerics.settle_tolerance: in (0, 1]; scene default 0.001'),
    ('max-periods', 'numerics.max_periods', 'float', (), 'numerics.max_periods: settle: stop after this many periods even if not settled; default max(5000, 50 m*_x/mu + 20 windows), m*_x the horizontal inertia of the settle method; in [1, 1e+07]'),
    ('friction', 'effects.friction', 'bool', (), 'effects.friction: tangential friction; off: x* is not integrated, no tangential law'),
    ('vertical-inertia', 'effects.vertical_inertia', 'bool', (), 'effects.vertical_inertia: rigid models only: off gives N* = 1 (no vertical inertia)'),
    ('normal-damping', 'effects.normal_damping', 'float', (), "effects.normal_damping: viscous normal damping c: N* += c a*' while in contact; in [0, inf); scene default 0.0"),
    ('horizontal-wave', 'effects.horizontal_wave', 'bool', (), 'effects.horizontal_wave: the horizontal wave component u_x'),
    ('rolling-resistance', 'effects.rolling_resistance', 'float', (), 'effects.rolling_resistance: rolling friction coefficient mu_r of an elastic-plastic rolling spring (needs rotation and a compliant model; 0: off); physically mu_r ~ (contact radius)/R = sqrt(a0/R) times a factor of order 1; in [0, inf); scene default 0.0'),
    ('rotation', 'effects.rotation', 'bool', (), "effects.rotation: the sphere turns: I phi'' = -R T with I = kappa m R^2 (particle.gyration); the contact point then moves like a mass m kappa / (1 + kappa). With a rigid model the particle is then a rigid sphere (a rigid point cannot turn)"),
    ('vertical-wave', 'effects.vertical_wave', 'bool', (), 'effects.vertical_wave: the vertical wave component u_y'),
    ('air-drag', 'effects.air_drag', 'float', (), "effects.air_drag: linear air drag c on the centre, relative to still air (compliant models; 0: off): m* x*'' += -c x*', m* y*'' += -c y*'; c = c_d a0 f / (M g), c_d = 6 pi eta R for Stokes drag; in [0, inf); scene default 0.0"),
)
