"""Where the spheres of a mixture start: the ``[particles]`` table, the species and their placement.

A scene's ``[particles]`` table (:class:`Particles`) places ``count`` spheres of one or two radii
(``fraction`` of them of the first) on the plane that carries the scene's wave.

Species. Every sphere has the scene's density and moduli, so a sphere of radius R_s has its own
static compression a0_s = (9 (m_s g)^2 / (16 R_s E*^2))^(1/3) and its own normalized numbers

    m*_s = a0_s m_s f^2 / (m_s g) = a0_s f^2 / g,        A*_s = A_y / a0_s,

(docs/physics.md): a0 grows as R^(5/3), so a larger sphere has a larger m* and a smaller A*, and
drifts at another speed; that is what separates a mixture. :func:`species_scene` is the
single-particle scene of one species (the device with that radius, or the normalized scene with
m*_s and A*_s), whose native ``hertz_mindlin_dem`` drift is the dilute limit of the mixture.

Placement (:func:`placement`). ``packing = "lattice"``: a jittered square lattice, spheres apart
(the dilute limit). ``packing = "rows"``: rows along x (the propagation), each sphere as close
to the one before it as it can be without overlap: it touches the sphere that limits it (two
resting spheres touch at the centre distance sqrt((R_i + R_j)^2 - (z_i - z_j)^2), z_s = R_s -
a0_s: zero overlap, no force; a small sphere between two large ones lets the large ones touch
each other and rattles in the gap under them); the rows are ``spacing`` largest diameters
apart in y, and a largest diameter of free plane closes each row at the periodic boundary.
``positions = [[x, y, species], ...]`` places each sphere by hand (x, y lengths; species 0 or 1,
the index into ``radius``), for chains and validation cases; :func:`touching_row` gives the x of
a row of given species that touch (zero overlap, no force) from the start.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator, model_validator

from ..errors import SceneError
from ..scene.bounds import NOT_A_NUMBER
from ..scene.device import to_si
from ..scene.messages import format_validation_error
from ..scene.schema import Scene
from ..scene.units import in_range
from .realize import Realization, realize


class Particles(BaseModel):
    """The ``[particles]`` table: how many spheres, of which radii, in which proportion."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    count: Annotated[int, Field(ge=1, le=100_000)] = Field(
        200, description="number of spheres, in [1, 100000]")
    radius: list[float | str] = Field(
        ..., description="one or two radii: lengths ('0.5 mm', or a number in m); on a normalized "
        "scene lengths of its realization, whose reference sphere has R = 1 mm")
    fraction: Annotated[float, Field(gt=0.0, lt=1.0)] = Field(
        0.5, description="share of the first radius with two radii, in (0, 1)")
    spacing: Annotated[float, Field(ge=1.05, le=1000.0)] = Field(
        3.0, description="lattice spacing (lattice) or distance between rows (rows) in largest "
        "diameters, in [1.05, 1000] (dilute: large)")
    packing: Literal["lattice", "rows"] = Field(
        "lattice", description="'lattice': a jittered square lattice, spheres apart (the dilute "
        "limit); 'rows': rows along x of spheres touching their neighbours from the start")
    row: Annotated[int, Field(ge=1, le=100_000)] | None = Field(
        None, description="spheres per row with packing = 'rows' (default: ceil(sqrt(count)))")
    seed: Annotated[int, Field(ge=0)] = Field(
        0, description="seed of the placement and the species' assignment, >= 0")
    positions: list[list[float | str]] | None = Field(
        None, description="explicit placement [[x, y, species], ...]: x, y lengths inside the "
        "box, species 0 or 1 (the index into radius); replaces packing, count follows from it")
    box: list[float | str] | None = Field(
        None, description="[lx, ly], the periodic box with explicit positions (default: the "
        "positions' extent and two largest diameters of free plane along x)")

    @model_validator(mode="before")
    @classmethod
    def _count_of_positions(cls, data: Any) -> Any:
        _no_booleans(data)
        if isinstance(data, dict) and isinstance(data.get("positions"), list):
            n = len(data["positions"])
            if "count" in data and data["count"] != n:
                raise ValueError(f"count = {data['count']} but {n} positions are given; give one "
                                 "of them")
            data = {**data, "count": n}
        return data

    @field_validator("positions")
    @classmethod
    def _triples(cls, value: list[list[float | str]] | None) -> list[list[float | str]] | None:
        for i, item in enumerate(value or []):
            if len(item) != 3 or not _is_index(item[2]):
                raise ValueError(f"entry {i} = {item!r}: give [x, y, species] (lengths, and the "
                                 "species as 0 or 1, the index into radius)")
            for v in item[:2]:
                if not math.isfinite(to_si(v, "length")) or to_si(v, "length") < 0.0:
                    raise ValueError(f"entry {i} = {item!r}: x and y are lengths >= 0")
        return value

    @field_validator("box")
    @classmethod
    def _box(cls, value: list[float | str] | None) -> list[float | str] | None:
        if value is not None and (len(value) != 2 or min(to_si(v, "length") for v in value) <= 0):
            raise ValueError(f"{value!r}: give [lx, ly], two positive lengths")
        return value

    @field_validator("radius", mode="before")
    @classmethod
    def _one_or_list(cls, value: Any) -> Any:
        return [value] if isinstance(value, (int, float, str)) else value

    @field_validator("radius")
    @classmethod
    def _lengths(cls, value: list[float | str]) -> list[float | str]:
        if len(value) not in (1, 2):
            raise ValueError(f"has {len(value)} values: give one or two radii (one or two species)")
        for i, item in enumerate(value):
            size = to_si(item, "length")
            if not size > 0.0:
                raise ValueError(f"{item!r} is not a positive length, e.g. '0.5 mm'")
            try:  # a device particle's range: lammps ran spheres of 0.5 m that sort refused
                in_range("particle.radius", size, "m", item)
            except ValueError as exc:
                raise ValueError(f"[{i}] = {item!r} {exc}") from None
        return value

    @model_validator(mode="after")
    def _both_species(self) -> Particles:
        if self.positions is not None:
            bad = [float(p[2]) for p in self.positions
                   if int(float(p[2])) not in range(len(self.radius))]
            if bad:
                raise ValueError(f"positions: species {bad[0]:g} is not an index into radius "
                                 f"(0 to {len(self.radius) - 1})")
            return self
        if len(self.radius) == 2 and self.count < 2:
            raise ValueError("two radii need count >= 2")
        return self

    def radii_m(self) -> list[float]:
        """The radii in m."""
        return [to_si(r, "length") for r in self.radius]

    def kinds(self) -> np.ndarray | None:
        """The species index of each explicit position (None without positions)."""
        if self.positions is None:
            return None
        return np.array([int(float(p[2])) for p in self.positions], dtype=int)

    def counts(self) -> list[int]:
        """Spheres of each species: round(fraction count) of the first (at least one of each);
        with explicit positions, those of each index."""
        kinds = self.kinds()
        if kinds is not None:
            return [int((kinds == k).sum()) for k in range(len(self.radius))]
        if len(self.radius) == 1:
            return [self.count]
        first = min(max(1, round(self.fraction * self.count)), self.count - 1)
        return [first, self.count - first]


