#!/usr/bin/env python3
"""Writes results/oracle.md from scripts/oracle.sh's runs: issue 63's diagnostic, the gap to
people in two parts, per category, on both halves of the dev split and on the validation split.

    python3 scripts/oracle.py OUT results/oracle.md

OUT holds <split>/oracle/centroids/ with the evaluator's models.csv, build, command and seconds.
The oracles read the people's segmentations: the file says so at its top, and no default may be
chosen by it.
"""
import csv
import datetime
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report import HALVES, fmt, half, machine, mean, one_build, write_atomically  # noqa: E402

SPLITS = ("dev", "val")
# (method in models.csv, column name)
METHODS = (("ours", "ours"), ("human", "people"), ("oracle", "oracle"),
           ("kmeans_oracle", "k-means oracle"), ("finest", "finest as it is"))


def read(out):
    """({(split, method): {id: [ri, hamming, segments]}}, {id: category}, {build: [runs]},
    [commands], {split: seconds})"""
    runs, categories, builds, commands, seconds = {}, {}, {}, [], {}
    for split in SPLITS:
        run = os.path.join(out, split, "oracle", "centroids")
        path = os.path.join(run, "models.csv")
        if not os.path.exists(path):
            continue
        build_file = os.path.join(run, "build")
        build = open(build_file).read().strip() if os.path.exists(build_file) else "unknown"
        builds.setdefault(build, []).append(run)
        commands.append(open(os.path.join(run, "command")).read().strip())
        if os.path.exists(os.path.join(run, "seconds")):
            seconds[split] = float(open(os.path.join(run, "seconds")).read())
        with open(path, newline="") as f:
            for row in csv.DictReader(f):
                if row["mode"] != "auto":
                    continue
                model_id = int(row["id"])
                categories[model_id] = row["category"]
                runs.setdefault((split, row["method"]), {})[model_id] = [
                    float(row["one_minus_rand_index"]), float(row["hamming"]),
                    float(row["segments"])]
    return runs, categories, builds, commands, seconds


class Table:
    def __init__(self, runs, categories):
        self.runs, self.categories = runs, categories
        self.cats = list(dict.fromkeys(categories[i] for i in sorted(categories)))

    def ids(self, split, group, category):
        """The models of a split ("dev" halves by group "1-3"/"4-6", "val" all) in a category
        ("Overall": every one)."""
        return [i for i in sorted({i for (s, _), v in self.runs.items() if s == split for i in v})
                if (category == "Overall" or self.categories[i] == category)
                and (group is None or half(i) == group)]

    def value(self, split, group, category, method, metric):
        per_model = self.runs.get((split, method), {})
        vals = [per_model[i][metric] for i in self.ids(split, group, category) if i in per_model]
        return mean(vals) if vals else float("nan")

    def cell(self, split, category, method, metric, digits=3):
        """The dev halves as 'a / b', or the validation split's mean."""
        if split == "val":
            return fmt(self.value("val", None, category, method, metric), digits)
        return " / ".join(fmt(self.value("dev", h, category, method, metric), digits)
                          for h in HALVES)

    def gap(self, split, category, a, b, metric):
        """a - b, signed, as cell() gives it."""
        def d(group):
            x = self.value(split, group, category, a, metric)
            y = self.value(split, group, category, b, metric)
            return "" if x != x or y != y else f"{x - y:+.3f}"
        return d(None) if split == "val" else " / ".join(d(h) for h in HALVES)


SPLIT_TITLES = {"dev": "dev split, halves base+1..3 / base+4..6",
                "val": "validation split, base+17..20"}


