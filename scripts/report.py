#!/usr/bin/env python3
"""Writes the report of scripts/report.sh's runs: every kind of input on both halves of the dev
split (models base+1..3 and base+4..6 of each category) and per category, beside LCCP, CPC and
the people; and, for every run named off-<stage>, what turning that stage off changes.

    python3 scripts/report.py OUT results/report.md

REPORT_TITLE replaces the title, for a report of some of the inputs (results/views_unknown_origin.md:
REPORT_TITLE="Views with the sensor origin unknown", from report.sh with INPUTS=views_unknown_origin).
OUT holds <config>/<input>/models.csv (the evaluator's) and <config>/<input>/command.
"""
import csv
import datetime
import os
import platform
import subprocess
import sys
from collections import defaultdict

INPUTS = [  # (folder, mode in models.csv, label)
    ("centroids", "auto", "face centroids"),
    ("samples", "auto", "20k area-uniform samples"),
    ("noise_0.5", "auto", "samples, noise 0.5 spacings"),
    ("noise_1.0", "auto", "samples, noise 1.0 spacings"),
    ("density", "auto", "samples, density 4:1"),
    ("views", "view", "view: organized frame"),
    ("views", "crop", "view: crop"),
    ("views", "voxel", "view: voxel-grid crop"),
    ("views", "laser", "view: laser-like"),
    ("views_unknown_origin", "view", "view: organized, origin unknown"),
    ("views_unknown_origin", "crop", "view: crop, origin unknown"),
    ("views_unknown_origin", "voxel", "view: voxel crop, origin unknown"),
    ("views_unknown_origin", "laser", "view: laser-like, origin unknown"),
]
HALVES = ("1-3", "4-6")
# Stages that the ablation below led to remove (their runs were made before the removal).
REMOVED = {"organized_rim"}
# A change smaller than this in a mean over a half (19 x 3 models) is noise.
NOISE = 0.002


def half(model_id):
    return HALVES[0] if (model_id - 1) % 20 < 3 else HALVES[1]


def read_runs(out):
    """{(config, folder, mode, method): {id: [ri, hamming, segments, seconds] over draws}}"""
    runs = defaultdict(lambda: defaultdict(list))
    categories = {}
    for config in sorted(os.listdir(out)):
        for folder, _, _ in INPUTS:
            path = os.path.join(out, config, folder, "models.csv")
            if not os.path.exists(path):
                continue
            with open(path, newline="") as f:
                for row in csv.DictReader(f):
                    model_id = int(row["id"])
                    categories[model_id] = row["category"]
                    key = (config, folder, row["mode"], row["method"])
                    runs[key][model_id].append(
                        [float(row["one_minus_rand_index"]), float(row["hamming"]),
                         float(row["segments"]), float(row["seconds"])])
    return runs, categories


def mean(values):
    return sum(values) / len(values) if values else float("nan")


def means(per_model, ids):
    """The means over the models (each model's draws averaged first)."""
    cols = [[], [], [], []]
    for model_id in ids:
        if model_id in per_model:
            draws = per_model[model_id]
            for c in range(4):
                cols[c].append(mean([d[c] for d in draws]))
    return [mean(c) for c in cols], len(cols[0])


def groups(categories):
    by = {"all": sorted(categories)}
    for h in HALVES:
        by[h] = [i for i in sorted(categories) if half(i) == h]
    return by


def fmt(v, digits=3):
    return "" if v != v else f"{v:.{digits}f}"


def pair(a, b, digits=3):
    return f"{fmt(a, digits)} / {fmt(b, digits)}" if a == a else ""


def machine():
    model = ""
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    mem = ""
    try:
        kb = int(open("/proc/meminfo").readline().split()[1])
        mem = f", {kb / 1024 / 1024:.0f} GiB"
    except (OSError, ValueError, IndexError):
        pass
    return f"{os.cpu_count()} cores ({model}){mem}, {platform.system()} {platform.release()}"


