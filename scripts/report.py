#!/usr/bin/env python3
"""Writes the report of scripts/report.sh's runs: every kind of input on both halves of the dev
split (models base+1..3 and base+4..6 of each category) and on the validation split (base+17..20,
where nothing was chosen), per category, beside LCCP, CPC and the people; and, for every run
named off-<stage>, what turning that stage off changes (the ablation, in a file of its own).

    python3 scripts/report.py OUT results/report.md [ABLATION_OUT [results/ablation.md]]

OUT holds <split>/<config>/<input>/ with the evaluator's models.csv and build, and report.sh's
command. Every run of a file must come from one build of the evaluator: the script refuses to
write a file whose runs name more than one.
"""
import csv
import datetime
import os
import platform
import sys
from collections import defaultdict

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from results_paths import relative_command  # noqa: E402  (the commands, relative to the repository)

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
    ("given", "given", "face centroids, the people's count given"),
]
SPLITS = ("dev", "val")
HALVES = ("1-3", "4-6")
# A change smaller than this in a mean over a half (19 x 3 models) is noise.
NOISE = 0.002
PEERS = (("lccp", "lccp", "LCCP"), ("cpc", "cpc", "CPC"))  # (method, config, name)


def half(model_id):
    return HALVES[0] if (model_id - 1) % 20 < 3 else HALVES[1]


def read_runs(out):
    """({(split, config, folder, mode, method): {id: [[ri, hamming, segments, seconds]...]}},
    {id: category}, {build: [run folders]}, [commands])"""
    runs = defaultdict(lambda: defaultdict(list))
    categories, builds, commands = {}, defaultdict(list), []
    for split in SPLITS:
        if not os.path.isdir(os.path.join(out, split)):
            continue
        for config in sorted(os.listdir(os.path.join(out, split))):
            for folder in sorted({f for f, _, _ in INPUTS}):
                run = os.path.join(out, split, config, folder)
                path = os.path.join(run, "models.csv")
                if not os.path.exists(path):
                    continue
                build = os.path.join(run, "build")
                builds[open(build).read().strip() if os.path.exists(build) else "unknown"].append(
                    run)
                commands.append(relative_command(
                    open(os.path.join(run, "command")).read().strip(), out))
                with open(path, newline="") as f:
                    for row in csv.DictReader(f):
                        model_id = int(row["id"])
                        categories[model_id] = row["category"]
                        key = (split, config, folder, row["mode"], row["method"])
                        runs[key][model_id].append(
                            [float(row["one_minus_rand_index"]), float(row["hamming"]),
                             float(row["segments"]), float(row["seconds"])])
    return runs, categories, builds, commands


def one_build(builds, out):
    """The one build every run came from; exits when there is none or more than one."""
    if len(builds) != 1:
        detail = "; ".join(f"{b}: {len(r)} runs, e.g. {r[0]}" for b, r in sorted(builds.items()))
        sys.exit(f"report.py: the runs under {out} come from {len(builds)} builds ({detail})")
    return next(iter(builds))


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


class Scores:
    """The runs of one report, read by split, config, input and method."""

    def __init__(self, runs, categories):
        self.runs = runs
        self.categories = categories
        self.ids = {split: sorted({i for k, v in runs.items() if k[0] == split for i in v})
                    for split in SPLITS}

    def get(self, split, config, folder, mode, method, ids=None):
        """[1 - RI, Hamming, segments, seconds] over the split's models (or ids), or None."""
        key = (split, config, folder, mode, method)
        if key not in self.runs:
            return None
        return means(self.runs[key], self.ids[split] if ids is None else ids)[0]

    def halves(self, config, folder, mode, method):
        """The dev halves: two lists as get(), or None."""
        if ("dev", config, folder, mode, method) not in self.runs:
            return None
        return [self.get("dev", config, folder, mode, method,
                         [i for i in self.ids["dev"] if half(i) == h]) for h in HALVES]

    def cell(self, config, folder, mode, method, metric):
        """'a / b | v': the dev halves, then the validation split."""
        h = self.halves(config, folder, mode, method)
        v = self.get("val", config, folder, mode, method)
        dev = pair(h[0][metric], h[1][metric]) if h else ""
        return f"{dev} | {fmt(v[metric]) if v else ''}"


def header(title, out, build, commands, md):
    md.append(f"# {title}\n")
    md.append(f"Written by `scripts/report.py` on {datetime.date.today()} from the runs in "
              f"`$OUT` (scripts/report.sh's OUT); every run's evaluator was build {build} "
              "(the build each run recorded). "
              f"Machine: {machine()}. The evaluator's commands:\n")
    md.append("```")
    md += commands
    md.append("```\n")
    md.append("Figures are means over models (each model's draws and views averaged first). "
              "'dev' gives the two halves of the dev split, models base+1..3 / base+4..6 of each "
              "category, on which every default was chosen; 'val' the validation split, models "
              "base+17..20, which chose nothing. Lower is better for 1 - RI and Hamming. "
              "Segments are per model, or per view on views.\n")


