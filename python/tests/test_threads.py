"""Segmenters in several Python threads at once (segment() releases the GIL; the library's
reasons and warnings come back as values, each call its own)."""
import os
import threading
import warnings

import numpy as np
import pytest

import pcl_ncut_seg
import shapes


def test_segmenters_in_threads():
    points = shapes.limbs(1500, seed=2)
    expected = pcl_ncut_seg.segment(points, segments=3)
    stderr_before = os.fstat(2)
    results, failures = [None] * 4, []

    def work(i):
        try:
            seg = pcl_ncut_seg.Segmenter(segments=3, threads=1)
            for _ in range(3):
                results[i] = seg.segment(points)
                with pytest.raises(ValueError, match="^the input has no finite point.$"):
                    pcl_ncut_seg.segment(np.full((3, 3), np.nan))
        except Exception as error:  # reported below, in the test's thread
            failures.append(error)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(results))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not failures
    assert all(np.array_equal(r, expected) for r in results)
    # stderr is where it was.
    stderr_after = os.fstat(2)
    assert (stderr_after.st_dev, stderr_after.st_ino) == (stderr_before.st_dev, stderr_before.st_ino)


def test_each_thread_gets_its_own_errors_and_warnings():
    """Two threads segment at the same time, one clouds the library refuses or warns about,
    the other a big cloud: each gets its own ValueError or RuntimeWarning, never the other's,
    and both run at once (no process-wide lock: the bad clouds are answered while the big one
    segments)."""
    big = shapes.limbs(8000, seed=3)
    few = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]], np.float32)
    big_started, few_done = threading.Event(), threading.Event()
    got, failures, warned = {}, [], []

    def record(message, category, *args, **kwargs):  # the calling thread's warning
        warned.append((threading.current_thread().name, category, str(message)))

    def big_cloud():
        try:
            seg = pcl_ncut_seg.Segmenter(segments=3, threads=1)
            seg.segment(big[:500])  # warm up, then the long call
            big_started.set()
            got["big"] = seg.segment(big)
            got["big_overlapped"] = few_done.is_set()
        except Exception as error:  # reported below, in the test's thread
            failures.append(error)
            big_started.set()

    def bad_clouds():
        try:
            big_started.wait(60)
            for k in (12, 13):
                with pytest.raises(ValueError, match="^the input has no finite point.$"):
                    pcl_ncut_seg.segment(np.full((4, 3), np.nan), k=k)
            got["few"] = pcl_ncut_seg.segment(few, k=12)
            few_done.set()
        except Exception as error:
            failures.append(error)

    # warnings' filters and hook are the process's: set once here, not in the threads.
    with warnings.catch_warnings():
        warnings.simplefilter("always")
        warnings.showwarning = record
        threads = [threading.Thread(target=big_cloud, name="big"),
                   threading.Thread(target=bad_clouds, name="bad")]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    assert not failures, failures
    assert got["big"].shape == (len(big),) and got["big"].max() == 3
    assert got["few"].shape == (5,) and got["few"].min() >= 1
    assert warned == [("bad", RuntimeWarning, "only 5 points: using 4 neighbours instead of 12.")]
    # The bad clouds were answered while the big one was segmenting: nothing serialised them.
    assert got["big_overlapped"]