def _is_index(value: Any) -> bool:
    """Whether a position's species is a whole number (a name such as 'small' said "could not
    convert string to float")."""
    try:
        return float(value).is_integer()
    except (TypeError, ValueError):
        return False


def _no_booleans(data: Any, where: str = "") -> None:
    """Refuse a boolean anywhere in the table: every field is a number, a length or a list of
    them, and ``true`` read as 1 placed 100 spheres of radius 1 m (``radius = [true, "1 mm"]``),
    a sphere at x = 1 m or a row of 1."""
    if isinstance(data, bool):
        raise ValueError(f"{where or 'particles'} = {str(data).lower()} {NOT_A_NUMBER}")
    items = (data.items() if isinstance(data, dict) else
             ((f"[{i}]", v) for i, v in enumerate(data)) if isinstance(data, list) else ())
    for key, value in items:
        _no_booleans(value, f"{where}.{key}" if where and not key.startswith("[") else
                     f"{where}{key}")


def parse_particles(data: Any) -> Particles:
    """Validate a ``[particles]`` table; errors are one SceneError line naming the field."""
    if not isinstance(data, dict):
        raise SceneError("particles must be a table: count, radius (one or two), fraction, "
                         "spacing, seed")
    try:
        return Particles.model_validate(data)
    except ValidationError as exc:
        line = format_validation_error(exc)
        raise SceneError(f"particles.{line}" if not line.startswith("scene:") else
                         f"particles: {line.removeprefix('scene: ')}") from None


