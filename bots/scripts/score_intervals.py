#!/usr/bin/env python3
"""Each pairing's score with its 95 % Wilson interval, from the JSON that
`bots tournament --json FILE` writes (a draw counts half a win)."""
import json
import math
import sys


def wilson(points, n, z=1.96):
    p = points / n
    d = 1 + z * z / n
    centre = (p + z * z / (2 * n)) / d
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / d
    return max(0.0, centre - half), min(1.0, centre + half)


for pairing in json.load(open(sys.argv[1]))["pairings"]:
    w = pairing["wdl"]
    n = w["wins"] + w["draws"] + w["losses"]
    lo, hi = wilson(w["wins"] + 0.5 * w["draws"], n)
    print(f"{pairing['a']} v {pairing['b']}: {100 * pairing['score']:.1f} % "
          f"[{100 * lo:.1f}, {100 * hi:.1f}] over {n} games")
