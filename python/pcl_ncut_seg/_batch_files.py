"""The files of the batch front end besides the outputs: writing any file whole or not at all,
the journal that makes a run resumable, and the results table (CSV, and Parquet where pyarrow
imports)."""
import csv
import io
import json
import os
import re
import tempfile

JOURNAL = ".batch.jsonl"  # one row per line as files finish: what a killed run had done
TABLE = "batch.csv"
PARQUET = "batch.parquet"
_FORMAT = 1  # of the journal

COLUMNS = ["input", "output", "points", "faces", "segments", "supernodes", "refined_supernodes",
           "read_s", "knn_s", "centrality_s", "supernodes_s", "refinement_s", "hierarchy_s",
           "points_s", "total_s", "write_s", "view", "view_origin_estimated", "rim_points",
           "residual_growth", "projected", "sampling_irregularity", "irregular", "error"]
TIME_COLUMNS = [c for c in COLUMNS if c.endswith("_s")]

_TEMPORARY = re.compile(r"^\..+\.[a-z0-9_]{8}\.part$")  # write_whole()'s names


def _umask():
    """The process' umask, read without setting it (os.umask would race with other threads)."""
    try:
        with open("/proc/self/status", encoding="ascii") as f:
            for line in f:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError):
        pass
    return 0o022


def write_whole(path, data):
    """Write bytes to path under a temporary name in its directory, then rename: a reader, or a
    run killed half-way, sees the old file or the new one, never part of one."""
    directory, name = os.path.split(os.path.abspath(path))
    os.makedirs(directory, exist_ok=True)
    fd, temporary = tempfile.mkstemp(dir=directory, prefix=f".{name}.", suffix=".part")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())  # the data is on disk before the name points at it
        os.chmod(temporary, 0o666 & ~_umask())  # mkstemp's 0600: give the usual mode
        os.replace(temporary, path)
    except BaseException:
        try:
            os.unlink(temporary)
        except OSError:
            pass
        raise


def remove_temporaries(directories):
    """Remove what write_whole() left behind in directories when its process was killed."""
    for directory in directories:
        try:
            names = os.listdir(directory)
        except OSError:
            continue
        for name in names:
            if _TEMPORARY.match(name):
                try:
                    os.unlink(os.path.join(directory, name))
                except OSError:
                    pass


class Journal:
    """OUT/.batch.jsonl: a header line (the parameters), then a line per finished input: its
    row, the size and modification time of the input it describes, and whether it is final (a
    result, or the input's own error) or to be tried again (the worker died, a write failed)."""

    def __init__(self, path, parameters, entries=None):
        self.path, self.parameters = path, parameters
        self.entries = dict(entries or {})  # input -> {"row", "stamp", "final"}
        self._file = None

    @classmethod
    def load(cls, path):
        """The journal at path, or None when there is none; a last line cut short by a kill is
        left out."""
        try:
            with open(path, encoding="utf-8") as f:
                lines = f.read().split("\n")
        except FileNotFoundError:
            return None
        try:
            header = json.loads(lines[0])
            assert header["format"] == _FORMAT
        except (ValueError, KeyError, AssertionError):
            return None  # not ours, or from another version: start again
        entries = {}
        for line in lines[1:]:
            try:
                entry = json.loads(line)
                entries[entry["row"]["input"]] = entry
            except (ValueError, KeyError, TypeError):
                continue
        return cls(path, header["parameters"], entries)

    def start(self, keep):
        """Rewrite the journal with the entries of the inputs in keep only, then append."""
        self.entries = {k: v for k, v in self.entries.items() if k in keep}
        lines = [json.dumps({"format": _FORMAT, "parameters": self.parameters})]
        lines += [json.dumps(self.entries[k]) for k in sorted(self.entries)]
        write_whole(self.path, ("\n".join(lines) + "\n").encode("utf-8"))
        self._file = open(self.path, "a", encoding="utf-8")

    def add(self, row, stamp, final):
        entry = {"row": row, "stamp": list(stamp), "final": final}
        self.entries[row["input"]] = entry
        self._file.write(json.dumps(entry) + "\n")
        self._file.flush()  # in the page cache: a killed process loses nothing written

    def close(self):
        if self._file:
            self._file.close()
            self._file = None

    def rows(self):
        return [self.entries[k]["row"] for k in sorted(self.entries)]


def write_tables(directory, rows):
    """batch.csv, and batch.parquet where pyarrow imports; returns the paths written."""
    text = io.StringIO()
    writer = csv.DictWriter(text, COLUMNS, extrasaction="ignore", lineterminator="\n")
    writer.writeheader()
    writer.writerows({c: ("" if row.get(c) is None else row[c]) for c in COLUMNS}
                     for row in rows)
    written = [os.path.join(directory, TABLE)]
    write_whole(written[0], text.getvalue().encode("utf-8"))
    try:
        import pyarrow
        import pyarrow.parquet
    except ImportError:  # not in Debian 12: the CSV is the table
        return written
    table = pyarrow.Table.from_pylist([{c: row.get(c) for c in COLUMNS} for row in rows])
    sink = pyarrow.BufferOutputStream()
    pyarrow.parquet.write_table(table, sink)
    written.append(os.path.join(directory, PARQUET))
    write_whole(written[1], sink.getvalue().to_pybytes())
    return written
