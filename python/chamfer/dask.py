"""Batch bakes of whole folders on dask.distributed: ``bake_folder`` and ``python -m chamfer.dask``.

A bake is a pure function of (input bytes, options), so a library of meshes is baked as independent
tasks on any Dask cluster (a LocalCluster, or a scheduler's address): one task per large file, or
per batch of small ones. Each file goes through ``chamfer.bake_if_changed`` on a worker:

- outputs are written atomically (a temporary file renamed into place), the asset before its
  ``.chamfer.key`` sidecar, so a worker killed at any point leaves either the old state or the new
  one; Dask runs the task again elsewhere, and files it had finished are then up to date;
- an input whose bytes (and the files an OBJ or .gltf refers to), options and format version match
  the sidecar is skipped, so a re-run bakes only what changed;
- a broken file is reported with its path and reason and never stops the batch.

The outputs are named as ``chamfer bake SRC/ -o DST/`` names them and are the same bytes. The
source folder must be readable, and the destination writable, from every worker (a shared file
system). Run one batch per destination at a time: at the end, temporary files left in it by killed
workers are removed.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import sys
import time
import uuid
from pathlib import Path
from typing import Callable, Dict, List, Optional, Sequence, Tuple

from . import _chamfer

#: Prefix and suffix of the temporary files outputs are written through (chamfer-preprocess's
#: write_atomically).
_TEMPORARY = (".chamfer-", ".tmp")


@dataclasses.dataclass(frozen=True)
class FileResult:
    """What happened to one input."""

    input: str
    output: str
    #: "baked", "skipped" (up to date) or "failed".
    status: str
    #: For a failure, the exception's class ("FormatError", ...) and its message (which names the
    #: file); None otherwise.
    error: Optional[str]
    reason: Optional[str]
    #: Size of the input file, bytes.
    bytes: int
    #: Time spent on it by the worker, seconds.
    seconds: float


@dataclasses.dataclass
class Report:
    """The outcome of a batch: one FileResult per input (sorted by input), and the totals."""

    src: str
    dst: str
    settings: Dict[str, str]
    results: List[FileResult]
    seconds: float
    workers: int
    tasks: int
    #: Temporary files left by killed workers and removed at the end.
    orphans_removed: int

    def _with(self, status: str) -> List[FileResult]:
        return [r for r in self.results if r.status == status]

    @property
    def baked(self) -> List[FileResult]:
        return self._with("baked")

    @property
    def skipped(self) -> List[FileResult]:
        return self._with("skipped")

    @property
    def failed(self) -> List[FileResult]:
        return self._with("failed")

    @property
    def input_bytes(self) -> int:
        return sum(r.bytes for r in self.results)

    def summary(self) -> str:
        """One line: counts, bytes, time, files/s and MB/s."""
        seconds = max(self.seconds, 1e-9)
        megabytes = self.input_bytes / 1e6
        return (
            f"{len(self.results)} files ({megabytes:.1f} MB) in {self.seconds:.2f} s on "
            f"{self.workers} workers, {self.tasks} tasks: {len(self.baked)} baked, "
            f"{len(self.skipped)} skipped (up to date), {len(self.failed)} failed; "
            f"{len(self.results) / seconds:.1f} files/s, {megabytes / seconds:.2f} MB/s"
        )

    def to_dict(self) -> dict:
        """The report as JSON-ready data."""
        data = dataclasses.asdict(self)
        data["summary"] = self.summary()
        return data


def bake_folder(
    src,
    dst,
    client=None,
    *,
    files_per_task: int = 32,
    bytes_per_task: int = 8 << 20,
    progress: Optional[Callable[[int, int], None]] = None,
    **options,
) -> Report:
    """Bakes every mesh under the folder ``src`` into ``dst`` on a Dask cluster; returns a Report.

    ``client`` is a ``distributed.Client``; by default the current one (``distributed.get_client``)
    or, when there is none, a LocalCluster of one worker process per core for the duration of the
    call. Files go to tasks in batches of at most ``files_per_task`` files and about
    ``bytes_per_task`` input bytes (1 and 0 make one task per file). ``progress(done, total)`` is
    called in this process as files complete. Options as for ``chamfer.bake``; wrong options raise
    OptionsError before anything is submitted, a folder that cannot be listed ReadError; a broken
    file is a "failed" entry of the report, never an exception.
    """
    settings = dict(_chamfer.settings(**options))
    plan = [(str(i), str(o)) for i, o in _chamfer.plan_folder(src, dst)]
    sizes = {i: os.stat(i).st_size for i, _ in plan}
    batches = _batches(plan, sizes, files_per_task, bytes_per_task)

    start = time.perf_counter()
    owned = None
    if client is None:
        client, owned = _default_client()
    try:
        workers = len(client.nthreads())
        run = uuid.uuid4().hex[:12]
        futures = {
            client.submit(_bake_batch, batch, options, key=f"chamfer-bake-{run}-{n}", pure=False): batch
            for n, batch in enumerate(batches)
        }
        from distributed import as_completed

        results: List[FileResult] = []
        for future in as_completed(futures):
            batch = futures[future]
            try:
                results.extend(FileResult(**r) for r in future.result())
            except Exception as lost:
                # The task itself failed: its workers kept dying (KilledWorker) or it could not
                # run. Its files are failures of this batch, not of the whole bake.
                reason = f"the task baking it failed: {type(lost).__name__}: {lost}"
                results.extend(
                    FileResult(i, o, "failed", type(lost).__name__, f"{i}: {reason}", sizes[i], 0.0)
                    for i, o in batch
                )
            future.release()
            if progress is not None:
                progress(len(results), len(plan))
    finally:
        if owned is not None:
            client.close()
            owned.close()
    orphans = _remove_orphans(Path(dst))
    results.sort(key=lambda r: r.input)
    return Report(
        src=str(src),
        dst=str(dst),
        settings=settings,
        results=results,
        seconds=time.perf_counter() - start,
        workers=workers,
        tasks=len(batches),
        orphans_removed=orphans,
    )


def _default_client():
    """The current Dask client, or a new LocalCluster's (returned second, to be closed)."""
    from distributed import Client, LocalCluster, get_client

    try:
        return get_client(), None
    except ValueError:
        cluster = LocalCluster(threads_per_worker=1, processes=True, dashboard_address=None)
        return Client(cluster), cluster


