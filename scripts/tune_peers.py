#!/usr/bin/env python3
"""LCCP's and CPC's settings as a demanding PCL user would tune them on the dev split, then
confirmed once on the validation split; and results/peers.md from those runs.

    python3 scripts/tune_peers.py run OUT           # the grid on psb-dev, then psb-val once
    python3 scripts/tune_peers.py write OUT peers.md [peer_settings.csv]

`write` also copies the chosen settings to results/peer_settings.csv, from which
scripts/report.sh and bench/ run the peers (the evaluator's -peer_settings).

Both peers run with PCL's sanity criterion and smoothness check on, normals estimated by PCL
(oriented outward by the mesh on whole objects, towards the sensor on views) or, on whole
objects, the mesh's own. The grid goes in three stages, each from the best setting of the one
before (the lowest mean of 1 - RI and Hamming over both halves of the dev split and the inputs
of a kind):
  1. voxel and seed resolution (and, on whole objects, where the normals come from), both peers;
  2. concavity tolerance and smallest segment, each peer from its own best;
  3. CPC's cut settings: the smallest cut score, then the most cuts.
Kinds: 'whole' (face centroids, and 20k area-uniform samples) and 'views' (two views per model
as a crop, a voxel-grid crop and laser-like samples, the sensor origin known). Runs that are
there already (models.csv written) are not run again.

Environment: EVAL (default build/eval/pcl_ncut_seg_eval), DEV and VAL (the splits, default
../shared/data/psb-dev and psb-val), JOBS (evaluator runs at a time, default 2).
"""
import concurrent.futures
import csv
import itertools
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report  # noqa: E402  (the same reading, means and machine line)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INPUTS = {  # kind -> {input name: evaluator flags}
    "whole": {"cent": ["-modes", "auto"], "samp": ["-modes", "auto", "-samples", "20000"]},
    "views": {"views": ["-views", "2", "-view_forms", "crop,voxel,laser"]},
}
LABELS = {"cent": "face centroids", "samp": "20k area-uniform samples",
          "views": "views (crop, voxel-grid crop, laser-like)"}
# Settings in the order of the evaluator's flags; a run's folder is named by its values.
KEYS = ["voxel", "seed", "normals", "concavity", "min_segment", "cut_score", "max_cuts"]
FLAG = {"voxel": "-peer_voxel", "seed": "-peer_seed", "normals": "-peer_normals",
        "concavity": "-peer_concavity", "min_segment": "-peer_min_segment",
        "cut_score": "-peer_cut_score", "max_cuts": "-peer_max_cuts"}
START = {"voxel": "0.01", "seed": "0.05", "normals": "estimated", "concavity": "10",
         "min_segment": "3", "cut_score": "0.16", "max_cuts": "25"}
STAGES = [  # (peers, {key: values}); a stage varies its keys over the best of the one before
    (("lccp", "cpc"), {"voxel": ["0.005", "0.01", "0.015", "0.02"],
                       "seed": ["0.02", "0.03", "0.05", "0.08", "0.12"],
                       "normals": ["estimated", "mesh"]}),
    (("lccp",), {"concavity": ["5", "10", "20", "30"], "min_segment": ["0", "3", "10"]}),
    (("cpc",), {"concavity": ["5", "10", "20", "30"], "min_segment": ["0", "3", "10"]}),
    (("cpc",), {"cut_score": ["0.08", "0.16", "0.25"]}),
    (("cpc",), {"max_cuts": ["10", "25", "50"]}),
]


def setting_name(setting):
    return "_".join(f"{k}{setting[k]}" for k in KEYS)


def setting_flags(setting):
    return [x for k in KEYS for x in (FLAG[k], setting[k])]


def run_dir(out, split, peers, inp, setting):
    return os.path.join(out, split, f"{inp}__{'+'.join(peers)}__{setting_name(setting)}")


