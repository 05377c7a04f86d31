"""Jaeger / Cattaneo-Mindlin superposition with the Masing rule: a closed-form tangential law.

At a fixed contact size a* the tangential history of a power-law profile has a closed form
(Cattaneo 1938, Mindlin 1949, Mindlin & Deresiewicz 1953; for any axisymmetric profile by the
superposition principle of Jaeger 1998, J. Tribol. 120, 677-684). In the memory-diagram (MDR)
picture of docs/physics.md, write the strip displacement as a function of the
distance u = a* - z from the contact edge. At fixed a* every profile v(u) reachable from an
unloaded contact is a zig-zag: slope s = +-1 (the current direction of motion) on [0, c], then
alternating slopes on [c, C_{n-1}], [C_{n-1}, C_{n-2}], ..., [C_1, C_0], and flat (a stuck core)
beyond C_0, with c < C_{n-1} < ... < C_0 <= a*. Since T* = integral v dN*'(z) = sum over linear
pieces of slope sigma on [u1, u2] of sigma [N*(a* - u1) - N*(a* - u2)], the force is

    T* = s N*(a*) - 2 s N*(a* - c) + 2 s N*(a* - C_{n-1}) - ... (alternating) -+ N*(a* - C_0),

with N*(x) = x^p for x > 0 and 0 otherwise. The breakpoints are the Masing memory:

* virgin loading from the origin o: c = |b* - o|, T* = N*(a*) - N*(a* - |b* - o|) (Cattaneo-
  Mindlin; for the sphere a*^(3/2) - (a* - b*)^(3/2));
* a reversal at b_k pushes the current extent on the stack and starts a branch with c = |b* -
  b_k| / 2: T* = T_k - 2 s [N*(a*) - N*(a* - |b* - b_k| / 2)] (Masing's doubled virgin curve; for
  the sphere the unloading formula of docs/physics.md);
* a branch that grows back to the enclosing breakpoint (c = C_{n-1}, i.e. b* re-crosses the
  previous turning point) erases both turning points and continues on the enclosing branch
  (memory wipe-out, Mindlin & Deresiewicz 1953);
* when the current extent reaches a* the whole contact slides, |T*| = N*(a*), and the memory is
  cleared (the origin is re-based so that c = a*).

At constant a* this is exact: it reproduces the memory-diagram law ``mmd`` to round-off.

When a* varies, the model evaluates the same breakpoints at the current a* ("the stack evaluated
at the current a*": the displacement profile is held fixed in the distance-from-edge coordinate u
and the contact edge carries it along). Precisely, compared with the full memory-diagram law it
ignores:

1. **Mindlin-Deresiewicz load-path dependence while loading.** Strips that enter contact while
   a* grows carry zero displacement in the MDR law, so raising a* at fixed b* leaves T*
   unchanged; here the profile stays attached to the moving edge, so T* = N*(a*) - N*(a* - c)
   grows with a*. Oblique loading from zero along b* = lambda a* gives T* = lambda N*(a*)
   exactly; here it gives N*(a*) - N*((1 - lambda) a*) (larger).
2. **Slip caused by normal unloading.** When a* falls at fixed b* the MDR law clips the strips
   next to the new edge (v(z) is fixed in z, the bound a* - z shrinks); here v(u) is fixed in u,
   so no strip slips until the current extent c itself reaches a* (full sliding).
3. **The displacement history of strips that left contact or entered while a* varied.** Memory
   breakpoints that lie beyond a shrinking a* are forgotten (collapsed into one breakpoint at the
   new a*, so the profile inside the contact is kept and the core beyond it is flat if a* grows
   again); the true history of those strips is not tracked.
4. **Contact re-entry.** A contact that starts at level a* = 0 on a straight path is treated as
   virgin tangential loading from the entry point at the current a* (item 1 again).

Full sliding (c >= a*) and the wipe-out of turning points are evaluated exactly along each
straight path (both are monotone events there), so splitting a straight step into sub-steps
changes nothing.

Memory capacity: the stack holds at most ``memory_capacity`` breakpoints. If a reversal would
overflow it, the interior pair of adjacent breakpoints with the smallest gap is dropped, which
changes T* by at most 2 N*'(a*) times that gap (never triggered by histories whose nesting depth
stays below the capacity).
"""

from __future__ import annotations

from typing import ClassVar

from pydantic import BaseModel, ConfigDict, Field

from sawdrift.contact import Capabilities
from sawdrift.contact.slots import LazyFunction, TangentialLaw
from sawdrift.hookspecs import hookimpl

# float state layout of the tangential slot: reference point of the current branch, breakpoints
_REF, _MEM = 0, 1
# int state layout: number of stored breakpoints, current direction of motion (+1 or -1)
_N, _DIR = 0, 1


