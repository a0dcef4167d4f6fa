"""python -m pcl_ncut_seg.batch as it is used: a folder of about 50 small inputs, some broken,
segmented on a local Dask cluster of two worker processes on loopback. Every good input's
output is the tool's (labels, and bytes), every bad one has its error and no output; a worker
killed mid-run and a run killed mid-way cost no file; a second run does nothing; --force redoes.

The comparisons with the tool run when PCL_NCUT_SEG_TOOL names it (CTest sets it when the tools
are built); the shared data's files when ../shared/data is there."""
import csv
import faulthandler
import os
import shutil
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import batch_inputs
import distributed
import pcd
from pcl_ncut_seg import batch
from pcl_ncut_seg._batch_files import TIME_COLUMNS

TOOL = os.environ.get("PCL_NCUT_SEG_TOOL")
SOURCE = os.environ.get("PCL_NCUT_SEG_SOURCE_DIR",
                        os.path.join(os.path.dirname(__file__), "..", ".."))
SHARED = os.path.join(SOURCE, "..", "shared", "data")
# -threads 1 for the tool and the command lines: the labels do not depend on it, and OpenMP's
# threads spin where cores are busy; run() is left to choose (one thread per worker here).
FLAGS = ["-segments", "3", "-k", "8", "-threads", "1"]
PARAMETERS = {"segments": "3", "k": "8"}
TIMEOUT = 120  # seconds: every wait of these tests is bounded


@pytest.fixture(scope="module", autouse=True)
def bounded():
    """A run that waits for ever (no worker ever comes) ends the tests, with every stack."""
    faulthandler.dump_traceback_later(5 * TIMEOUT, exit=True)
    yield
    faulthandler.cancel_dump_traceback_later()


@pytest.fixture(scope="module")
def inputs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("batch") / "in"
    good, bad = batch_inputs.make(str(folder))
    shutil.copy(os.path.join(SOURCE, "data", "hand.pcd"), folder / "pcd" / "hand.pcd")
    return folder, sorted(good + ["pcd/hand.pcd"]), bad


def local_cluster():
    """Two single-threaded worker processes on loopback, restarted by their nannies."""
    return distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                    host="127.0.0.1", dashboard_address=None, memory_limit=0)


@pytest.fixture(scope="module")
def cluster():
    with local_cluster() as local, distributed.Client(local) as client:
        yield local.scheduler_address, client


@pytest.fixture(scope="module")
def first(inputs, cluster, tmp_path_factory):
    """The uninterrupted run every other run is compared with."""
    out = tmp_path_factory.mktemp("batch") / "out"
    rows = batch.run(inputs[0], out, PARAMETERS, scheduler=cluster[0], progress=False)
    return out, rows


def output_name(name):
    return {"meshes/same_stem.off": "meshes/same_stem.off.pcd",
            "meshes/same_stem.ply": "meshes/same_stem.ply.pcd"}.get(
        name, os.path.splitext(name)[0] + ".pcd")


def without_times(rows):
    return [{k: v for k, v in row.items() if k not in TIME_COLUMNS} for row in rows]


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


def files_under(folder):
    return sorted(os.path.relpath(os.path.join(d, n), folder)
                  for d, _, names in os.walk(folder) for n in names)


def tool_output(tmp_path, path):
    """The tool's output for an input (its bytes), or its error (a str)."""
    out = tmp_path / "tool.pcd"
    done = subprocess.run([TOOL, path, str(out), "-quiet", *FLAGS], stdout=subprocess.DEVNULL,
                          stderr=subprocess.PIPE, timeout=TIMEOUT)
    return read_bytes(out) if done.returncode == 0 else done.stderr.decode()


