"""The batch front end and the tool agree, file by file, on files from anywhere: a corpus of
mutations of the batch tests' inputs (every format and encoding), made from a fixed seed:
header counts, sizes and types changed, header lines swapped, data truncated, bytes flipped,
tokens the formats do not allow, CRLF line ends. For each file, both segment it into the same
bytes, or both refuse it, the tool with the batch's reason."""
import os
import random
import re
import subprocess

import pytest

import batch_inputs
from pcl_ncut_seg import batch

TOOL = os.environ.get("PCL_NCUT_SEG_TOOL")
FLAGS = ["-segments", "3", "-k", "8", "-threads", "1"]
PARAMETERS = {"segments": "3", "k": "8", "threads": "1"}
MUTANTS_PER_INPUT = 6
SEED = 62

pytestmark = pytest.mark.skipif(not TOOL, reason="PCL_NCUT_SEG_TOOL is not set (no tools built)")


def _header_end(data):
    for marker in (b"DATA ", b"end_header", b"}"):
        at = data.find(marker)
        if at >= 0:
            end = data.find(b"\n", at)
            return len(data) if end < 0 else end + 1
    return min(len(data), 200)


def _edit_number(data, rng):
    """A number of the header becomes another: 0, 1, a neighbour, or far too large."""
    end = _header_end(data)
    numbers = list(re.finditer(rb"\d+", data[:end]))
    if not numbers:
        return data
    m = rng.choice(numbers)
    value = rng.choice([b"0", b"1", b"3", str(int(m.group()) + 1).encode(), b"1000000",
                        b"4294967295"])
    return data[:m.start()] + value + data[m.end():]


def _edit_word(data, rng):
    """A word of the header (a TYPE, a format, a key) becomes another the format may not allow."""
    end = _header_end(data)
    words = list(re.finditer(rb"[A-Za-z_]+", data[:end]))
    if not words:
        return data
    m = rng.choice(words)
    value = rng.choice([b"X", b"F", b"U", b"list", b"ascii", b"binary", b"float", b"uchar"])
    return data[:m.start()] + value + data[m.end():]


def _swap_lines(data, rng):
    lines = data[:_header_end(data)].split(b"\n")
    if len(lines) < 3:
        return data
    i, j = rng.sample(range(len(lines) - 1), 2)
    lines[i], lines[j] = lines[j], lines[i]
    return b"\n".join(lines) + data[_header_end(data):]


def _truncate(data, rng):
    return data[:rng.randrange(len(data))]


def _flip(data, rng):
    out = bytearray(data)
    for _ in range(rng.randint(1, 4)):
        out[rng.randrange(len(out))] ^= 1 << rng.randrange(8)
    return bytes(out)


def _token(data, rng):
    """A value of the data becomes a token the formats do not allow, or gains a neighbour."""
    start = _header_end(data)
    values = list(re.finditer(rb"-?\d+\.?\d*(e-?\d+)?", data[start:]))
    if not values:
        return _flip(data, rng)
    m = rng.choice(values)
    token = rng.choice([m.group() + b"f", b"", m.group() + b" 7", b"0x10", b"1e400", b"  \t"])
    return data[:start + m.start()] + token + data[start + m.end():]


def _crlf(data, rng):
    return data.replace(b"\n", b"\r\n")


MUTATIONS = [_edit_number, _edit_number, _edit_word, _swap_lines, _truncate, _flip, _token,
             _crlf]


def _mutants(folder, names, out):
    rng = random.Random(SEED)
    made = []
    for name in names:
        with open(folder / name, "rb") as f:
            data = f.read()
        for k in range(MUTANTS_PER_INPUT):
            mutation = rng.choice(MUTATIONS)
            path = out / f"{k}_{mutation.__name__[1:]}_{name.replace('/', '_')}"
            with open(path, "wb") as f:
                f.write(mutation(data, rng))
            made.append(path)
    return made


def _tool(path, out):
    if out.exists():
        out.unlink()
    done = subprocess.run([TOOL, str(path), str(out), "-quiet", *FLAGS],
                          stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, timeout=120)
    assert done.returncode >= 0, f"{path.name}: the tool died of signal {-done.returncode}"
    if done.returncode == 0:
        with open(out, "rb") as f:
            return f.read(), None
    assert not out.exists(), f"{path.name}: the tool failed and left its output"
    return None, done.stderr.decode(errors="replace")


def test_the_batch_and_the_tool_agree_on_every_mutated_file(tmp_path):
    folder = tmp_path / "in"
    good, _ = batch_inputs.make(folder)
    mutants = tmp_path / "mutants"
    mutants.mkdir()
    paths = _mutants(folder, good, mutants)
    assert len(paths) >= 150
    disagreements, refused = [], 0
    for path in paths:
        expected, reason = _tool(path, tmp_path / "tool.pcd")
        target = tmp_path / "batch.pcd"
        row = batch.segment_file(str(path), str(target), PARAMETERS)
        if expected is not None:
            got = target.read_bytes() if target.exists() else None
            if row.get("error") or got != expected:
                disagreements.append(f"{path.name}: the tool segments it, the batch "
                                     f"{'refuses: ' + row['error'] if row.get('error') else 'differs'}")
        elif not row.get("error"):
            disagreements.append(f"{path.name}: the batch segments it, the tool refuses: "
                                 f"{reason.strip()}")
        else:
            refused += 1
            assert "\n" not in row["error"] and row["error"], path.name
            # A reader's reason names the file: the tool gives the same words.
            if str(path) in row["error"] and row["error"] not in reason:
                disagreements.append(f"{path.name}: two reasons: '{row['error']}' and "
                                     f"'{reason.strip()}'")
        if target.exists():
            target.unlink()
    assert not disagreements, "\n".join(disagreements)
    assert 0 < refused < len(paths)  # the corpus holds both kinds