def main_tables(s, md):
    md.append("## Every kind of input: ours beside LCCP, CPC and the people\n")
    md.append("LCCP and CPC run at the settings of `results/peers.md` "
              "(`results/peer_settings.csv`). 'whole' is ours on the whole object (face "
              "centroids) scored on the faces the view sees.\n")
    for metric, name in ((0, "1 - RI"), (1, "Hamming")):
        md.append(f"### {name}\n")
        md.append("| input | ours dev | ours val | whole dev | whole val | LCCP dev | LCCP val | "
                  "CPC dev | CPC val | people dev | people val |")
        md.append("|---" * 11 + "|")
        for folder, mode, label in INPUTS:
            if not s.halves("defaults", folder, mode, "ours"):
                continue
            cells = [s.cell("defaults", folder, mode, "ours", metric),
                     s.cell("defaults", folder, mode, "ours whole", metric),
                     *(s.cell(cfg, folder, mode, m, metric) for m, cfg, _ in PEERS),
                     s.cell("lccp", folder, mode, "human", metric)]
            md.append(f"| {label} | " + " | ".join(cells) + " |")
        md.append("")
    md.append("### Segments (per model or view; dev | val)\n")
    md.append("| input | ours | LCCP | CPC | people |")
    md.append("|---" * 5 + "|")
    for folder, mode, label in INPUTS:
        if not s.halves("defaults", folder, mode, "ours"):
            continue
        cells = []
        for method, cfg in (("ours", "defaults"), ("lccp", "lccp"), ("cpc", "cpc"),
                            ("human", "lccp")):
            d, v = s.get("dev", cfg, folder, mode, method), s.get("val", cfg, folder, mode, method)
            cells.append(f"{fmt(d[2], 1) if d else ''} / {fmt(v[2], 1) if v else ''}")
        md.append(f"| {label} | " + " | ".join(cells) + " |")
    md.append("")


def peer_wins(s, md):
    """Where a peer does better than ours: every (input, peer, metric) with the peer lower on a
    dev half or on the validation split."""
    md.append("## Where a peer does better than ours\n")
    md.append("Every input, peer and measure where the peer's mean is lower than ours on a half "
              "of the dev split or on the validation split (by any margin).\n")
    rows = []
    for folder, mode, label in INPUTS:
        ours_h = s.halves("defaults", folder, mode, "ours")
        if not ours_h:
            continue
        ours_v = s.get("val", "defaults", folder, mode, "ours")
        for method, cfg, name in PEERS:
            peer_h = s.halves(cfg, folder, mode, method)
            peer_v = s.get("val", cfg, folder, mode, method)
            for metric, mname in ((0, "1 - RI"), (1, "Hamming")):
                where = [f"dev {h}" for k, h in enumerate(HALVES)
                         if peer_h and peer_h[k][metric] < ours_h[k][metric]]
                if peer_v and ours_v and peer_v[metric] < ours_v[metric]:
                    where.append("val")
                if where:
                    rows.append(f"| {label} | {name} | {mname} | {', '.join(where)} |")
    if rows:
        md.append("| input | peer | measure | where the peer is lower |")
        md.append("|---|---|---|---|")
        md += rows
    else:
        md.append("Nowhere: ours is lower on every input, measure, dev half and the validation "
                  "split.")
    md.append("")
    md.append("Per category: the categories where the peer's 1 - RI is lower than ours on the "
              "dev split (its six models) or on the validation split.\n")
    md.append("| input | peer | categories (dev) | categories (val) |")
    md.append("|---|---|---|---|")
    cats = list(dict.fromkeys(s.categories[i] for i in sorted(s.categories)))
    for folder, mode, label in INPUTS:
        if not s.halves("defaults", folder, mode, "ours"):
            continue
        for method, cfg, name in PEERS:
            if not s.halves(cfg, folder, mode, method):
                continue  # no run of this peer here (the count given: the peers take none)
            lower = []
            for split in SPLITS:
                names = []
                for c in cats:
                    ids = [i for i in s.ids[split] if s.categories[i] == c]
                    ours = s.get(split, "defaults", folder, mode, "ours", ids)
                    peer = s.get(split, cfg, folder, mode, method, ids)
                    if ours and peer and peer[0] < ours[0]:
                        names.append(c)
                lower.append(", ".join(names) or "—")
            md.append(f"| {label} | {name} | {lower[0]} | {lower[1]} |")
    md.append("")


def category_tables(s, md):
    md.append("## Per category (1 - RI / Hamming; dev: all six models, val: all four)\n")
    cats = []
    for i in sorted(s.categories):
        if s.categories[i] not in cats:
            cats.append(s.categories[i])
    for folder, mode, label in INPUTS:
        if not s.halves("defaults", folder, mode, "ours"):
            continue
        md.append(f"### {label}\n")
        md.append("| category | ours dev | ours val | seg. dev / val | LCCP dev | LCCP val | "
                  "CPC dev | CPC val | people dev | people val |")
        md.append("|---" * 10 + "|")
        for c in cats + ["Overall"]:
            cells = ["**Overall**" if c == "Overall" else c]
            for method, cfg in (("ours", "defaults"), ("lccp", "lccp"), ("cpc", "cpc"),
                                ("human", "lccp")):
                seg = []
                for split in SPLITS:
                    ids = [i for i in s.ids[split] if c == "Overall" or s.categories[i] == c]
                    m = s.get(split, cfg, folder, mode, method, ids)
                    cells.append(pair(m[0], m[1]) if m else "")
                    seg.append(fmt(m[2], 1) if m else "")
                if method == "ours":
                    cells.append(" / ".join(seg))
            md.append("| " + " | ".join(cells) + " |")
        md.append("")


