"""Files per second of python -m pcl_ncut_seg.batch on 1, 2 and all cores against the shell
loop over the pcl_ncut_seg tool that it replaces, on the same folder; prints a Markdown
report (scripts/bench_batch.sh writes it to results/batch.md).

    python3 python/benchmarks/bench_batch.py TOOL IN [FILES] [-- TOOL FLAGS]

TOOL: the pcl_ncut_seg binary; IN: a folder of inputs (the first FILES by name, default all,
are copied to a temporary folder). Each batch run is the whole command, cluster start-up
included: what a user waits for. The loop is `for f in IN/*; do pcl_ncut_seg "$f" OUT/...; done`,
once with the tool's default threads (all cores for each file) and once with -threads 1. Every
run's outputs are checked to be the first loop's, byte for byte.
"""
import os
import shutil
import subprocess
import sys
import tempfile
import time


def main(argv):
    flags = argv[argv.index("--") + 1:] if "--" in argv else []
    argv = argv[:argv.index("--")] if "--" in argv else argv
    if len(argv) not in (2, 3):
        sys.exit(__doc__)
    tool, source = argv[0], argv[1]
    limit = int(argv[2]) if len(argv) == 3 else None
    with tempfile.TemporaryDirectory() as work:
        names = copy_inputs(source, os.path.join(work, "in"), limit)
        runs = [("shell loop over the tool", loop(tool, work, "loop", names, flags)),
                ("shell loop over the tool, -threads 1",
                 loop(tool, work, "loop1", names, flags + ["-threads", "1"]))]
        cores = len(os.sched_getaffinity(0))
        for workers in sorted({1, 2, cores}):
            label = f"batch, {workers} worker{'s' * (workers > 1)}"
            label += " (all cores)" if workers == cores else ""
            runs.append((label, batch(work, workers, flags)))
        reference = outputs(os.path.join(work, "loop"))
        folders = ["loop1"] + [f"batch{w}" for w in sorted({1, 2, cores})]
        same = {label: outputs(os.path.join(work, folder)) == reference
                for (label, _), folder in zip(runs[1:], folders)}
    report(names, flags, runs, same, cores)


def copy_inputs(source, folder, limit):
    names = sorted(n for n in os.listdir(source) if not n.startswith("."))[:limit]
    os.makedirs(folder)
    for name in names:
        shutil.copy(os.path.join(source, name), folder)
    return names


def loop(tool, work, name, names, flags):
    out = os.path.join(work, name)
    os.makedirs(out)
    script = ('for f in "$1"/*; do n="${f##*/}"; "$2" "$f" "$3/${n%.*}.pcd" -quiet "${@:4}" '
              '|| true; done')
    start = time.perf_counter()
    subprocess.run(["bash", "-c", script, "loop", os.path.join(work, "in"), tool, out, *flags],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def batch(work, workers, flags):
    out = os.path.join(work, f"batch{workers}")
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "pcl_ncut_seg.batch", os.path.join(work, "in"), out,
                    *flags, "--workers", str(workers), "--no-progress"],
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def outputs(folder):
    """{name: bytes} of the PCD outputs of a folder."""
    found = {}
    for name in sorted(os.listdir(folder)):
        if name.endswith(".pcd"):
            with open(os.path.join(folder, name), "rb") as f:
                found[name] = f.read()
    return found


def report(names, flags, runs, same, cores):
    loop_seconds = runs[0][1]
    print(f"{len(names)} files ({names[0]} .. {names[-1]}), flags: "
          f"{' '.join(flags) or 'none (the defaults)'}; {cores} cores; load average after the "
          f"runs {' '.join(f'{v:.2f}' for v in os.getloadavg())}.")
    print()
    print("| run | seconds | files per second | against the loop | outputs the loop's |")
    print("|---|---:|---:|---:|---|")
    for label, seconds in runs:
        check = "-" if label not in same else ("yes" if same[label] else "**no**")
        print(f"| {label} | {seconds:.1f} | {len(names) / seconds:.2f} | "
              f"{loop_seconds / seconds:.2f}x | {check} |")


if __name__ == "__main__":
    main(sys.argv[1:])
