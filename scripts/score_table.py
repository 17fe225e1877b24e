"""Reading scripts/score_video.sh's OUT/scores.tsv: one definition for the research scripts that
read it (latency_band.py, half_cells_table.py). Research tooling; the product never runs it."""
import os
import sys


def fail(message, status=2):
    """Exits with `status` (2: bad arguments or input), the calling script's name before the
    message."""
    print(f"{os.path.basename(sys.argv[0])}: {message}", file=sys.stderr)
    sys.exit(status)


def read_rows(path, required):
    """The table's rows, each (line number, {column: text}); exits 2 naming the file and line where
    it cannot be read, lacks one of the `required` columns or a row has the wrong number of
    fields."""
    try:
        with open(path, encoding="utf-8") as table:
            lines = table.read().splitlines()
    except OSError as error:
        fail(f"{path}: {error.strerror}")
    if not lines:
        fail(f"{path}: empty")
    header = lines[0].split("\t")
    missing = [c for c in required if c not in header]
    if missing:
        fail(f"{path}:1: no column {', '.join(missing)} (not a score_video.sh table?)")
    rows = []
    for number, line in enumerate(lines[1:], 2):
        values = line.split("\t")
        if len(values) != len(header):
            fail(f"{path}:{number}: {len(values)} fields, expected {len(header)}")
        rows.append((number, dict(zip(header, values))))
    return rows