def stage_deltas(s, off):
    """Per input: (label, [(d RI, d Hamming) per dev half, then val], base, off segments)."""
    out = []
    for folder, mode, label in INPUTS:
        base_h = s.halves("base", folder, mode, "ours")
        off_h = s.halves(off, folder, mode, "ours")
        if not base_h or not off_h:
            continue
        d = [(off_h[k][0] - base_h[k][0], off_h[k][1] - base_h[k][1]) for k in range(2)]
        base_v = s.get("val", "base", folder, mode, "ours")
        off_v = s.get("val", off, folder, mode, "ours")
        d.append((off_v[0] - base_v[0], off_v[1] - base_v[1]) if base_v and off_v else None)
        base_d = s.get("dev", "base", folder, mode, "ours")
        off_d = s.get("dev", off, folder, mode, "ours")
        out.append((label, d, base_d[2], off_d[2]))
    return out


def verdict(deltas):
    """(inputs where the stage pays, inputs where it costs), on the dev halves and on val."""
    pays, costs = [], []
    for label, d, _, _ in deltas:
        parts = [x for x in d if x is not None]
        if any(v <= -NOISE for x in parts for v in x):
            costs.append(label)
        elif any(all(x[k] >= NOISE for x in parts) for k in (0, 1)):
            pays.append(label)
    return pays, costs


def signed(x, k):
    return f"{x[k]:+.3f}" if x is not None else ""


def ablation(s, md, out):
    offs = sorted({k[1] for k in s.runs if k[1].startswith("off-")})
    md.append(f"From the runs in `$OUT`, with fewer draws and views than the report: each stage "
              "off against the defaults on the same points, on both halves of the dev split "
              "and on the validation split. A stage pays on an input when turning it off makes "
              f"the dev halves and the validation split all worse by at least {NOISE} in 1 - RI "
              "or Hamming and none better by as much in the other; it costs on an input when "
              f"turning it off makes a dev half or the validation split better by at least "
              f"{NOISE} in either. Detail per input follows the table.\n")
    md.append("| stage | pays on | costs on |")
    md.append("|---|---|---|")
    for off in offs:
        pays, costs = verdict(stage_deltas(s, off))
        md.append(f"| {off[4:]} | {', '.join(pays) or '—'} | {', '.join(costs) or '—'} |")
    md.append("")
    md.append("## Each stage off, per input\n")
    md.append("Off minus defaults, `dev 1-3 / dev 4-6 | val`: positive means the stage helps "
              "there. (Times are not compared here; speed is `bench/`'s.)\n")
    for off in offs:
        md.append(f"### {off[4:]}\n")
        md.append("| input | Δ 1 - RI dev | Δ 1 - RI val | Δ Hamming dev | Δ Hamming val | "
                  "segments dev (defaults → off) |")
        md.append("|---|---|---|---|---|---|")
        for label, d, seg_base, seg_off in stage_deltas(s, off):
            md.append(f"| {label} | {signed(d[0], 0)} / {signed(d[1], 0)} | {signed(d[2], 0)} | "
                      f"{signed(d[0], 1)} / {signed(d[1], 1)} | {signed(d[2], 1)} | "
                      f"{fmt(seg_base, 1)} → {fmt(seg_off, 1)} |")
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
    runs, categories, builds, commands = read_runs(out)
    if not runs:
        sys.exit(f"report.py: no <split>/<config>/<input>/models.csv under {out}")
    s = Scores(runs, categories)
    md = []
    header("Every kind of input, on the dev and validation splits", out, one_build(builds, out),
           commands, md)
    main_tables(s, md)
    peer_wins(s, md)
    category_tables(s, md)
    if len(sys.argv) >= 4:  # the ablation, in its own file: it comes from its own runs
        abl_out = sys.argv[3]
        abl_target = sys.argv[4] if len(sys.argv) == 5 else os.path.join(
            os.path.dirname(os.path.abspath(target)), "ablation.md")
        abl_runs, abl_categories, abl_builds, abl_commands = read_runs(abl_out)
        if not abl_runs:
            sys.exit(f"report.py: no runs under {abl_out}")
        build = one_build(abl_builds, abl_out)
        if build != one_build(builds, out):
            sys.exit(f"report.py: the ablation's build {build} is not the report's")
        abl = []
        header("What each stage buys", abl_out, build, abl_commands, abl)
        ablation(Scores(abl_runs, abl_categories), abl, abl_out)
        write_atomically(abl_target, abl)
        print(f"report.py: wrote {abl_target}")
    write_atomically(target, md)
    print(f"report.py: wrote {target}")


if __name__ == "__main__":
    main()