@dataclass(frozen=True)
class Species:
    """One species: its radius and mass (SI), static compression, normalized m*_s and A*_s."""

    radius: float
    mass: float
    a0: float
    m_star: float
    amplitude: float
    count: int


def species_of(scene: Scene, spec: Particles, real: Realization | None = None) -> list[Species]:
    """The species of ``spec`` on ``scene``'s realization (module docstring)."""
    real = realize(scene) if real is None else real
    g = real.weight / real.mass
    rho = real.density
    out = []
    for radius, count in zip(spec.radii_m(), spec.counts(), strict=True):
        mass = rho * 4.0 / 3.0 * math.pi * radius**3
        a0 = (9.0 * (mass * g) ** 2 / (16.0 * radius * real.e_star**2)) ** (1.0 / 3.0)
        out.append(Species(radius, mass, a0, a0 * real.frequency**2 / g, real.amplitude / a0, count))
    return out


def species_scene(scene: Scene, sp: Species) -> Scene:
    """The single-particle scene of species ``sp`` (its native drift is the dilute limit)."""
    if scene.device is not None:
        return scene.with_updates(**{"device.particle.radius": sp.radius})
    return scene.with_updates(**{"particle.m_star": sp.m_star, "drive.amplitude": sp.amplitude})


def check_many(scene: Scene) -> None:
    """One SceneError line if ``scene`` cannot carry many particles (a preload, load or incline)."""
    if scene.particle.preload != 0.0 or (scene.device is not None and scene.device.preload != 0.0):
        raise SceneError("particles: a preload acts on one slider; many particles feel gravity "
                         "only (set device.preload / particle.preload to 0)")
    if scene.particle.load != 0.0:
        raise SceneError("particles: a tangential load or incline is not supported with many "
                         "particles (set device.load, device.incline, particle.load to 0)")
    if scene.effects.normal_damping > 0.0:
        raise SceneError("particles: effects.normal_damping is one particle's viscous damping; "
                         "damp a mixture with material.restitution (every pair and the plate)")
    if scene.device is not None and scene.device.particle.density is None:
        raise SceneError("particles: device.particle needs a density (each species' mass is "
                         "4/3 pi R^3 rho)")


def touching_row(species: list[Species], kinds: np.ndarray | list[int]) -> np.ndarray:
    """x of a row of spheres of ``kinds`` in this order, each touching the one that limits it.

    The first sphere's centre is at its radius; each next one sits as close to the ones before
    as it can without overlap, at rest on the plane (centre height R_s - a0_s): the centre
    distance to sphere i is sqrt((R + R_i)^2 - (z - z_i)^2), zero overlap and no force (a small
    sphere under two large ones lets them touch each other).
    """
    kinds = np.asarray(kinds, dtype=int)
    r = np.array([species[k].radius for k in kinds])
    z = np.array([species[k].radius - species[k].a0 for k in kinds])
    xs = np.empty(kinds.size)
    xs[0] = r[0]
    for j in range(1, kinds.size):
        reach = np.sqrt(np.maximum((r[j] + r[:j]) ** 2 - (z[j] - z[:j]) ** 2, 0.0))
        xs[j] = float(np.max(xs[:j] + reach))
    return xs


