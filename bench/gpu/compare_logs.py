#!/usr/bin/env python3
"""Compares two benchmark logs with their timings masked (bench/gpu/check_bundle.sh).

    compare_logs.py A.log B.log     # exit 0 when they agree, else prints a diff

Masked: table columns whose header names a time, a rate, a ratio of times or
a load (ms, s, frames/s, x ratios of times, load, CPU, share), numbers after
"load", durations ("0.3 s", "12 ms"), /proc/loadavg lines,
bench_environment's "cpu ms" column, temporary paths and the "$ command" line
run_benches.sh writes, bench_decimate's CPU seconds and page faults. What
is left (triangle counts, draw calls, image errors, memory, fragment
counts, decimation output hashes and errors) must be identical.
"""
import difflib
import re
import sys

TIME_HEADER = re.compile(
    r"\bms\b|\bs\b|s/frame|frames/s|load|time / full|phong / gouraud|brute / clustered|stereo / mono|"
    r"after / before|time / meshopt|share|cpu|wall",
    re.I,
)
LOADAVG = re.compile(r"[0-9.]+ [0-9.]+ [0-9.]+ \d+/\d+ \d+")


def cells(line):
    return [c.strip() for c in line.strip().strip("|").split("|")]


def mask(lines):
    out, header = [], None
    env_table = False
    for line in lines:
        line = line.rstrip("\n")
        if line.startswith("$ ") or "XDG_RUNTIME_DIR" in line:
            continue
        line = re.sub(r"/tmp/[^ ]*", "<path>", line)
        line = LOADAVG.sub("<loadavg>", line)
        if line.lstrip().startswith("|"):
            c = cells(line)
            if header is None:
                header = c
                out.append(line)
                continue
            if all(re.fullmatch(r":?-+:?", x) for x in c if x):
                out.append(line)
                continue
            masked = [("~" if i < len(header) and TIME_HEADER.search(header[i]) else x) for i, x in enumerate(c)]
            out.append("| " + " | ".join(masked) + " |")
            continue
        header = None
        if line.startswith("sun ") and "cpu ms" in line:
            env_table = True
        elif env_table and re.match(r"^\d+ deg\s", line):
            f = line.split()
            f[3] = "~"
            line = " ".join(f)
        else:
            env_table = False
        line = re.sub(r"(load[^:]*?)[:\s][^;,)]*", r"\1 <load>", line, flags=re.I)
        line = re.sub(r"\b\d+(\.\d+)? ?(ms|s)\b", "<t>", line)
        line = re.sub(r"ratio [0-9.]+x", "ratio <x>", line)
        line = re.sub(r"CPU [0-9.]+ s", "CPU <t>", line)
        # bench_decimate's per-target lines on stderr: CPU seconds and page faults
        # (its output hashes, on the lines before them, must agree).
        line = re.sub(r"(: CPU s|: minor page faults) .*", r"\1 <masked>", line)
        out.append(line)
    return out


def main():
    a, b = (mask(open(p, errors="replace").readlines()) for p in sys.argv[1:3])
    if a == b:
        return 0
    sys.stdout.writelines(l + "\n" for l in difflib.unified_diff(a, b, sys.argv[1], sys.argv[2], lineterm="", n=1))
    return 1


if __name__ == "__main__":
    sys.exit(main())
