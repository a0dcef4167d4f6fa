"""Segmenters in several Python threads at once (segment() releases the GIL; the library's
console output is captured one call at a time)."""
import os
import threading

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
