#!/usr/bin/env python3
"""The commands a results file names, relative to the repository: the checkout becomes '.' (the
shared data '../shared/data'), the run folder '$OUT', an evaluator kept outside the checkout
'build/eval/pcl_ncut_seg_eval' (its build is named beside it). report.py and tune_peers.py
write their commands through relative_command(); run as a program, it rewrites the command
lines of results files written before they did, and nothing else:

    python3 scripts/results_paths.py --root OLD_CHECKOUT FILE...
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EVALUATOR = "build/eval/pcl_ncut_seg_eval"


def relative_command(command, out, root=ROOT):
    """command with out as '$OUT' and root as the repository, paths normalised."""
    words = []
    for i, word in enumerate(command.split()):
        if word.startswith("/"):
            path = os.path.normpath(word)
            out_abs = os.path.normpath(out)
            if path == out_abs or path.startswith(out_abs + os.sep):
                word = "$OUT" + path[len(out_abs):]
            elif path == root or path.startswith(os.path.normpath(root) + os.sep) or \
                    path.startswith(os.path.dirname(os.path.normpath(root)) + os.sep + "shared"):
                word = os.path.relpath(path, root)
            elif i == 0:
                word = EVALUATOR
        words.append(word)
    return " ".join(words)


# What each writer now says $OUT is, after the run folder in its header.
OUT_NAMED = [
    (r"(Written by `scripts/report\.py` on \S+ from the runs in `\$OUT`);",
     r"\1 (scripts/report.sh's OUT);"),
    (r"(Written by `scripts/tune_peers\.py` from the runs in `\$OUT`);",
     r"\1 (scripts/tune_peers.sh's OUT);"),
]


def rewrite(path, root):
    """Rewrite the run folder and the commands of a results file written with absolute paths,
    and name $OUT in its header as its writer now does."""
    with open(path, encoding="utf-8") as f:
        original = text = f.read()
    match = re.search(r"[Ff]rom the runs in `(/[^`]+)`", text)
    if match:
        out = match.group(1)
        lines = text.split("\n")
        for i, line in enumerate(lines):
            if line.startswith("/") and " " in line:
                lines[i] = relative_command(line, out, root)
        text = "\n".join(lines).replace(f"the runs in `{out}`", "the runs in `$OUT`")
    for pattern, replacement in OUT_NAMED:
        text = re.sub(pattern, replacement, text, count=1)
    if text == original:
        return False
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(path + ".tmp", path)
    return True


def main(argv):
    if len(argv) < 4 or argv[1] != "--root":
        sys.exit("usage: results_paths.py --root OLD_CHECKOUT FILE...")
    for path in argv[3:]:
        print(f"results_paths.py: {path}: {'rewritten' if rewrite(path, argv[2]) else 'unchanged'}")


if __name__ == "__main__":
    main(sys.argv)