def _batches(
    plan: Sequence[Tuple[str, str]], sizes: Dict[str, int], files_per_task: int, bytes_per_task: int
) -> List[List[Tuple[str, str]]]:
    """The plan cut into runs of at most ``files_per_task`` files and about ``bytes_per_task``."""
    batches: List[List[Tuple[str, str]]] = []
    current: List[Tuple[str, str]] = []
    size = 0
    for job in plan:
        current.append(job)
        size += sizes[job[0]]
        if len(current) >= max(files_per_task, 1) or size >= bytes_per_task:
            batches.append(current)
            current, size = [], 0
    if current:
        batches.append(current)
    return batches


def _bake_batch(batch: Sequence[Tuple[str, str]], options: dict) -> List[dict]:
    """Runs on a worker: each file through bake_if_changed; a failure is a result, not an error."""
    results = []
    for input, output in batch:
        start = time.perf_counter()
        status, error, reason = "baked", None, None
        try:
            if not _chamfer.bake_if_changed(input, output, **options):
                status = "skipped"
        except Exception as failure:  # ChamferError, or anything unforeseen: reported, not raised
            status, error, reason = "failed", type(failure).__name__, str(failure)
        except BaseException as failure:
            # A Rust panic arrives as pyo3's PanicException, a BaseException; it too is one file's
            # failure. KeyboardInterrupt and SystemExit still stop the worker.
            if type(failure).__name__ != "PanicException":
                raise
            status, error, reason = "failed", "PanicException", f"{input}: {failure}"
        try:
            size = os.stat(input).st_size
        except OSError:
            size = 0
        results.append(
            dict(
                input=input,
                output=output,
                status=status,
                error=error,
                reason=reason,
                bytes=size,
                seconds=time.perf_counter() - start,
            )
        )
    return results