def metric_table(t, split, metric, name, md):
    md.append(f"### {name}, {SPLIT_TITLES[split]}\n")
    heads = [n for m, n in METHODS if m != "finest"]
    md.append("| category | " + " | ".join(heads) + " | analysis: oracle − people | "
              "choice: ours − oracle | k-means oracle − oracle |")
    md.append("|---" * (len(heads) + 4) + "|")
    for c in t.cats + ["Overall"]:
        cells = [t.cell(split, c, m, metric) for m, _ in METHODS if m != "finest"]
        cells += [t.gap(split, c, "oracle", "human", metric),
                  t.gap(split, c, "ours", "oracle", metric),
                  t.gap(split, c, "kmeans_oracle", "oracle", metric)]
        md.append(f"| {'**Overall**' if c == 'Overall' else c} | " + " | ".join(cells) + " |")
    md.append("")


def segments_table(t, split, md):
    md.append(f"### Segments per model, {SPLIT_TITLES[split]}\n")
    md.append("| category | ours | people | finest level | finest as it is, 1 - RI | "
              "finest as it is, Hamming |")
    md.append("|---" * 6 + "|")
    for c in t.cats + ["Overall"]:
        cells = [t.cell(split, c, "ours", 2, 1), t.cell(split, c, "human", 2, 1),
                 t.cell(split, c, "finest", 2, 1), t.cell(split, c, "finest", 0),
                 t.cell(split, c, "finest", 1)]
        md.append(f"| {'**Overall**' if c == 'Overall' else c} | " + " | ".join(cells) + " |")
    md.append("")


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: oracle.py OUT results/oracle.md")
    out, target = sys.argv[1], sys.argv[2]
    runs, categories, builds, commands, seconds = read(out)
    if not runs:
        sys.exit(f"oracle.py: no <split>/oracle/centroids/models.csv under {out}")
    build = one_build(builds, out)
    t = Table(runs, categories)
    md = ["# The gap in two parts: the finest-level oracle (issue 63)\n"]
    md.append("**A diagnostic that reads the people's answers.** The oracle and its k-means "
              "control merge each of their segments into the segment of the person it overlaps "
              "most (by face area), separately for each person, and are scored against that "
              "person. They bound what a choice among the finest level's boundaries could "
              "reach; they are not methods, and no default may be chosen by them "
              "([docs/evaluation.md](../docs/evaluation.md#the-finest-level-oracle)).\n")
    times = ", ".join(f"{s} {seconds[s]:.0f} s" for s in SPLITS if s in seconds)
    md.append(f"Written by `scripts/oracle.py` on {datetime.date.today()}; every run's evaluator "
              f"was build {build}. Machine: {machine()}. Wall time per split (one evaluator run, "
              f"one thread): {times or 'not recorded'}. The commands, from the repository's "
              "root:\n")
    md.append("```")
    md += commands
    md.append("```\n")
    md.append("Face centroids, automatic mode. 'ours': the defaults. 'people': each person "
              "against the others. 'oracle': ours asked for many parts (`-oracle_segments`; the "
              "hierarchy stops where it has nothing left to split), merged onto each person. "
              "'k-means oracle': k-means of the face centroids (fixed seed per model) with the "
              "finest level's count, merged likewise. 'dev' gives the halves of the dev split "
              "(models base+1..3 / base+4..6 of each category), 'val' the validation split "
              "(base+17..20). Lower is better.\n")
    for metric, name in ((0, "1 - RI"), (1, "Hamming")):
        md.append(f"## {name} per category\n")
        md.append("The analysis's part of the gap is oracle minus people (below 0: the finest "
                  "level already holds the people's boundaries); the choice's part is ours "
                  "minus oracle; k-means oracle minus oracle is how much better placed the "
                  "finest level's boundaries are than an arbitrary over-segmentation's.\n")
        for split in SPLITS:
            metric_table(t, split, metric, name, md)
    md.append("## Segments per model\n")
    md.append("The finest level's count is the oracles' (k-means takes it per model); beside it, "
              "the finest level scored as it is, without the merge.\n")
    for split in SPLITS:
        segments_table(t, split, md)
    write_atomically(target, md)
    print(f"oracle.py: wrote {target}")


if __name__ == "__main__":
    main()