def test_the_table_has_a_row_per_input_and_outputs_only_for_good_ones(inputs, first):
    folder, good, bad = inputs
    out, rows = first
    assert [r["input"] for r in rows] == sorted(good + bad)
    with open(out / "batch.csv", newline="") as f:
        table = list(csv.DictReader(f))
    assert [r["input"] for r in table] == [r["input"] for r in rows]
    for row, line in zip(rows, table):
        if row["input"] in good:
            assert not row.get("error") and line["error"] == "", row
            assert row["output"] == line["output"] == output_name(row["input"])
            assert row["segments"] >= 1 and row["points"] >= row["segments"]
            assert row["total_s"] > 0 and line["view"] in ("True", "False")
        else:
            assert batch_inputs.BAD[row["input"]] in row["error"], row
            assert line["error"] == row["error"] and line["output"] == "" and not row["output"]
            assert line["points"] == "" or row["input"].startswith("broken/all_nan")
    expected = sorted(output_name(n) for n in good) + [".batch.jsonl", "batch.csv"]
    assert files_under(out) == sorted(expected)  # no output for a bad input, no temporaries


def test_every_output_is_a_labelled_pcd_of_the_inputs_points(inputs, first):
    folder, good, _ = inputs
    out, rows = first
    by_input = {r["input"]: r for r in rows}
    for name in [n for n in good if n.endswith((".npy", ".pcd"))]:
        fields = pcd.read_fields(out / output_name(name))
        assert list(fields) == ["x", "y", "z", "rgb", "label"]
        labels = fields["label"].astype(np.int64)
        assert labels.max() == by_input[name]["segments"]
        if name.endswith(".npy"):
            points = np.load(folder / name).astype(np.float32).reshape(-1, 3)
            got = np.stack([fields[c] for c in "xyz"], axis=1)
            assert np.array_equal(got, points, equal_nan=True)
            assert np.all(labels[~np.isfinite(points).all(axis=1)] == 0)


@pytest.mark.skipif(not TOOL, reason="PCL_NCUT_SEG_TOOL is not set (no tools built)")
def test_every_output_is_the_tools_and_the_tool_fails_on_every_bad_input(inputs, first,
                                                                         tmp_path):
    folder, good, bad = inputs
    out = first[0]
    for name in good:
        expected = tool_output(tmp_path, str(folder / name))
        assert isinstance(expected, bytes), f"{name}: the tool failed: {expected}"
        got = read_bytes(out / output_name(name))
        labels = [pcd.read_fields(p)["label"] for p in (tmp_path / "tool.pcd",
                                                        out / output_name(name))]
        assert np.array_equal(*labels), f"{name}: not the tool's labels"
        assert got == expected, f"{name}: the labels are the tool's, the bytes are not"
    rows = {r["input"]: r for r in first[1]}
    for name in bad:
        error = tool_output(tmp_path, str(folder / name))
        assert isinstance(error, str), name
        assert rows[name]["error"] in error, f"{name}: the tool's reason is not the batch's"


def test_a_second_run_does_nothing_and_force_redoes(inputs, first, cluster):
    out, rows = first
    before = {n: os.stat(out / n).st_mtime_ns for n in files_under(out) if n.endswith(".pcd")}
    # Nothing to do: no cluster is asked (there is none at this address).
    again = batch.run(inputs[0], out, PARAMETERS, scheduler="tcp://127.0.0.1:9",
                      progress=False)
    assert again == rows
    assert {n: os.stat(out / n).st_mtime_ns for n in before} == before
    contents = {n: read_bytes(out / n) for n in before}
    redone = batch.run(inputs[0], out, PARAMETERS, scheduler=cluster[0],
                       force=True, progress=False)
    assert without_times(redone) == without_times(rows)
    assert all(os.stat(out / n).st_mtime_ns > before[n] for n in before)
    assert {n: read_bytes(out / n) for n in before} == contents


def test_other_parameters_are_refused_on_the_same_out(inputs, first):
    with pytest.raises(batch.BatchError, match=r"other parameters \(segments\).*--force"):
        batch.run(inputs[0], first[0], {"segments": 4, "k": 8}, scheduler="tcp://127.0.0.1:9")


