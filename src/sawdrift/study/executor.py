"""The one executor of every study: serial, local processes, or a dask.distributed cluster.

Sweeps (and the adaptive maps and drift fields built on them), load curves and bifurcation
diagrams hand their work here as a top-level function and a list of picklable items;
:meth:`Executor.imap` yields ``(index, result)`` in completion order, :meth:`Executor.map` the
results in order. The backend is chosen per batch, as the studies always did:

* ``scheduler`` given (an address, a ``Client`` or a cluster object): dask.distributed;
* ``workers == 1``, or a batch of at most one item with no pool open: serially, in this
  process;
* otherwise a local process pool of ``min(workers, items)`` processes, opened on the first
  parallel batch and kept for the next ones (a load curve's rounds, a field's refinements) until
  :meth:`Executor.close`.

Every backend runs the same function on the same item, so the values are identical. On an
exception or Ctrl-C in the consumer the batch's pending work is cancelled (the ``finally`` of
:meth:`imap`); a ``Client`` given by the caller stays open, one made here is closed.
"""

from __future__ import annotations

import os
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, InvalidStateError, ProcessPoolExecutor, wait
from pathlib import Path
from typing import Any

from ..codegen.loading import load_cached_code_lightly
from ..errors import SceneError

__all__ = ["Executor", "check_scheduler", "resolve_workers"]

#: tasks a process batch keeps submitted per worker process
AHEAD_PER_WORKER = 4

#: most items in one task of a long process batch
MAX_PER_TASK = 4


def _run_task(fn: Callable[[Any], Any], items: list[Any]) -> list[Any]:
    """``fn`` of each item of one task, in a worker process."""
    return [fn(item) for item in items]


#: the address schemes dask.distributed's comms know
SCHEMES = ("tcp", "tls", "inproc", "ucx", "ws", "wss")


def check_scheduler(address: str) -> str:
    """``address`` if it has the form of a dask.distributed scheduler address, [scheme://]host:port
    with a port in 1..65535 (:data:`SCHEMES`), else a one-line SceneError naming the form: a
    malformed one reached dask only after the study's calibration and was an "internal
    failure" there ('missing port number in address')."""
    text = address.strip()
    scheme, sep, rest = text.partition("://")
    if not sep:
        scheme, rest = "tcp", text
    host, colon, port = rest.rpartition(":")
    ok = (scheme in SCHEMES and colon and host.strip("[]") and port.isdigit()
          and 0 < int(port) < 65536) or (scheme == "inproc" and rest)
    if not ok:
        raise SceneError(f"scheduler = {address!r} is not a dask.distributed address: give "
                         "[tcp://]host:port, e.g. tcp://127.0.0.1:8786 (the port 1-65535)")
    return text


def resolve_workers(workers: int | None) -> int:
    """``workers``, or every core when None; a one-line error below 1."""
    workers = workers if workers is not None else (os.cpu_count() or 1)
    if workers < 1:
        raise SceneError(f"workers = {workers} must be >= 1")
    return int(workers)


#: seconds between a worker's checks that the process that started it is still there
PARENT_CHECK_S = 0.5


def _start_worker(parent: int) -> None:
    """What a worker process does first: watch its parent (:func:`_leave_with`), and load the
    compiled code cached on disk without numba's lowering registries
    (:mod:`sawdrift.codegen.loading`; 0.4 s less per worker before its first cell, measured on
    the benchmarks' 2-core machine). The worker is a process of ours, running sawdrift's cells
    only."""
    _leave_with(parent)
    load_cached_code_lightly()


def _leave_with(parent: int) -> None:
    """End this worker once the study process ``parent`` is gone: a study killed outright
    (``kill -9``, an out-of-memory kill) runs no shutdown, and its workers were left running
    their cells for nobody (two of them still busy two minutes after the kill). A daemon thread
    checks every :data:`PARENT_CHECK_S` seconds (:func:`_alive`)."""

    def watch() -> None:
        while _alive(parent):
            time.sleep(PARENT_CHECK_S)
        os._exit(1)

    threading.Thread(target=watch, name="sawdrift-parent-watch", daemon=True).start()