class JaegerParams(BaseModel):
    """Parameters of the Jaeger / Masing model."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    memory_capacity: int = Field(
        64,
        ge=4,
        le=4096,
        description=(
            "Maximum number of Masing memory breakpoints (nested unclosed loops) kept; on "
            "overflow the closest interior pair is merged (error <= 2 N*'(a*) x its gap)."
        ),
    )


class JaegerReference:
    """Pure-Python Jaeger / Masing tangential step: the same rules as the kernel, written plainly.

    Parameters
    ----------
    p
        Exponent of the normal law N*(a*) = a*^p.
    capacity
        Maximum number of memory breakpoints.
    """

    def __init__(self, p: float, capacity: int = 64) -> None:
        self.p = p
        self.capacity = capacity
        self.reset()

    def reset(self) -> None:
        """Forget all history: a virgin branch loading in +b."""
        self.ref = 0.0  # origin o of the virgin curve, or the last turning point b_k
        self.direction = 1
        self.breakpoints: list[float] = []  # C_0 > C_1 > ... (outermost first)

    def _n(self, x: float) -> float:
        return x**self.p if x > 0.0 else 0.0

    def extent(self, b: float) -> float:
        """Extent c of the current branch (virgin: |b - o|; Masing branch: |b - b_k| / 2)."""
        factor = 1.0 if not self.breakpoints else 0.5
        return factor * self.direction * (b - self.ref)

    def _reverse(self, b_turn: float, direction: int) -> None:
        mem = self.breakpoints
        if len(mem) >= self.capacity:
            gaps = [mem[j] - mem[j + 1] for j in range(1, len(mem) - 1)]
            j = 1 + gaps.index(min(gaps))
            del mem[j : j + 2]
        mem.append(self.extent(b_turn))
        self.ref = b_turn
        self.direction = direction

    def _move(self, a1: float, b0: float, b1: float) -> None:
        direction = (b1 > b0) - (b1 < b0)
        if direction != 0:
            if direction != self.direction:
                self._reverse(b0, direction)
            mem = self.breakpoints
            while mem and self.extent(b1) >= mem[-1]:
                top = mem.pop()
                b_wipe = self.ref + 2.0 * self.direction * top
                c_wipe = mem.pop() if mem else top  # extent of the re-joined branch there
                factor = 1.0 if not mem else 0.5
                self.ref = b_wipe - self.direction * c_wipe / factor
        if self.extent(b1) >= a1:
            self.breakpoints = []
            self.ref = b1 - self.direction * a1
        elif self.breakpoints and self.breakpoints[0] >= a1:
            inside = [c for c in self.breakpoints if c < a1]
            self.breakpoints = [a1, *inside]

    def tangential(self, a: float, b: float) -> float:
        """T* = sum over the linear pieces of the memory profile v(u) (module docstring)."""
        sign = float(self.direction)
        c = self.extent(b)
        t = sign * (self._n(a) - self._n(a - c))
        u_prev = c
        for u_k in reversed(self.breakpoints):
            sign = -sign
            t += sign * (self._n(a - u_prev) - self._n(a - u_k))
            u_prev = u_k
        return t

    def step(self, a0: float, b0: float, a: float, b: float) -> float:
        """T* at the end of the straight path (a0, b0) -> (a, b); a0 = 0 starts a virgin contact."""
        if a0 == 0.0:
            self.ref = b0
        self._move(a, b0, b)
        return self.tangential(a, b)


class Jaeger(TangentialLaw):
    """Closed-form Cattaneo-Mindlin / Jaeger superposition with Masing memory (see module doc).

    Exact at constant contact size a*; with varying a* it evaluates the turning-point memory at
    the current a* and ignores the load-path effects listed in the module docstring
    (Mindlin & Deresiewicz 1953; Jaeger 1998, J. Tribol. 120, 677-684).
    """

    name: ClassVar[str] = "jaeger"
    summary: ClassVar[str] = (
        "Cattaneo-Mindlin/Jaeger closed form with Masing turning-point memory; exact at fixed a*, "
        "evaluated at the current a* when the normal load varies"
    )
    Params: ClassVar[type[BaseModel]] = JaegerParams
    capabilities: ClassVar[Capabilities] = Capabilities(
        rigid=False, compiled=True, history=True, uses_velocity=False, straight_path_exact=True,
        deviations=(("passivity", "the Masing memory is evaluated at the current a*, so closed "
                     "(a*, b*) cycles with a* varying can create energy (rectangle (1,0)-(1,0.2)-"
                     "(2,0.2)-(2,0): -0.0127 per cycle); exact and passive at constant a*"),),
    )
    step: ClassVar[LazyFunction] = LazyFunction("sawdrift_builtin.jaeger_kernel", "jaeger_step")
    reset_state: ClassVar[LazyFunction] = LazyFunction("sawdrift_builtin.jaeger_kernel", "jaeger_reset")

    def tangential_sizes(self) -> tuple[int, int]:
        """Float state: branch reference and the breakpoints; int state: count, direction.

        The capacity is carried by the size of the float state.
        """
        return _MEM + int(self.params.memory_capacity), 2

    def reference_step(self) -> JaegerReference:
        """The readable step (a fresh :class:`JaegerReference`) for the python engine."""
        return JaegerReference(self.profile.p, int(self.params.memory_capacity))


@hookimpl
def sawdrift_contact_models() -> list[type[TangentialLaw]]:
    """Register the ``jaeger`` model."""
    return [Jaeger]