def test_a_changed_input_is_redone_with_a_progress_bar(inputs, cluster, tmp_path, capfd):
    folder = tmp_path / "in"
    shutil.copytree(inputs[0] / "pcd", folder)
    out = tmp_path / "out"
    batch.run(folder, out, PARAMETERS, scheduler=cluster[0], progress=False)
    stamp = os.stat(out / "binary_0.pcd").st_mtime_ns
    shutil.copy(folder / "binary_1.pcd", folder / "binary_0.pcd")
    os.utime(folder / "binary_0.pcd", ns=(stamp + 10**9, stamp + 10**9))
    capfd.readouterr()
    rows = batch.run(folder, out, PARAMETERS, scheduler=cluster[0], progress=True)
    bar = capfd.readouterr().err
    assert "segmenting (" in bar and "up to date)" in bar and "1/1" in bar, bar
    assert "file/s" in bar and "failed=0" in bar, bar
    assert read_bytes(out / "binary_0.pcd") == read_bytes(out / "binary_1.pcd")
    assert rows[[r["input"] for r in rows].index("binary_0.pcd")]["points"] == 340


def test_a_worker_killed_mid_run_costs_no_file(inputs, first, tmp_path):
    with local_cluster() as local, distributed.Client(local) as client:
        kill_a_worker_mid_run(inputs, local.scheduler_address, client, tmp_path / "out")
    out = tmp_path / "out"
    assert files_under(out) == files_under(first[0])
    for name in files_under(out):
        if name.endswith(".pcd"):
            assert read_bytes(out / name) == read_bytes(first[0] / name), name
    assert without_times(read_table(out)) == without_times(read_table(first[0]))


def kill_a_worker_mid_run(inputs, address, client, out):
    """SIGKILL a worker while it segments, then wait for the run to end."""
    result = {}
    thread = threading.Thread(target=lambda: result.update(rows=batch.run(
        inputs[0], out, PARAMETERS, scheduler=address, progress=False)))
    thread.start()
    wait_for(lambda: journal_rows(out) >= 3)
    busy = wait_for(lambda: [w for w, keys in client.processing().items() if keys]
                    or not thread.is_alive())
    assert thread.is_alive(), "the run ended before a worker could be killed"
    pid = client.run(os.getpid, workers=[busy[0]])[busy[0]]
    os.kill(pid, signal.SIGKILL)
    thread.join(TIMEOUT)
    assert not thread.is_alive() and "rows" in result


def test_a_run_killed_and_started_again_ends_with_the_same_table(inputs, first, cluster,
                                                                  tmp_path):
    out = tmp_path / "out"
    command = [sys.executable, "-m", "pcl_ncut_seg.batch", str(inputs[0]), str(out), *FLAGS,
               "--scheduler", cluster[0], "--no-progress"]
    process = subprocess.Popen(command, stderr=subprocess.DEVNULL)
    try:
        wait_for(lambda: journal_rows(out) >= 10 or process.poll() is not None)
    finally:
        process.kill()
        process.wait(TIMEOUT)
    done = journal_rows(out)
    assert 10 <= done < len(first[1]), "the run was not killed mid-way"
    rows = batch.run(inputs[0], out, PARAMETERS, scheduler=cluster[0], progress=False)
    assert without_times(rows) == without_times(first[1])
    assert without_times(read_table(out)) == without_times(read_table(first[0]))
    assert files_under(out) == files_under(first[0])


