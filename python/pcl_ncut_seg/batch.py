"""A folder of point clouds and meshes segmented into a folder of results, on one machine or a
Dask cluster:

    python -m pcl_ncut_seg.batch IN OUT [the tool's flags: -segments 6, -paper, ...]
        [--scheduler tcp://HOST:PORT] [--workers N] [--force] [--no-progress]

Every .pcd, .ply, .off, .obj and .npy under IN is read as the pcl_ncut_seg tool reads it and
segmented with the given parameters; its labelled PCD (x y z rgb label, as the tool writes it)
goes under OUT with the same relative path and the extension .pcd. OUT/batch.csv (and
OUT/batch.parquet where pyarrow imports) has a row per input: its points, segments, each
phase's time, the view and noise tests, or the error that stopped it.

Nothing is lost and nothing done twice: every file is written under a temporary name and
renamed; an input whose output is newer than it (or whose error is recorded) is skipped on the
next run unless --force; OUT/.batch.jsonl records each row as it comes, so a run killed and
started again ends with the table of an uninterrupted one. run() is the same as a function.
"""
import argparse
import os
import sys
import time
from urllib.parse import urlparse

from . import parameter_shorthands, parameter_table
from ._batch_files import (JOURNAL, TABLE, Journal, remove_temporaries, write_tables,
                           write_whole)
from ._inputs import EXTENSIONS, InputError, read_cloud
from ._pcd import labelled_pcd

__all__ = ["BatchError", "main", "run", "segment_file"]


class BatchError(RuntimeError):
    """A run that cannot start: bad folders, parameters that are not OUT's, no cluster."""


def segment_file(source, target, parameters, host_threads=None):
    """Segment the file source and write its labelled PCD to target (on a worker: only the row
    goes back). Returns the row; an input that cannot be segmented gives a row with its error,
    and no output. host_threads: the Dask threads per host, to share the host's cores."""
    row, start = {}, time.perf_counter()
    try:
        cloud = read_cloud(source)
    except InputError as error:
        return dict(row, error=str(error))
    row.update(points=cloud.points.size // 3, faces=cloud.faces,
               read_s=time.perf_counter() - start)
    options = dict(parameters)
    if "threads" not in options:
        options["threads"] = _threads_per_task(host_threads)
    segmenter = _segmenter(options)
    try:
        labels = segmenter.segment(cloud.points, sensor_origin=cloud.sensor_origin)
    except ValueError as error:
        return dict(row, error=str(error))
    row.update(_results(segmenter))
    start = time.perf_counter()
    write_whole(target, labelled_pcd(cloud.points, labels, cloud.viewpoint))
    row["write_s"] = time.perf_counter() - start
    return row


def _segmenter(parameters):
    # Imported here: a name of this module would be checked by stubtest, which allows
    # pybind11's metaclass for pcl_ncut_seg.Segmenter only.
    from . import Segmenter

    return Segmenter(**parameters)


def _results(segmenter):
    times, view, noise = segmenter.phase_times, segmenter.view_test, segmenter.noise_test
    row = {f"{phase}_s": seconds for phase, seconds in times.items()}
    row.update(segments=segmenter.num_segments, supernodes=segmenter.num_supernodes,
               refined_supernodes=segmenter.num_refined_supernodes, view=view["view"],
               view_origin_estimated=view["origin_estimated"], rim_points=view["rim_points"],
               residual_growth=noise["residual_growth"], projected=noise["projected"],
               sampling_irregularity=noise["sampling_irregularity"],
               irregular=noise["irregular"])
    return row


