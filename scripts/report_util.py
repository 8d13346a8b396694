"""What the report scripts (accuracy_report.py, modes_report.py) share: running a command,
formatting numbers, describing the machine, and replacing the generated blocks of a document.
Python 3 standard library only."""

import csv
import datetime
import math
import os
import platform
import re
import subprocess
import sys
import time


def run(cmd, **kw):
    """Runs `cmd`; returns (CompletedProcess, seconds). Raises with the output's tail if it fails."""
    t0 = time.time()
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)
    if proc.returncode != 0:
        raise RuntimeError(f"command failed ({proc.returncode}): {' '.join(cmd)}\n{proc.stdout[-1500:]}{proc.stderr[-1500:]}")
    return proc, time.time() - t0


def num(x, digits=3):
    if x is None:
        return "n/a"
    if isinstance(x, float) and math.isinf(x):
        return "inf"
    return f"{x:.{digits}g}"


def machine():
    """The machine a figure was measured on: CPU model, cores, kernel, date and load."""
    cpu = "?"
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    u = platform.uname()
    return {"uname": f"{u.system} {u.release} {u.machine}", "nproc": os.cpu_count(), "cpu": cpu,
            "date": datetime.datetime.now().isoformat(timespec="seconds"),
            "load": " ".join(f"{x:.2f}" for x in os.getloadavg()), "kernel": platform.release()}


def scene_names(text, known):
    """The comma-separated scene names of text; exits naming those not in known."""
    names = [s for s in text.split(",") if s]
    unknown = [n for n in names if n not in known]
    if unknown:
        sys.exit(f"unknown scenes {unknown}; known: {', '.join(known)}")
    return names


def measure_scenes(names, spec_for, measure, log):
    """The rows measure(spec) gives for each scene named, the scenes whose file is missing
    skipped (and logged); exits when no scene gave any."""
    rows = []
    for name in names:
        spec = spec_for(name)
        if not os.path.exists(spec.path):
            log(f"{name}: {spec.path} missing, skipped")
            continue
        rows += measure(spec)
    if not rows:
        sys.exit("nothing measured")
    return rows


def write_rows_csv(path, rows):
    """Writes rows (dicts with the same keys, the first row's order) to the CSV file path,
    making its folder."""
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


def splice(doc_path, parts, log):
    """Replaces each <!-- BEGIN GENERATED key --> ... <!-- END GENERATED key --> block of the
    document with parts[key]; the prose around them is kept. `log` reports what is missing."""
    if not os.path.exists(doc_path):
        log(f"{doc_path} is missing: not written")
        return
    with open(doc_path, encoding="utf-8") as f:
        text = f.read()
    for key, body in parts.items():
        pattern = re.compile(rf"(<!-- BEGIN GENERATED {re.escape(key)} -->\n).*?(<!-- END GENERATED {re.escape(key)} -->)", re.S)
        text, n = pattern.subn(lambda m: m.group(1) + body + "\n" + m.group(2), text)
        if n == 0:
            log(f"{doc_path} has no GENERATED {key} block: not written there")
    with open(doc_path, "w", encoding="utf-8") as f:
        f.write(text)