def _explicit(spec: Particles, species: list[Species]) -> tuple[np.ndarray, np.ndarray, float, float]:
    """Explicit positions, their species and the box; overlapping spheres are a SceneError."""
    assert spec.positions is not None
    kinds = spec.kinds()
    assert kinds is not None
    xy = np.array([[to_si(p[0], "length"), to_si(p[1], "length")] for p in spec.positions])
    r = np.array([species[k].radius for k in kinds])
    z = np.array([species[k].radius - species[k].a0 for k in kinds])
    r_max = float(r.max())
    if spec.box is not None:
        lx, ly = (to_si(v, "length") for v in spec.box)
    else:
        # periodic: the spheres at the far edges must clear the images of those at 0
        lx = float((xy[:, 0] + r).max()) + 2.0 * r_max
        ly = max(float((xy[:, 1] + r).max()) + r_max, 2.0 * r_max * spec.spacing)
    if (xy[:, 0] >= lx).any() or (xy[:, 1] >= ly).any():
        raise SceneError(f"particles.positions: every x, y must lie inside the box [{lx:g}, {ly:g}] m")
    if kinds.size <= 2000:
        # the box is periodic in x and y: the nearest image of each pair (two spheres 1 mm
        # apart across the boundary overlapped unseen and slowed the 1 mm species 6000-fold)
        dxy = xy[:, None, :] - xy[None, :, :]
        dxy -= np.array([lx, ly]) * np.round(dxy / np.array([lx, ly]))
        d2 = (dxy ** 2).sum(axis=2) + (z[:, None] - z[None, :]) ** 2
        gap = np.sqrt(d2) - (r[:, None] + r[None, :])
        np.fill_diagonal(gap, np.inf)
        i, j = np.unravel_index(int(np.argmin(gap)), gap.shape)
        if gap[i, j] < -1e-9 * r_max:
            raise SceneError(f"particles.positions: spheres {min(i, j)} and {max(i, j)} overlap by "
                             f"{-gap[i, j]:.3g} m (the box [{lx:g}, {ly:g}] m is periodic); place "
                             "them at least R_i + R_j apart, or give a larger particles.box")
    return xy, kinds, lx, ly


def placement(spec: Particles, species: list[Species]) -> tuple[np.ndarray, np.ndarray, float, float]:
    """Positions (x, y), species index of each sphere and the box (lx, ly).

    ``lattice``: a square lattice of constant ``spacing`` largest diameters, each sphere moved at
    random within its cell by up to half the free gap (no two touch). ``rows``: rows of ``row``
    spheres along x, neighbours touching (module docstring), rows ``spacing`` largest diameters
    apart. The species are shuffled with ``seed`` in both.
    """
    rng = np.random.default_rng(spec.seed)
    r_max = max(s.radius for s in species)
    cell = 2.0 * r_max * spec.spacing
    n = spec.count
    if spec.positions is not None:
        return _explicit(spec, species)
    kinds = np.repeat(np.arange(len(species)), [s.count for s in species])
    if spec.packing == "rows":
        rng.shuffle(kinds)
        per_row = spec.row if spec.row is not None else max(1, math.ceil(math.sqrt(n)))
        xy = np.empty((n, 2))
        longest = 0.0
        for start in range(0, n, per_row):
            idx = np.arange(start, min(n, start + per_row))
            xs = touching_row(species, kinds[idx])
            r = np.array([species[k].radius for k in kinds[idx]])
            xy[idx, 0] = xs
            xy[idx, 1] = (start // per_row + 0.5) * cell
            longest = max(longest, float(xs[-1] + r[-1]))
        rows = math.ceil(n / per_row)
        return xy, kinds, longest + 2.0 * r_max, rows * cell
    nx = max(1, math.ceil(math.sqrt(n)))
    ny = max(1, math.ceil(n / nx))
    idx = np.arange(n)
    jitter = 0.5 * (cell - 2.0 * r_max) * rng.uniform(-1.0, 1.0, size=(n, 2))
    xy = np.column_stack([(idx % nx + 0.5) * cell, (idx // nx + 0.5) * cell]) + jitter
    rng.shuffle(kinds)
    return xy, kinds, nx * cell, ny * cell
