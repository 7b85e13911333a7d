#!/usr/bin/env python3
"""Whether two `penumbra tune` output folders hold the same result but for measured times.

Usage: tune_outputs_equal.py SINGLE MERGED  (exit 0: equal; 1: the first differences, listed)

A single run and a merge of shards must agree everywhere except where a time was measured:
- the same files;
- tune.json and units/*/unit.json equal once every "time_ms" key is left out;
- index.html equal once the cells under a "time (ms)" header are blanked and the tables ranked
  by time budget (whose rows are decided by timings) are left out;
- plots/*_time.png (a frontier against measured time) may differ;
- every other file (best/, the images, plots against memory) byte for byte.
"""
import json
import re
import sys
from pathlib import Path

TIME_KEY = "time_ms"
TIME_PLOT = re.compile(r"^plots/.*_time\.png$")
UNIT_JSON = re.compile(r"^units/[^/]+/unit\.json$")


def without_times(value):
    if isinstance(value, dict):
        return {k: without_times(v) for k, v in value.items() if k != TIME_KEY}
    if isinstance(value, list):
        return [without_times(v) for v in value]
    return value


def first_json_difference(a, b, path="$"):
    if type(a) is not type(b):
        return f"{path}: {a!r} (single run) != {b!r} (merge)"
    if isinstance(a, dict):
        for key in sorted(set(a) | set(b)):
            if key not in a or key not in b:
                return f"{path}.{key}: only in the {'merge' if key in b else 'single run'}"
            found = first_json_difference(a[key], b[key], f"{path}.{key}")
            if found:
                return found
        return None
    if isinstance(a, list):
        if len(a) != len(b):
            return f"{path}: {len(a)} entries (single run) != {len(b)} (merge)"
        for i, (x, y) in enumerate(zip(a, b)):
            found = first_json_difference(x, y, f"{path}[{i}]")
            if found:
                return found
        return None
    return None if a == b else f"{path}: {a!r} (single run) != {b!r} (merge)"


TABLE = re.compile(r"<table>.*?</table>", re.S)
ROW = re.compile(r"<tr>(.*?)</tr>", re.S)
CELL = re.compile(r"<t[dh][^>]*>.*?</t[dh]>", re.S)


def html_without_times(text):
    def table(match):
        rows = ROW.findall(match.group(0))
        headers = [re.sub(r"<[^>]+>", "", c) for c in CELL.findall(rows[0])] if rows else []
        if headers and headers[0] == "time budget":
            return "<table>(ranked by measured time)</table>"
        if "time (ms)" not in headers:
            return match.group(0)
        column = headers.index("time (ms)")
        out = []
        for row in rows:
            cells = CELL.findall(row)
            if len(cells) > column and cells[column].startswith("<td"):
                cells[column] = "<td>(time)</td>"
            out.append("<tr>" + "".join(cells) + "</tr>")
        return "<table>" + "".join(out) + "</table>"

    return TABLE.sub(table, text)


def first_text_difference(a, b):
    for i, (x, y) in enumerate(zip(a, b)):
        if x != y:
            return f"at character {i}: ...{a[max(0, i - 60):i + 60]!r} (single run) != ...{b[max(0, i - 60):i + 60]!r} (merge)"
    return f"lengths {len(a)} (single run) != {len(b)} (merge)"


def compare(single: Path, merged: Path):
    files = lambda root: sorted(str(p.relative_to(root)) for p in root.rglob("*") if p.is_file())
    single_files, merged_files = files(single), files(merged)
    problems = []
    if single_files != merged_files:
        only_single = sorted(set(single_files) - set(merged_files))
        only_merged = sorted(set(merged_files) - set(single_files))
        problems.append(f"different files: only in the single run {only_single[:5]}, "
                        f"only in the merge {only_merged[:5]}")
    for name in sorted(set(single_files) & set(merged_files)):
        a, b = single / name, merged / name
        if TIME_PLOT.match(name):
            continue
        if name == "tune.json" or UNIT_JSON.match(name):
            found = first_json_difference(without_times(json.loads(a.read_text())),
                                          without_times(json.loads(b.read_text())))
            if found:
                problems.append(f"{name} differs beyond {TIME_KEY}: {found}")
        elif name == "index.html":
            x, y = html_without_times(a.read_text()), html_without_times(b.read_text())
            if x != y:
                problems.append(f"{name} differs beyond its times: {first_text_difference(x, y)}")
        elif a.read_bytes() != b.read_bytes():
            problems.append(f"{name} differs")
    return single_files, problems


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    single, merged = Path(sys.argv[1]), Path(sys.argv[2])
    for root in (single, merged):
        if not (root / "tune.json").is_file():
            sys.exit(f"{root} holds no tune.json")
    names, problems = compare(single, merged)
    if problems:
        print(f"{len(problems)} difference(s) between {single} and {merged}:")
        for problem in problems[:20]:
            print("  " + problem)
        sys.exit(1)
    print(f"{len(names)} files equal but for measured times")


if __name__ == "__main__":
    main()