def _remove_orphans(dst: Path) -> int:
    """Removes the temporary files that workers killed while writing left under ``dst``."""
    removed = 0
    if not dst.is_dir():
        return 0
    for folder, _, files in os.walk(dst):
        for name in files:
            if name.startswith(_TEMPORARY[0]) and name.endswith(_TEMPORARY[1]):
                try:
                    os.remove(os.path.join(folder, name))
                    removed += 1
                except FileNotFoundError:
                    pass
    return removed


def _write_atomically(path: Path, text: str) -> None:
    """Writes ``text`` to ``path`` through a temporary file beside it, renamed into place."""
    temporary = path.with_name(f"{_TEMPORARY[0]}{uuid.uuid4().hex}{_TEMPORARY[1]}")
    try:
        temporary.write_text(text, encoding="utf-8")
        os.replace(temporary, path)
    finally:
        if temporary.exists():
            temporary.unlink()


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="python -m chamfer.dask",
        description="Bake every mesh under SRC into DST on a Dask cluster (a LocalCluster unless "
        "--scheduler names one). Unchanged inputs are skipped; broken ones are reported and the "
        "exit status is 1.",
    )
    parser.add_argument("src", help="folder of meshes (.obj, .gltf, .glb, .ply, .ply.gz)")
    parser.add_argument("dst", help="folder for the .chamfer assets (created if missing)")
    parser.add_argument("--scheduler", metavar="ADDRESS", help="a running Dask scheduler")
    parser.add_argument("--workers", type=int, help="LocalCluster worker processes (default: cores)")
    parser.add_argument("--files-per-task", type=int, default=32)
    parser.add_argument("--bytes-per-task", type=int, default=8 << 20)
    parser.add_argument("--report", metavar="FILE", help="also write the report as JSON")
    bake = parser.add_argument_group("bake options (as chamfer bake's)")
    # The flags come from the extension's option table: one source of truth with chamfer.bake.
    for name, kind, help in _chamfer.OPTIONS:
        flag = "--" + name.replace("_", "-")
        if kind == "bool":
            bake.add_argument(flag, dest=name, action="store_true", default=None, help=help)
        else:
            bake.add_argument(flag, dest=name, type=float if kind == "float" else int, help=help)
    return parser


def main(argv: Optional[Sequence[str]] = None) -> int:
    """The command line: ``python -m chamfer.dask SRC DST [options]`` (also ``chamfer-dask``)."""
    args = _parser().parse_args(argv)
    options = {name: getattr(args, name) for name, _, _ in _chamfer.OPTIONS}
    options = {k: v for k, v in options.items() if v is not None}
    from distributed import Client, LocalCluster

    client = cluster = None
    try:
        if args.scheduler:
            client = Client(args.scheduler)
        else:
            cluster = LocalCluster(
                n_workers=args.workers, threads_per_worker=1, processes=True, dashboard_address=None
            )
            client = Client(cluster)
        report = bake_folder(
            args.src,
            args.dst,
            client,
            files_per_task=args.files_per_task,
            bytes_per_task=args.bytes_per_task,
            **options,
        )
    except _chamfer.ChamferError as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    finally:
        if client is not None:
            client.close()
        if cluster is not None:
            cluster.close()
    for failure in report.failed:
        print(f"error: {failure.reason}", file=sys.stderr)
    print(report.summary())
    if args.report:
        _write_atomically(Path(args.report), json.dumps(report.to_dict(), indent=2) + "\n")
    return 1 if report.failed else 0


if __name__ == "__main__":
    sys.exit(main())
