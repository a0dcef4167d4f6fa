#!/usr/bin/env python3
"""Writes results/peers.md from scripts/tune_peers.sh's runs: LCCP's and CPC's scores for each
setting on each kind of input, both halves of the dev split, and the setting a user would pick
for each (the lowest mean of 1 - RI and Hamming over both halves).

    python3 scripts/tune_peers.py OUT results/peers.md
"""
import csv
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report  # noqa: E402  (the same reading and means)

LABELS = {("cent", "auto"): "face centroids", ("samp", "auto"): "20k area-uniform samples",
          ("views", "crop"): "view: crop (and organized frame)",
          ("views", "voxel"): "view: voxel-grid crop", ("views", "laser"): "view: laser-like"}


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: tune_peers.py OUT peers.md")
    out, target = sys.argv[1], sys.argv[2]
    results = {}  # (input, mode, peer) -> [(setting, [A], [B])]
    categories = {}
    commands = []
    for name in sorted(os.listdir(out)):
        m = re.fullmatch(r"(views|cent|samp)_ms(\d+)_s([0-9.]+)", name)
        path = os.path.join(out, name, "models.csv")
        if not m or not os.path.exists(path):
            continue
        commands.append(open(os.path.join(out, name, "command")).read().strip()
                        if os.path.exists(os.path.join(out, name, "command")) else name)
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        per = {}
        for row in rows:
            categories[int(row["id"])] = row["category"]
            per.setdefault((row["mode"], row["method"]), {}).setdefault(int(row["id"]), []).append(
                [float(row["one_minus_rand_index"]), float(row["hamming"]),
                 float(row["segments"]), float(row["seconds"])])
        setting = f"smallest segment {m.group(2)}, seed {m.group(3)}"
        for (mode, peer), per_model in per.items():
            results.setdefault((m.group(1), mode, peer), []).append((setting, per_model))
    if not results:
        sys.exit(f"tune_peers.py: no runs under {out}")
    ids_by = report.groups(categories)
    md = ["# LCCP and CPC at the settings a user would choose\n",
          f"Written by `scripts/tune_peers.py` from the runs in `{out}`; build {report.build()}; "
          f"machine: {report.machine()}. Every other setting is `eval/psb_peers.h`'s (voxel "
          "0.01 diagonals, concavity tolerance 10 degrees, normals from 10 neighbours towards "
          "the sensor, or away from the centroid on whole objects). `a / b`: the halves of the "
          "dev split, models base+1..3 / base+4..6. The chosen setting has the lowest mean of "
          "1 - RI and Hamming over both halves.\n", "```", *commands, "```\n"]
    for key in sorted(results, key=lambda k: (list(LABELS).index(k[:2]) if k[:2] in LABELS
                                              else 99, k[2])):
        inp, mode, peer = key
        md.append(f"## {peer.upper()}, {LABELS.get((inp, mode), inp + ' ' + mode)}\n")
        md.append("| setting | 1 - RI | Hamming | segments | chosen |")
        md.append("|---|---|---|---|---|")
        scored = []
        for setting, per_model in results[key]:
            a, _ = report.means(per_model, ids_by["1-3"])
            b, _ = report.means(per_model, ids_by["4-6"])
            allm, _ = report.means(per_model, ids_by["all"])
            scored.append((setting, a, b, allm, (a[0] + a[1] + b[0] + b[1]) / 4))
        best = min(scored, key=lambda s: s[4])[0]
        for setting, a, b, allm, _ in scored:
            md.append(f"| {setting} | {report.pair(a[0], b[0])} | {report.pair(a[1], b[1])} | "
                      f"{report.fmt(allm[2], 1)} | {'**yes**' if setting == best else ''} |")
        md.append("")
    report.write_atomically(target, md)
    print(f"tune_peers.py: wrote {target}")


if __name__ == "__main__":
    main()
