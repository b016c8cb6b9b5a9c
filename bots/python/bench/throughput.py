"""Shots per CPU second through the Python binding: the N requests of
chapaev.random_requests(S, N), each played through Simulator.play (one
Simulator per request, as a bot builds one per position). Prints one JSON
line per entry point (api "Simulator.play", then "Simulator.play_many": the
same shots, each through the batch method, the Simulator built in the timed
loop and then beforehand), the shape of the native twin `cargo run --release -p bots --
throughput --count N --seed S`:

  {"binding": "python", "api": ..., "shots": N, "cpu_seconds": ..., "shots_per_cpu_second": ...}

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
    report("Simulator.play", args.count, cpu)

    # The batch path: the same shots, each position's through play_many (5
    # floats in, PLAY_MANY_STRIDE out; nan, nan for no noise draw).
    nan = float("nan")
    shots = [
        [r["piece"], r["velocity"][0], r["velocity"][1],
         (r.get("noise") or {}).get("angle", nan), (r.get("noise") or {}).get("speed", nan)]
        for r in requests
    ]
    start = time.process_time()
    for r, shot in zip(requests, shots):
        sim = chapaev.Simulator(r["config"], r["board"])
        sim.play_many(shot)
    cpu = time.process_time() - start
    report("Simulator.play_many", args.count, cpu)

    # The same, the Simulators built beforehand (untimed, as the JS twin and
    # the native one prepare positions): the shots alone.
    prepared = [(chapaev.Simulator(r["config"], r["board"]), shot) for r, shot in zip(requests, shots)]
    start = time.process_time()
    for sim, shot in prepared:
        sim.play_many(shot)
    cpu = time.process_time() - start
    report("Simulator.play_many (Simulators built untimed)", args.count, cpu)


def report(api: str, shots: int, cpu: float) -> None:
    print(json.dumps({
        "binding": "python",
        "api": api,
        "shots": shots,
        "cpu_seconds": round(cpu, 6),
        "shots_per_cpu_second": round(shots / cpu, 1) if cpu > 0 else None,
    }))


if __name__ == "__main__":
    main()
