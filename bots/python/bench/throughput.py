"""Shots per CPU second through the Python binding: the N requests of
chapaev.random_requests(S, N), each played through Simulator.play (one
Simulator per request, as a bot builds one per position). Prints one JSON
line, the shape of the native twin `cargo run --release -p bots --
throughput --count N --seed S`:

  {"binding": "python", "shots": N, "cpu_seconds": ..., "shots_per_cpu_second": ...}

Only the plays are timed (time.process_time), not making the requests.
"""

import argparse
import json
import time

import chapaev


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--count", type=int, default=10_000)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    requests = chapaev.random_requests(args.seed, args.count)
    start = time.process_time()
    for r in requests:
        sim = chapaev.Simulator(r["config"], r["board"])
        sim.play(r["piece"], r["velocity"], r.get("noise"))
    cpu = time.process_time() - start
    print(json.dumps({
        "binding": "python",
        "shots": args.count,
        "cpu_seconds": round(cpu, 6),
        "shots_per_cpu_second": round(args.count / cpu, 1) if cpu > 0 else None,
    }))


if __name__ == "__main__":
    main()
