"""Reading the two sides' results, for compare.sh and public.sh.

- `pinocchio(path)`: build/timing's records (see timing.cpp's header): the medians by
  (model, algorithm), the states' fingerprints by model, the frame counts by model and the
  header line.
- `states(log_path, script)`: the fingerprints the Rust benchmarks print
  (`states <name> <count> <hex>`); a name printed twice with different states stops the
  script.
- `criterion_medians(directory, baseline)`: criterion's median point estimate (ns) by
  benchmark id, for every benchmark saved under `baseline` below `directory`.
"""

import json
import os
import re
import sys


def pinocchio(path):
    times, fingerprints, frames, header = {}, {}, {}, ""
    for line in open(path):
        f = line.rstrip("\n").split("\t")
        if line.startswith("#"):
            header = line[1:].strip()
        elif f[0] == "states":
            fingerprints[f[1]] = f[3]
        elif f[0] == "frames":
            frames[f[1]] = int(f[2])
        elif f[0] == "time":
            times[(f[1], f[2])] = float(f[3])
    return times, fingerprints, frames, header


def states(log_path, script):
    fingerprints = {}
    log = open(log_path).read()
    for m in re.finditer(r"^states (\w+) (\d+) ([0-9a-f]{16})", log, re.M):
        if fingerprints.setdefault(m.group(1), m.group(3)) != m.group(3):
            print(f"{script}: {m.group(1)}'s states changed between runs", file=sys.stderr)
            sys.exit(1)
    return fingerprints


def criterion_medians(directory, baseline):
    medians = {}
    for path, _, files in os.walk(directory):
        if os.path.basename(path) == baseline and "estimates.json" in files:
            bench = json.load(open(os.path.join(path, "benchmark.json")))
            estimates = json.load(open(os.path.join(path, "estimates.json")))
            medians[bench["full_id"]] = estimates["median"]["point_estimate"]
    return medians