def evaluate(evaluator, data, folder, peers, inp, setting):
    """One evaluator run into folder, unless it is there already."""
    if os.path.exists(os.path.join(folder, "models.csv")):
        return folder
    os.makedirs(folder, exist_ok=True)
    kind = "views" if inp == "views" else "whole"
    cmd = [evaluator, data, folder, "-quiet", "-methods", ",".join(peers),
           *INPUTS[kind][inp], *setting_flags(setting)]
    with open(os.path.join(folder, "command"), "w") as f:
        f.write(" ".join(cmd) + "\n")
    with open(os.path.join(folder, "log"), "w") as log:
        if subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT).returncode != 0:
            raise RuntimeError(f"tune_peers.py: {folder} failed; see its log")
    return folder


def read_scores(folder, peer):
    """{(mode, id): [1 - RI, Hamming, segments]} of one peer in one run."""
    scores = {}
    with open(os.path.join(folder, "models.csv"), newline="") as f:
        for row in csv.DictReader(f):
            if row["method"] == peer:
                scores.setdefault((row["mode"], int(row["id"])), []).append(
                    [float(row["one_minus_rand_index"]), float(row["hamming"]),
                     float(row["segments"])])
    return {k: [report.mean([d[c] for d in v]) for c in range(3)] for k, v in scores.items()}


def halves_of(scores):
    """Per mode: the means over each half of the split's models, [half][1 - RI, Hamming, seg.]."""
    out = {}
    for mode in sorted({m for m, _ in scores}):
        per_half = []
        for h in report.HALVES:
            rows = [v for (m, i), v in scores.items() if m == mode and report.half(i) == h]
            per_half.append([report.mean([r[c] for r in rows]) for c in range(3)])
        out[mode] = per_half
    return out


def overall_of(scores):
    """Per mode: the means over all the split's models, [1 - RI, Hamming, segments]."""
    return {mode: [report.mean([v[c] for (m, _), v in scores.items() if m == mode])
                   for c in range(3)]
            for mode in sorted({m for m, _ in scores})}


def objective(out, split, peers, peer, kind, setting):
    """The mean of 1 - RI and Hamming over both halves, every mode and every input of a kind."""
    values = []
    for inp in INPUTS[kind]:
        for per_half in halves_of(read_scores(run_dir(out, split, peers, inp, setting),
                                              peer)).values():
            values += [h[0] for h in per_half] + [h[1] for h in per_half]
    return report.mean(values)


