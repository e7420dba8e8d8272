#!/usr/bin/python3
"""Largest relative difference between the elastic frequencies of `geardyn modal --json`
and a `freqs` line of floor_modal.py (or between two such lines). Frequencies below
1e-3 of the highest one listed are rigid-body zeros (the floor gives them as a
defective pair of tiny values) and are left out; the rest are compared in order.

usage: compare_freqs.py A B   (each: a geardyn JSON file or a floor_modal.py output)
"""
import json
import sys


def freqs(path):
    text = open(path).read()
    if text.lstrip().startswith("{"):
        f = [m["frequency_hz"] for m in json.loads(text)["modes"]]
    else:
        f = [float(x) for line in text.splitlines() if line.startswith("freqs ")
             for x in line.split()[1:]]
    top = max(f)
    return sorted(x for x in f if x > 1e-3 * top)


a, b = freqs(sys.argv[1]), freqs(sys.argv[2])
k = min(len(a), len(b))
print(f"{max(abs(x - y) / y for x, y in zip(a[:k], b[:k])):.1e}")
