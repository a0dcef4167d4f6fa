#!/usr/bin/env python3
"""Writes the hand-made seed inputs of test/fuzz/corpus (the fuzzer adds its own beside them).
Layout, as fuzz_extract.cpp reads it: 14 parameter bytes (flags, k, samples, crossing, area,
height, beta, alpha1, alpha2, threshold, segments, max_points, threads, scale), then 3 signed bytes
per point (-128 = NaN, 127 = infinity), then up to two bytes of options beyond the paper (see
fuzz_extract.cpp; none or zeros keep the defaults); the samples byte's high 5 bits set the
boundary refinement and the crease splits."""
import math
import os
import struct

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")


def params(flags=0x06, k=8, samples=0, crossing=77, area=3, height=3, beta=5, alpha1=5,
           alpha2=3, threshold=2, segments=5, max_points=99, threads=1, scale=5):
    return bytes([flags, k, samples, crossing, area, height, beta, alpha1, alpha2, threshold,
                  segments, max_points, threads, scale])


def pts(points):
    return b"".join(struct.pack("bbb", *p) for p in points)


def sphere(n, r, c=(0, 0, 0)):
    out = []
    for i in range(n):
        z = 1 - 2 * (i + 0.5) / n
        rho = math.sqrt(1 - z * z)
        phi = i * 2.39996323
        out.append(tuple(max(-127, min(126, int(round(c[j] + r * v))))
                         for j, v in enumerate((rho * math.cos(phi), rho * math.sin(phi), z))))
    return out


seeds = {
    "empty": b"",
    "no_points": params(),
    "one_point": params() + pts([(1, 2, 3)]),
    "two_points": params() + pts([(1, 2, 3), (-4, 0, 9)]),
    "sphere": params() + pts(sphere(150, 60)),
    "two_spheres": params(flags=0x07) + pts(sphere(80, 20, (-90, 0, 0)) + sphere(80, 20, (90, 0, 0))),
    "dumbbell": params(flags=0x07, segments=2) + pts(
        sphere(90, 30, (-70, 0, 0)) + sphere(90, 30, (70, 0, 0)) +
        [(x, y, z) for x in range(-40, 41, 4) for (y, z) in ((6, 0), (-6, 0), (0, 6), (0, -6))]),
    "duplicates": params() + pts([(5, 5, 5)] * 60 + [(i, 0, 0) for i in range(40)]),
    "grid_plane": params(k=4) + pts([(i * 10, j * 10, 0) for i in range(-6, 7) for j in range(-6, 7)]),
    "line": params(k=2) + pts([(i, 2 * i // 3, -i // 2) for i in range(-60, 61)]),
    "non_finite": params() + pts(sphere(100, 50) + [(-128, 0, 0), (0, 127, 0), (3, -128, 127)]),
    "indices": params(flags=0x26) + pts(sphere(120, 40)),
    "indices_out_of_range": params(flags=0x66) + pts(sphere(60, 40)),
    "all_nan": params() + pts([(-128, -128, -128)] * 20),
    "huge_splits_far": params(flags=0x17, max_points=255, scale=12) + pts(sphere(100, 50)),
    "tiny_scale": params(scale=0, threads=2) + pts(sphere(100, 50)),
    # Options beyond the paper: CAD mode; every option at its extreme with exact centrality;
    # every option off (the paper).
    "sphere_cad": params() + pts(sphere(150, 60)) + bytes([0x80]),
    "dumbbell_extremes": params(flags=0x07, segments=0) + pts(
        sphere(90, 30, (-70, 0, 0)) + sphere(90, 30, (70, 0, 0))) + bytes([0x3F, 0xC2]),
    "dumbbell_band_crease_extremes": params(flags=0x07, segments=0, samples=(0x2 | 0x4 | 0x10) << 3) + pts(
        sphere(90, 30, (-70, 0, 0)) + sphere(90, 30, (70, 0, 0))),
    "two_spheres_paper": params(flags=0x07, threads=2) + pts(
        sphere(80, 20, (-90, 0, 0)) + sphere(80, 20, (90, 0, 0))) + bytes([0x55, 0x30]),
}
os.makedirs(HERE, exist_ok=True)
for name, data in seeds.items():
    with open(os.path.join(HERE, "seed_" + name), "wb") as f:
        f.write(data)
print("wrote %d seeds to %s" % (len(seeds), HERE))
