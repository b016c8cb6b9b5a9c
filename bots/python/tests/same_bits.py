"""Same bits as native Rust: reads JSON-lines SimulateRequests from the file
given as argv[1] and writes, for each, one JSON line to stdout: what
chapaev.simulate returned, or {"error": code} when it refused the request.

The e2e test tests/tests/bindings_python.rs compares every line with the
native SimulateRequest::run, bit for bit.

Each request without a film is also played through Simulator.play and
Simulator.play_many (its shot twice, around a refused one): play_many must
give the very bits of play, or the status of the code play raised; if not,
the line is {"error": "play-many-differs", ...}.
"""

import json
import sys

import chapaev

# The wire codes of play_many's status numbers.
STATUS = ["played", "bad-message", "not-finite", "zero-speed", "too-fast", "piece-off-board", "internal"]
VERDICTS = [
    {"verdict": "shoot-again"},
    {"verdict": "pass-turn"},
    {"verdict": "round-over", "result": "won", "side": "white"},
    {"verdict": "round-over", "result": "won", "side": "black"},
    {"verdict": "round-over", "result": "draw"},
]
END_REASONS = ["rest", "free", "until", "max-collisions", "max-events"]
NAN = float("nan")


def same(a, b) -> bool:
    """Equal as JSON text (repr keeps every bit of a float, and -0.0)."""
    return json.dumps(a, sort_keys=True) == json.dumps(b, sort_keys=True)


def unpack(a, k):
    """Shot `k` of a play_many answer as the dict play returns, or {"status": n}."""
    stride = chapaev.PLAY_MANY_STRIDE
    row = a[stride * k : stride * (k + 1)]
    if row[0] != 0.0:
        return {"status": row[0]}
    knocked = [int(x) for x in row[8:24] if x == x]
    board = []
    for i in range(16):
        x, y = row[24 + 2 * i], row[25 + 2 * i]
        if (x != x) != (y != y):
            return {"status": "half-a-position"}
        if x == x:
            board.append({"id": i, "pos": [x, y]})
    white = sum(1 for i in knocked if i < 8)
    if row[6] != white or row[7] != len(knocked) - white:
        return {"status": "bad-counts"}
    return {
        "played": [row[2], row[3]],
        "knocked_off": knocked,
        "board": board,
        "verdict": VERDICTS[int(row[1])],
        "duration": row[4],
        "end_reason": END_REASONS[int(row[5])],
    }


def check_play_many(request):
    """None when play_many agrees with play on `request`, else why not."""
    if not isinstance(request, dict):
        return None
    piece, velocity, noise = request.get("piece"), request.get("velocity"), request.get("noise")
    numbers = (
        isinstance(piece, int)
        and not isinstance(piece, bool)
        and isinstance(velocity, list)
        and len(velocity) == 2
        and all(isinstance(v, (int, float)) for v in velocity)
        and (noise is None or (isinstance(noise, dict) and all(isinstance(noise.get(k), (int, float)) for k in ("angle", "speed"))))
    )
    if request.get("film") or not numbers:
        return None
    if noise is not None and noise["angle"] != noise["angle"] and noise["speed"] != noise["speed"]:
        return None  # nan, nan is no draw to play_many, a refused one to play
    try:
        sim = chapaev.Simulator(request.get("config"), request.get("board"))
    except chapaev.SimulateError:
        return None  # the position itself is refused
    try:
        played, code = sim.play(piece, velocity, noise), None
    except chapaev.SimulateError as e:
        played, code = None, e.code
    shot = [piece, velocity[0], velocity[1], noise["angle"] if noise else NAN, noise["speed"] if noise else NAN]
    a = sim.play_many(shot + [99, 1.0, 0.0, NAN, NAN] + shot)
    stride = chapaev.PLAY_MANY_STRIDE
    if not isinstance(a, list) or len(a) != 3 * stride:
        return "wrong length"
    if a[stride] != 1.0 or any(x == x for x in a[stride + 1 : 2 * stride]):
        return "refused shot not status 1 and nan"
    for k in (0, 2):
        got = unpack(a, k)
        if code is not None:
            if got.get("status") not in range(len(STATUS)) or STATUS[int(got["status"])] != code:
                return f"status {got.get('status')} for {code}"
            if any(x == x for x in a[stride * k + 1 : stride * (k + 1)]):
                return "refused shot not nan"
        elif not same(got, played):
            return json.dumps(got)
    return None


def main() -> int:
    if len(sys.argv) != 2:
        print("usage: same_bits.py REQUESTS.jsonl", file=sys.stderr)
        return 2
    out = []
    with open(sys.argv[1], encoding="utf-8") as f:
        for line in f:
            if not line.strip():
                continue
            request = json.loads(line)
            try:
                result = chapaev.simulate(request)
            except chapaev.SimulateError as e:
                result = {"error": e.code}
            many = check_play_many(request)
            if many is not None:
                result = {"error": "play-many-differs", "play_many": many}
            out.append(json.dumps(result))
    sys.stdout.write("\n".join(out) + ("\n" if out else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
