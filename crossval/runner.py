"""Run many (scene, method, resolution) jobs: serially, in local processes, or on a dask
cluster, with the same results in every case (each solve is deterministic and uses one FFT
thread)."""

from __future__ import annotations

import logging
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import contact_scene as cs

from .cache import ResultCache
from .methods import METHODS

__all__ = ["Job", "run_jobs", "default_workers"]

log = logging.getLogger("crossval")


@dataclass(frozen=True)
class Job:
    scene: cs.Scene
    method: str
    resolution: float | None = None


def _run(job: Job) -> cs.Result:
    return METHODS[job.method].solve(job.scene, resolution=job.resolution)


def default_workers() -> int:
    return max(1, os.cpu_count() or 1)


def run_jobs(
    jobs: Sequence[Job],
    *,
    workers: int = 1,
    scheduler: str | None = None,
    cache: ResultCache | None = None,
    callback: Callable[[Job, cs.Result], None] | None = None,
) -> list:
    """Results in the order of ``jobs``.  ``scheduler`` is a dask.distributed address (or a
    ``distributed.Client``); ``workers`` > 1 uses local processes.  Cached results are reused
    and new ones stored."""
    cache = cache or ResultCache(None)
    keys = [ResultCache.key(j.scene, j.method, j.resolution) for j in jobs]
    out: list = [cache.get(k) for k in keys]
    todo = [i for i, r in enumerate(out) if r is None]
    for i, r in enumerate(out):
        if r is not None and callback:
            callback(jobs[i], r)

    def done(i, r):
        out[i] = r
        cache.put(keys[i], r)
        if callback:
            callback(jobs[i], r)

    if not todo:
        return out
    if scheduler is not None:
        from distributed import Client, as_completed

        client: Client
        if isinstance(scheduler, Client):
            client = scheduler
        else:
            try:
                client = Client(scheduler)
            except (OSError, ValueError, TypeError) as exc:  # a malformed or unreachable address
                raise cs.SceneError("--scheduler", f"cannot connect to {scheduler!r}: {exc}") from None
        try:
            futs = {client.submit(_run, jobs[i], pure=False): i for i in todo}
            for f in as_completed(futs):
                done(futs[f], f.result())
        finally:
            if client is not scheduler:
                client.close()
    elif workers > 1 and len(todo) > 1:
        from concurrent.futures import ProcessPoolExecutor, as_completed as cf_completed

        with ProcessPoolExecutor(max_workers=workers) as ex:
            pending = {ex.submit(_run, jobs[i]): i for i in todo}
            for g in cf_completed(pending):
                done(pending[g], g.result())
    else:
        for i in todo:
            done(i, _run(jobs[i]))
    return out