def run(out):
    evaluator = os.environ.get("EVAL", os.path.join(ROOT, "build/eval/pcl_ncut_seg_eval"))
    dev = os.environ.get("DEV", os.path.join(ROOT, "../shared/data/psb-dev"))
    val = os.environ.get("VAL", os.path.join(ROOT, "../shared/data/psb-val"))
    jobs = int(os.environ.get("JOBS", "2"))
    best = {(peer, kind): dict(START) for peer in ("lccp", "cpc") for kind in INPUTS}
    history = []  # (stage, peers, kind, setting) of every dev run, for the write step
    with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
        for stage, (peers, grid) in enumerate(STAGES, 1):
            for kind in INPUTS:
                base = best[(peers[0], kind)]
                keys = [k for k in grid if not (kind == "views" and k == "normals")]
                settings = [dict(base, **dict(zip(keys, values)))
                            for values in itertools.product(*(grid[k] for k in keys))]
                settings = [s for s in settings if float(s["voxel"]) < float(s["seed"])]
                futures = [pool.submit(evaluate, evaluator, dev,
                                       run_dir(out, "dev", peers, inp, s), peers, inp, s)
                           for s in settings for inp in INPUTS[kind]]
                for f in futures:
                    f.result()
                for peer in peers:
                    best[(peer, kind)] = min(
                        settings, key=lambda s: objective(out, "dev", peers, peer, kind, s))
                    print(f"tune_peers.py: stage {stage}, {peer} on {kind}: "
                          f"{' '.join(setting_flags(best[(peer, kind)]))}", flush=True)
                history += [(stage, peers, kind, s) for s in settings]
        # The validation split, once, at the chosen settings.
        futures = [pool.submit(evaluate, evaluator, val,
                               run_dir(out, "val", (peer,), inp, best[(peer, kind)]), (peer,),
                               inp, best[(peer, kind)])
                   for (peer, kind) in best for inp in INPUTS[kind]]
        for f in futures:
            f.result()
    with open(os.path.join(out, "chosen.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["peer", "kind", *KEYS])
        for (peer, kind), s in sorted(best.items()):
            w.writerow([peer, kind, *(s[k] for k in KEYS)])
    with open(os.path.join(out, "history.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["stage", "peers", "kind", *KEYS])
        for stage, peers, kind, s in history:
            w.writerow([stage, "+".join(peers), kind, *(s[k] for k in KEYS)])


def read_table(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def describe(setting, kind):
    parts = [f"voxel {setting['voxel']}", f"seed {setting['seed']}"]
    if kind == "whole":
        parts.append(f"normals {setting['normals']}")
    parts += [f"concavity {setting['concavity']}°", f"smallest {setting['min_segment']}"]
    return ", ".join(parts)


def write(out, target, settings_target):
    chosen = {(r["peer"], r["kind"]): {k: r[k] for k in KEYS}
              for r in read_table(os.path.join(out, "chosen.csv"))}
    history = read_table(os.path.join(out, "history.csv"))
    builds, commands = set(), []
    md = ["# LCCP and CPC at the settings a user would choose\n"]
    body = []
    for (peer, kind), best in sorted(chosen.items()):
        body.append(f"## {peer.upper()}, {kind}\n")
        body.append("Chosen: `" + " ".join(setting_flags(best)) + "`"
                    + ("" if peer == "cpc" else " (CPC's cut settings unused)") + ".\n")
        edges = grid_edges(best, peer, kind)
        if edges:
            body.append("At the edge of the grid (a value beyond it might do better still): "
                        + ", ".join(edges) + ".\n")
        body.append("| input | dev 1 - RI | dev Hamming | dev seg. | validation 1 - RI | "
                    "validation Hamming | validation seg. |")
        body.append("|---" * 7 + "|")
        for inp in INPUTS[kind]:
            dev = halves_of(read_scores(run_dir(out, "dev", (peer,) if (peer,) in
                                                 _peers_with(history, best, kind) else
                                                 ("lccp", "cpc"), inp, best), peer))
            val = overall_of(read_scores(run_dir(out, "val", (peer,), inp, best), peer))
            for mode in dev:
                d = dev[mode]
                label = LABELS[inp] if kind == "whole" else f"view: {mode}"
                vm = val.get(mode, [float("nan")] * 3)
                body.append(f"| {label} | {report.pair(d[0][0], d[1][0])} | "
                            f"{report.pair(d[0][1], d[1][1])} | "
                            f"{report.fmt(report.mean([d[0][2], d[1][2]]), 1)} | "
                            f"{report.fmt(vm[0])} | {report.fmt(vm[1])} | {report.fmt(vm[2], 1)} |")
        body.append("")
        body.append(f"Every setting tried for {peer.upper()} on {kind} (dev split, `a / b` the "
                    "halves; the objective is the mean of 1 - RI and Hamming over both halves "
                    "and the inputs):\n")
        body.append("| stage | setting | 1 - RI | Hamming | segments | objective |")
        body.append("|---|---|---|---|---|---|")
        for r in history:
            if r["kind"] != kind or peer not in r["peers"].split("+"):
                continue
            s = {k: r[k] for k in KEYS}
            peers = tuple(r["peers"].split("+"))
            ri, ham, seg = [[], []], [[], []], []
            for inp in INPUTS[kind]:
                folder = run_dir(out, "dev", peers, inp, s)
                builds.add(open(os.path.join(folder, "build")).read().strip())
                for per_half in halves_of(read_scores(folder, peer)).values():
                    for h in range(2):
                        ri[h].append(per_half[h][0])
                        ham[h].append(per_half[h][1])
                    seg.append(report.mean([per_half[0][2], per_half[1][2]]))
            obj = objective(out, "dev", peers, peer, kind, s)
            mark = " **chosen**" if s == best else ""
            extra = f", cut score {s['cut_score']}, most cuts {s['max_cuts']}" if peer == "cpc" else ""
            body.append(f"| {r['stage']} | {describe(s, kind)}{extra}{mark} | "
                        f"{report.pair(report.mean(ri[0]), report.mean(ri[1]))} | "
                        f"{report.pair(report.mean(ham[0]), report.mean(ham[1]))} | "
                        f"{report.fmt(report.mean(seg), 1)} | {report.fmt(obj, 4)} |")
        body.append("")
    for split in ("dev", "val"):
        for name in sorted(os.listdir(os.path.join(out, split))):
            folder = os.path.join(out, split, name)
            if os.path.exists(os.path.join(folder, "build")):
                builds.add(open(os.path.join(folder, "build")).read().strip())
                if split == "val":
                    commands.append(report.relative_command(
                        open(os.path.join(folder, "command")).read().strip(), out))
    if len(builds) != 1:
        sys.exit(f"tune_peers.py: the runs come from more than one build: {sorted(builds)}")
    md.append("Written by `scripts/tune_peers.py` from the runs in `$OUT` "
              "(scripts/tune_peers.sh's OUT); build "
              f"{builds.pop()} (every run's evaluator); machine: {report.machine()}. "
              "Both peers run PCL's supervoxels (colour importance 0, spatial 1, normal 4), then "
              "LCCP or CPC with the sanity criterion and the smoothness check on (threshold "
              "0.1), resolutions in bounding-box diagonals. Normals: PCL's estimate from 10 "
              "neighbours, oriented outward by the mesh on whole objects ('estimated') or the "
              "mesh's face normals ('mesh'); on views, the estimate oriented towards the "
              "sensor. The grid (`scripts/tune_peers.py`) chooses on the dev split's two halves "
              "(models base+1..3 / base+4..6, `a / b`), in stages; the validation split "
              "(base+17..20) ran once, at the chosen settings, and chose nothing. "
              "`scripts/report.sh` and `bench/` run the peers at these settings "
              "(`results/peer_settings.csv`, the evaluator's `-peer_settings`).\n")
    md.append("The validation runs:\n\n```")
    md += commands
    md.append("```\n")
    report.write_atomically(target, md + body)
    with open(os.path.join(out, "chosen.csv")) as f:
        report.write_atomically(settings_target, f.read().rstrip("\n").split("\n"))
    print(f"tune_peers.py: wrote {target} and {settings_target}")


def grid_edges(setting, peer, kind):
    """The chosen values that are the smallest or largest of their grid (numbers only)."""
    edges = []
    for peers, grid in STAGES:
        if peer not in peers:
            continue
        for key, values in grid.items():
            if key == "normals":
                continue
            numbers = [float(v) for v in values]
            value = float(setting[key])
            if value == min(numbers) and value > 0:  # 0 (no smallest segment) has no beyond
                edges.append(f"{key} {setting[key]} (the smallest tried)")
            elif value == max(numbers):
                edges.append(f"{key} {setting[key]} (the largest tried)")
    return edges


def _peers_with(history, setting, kind):
    """The peer groups whose dev runs hold this setting."""
    return {tuple(r["peers"].split("+")) for r in history
            if r["kind"] == kind and {k: r[k] for k in KEYS} == setting}


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "run":
        run(sys.argv[2])
    elif len(sys.argv) in (4, 5) and sys.argv[1] == "write":
        write(sys.argv[2], sys.argv[3], sys.argv[4] if len(sys.argv) == 5 else os.path.join(
            os.path.dirname(os.path.abspath(sys.argv[3])), "peer_settings.csv"))
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