def _quiet_cancelled(args: threading.ExceptHookArgs) -> None:
    """``threading.excepthook`` while an interrupted pool ends: the pool's manager thread, seeing
    its workers gone, sets an error on every future it still holds, and one the study had
    cancelled raises ``InvalidStateError`` there (CPython before 3.12 does not skip cancelled
    futures): a traceback after the "interrupted" line, 2 times in 3 with 2 workers. Anything
    else goes to the hook as before."""
    if isinstance(args.exc_value, InvalidStateError) and "CANCELLED" in str(args.exc_value):
        return
    _HOOK[0](args)


#: the ``threading.excepthook`` :func:`_quiet_cancelled` passes other errors on to
_HOOK = [threading.excepthook]


def _end_workers(pool: ProcessPoolExecutor) -> None:
    """Terminate the pool's worker processes (Python 3.14's ``terminate_workers``, else each
    process of the pool)."""
    if threading.excepthook is not _quiet_cancelled:
        _HOOK[0] = threading.excepthook
        threading.excepthook = _quiet_cancelled
    terminate = getattr(pool, "terminate_workers", None)
    if terminate is not None:
        terminate()
        return
    for proc in list((getattr(pool, "_processes", None) or {}).values()):
        proc.terminate()


def _alive(parent: int) -> bool:
    """Whether the study process ``parent`` still runs: this worker's parent (a forked worker),
    or a process of that id that is not a zombie (a worker started by a fork server has the
    server for its parent: reading the parent's id alone ended every such worker at once)."""
    if os.getppid() == parent:
        return True
    try:
        os.kill(parent, 0)
    except ProcessLookupError:
        return False
    except OSError:
        return True  # not ours to signal: some process has the id
    try:  # a study killed but not yet reaped by its shell
        return Path(f"/proc/{parent}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except (OSError, IndexError):
        return True


class Executor:
    """Runs a study's batches serially, in local processes, or on dask (module docstring).

    Parameters
    ----------
    workers
        1 runs serially; K > 1 uses up to K local processes; None: all cores.
    scheduler
        A dask.distributed scheduler address, ``Client`` or cluster object (then ``workers`` is
        the cluster's business).
    """

    def __init__(self, workers: int | None = None, scheduler: Any = None) -> None:
        self.workers = resolve_workers(workers)
        self.scheduler = check_scheduler(scheduler) if isinstance(scheduler, str) else scheduler
        self._pool: ProcessPoolExecutor | None = None
        self._pool_size = 0
        self._client: Any = None
        #: a Ctrl-C came through a process batch: closing ends the workers instead of waiting
        self._interrupted = False

    def __enter__(self) -> Executor:
        return self

    def __exit__(self, exc_type: object, *exc: object) -> None:
        if isinstance(exc_type, type) and issubclass(exc_type, KeyboardInterrupt):
            # a Ctrl-C anywhere in the block, also where the caller held the results between
            # two of them (outside the batch's own frame, which marks it): end the workers
            self._interrupted = True
        self.close()

    def backend(self, n_items: int) -> str:
        """``"dask"``, ``"serial"`` or ``"processes"``: what a batch of ``n_items`` runs on."""
        if self.scheduler is not None:
            return "dask"
        if self.workers == 1 or n_items == 0 or (n_items == 1 and self._pool is None):
            return "serial"
        # one item goes to a pool already open: its workers have the compiled loops loaded,
        # this process may not (0.8 s for the last one-cell round of an adaptive map)
        return "processes"

    def imap(self, fn: Callable[[Any], Any], items: Sequence[Any],
             tick: float | None = None) -> Iterator[tuple[int | None, Any]]:
        """``(index, fn(items[index]))`` for every item, in completion order.

        With ``tick`` (seconds) a process batch also yields ``(None, None)`` whenever that long
        has passed without a result, so that the caller may poll its journals in between.
        """
        kind = self.backend(len(items))
        if kind == "serial":
            for i, item in enumerate(items):
                yield i, fn(item)
        elif kind == "processes":
            yield from self._processes(fn, items, tick)
        else:
            yield from self._dask(fn, items)

    def map(self, fn: Callable[[Any], Any], items: Sequence[Any]) -> list[Any]:
        """``[fn(item) for item in items]``, computed on this executor."""
        out: list[Any] = [None] * len(items)
        for i, res in self.imap(fn, items):
            if i is not None:
                out[i] = res
        return out

    def close(self) -> None:
        """Shut the process pool down and close a dask client made here (a given one stays).

        After a Ctrl-C the workers are ended rather than waited for: a study's finished cells
        and values are in its journals already, and a bifurcation branch is one task of minutes
        (a SIGINT to the study alone, as `timeout -s INT` sends it, printed "interrupted" and
        then waited for both branches to end)."""
        if self._pool is not None:
            if self._interrupted:
                _end_workers(self._pool)
            # after Ctrl-C nothing more is started
            self._pool.shutdown(wait=not self._interrupted, cancel_futures=True)
            self._pool, self._pool_size = None, 0
        if self._client is not None and self._client is not self.scheduler:
            self._client.close()
        self._client = None

    # -- backends ------------------------------------------------------------------------------

    def _processes(self, fn: Callable[[Any], Any], items: Sequence[Any],
                   tick: float | None) -> Iterator[tuple[int | None, Any]]:
        size = min(self.workers, len(items))
        if self._pool is not None and self._pool_size < size:
            self._pool.shutdown()
            self._pool = None
        if self._pool is None:
            self._pool = ProcessPoolExecutor(max_workers=size, initializer=_start_worker,
                                             initargs=(os.getpid(),))
            self._pool_size = size
        # a bounded number of tasks in flight: waiting on every pending future at each
        # completion cost O(items) per result (3 s of this process's CPU for 1681 cells,
        # taken from the workers on a 2-core machine); a few per worker keep them busy. A long
        # batch goes in tasks of a few items: each task costs this process a submission, a
        # wake-up of the pool's threads and a result to read (about 1 ms of its CPU per item
        # on the 2-core machine, which the workers need)
        ahead = AHEAD_PER_WORKER * size
        # items per task: up to MAX_PER_TASK, as long as the batch still makes four rounds of
        # the tasks in flight (a short batch keeps one item a task, so no worker waits on another)
        per_task = max(1, min(MAX_PER_TASK, len(items) // (4 * ahead)))
        futures: dict[Any, list[int]] = {}
        queued = iter(range(0, len(items), per_task))

        def top_up() -> None:
            while len(futures) < ahead:
                start = next(queued, None)
                if start is None:
                    return
                idx = list(range(start, min(start + per_task, len(items))))
                task = self._pool.submit(_run_task, fn, [items[i] for i in idx])
                futures[task] = idx

        try:
            top_up()
            while futures:
                finished, _ = wait(futures, timeout=tick, return_when=FIRST_COMPLETED)
                for fut in finished:
                    idx = futures.pop(fut)
                    top_up()
                    yield from zip(idx, fut.result(), strict=True)
                if tick is not None:
                    yield None, None
        except KeyboardInterrupt:
            self._interrupted = True
            raise
        finally:
            for fut in futures:
                fut.cancel()

    def _dask(self, fn: Callable[[Any], Any], items: Sequence[Any]) -> Iterator[tuple[int, Any]]:
        try:
            from distributed import as_completed as dask_completed
        except ImportError:
            raise SceneError("--scheduler needs dask.distributed: pip install 'sawdrift[dask]'") from None
        client = self._connect()
        futures = client.map(fn, list(items), pure=False)
        index = {fut.key: i for i, fut in enumerate(futures)}
        try:
            for fut in dask_completed(futures):
                yield index[fut.key], fut.result()
        finally:
            for fut in futures:
                if not fut.done():
                    fut.cancel()

    def _connect(self) -> Any:
        """The dask client: the one given, or one made for the scheduler's address or cluster."""
        from distributed import Client

        if self._client is not None:
            return self._client
        scheduler = self.scheduler
        try:
            if isinstance(scheduler, Client):
                self._client = scheduler
            elif isinstance(scheduler, str):
                self._client = Client(scheduler, timeout="10s")
            else:
                self._client = Client(scheduler)  # a cluster object (LocalCluster, ...)
        except OSError as exc:
            raise SceneError(f"scheduler = {scheduler!r} could not be reached ({exc})") from None
        return self._client
