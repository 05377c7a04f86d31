"""Code generation setting for every compiled kernel: jumps padded off 32-byte boundaries.

Intel CPUs of the Skylake family (the "JCC erratum" microcode update) run a jump that crosses or
ends on a 32-byte boundary from the legacy decoders instead of the decoded-instruction cache.
Where the loop of a kernel lands relative to those boundaries depends on the address its code is
loaded at, so the same compiled kernel ran at 21 ns per step in most processes and at 36 to
40 ns in about one in twenty (mmd on a prescribed random history: 4 of 84 processes on this
project's 2-core Xeon). With the padding LLVM emits for ``-x86-branches-within-32B-boundaries``
(the counterpart of GCC's and Clang's ``-mbranches-within-32B-boundaries``) none of 106
processes was slow. The padding only moves code: results are the same bit for bit.
"""

from __future__ import annotations

import platform

#: the LLVM option, also part of the key of generated cache modules (see :mod:`sawdrift.codegen.modules`)
OPTION = "-x86-branches-within-32B-boundaries"
_done = False


def align_branches() -> str:
    """Set :data:`OPTION` in LLVM once per process on x86-64; return the setting's tag ("" if not).

    The option is process-wide and affects only code compiled after this call; it is harmless
    for other numba code in the same process.
    """
    global _done
    if platform.machine().lower() not in ("x86_64", "amd64"):
        return ""
    if not _done:
        import llvmlite.binding as llvm

        llvm.set_option("sawdrift", OPTION)
        _done = True
    return OPTION