def build():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    try:
        return subprocess.run(["git", "-C", root, "describe", "--always", "--dirty"],
                              capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def run_build(out, config, folder):
    """The build a run was made with, as report.sh recorded it."""
    path = os.path.join(out, config, folder, "build")
    return f"  # build {open(path).read().strip()}" if os.path.exists(path) else ""


def header(out, configs, md):
    md.append("# " + os.environ.get("REPORT_TITLE", "Every kind of input, every stage") + "\n")
    md.append(f"Written by `scripts/report.py` on {datetime.date.today()} from the runs in "
              f"`{out}`; build {build()}; machine: {machine()}. The evaluator's commands:\n")
    md.append("```")
    for config in configs:
        for folder in sorted({f for f, _, _ in INPUTS}):
            path = os.path.join(out, config, folder, "command")
            if os.path.exists(path):
                md.append(open(path).read().strip() + run_build(out, config, folder))
    md.append("```\n")
    md.append("Figures are means over models (each model's draws and views averaged first); "
              "`a / b` gives the two halves of the dev split, models base+1..3 / base+4..6 of "
              "each category. Lower is better for 1 - RI and Hamming. Segments are per model, "
              "or per view on views.\n")


def method_cell(runs, config, folder, mode, method, ids_by, metric):
    key = (config, folder, mode, method)
    if key not in runs:
        return ""
    a, _ = means(runs[key], ids_by[HALVES[0]])
    b, _ = means(runs[key], ids_by[HALVES[1]])
    if metric == 2:
        return fmt(means(runs[key], ids_by["all"])[0][2], 1)
    return pair(a[metric], b[metric])


def main_table(runs, ids_by, md):
    md.append("## Every kind of input: ours beside LCCP, CPC and the people\n")
    md.append("LCCP and CPC run at the settings of `results/peers.md`. 'whole' is ours on the "
              "whole object (face centroids) scored on the faces the view sees.\n")
    md.append("| input | ours 1 - RI | ours Hamming | ours seg. | whole 1 - RI | LCCP 1 - RI | "
              "LCCP Hamming | LCCP seg. | CPC 1 - RI | CPC Hamming | CPC seg. | people 1 - RI | "
              "people seg. |")
    md.append("|---" * 13 + "|")
    for folder, mode, label in INPUTS:
        if ("defaults", folder, mode, "ours") not in runs:
            continue
        cells = [label]
        for method, cfg, metrics in (("ours", "defaults", (0, 1, 2)),
                                     ("ours whole", "defaults", (0,)),
                                     ("lccp", "lccp", (0, 1, 2)), ("cpc", "cpc", (0, 1, 2)),
                                     ("human", "lccp", (0, 2))):
            for m in metrics:
                cells.append(method_cell(runs, cfg, folder, mode, method, ids_by, m))
        md.append("| " + " | ".join(cells) + " |")
    md.append("")


def category_tables(runs, categories, md):
    md.append("## Per category (1 - RI / Hamming, all six models)\n")
    cats = []
    for i in sorted(categories):
        if categories[i] not in cats:
            cats.append(categories[i])
    for folder, mode, label in INPUTS:
        if ("defaults", folder, mode, "ours") not in runs:
            continue
        md.append(f"### {label}\n")
        md.append("| category | ours | segments | LCCP | segments | CPC | segments | people |")
        md.append("|---" * 8 + "|")
        for c in cats + ["Overall"]:
            ids = [i for i in sorted(categories) if c == "Overall" or categories[i] == c]
            cells = ["**Overall**" if c == "Overall" else c]
            for method, cfg, seg in (("ours", "defaults", True), ("lccp", "lccp", True),
                                     ("cpc", "cpc", True), ("human", "lccp", False)):
                key = (cfg, folder, mode, method)
                if key not in runs:
                    cells += [""] * (2 if seg else 1)
                    continue
                m, _ = means(runs[key], ids)
                cells.append(pair(m[0], m[1]))
                if seg:
                    cells.append(fmt(m[2], 1))
            md.append("| " + " | ".join(cells) + " |")
        md.append("")


def stage_deltas(runs, ids_by, off):
    """Per input: (label, [(d RI, d Hamming) per half], base means, off means)."""
    out = []
    for folder, mode, label in INPUTS:
        base = runs.get(("base", folder, mode, "ours"))
        other = runs.get((off, folder, mode, "ours"))
        if not base or not other:
            continue
        halves = [[i for i in ids_by[h] if i in other] for h in HALVES]
        d = []
        for ids in halves:
            mb, _ = means(base, ids)
            mo, _ = means(other, ids)
            d.append((mo[0] - mb[0], mo[1] - mb[1]))
        mb, _ = means(base, halves[0] + halves[1])
        mo, _ = means(other, halves[0] + halves[1])
        out.append((label, d, mb, mo))
    return out


def verdict(deltas):
    """(inputs where the stage pays, inputs where it costs)."""
    pays, costs = [], []
    for label, d, _, _ in deltas:
        if any(x <= -NOISE for h in d for x in h):
            costs.append(label)
        elif any(all(h[k] >= NOISE for h in d) for k in (0, 1)):
            pays.append(label)
    return pays, costs


def ablation(runs, ids_by, configs, md, abl_dir):
    offs = [c for c in configs if c.startswith("off-")]
    if not offs:
        return
    builds = sorted({open(os.path.join(abl_dir, c, f, "build")).read().strip()
                     for c in configs for f, _, _ in INPUTS
                     if os.path.exists(os.path.join(abl_dir, c, f, "build"))})
    md.append(f"From the runs in `{abl_dir}` (build {', '.join(builds) or 'unknown'}; their "
              "commands are in each run's folder): "
              "fewer draws and views than the report, each stage off against the "
              "defaults on the same points. A stage pays on an input when turning it off makes "
              f"both halves worse by at least {NOISE} in 1 - RI or Hamming and neither better by "
              "as much in the other; it costs on an input when turning it off makes a half "
              f"better by at least {NOISE} in either. Detail per input follows the table.\n")
    md.append("| stage | pays on | costs on |")
    md.append("|---|---|---|")
    for off in offs:
        pays, costs = verdict(stage_deltas(runs, ids_by, off))
        name = off[4:] + (" (removed)" if off[4:] in REMOVED else "")
        md.append(f"| {name} | {', '.join(pays) or '—'} | {', '.join(costs) or '—'} |")
    md.append("")
    md.append("## Each stage off, per input\n")
    md.append("Off minus defaults, `1-3 / 4-6`: positive means the stage helps there. (The "
              "runs shared a loaded machine, so their times are not compared here; speed is "
              "`bench/`'s.)\n")
    for off in offs:
        md.append(f"### {off[4:]}\n")
        md.append("| input | Δ 1 - RI | Δ Hamming | segments (defaults → off) |")
        md.append("|---|---|---|---|")
        for label, d, mb, mo in stage_deltas(runs, ids_by, off):
            md.append(f"| {label} | {d[0][0]:+.3f} / {d[1][0]:+.3f} | "
                      f"{d[0][1]:+.3f} / {d[1][1]:+.3f} | {fmt(mb[2], 1)} → {fmt(mo[2], 1)} |")
        md.append("")


def write_atomically(target, lines):
    """The lines into target, whole or not at all."""
    os.makedirs(os.path.dirname(os.path.abspath(target)), exist_ok=True)
    tmp = target + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(tmp, target)


def main():
    if len(sys.argv) not in (3, 4, 5):
        sys.exit("usage: report.py OUT REPORT.md [ABLATION_OUT [ABLATION.md]]")
    out, target = sys.argv[1], sys.argv[2]
    runs, categories = read_runs(out)
    if not runs:
        sys.exit(f"report.py: no models.csv under {out}")
    configs = sorted({k[0] for k in runs}, key=lambda c: (c != "defaults", c))
    ids_by = groups(categories)
    md = []
    header(out, configs, md)
    main_table(runs, ids_by, md)
    category_tables(runs, categories, md)
    write_atomically(target, md)
    print(f"report.py: wrote {target}")
    if len(sys.argv) >= 4:  # the ablation, in its own file: it comes from its own runs
        abl_target = sys.argv[4] if len(sys.argv) == 5 else os.path.join(
            os.path.dirname(os.path.abspath(target)), "ablation.md")
        abl_runs, _ = read_runs(sys.argv[3])
        abl_configs = sorted({k[0] for k in abl_runs})
        abl = [f"# What each stage buys\n",
               f"Written by `scripts/report.py` on {datetime.date.today()}; machine: {machine()}. "
               f"The inputs are those of [{os.path.basename(target)}]"
               f"({os.path.basename(target)}).\n"]
        ablation(abl_runs, ids_by, abl_configs, abl, sys.argv[3])
        write_atomically(abl_target, abl)
        print(f"report.py: wrote {abl_target}")


if __name__ == "__main__":
    main()