def test_the_command_line_with_one_worker_gives_the_same_outputs(inputs, first, tmp_path):
    folder, out = tmp_path / "in", tmp_path / "out"
    for part in ("ply", "views", "broken"):  # a part of the folder: one worker is slower
        shutil.copytree(inputs[0] / part, folder / part)
    done = subprocess.run([sys.executable, "-m", "pcl_ncut_seg.batch", str(folder), str(out),
                           *FLAGS, "--workers", "1", "--no-progress"],
                          capture_output=True, text=True, timeout=TIMEOUT)
    assert done.returncode == 1, done.stderr  # 1: some inputs failed
    assert done.stderr.strip().splitlines()[-1] == (
        f"pcl_ncut_seg.batch: {len(files_under(folder))} inputs, "
        f"{len(files_under(folder)) - len(batch_inputs.BAD)} segmented, "
        f"{len(batch_inputs.BAD)} failed; table {out / 'batch.csv'}")
    for name in files_under(out):
        if name.endswith(".pcd"):
            assert read_bytes(out / name) == read_bytes(first[0] / name), name


def test_command_line_errors_are_one_line(tmp_path):
    def error(*args):
        done = subprocess.run([sys.executable, "-m", "pcl_ncut_seg.batch", *args],
                              capture_output=True, text=True, timeout=TIMEOUT)
        assert done.returncode == 2
        return done.stderr.strip()

    assert error(str(tmp_path / "nowhere"), str(tmp_path / "out")) == (
        f"pcl_ncut_seg.batch: IN '{tmp_path / 'nowhere'}' is not a folder")
    assert error(str(tmp_path), str(tmp_path)).startswith(
        "pcl_ncut_seg.batch: OUT must be another folder than IN")
    assert "k must be" in error(str(tmp_path), str(tmp_path / "out"), "-k", "1")


def test_without_tqdm_the_command_line_says_so_in_one_line(tmp_path):
    (tmp_path / "in").mkdir()
    blocked = ("import sys, runpy; sys.modules['tqdm'] = None; sys.argv[0] = 'batch'; "
               "runpy.run_module('pcl_ncut_seg.batch', run_name='__main__')")

    def command(*args):
        return subprocess.run([sys.executable, "-c", blocked, str(tmp_path / "in"),
                               str(tmp_path / "out"), *args],
                              capture_output=True, text=True, timeout=TIMEOUT)

    done = command()
    assert done.returncode == 2, done.stderr
    assert done.stderr.strip() == ("pcl_ncut_seg.batch: the progress bar needs tqdm: apt-get "
                                   "install python3-tqdm (Debian 12), or run with --no-progress")
    assert not (tmp_path / "out").exists()  # nothing written
    done = command("--no-progress")  # an empty IN: nothing to segment, and no bar needed
    assert done.returncode == 0, done.stderr


@pytest.mark.skipif(not (TOOL and os.path.isdir(SHARED)),
                    reason="needs the tool and ../shared/data")
def test_the_shared_datas_files_are_the_tools(cluster, tmp_path):
    folder = tmp_path / "in"
    folder.mkdir()
    for name in ("models/bunny-small.off", "pcl/bun0.pcd", "pcl/bunny.pcd", "pcl/lamppost.pcd",
                 "pcl/colored_cloud.pcd", "pcl/noisy_slice_displaced.pcd"):
        shutil.copy(os.path.join(SHARED, name), folder)
    rows = batch.run(folder, tmp_path / "out", PARAMETERS, scheduler=cluster[0],
                     progress=False)
    assert not [r for r in rows if r.get("error")]
    for row in rows:
        expected = tool_output(tmp_path, str(folder / row["input"]))
        assert read_bytes(tmp_path / "out" / row["output"]) == expected, row["input"]


def read_table(out):
    with open(out / "batch.csv", newline="") as f:
        return list(csv.DictReader(f))


def journal_rows(out):
    try:
        with open(out / ".batch.jsonl") as f:
            return max(0, len(f.read().splitlines()) - 1)
    except FileNotFoundError:
        return 0


def wait_for(condition):
    deadline = time.monotonic() + TIMEOUT
    while time.monotonic() < deadline:
        value = condition()
        if value:
            return value
        time.sleep(0.02)
    raise AssertionError("timed out")