def _threads_per_task(host_threads):
    """This host's cores over the Dask threads running on it (1 with a worker per core)."""
    try:
        from distributed import get_worker

        host = urlparse(get_worker().address).hostname
    except (ImportError, ValueError):  # not in a Dask worker
        return 0
    cores = len(os.sched_getaffinity(0))
    return max(1, cores // (host_threads or {}).get(host, cores))


def list_inputs(source, target):
    """The relative paths of the inputs under source, sorted; hidden files and the folder
    target (when it is inside source) left out."""
    inputs, skip = [], os.path.realpath(target)
    for directory, subdirectories, names in os.walk(source):
        subdirectories[:] = sorted(
            d for d in subdirectories if not d.startswith(".")
            and os.path.realpath(os.path.join(directory, d)) != skip)
        for name in sorted(names):
            if not name.startswith(".") and os.path.splitext(name)[1].lower() in EXTENSIONS:
                inputs.append(os.path.relpath(os.path.join(directory, name), source))
    return sorted(inputs)


def output_names(inputs):
    """input -> its output's relative path: the extension replaced by .pcd, or .pcd appended
    to the name when two inputs of a folder differ only by their extension (a.off, a.ply)."""
    stems = {}
    for path in inputs:
        stems.setdefault(os.path.splitext(path)[0], []).append(path)
    return {path: (stem + ".pcd" if len(paths) == 1 else path + ".pcd")
            for stem, paths in stems.items() for path in paths}


def run(source, target, parameters=None, *, scheduler=None, workers=None, force=False,
        progress=None):
    """run(source, target, parameters=None, *, scheduler=None, workers=None, force=False,
    progress=None) -> list of dict

    Segment every input under the folder source into the folder target (see the module's
    help) with parameters (segment()'s keywords: {"segments": 6}, {"paper": True}, or the
    tool's strings). scheduler: a running Dask scheduler's address (tcp://HOST:PORT), whose
    workers see source and target at the same paths; None: a local cluster of `workers`
    processes (default: one per core). force: redo the inputs that are up to date.
    progress: a tqdm bar on stderr (None: when stderr is a terminal).

    Returns the table's rows, by input. Raises BatchError when the run cannot start.
    """
    source, target = os.path.abspath(source), os.path.abspath(target)
    parameters = dict(parameters or {})
    if progress is not False:
        _tqdm()  # before anything is written: a run that cannot show its bar does not start
    resolved = _resolved(parameters)
    inputs = _check_folders(source, target)
    journal = _open_journal(target, resolved, force)
    names = output_names(inputs)
    stamps = {path: _stamp(os.path.join(source, path)) for path in inputs}
    todo = [path for path in inputs
            if force or not _up_to_date(journal, path, stamps[path], target, names[path])]
    journal.start(keep=set(inputs) - set(todo))
    try:
        if todo:
            jobs = {path: (os.path.join(source, path), os.path.join(target, names[path]))
                    for path in todo}
            _segment_all(jobs, parameters, stamps, journal, scheduler, workers,
                         _bar(progress, len(todo), len(inputs) - len(todo)))
    finally:  # also on Ctrl-C: the table of what is done, the journal for the next run
        journal.close()
        remove_temporaries({os.path.dirname(os.path.join(target, n)) for n in names.values()})
        rows = journal.rows()
        for row in rows:
            row["output"] = None if row.get("error") else names[row["input"]]
        write_tables(target, rows)
    return rows


def _resolved(parameters):
    """The full parameters the keywords give (a bad one: BatchError), threads left out: the
    labels do not depend on it."""
    try:
        values = _segmenter(parameters).parameters
    except (ValueError, TypeError) as error:
        raise BatchError(str(error)) from None
    values.pop("threads", None)
    return values


def _check_folders(source, target):
    if not os.path.isdir(source):
        raise BatchError(f"IN '{source}' is not a folder")
    if os.path.realpath(source) == os.path.realpath(target):
        raise BatchError("OUT must be another folder than IN: the outputs would replace "
                         "the .pcd inputs")
    if os.path.exists(target) and not os.path.isdir(target):
        raise BatchError(f"OUT '{target}' is not a folder")
    inputs = list_inputs(source, target)
    names = output_names(inputs)
    sources = {os.path.realpath(os.path.join(source, path)) for path in inputs}
    for path in inputs:
        if os.path.realpath(os.path.join(target, names[path])) in sources:
            raise BatchError(f"the output of '{path}' would replace an input: choose an OUT "
                             "outside IN")
    os.makedirs(target, exist_ok=True)
    return inputs


def _open_journal(target, parameters, force):
    path = os.path.join(target, JOURNAL)
    journal = Journal.load(path)
    if journal and journal.parameters != parameters and not force:
        changed = sorted(k for k in parameters if journal.parameters.get(k) != parameters[k])
        raise BatchError(f"OUT holds results of other parameters ({', '.join(changed)}): "
                         "give --force to redo them, or another OUT")
    if journal is None or force:
        journal = Journal(path, parameters)
    return journal


def _stamp(path):
    stat = os.stat(path)
    return [stat.st_size, stat.st_mtime_ns]


def _up_to_date(journal, path, stamp, target, name):
    """Its row is there for this very input, and its output is no older than it (make's rule),
    or its error is the input's own."""
    entry = journal.entries.get(path)
    if not entry or entry["stamp"] != stamp or not entry["final"]:
        return False
    if entry["row"].get("error"):
        return True
    try:
        return os.stat(os.path.join(target, name)).st_mtime_ns >= stamp[1]
    except OSError:
        return False


def _tqdm():
    try:
        from tqdm import tqdm
    except ImportError:
        raise BatchError("the progress bar needs tqdm: apt-get install python3-tqdm (Debian 12), "
                         "or run with --no-progress") from None
    return tqdm


def _bar(progress, total, skipped):
    if progress is False:
        return None
    return _tqdm()(total=total, unit="file", dynamic_ncols=True, smoothing=0.1,
                disable=None if progress is None else False,
                desc="segmenting" + (f" ({skipped} up to date)" if skipped else ""))


def _segment_all(jobs, parameters, stamps, journal, scheduler, workers, bar):
    """Send the jobs to the cluster and journal each row as it comes back."""
    with _client(scheduler, min(workers or len(os.sched_getaffinity(0)), len(jobs))) as client:
        _check_workers_see(client, jobs)
        host_threads = _host_threads(client)
        # Largest first: the long files start early instead of ending a run alone.
        order = sorted(jobs, key=lambda path: (-stamps[path][0], path))
        futures = {client.submit(segment_file, *jobs[path], parameters, host_threads,
                                 pure=False): path for path in order}
        failed = 0
        from distributed import as_completed

        for future in as_completed(futures):
            path = futures.pop(future)
            row, final = _row_of(future, path)
            journal.add(row, stamps[path], final)
            future.release()
            failed += bool(row.get("error"))
            if bar is not None:
                bar.set_postfix(failed=failed, refresh=False)
                bar.update()
    if bar is not None:
        bar.close()


def _row_of(future, path):
    """The row of a finished job, and whether it is final: a row, or the error of a job that
    did not finish (its worker died, a write failed), which the next run tries again."""
    try:
        row = future.result()
        final = True
    except Exception as error:  # anything the task raised or Dask reports for it
        text = " ".join(str(error).split()) or type(error).__name__
        row, final = {"error": f"{type(error).__name__}: {text}"}, False
    row["input"] = path
    return row, final


class _client:
    """A Dask client of the scheduler given, or of a local cluster of one single-threaded
    worker process per core (or `workers`), on loopback; closed on leaving."""

    def __init__(self, scheduler, workers):
        self.scheduler, self.workers, self.cluster, self.client = scheduler, workers, None, None

    def __enter__(self):
        try:
            from distributed import Client, LocalCluster
        except ImportError:
            raise BatchError("the batch front end needs Dask: apt-get install "
                             "python3-distributed (Debian 12)") from None
        if self.scheduler:
            try:
                self.client = Client(self.scheduler, timeout="30s")
            except (OSError, TimeoutError) as error:
                raise BatchError(f"no Dask scheduler at {self.scheduler}: {error}") from None
            return self.client
        import logging

        # No memory limit: one large cloud may take more than RAM / workers, as in a loop.
        self.cluster = LocalCluster(n_workers=self.workers, threads_per_worker=1, processes=True,
                                    host="127.0.0.1", dashboard_address=None, memory_limit=0,
                                    silence_logs=logging.ERROR)
        self.client = Client(self.cluster)
        return self.client

    def __exit__(self, *exc):
        if self.client:
            self.client.close()
        if self.cluster:
            self.cluster.close()


def _check_workers_see(client, jobs):
    """Each worker reads its input and writes its output: the folders must be shared."""
    folders = sorted({os.path.dirname(source) for source, _ in jobs.values()})[:1]
    seen = client.run(os.path.isdir, folders[0])
    blind = sorted(worker for worker, ok in seen.items() if not ok)
    if blind:
        raise BatchError(f"worker {blind[0]} does not see {folders[0]}: the workers need IN "
                         "and OUT at the same paths (shared storage)")


def _host_threads(client):
    threads = {}
    for address, info in client.scheduler_info()["workers"].items():
        host = urlparse(address).hostname
        threads[host] = threads.get(host, 0) + info["nthreads"]
    return threads


def _parser():
    parser = argparse.ArgumentParser(
        prog="python -m pcl_ncut_seg.batch", allow_abbrev=False,
        formatter_class=argparse.RawDescriptionHelpFormatter,
        description=__doc__.split("\n\n", 1)[0],
        epilog="Exit status: 0 when every input was segmented, 1 when some failed (their "
               "errors are in the table), 2 when the run could not start.")
    parser.add_argument("source", metavar="IN", help="the folder of inputs")
    parser.add_argument("target", metavar="OUT", help="the folder of results (made if absent)")
    parser.add_argument("--scheduler", metavar="tcp://HOST:PORT",
                        help="a running Dask scheduler whose workers see IN and OUT at the same "
                             "paths (default: a local cluster)")
    parser.add_argument("--workers", type=_positive, metavar="N",
                        help="worker processes of the local cluster (default: one per core)")
    parser.add_argument("--force", action="store_true",
                        help="redo the inputs whose results are up to date")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    group = parser.add_argument_group("parameters", "the pcl_ncut_seg tool's flags")
    group.add_argument("-paper", action="store_true", default=None,
                       help="start from the paper's parameters")
    for short in parameter_shorthands():
        group.add_argument(f"-{short['name']}", dest=short["parameter"], action="store_const",
                           const=short["value"], help=short["help"])
    for row in parameter_table():
        name, default = row["name"], "off" if row["default"] is None else row["default"]
        if row["kind"] == "switch":
            group.add_argument(f"-{name}", action="store_true", default=None, help=row["help"])
        else:
            group.add_argument(f"-{name}", metavar="VALUE",
                               help=f"{row['help']}; {row['range']} (default: {default})")
    return parser


def _positive(text):
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be >= 1, got {value}")
    return value


def main(argv=None):
    """The command line; returns the exit status."""
    parser = _parser()
    args = vars(parser.parse_args(argv))
    options = {k: args.pop(k) for k in ("source", "target", "scheduler", "workers", "force",
                                        "no_progress")}
    parameters = {k: v for k, v in args.items() if v is not None}
    try:
        rows = run(options["source"], options["target"], parameters,
                   scheduler=options["scheduler"], workers=options["workers"],
                   force=options["force"], progress=False if options["no_progress"] else None)
    except BatchError as error:
        print(f"pcl_ncut_seg.batch: {error}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("pcl_ncut_seg.batch: interrupted; run again to finish", file=sys.stderr)
        return 130
    failed = sum(1 for row in rows if row.get("error"))
    table = os.path.join(options["target"], TABLE)
    print(f"pcl_ncut_seg.batch: {len(rows)} inputs, {len(rows) - failed} segmented, "
          f"{failed} failed; table {table}", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
