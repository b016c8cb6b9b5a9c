"""A Chapaev bot in Python: plays one whole match on a server.

It creates a match against a built-in level (or joins one by id), follows
the protocol of docs/protocol.md over a WebSocket, and on each of its turns
searches: every own piece aimed at every enemy piece (straight, and turned
a little to either side) at a few speeds, each candidate played on
chapaev.Simulator (the server's exact physics) under a few noise draws of
its own, and the best average score is sent.

    python bots/examples/python/bot.py --server http://127.0.0.1:8080
    python bots/examples/python/bot.py --server http://127.0.0.1:8080 --join MATCH_ID
    bots match --bot "python bots/examples/python/bot.py --stdio" --bot greedy --seed 1

Install first (from the repository root):
    pip install -r bots/examples/python/requirements.txt
"""

import argparse
import json
import math
import sys
import time
import urllib.error
import urllib.request
from typing import Any, Dict, List, Optional, Tuple

import chapaev
from websockets.sync.client import connect

Message = Dict[str, Any]


def log(*args: Any) -> None:
    print("bot:", *args, file=sys.stderr, flush=True)


# ----- HTTP -----


def post(server: str, path: str, body: Message) -> Message:
    """POST `body` as JSON; the JSON answer (an error answer raises, with its code)."""
    req = urllib.request.Request(
        server.rstrip("/") + path,
        data=json.dumps(body).encode(),
        headers={"Content-Type": "application/json"},
        method="POST",
    )
    try:
        with urllib.request.urlopen(req, timeout=10) as r:
            return json.load(r)
    except urllib.error.HTTPError as e:
        raise SystemExit(f"POST {path}: {e.code} {e.read().decode(errors='replace')}")


# ----- the search -----

SPEEDS = (0.45, 0.7, 1.0)  # fractions of config["max_speed"]
TURNS = (0.0, -0.03, 0.03)  # radians off the straight line to the target


def score(sim: Message, me: str) -> float:
    """How good one simulated shot is for side `me`."""
    enemy = sum(1 for p in sim["knocked_off"] if side_of(p) != me)
    own = len(sim["knocked_off"]) - enemy
    verdict = sim["verdict"]
    s = enemy - 1.5 * own
    if verdict["verdict"] == "shoot-again":
        s += 0.5
    elif verdict["verdict"] == "round-over":
        if verdict.get("result") == "won":
            s += 20.0 if verdict["side"] == me else -20.0
    return s


def side_of(piece: int) -> str:
    return "white" if piece < 8 else "black"


def candidates(config: Message, board: List[Message], me: str) -> List[Tuple[int, List[float]]]:
    """Every own piece at every enemy piece, straight and turned, at each speed."""
    out = []
    mine = [p for p in board if side_of(p["id"]) == me]
    enemies = [p for p in board if side_of(p["id"]) != me]
    for m in mine:
        for e in enemies:
            dx, dy = e["pos"][0] - m["pos"][0], e["pos"][1] - m["pos"][1]
            d = math.hypot(dx, dy)
            if d == 0.0:
                continue
            for turn in TURNS:
                c, s = math.cos(turn), math.sin(turn)
                ux, uy = (dx * c - dy * s) / d, (dx * s + dy * c) / d
                for f in SPEEDS:
                    v = config["max_speed"] * f
                    # Rounding may put |velocity| a hair above the maximum.
                    out.append((m["id"], [ux * v * (1 - 1e-12), uy * v * (1 - 1e-12)]))
    return out


class Brain:
    def __init__(self, seed: int, draws: int, budget_s: float) -> None:
        self.rng = chapaev.NoiseRng(seed)
        self.draws = draws
        self.budget_s = budget_s

    def shot(self, config: Message, board: List[Message], me: str) -> Tuple[int, List[float]]:
        start = time.monotonic()
        sim = chapaev.Simulator(config, board)
        noisy = config["variants"].get("noise") is not None
        # The same draws for every candidate (common random numbers).
        draws: List[Optional[Message]] = (
            [self.rng.sample() for _ in range(self.draws)] if noisy else [None]
        )
        best, best_score, tried = None, -math.inf, 0
        for piece, velocity in candidates(config, board, me):
            if time.monotonic() - start > self.budget_s:
                break
            total = 0.0
            for draw in draws:
                total += score(sim.play(piece, velocity, draw), me)
            tried += 1
            if total / len(draws) > best_score:
                best, best_score = (piece, velocity), total / len(draws)
        if best is None:  # no enemy in reach of anything: any legal flick
            piece = chapaev.legal_pieces(board, me)[0]
            best = (piece, [0.0, config["max_speed"] * (0.5 if me == "white" else -0.5)])
        log(f"{me}: {tried} candidates x {len(draws)} draws in "
            f"{time.monotonic() - start:.3f} s, best {best_score:.2f}: piece {best[0]}")
        return best

    def pie(self, board: List[Message], then: str) -> bool:
        """Black's pie decision after White's first shot: take White's side
        when White came out ahead."""
        white = sum(1 for p in board if p["id"] < 8)
        black = len(board) - white
        return white > black or (white == black and then == "white")


# ----- the match -----


class Match:
    """What the bot knows of the match, kept from the server's messages."""

    def __init__(self) -> None:
        self.config: Message = {}
        self.board: List[Message] = []
        self.seat: Optional[str] = None
        self.swapped = False
        self.phase = "shooting"
        self.turn: Optional[str] = None
        self.then: Optional[str] = None
        self.result: Optional[Message] = None
        self.shots = 0

    @property
    def me(self) -> str:
        first = "white" if not self.swapped else "black"
        return first if self.seat == "first" else ("black" if first == "white" else "white")

    def state(self, msg: Message) -> None:
        view = msg["view"]
        self.config, self.board = view["config"], view["board"]
        self.seat, self.swapped = msg["you"], view["swapped"]
        self.phase, self.turn, self.shots = view["phase"]["phase"], view["turn"], view["shots"]
        if self.phase == "over":
            self.result = view["phase"]["result"]

    def shot_played(self, msg: Message) -> None:
        # The server sends the match as it stands after the shot: at a round
        # end, the new round's board, and in `turn` the side that opens it.
        view = msg["view"]
        self.board, self.shots, self.turn = view["board"], view["shots"], view["turn"]
        self.phase = view["phase"]["phase"]
        if self.phase == "pie-decision":
            self.then = view["turn"]
        elif self.phase == "over":
            self.result = view["phase"]["result"]


def play(server: str, grant: Message, brain: Brain) -> Message:
    """Plays the seat of `grant` to the end of the match; the result."""
    ws_url = server.replace("http://", "ws://").replace("https://", "wss://").rstrip("/") + grant["ws"]
    m = Match()
    while m.result is None:
        with connect(ws_url, max_size=None, open_timeout=10) as ws:
            # The seat token goes in the hello, never in the URL.
            ws.send(json.dumps({"type": "hello", "protocol": chapaev.PROTOCOL_VERSION,
                                "name": "python-example", "token": grant["token"]}))
            waiting = False  # a move sent, its answer not seen yet
            resync = False
            for raw in ws:
                msg = json.loads(raw)
                kind = msg["type"]
                if kind == "match-state":
                    m.state(msg)
                    waiting = False
                elif kind == "shot-played":
                    m.shot_played(msg)
                    waiting = False
                elif kind == "pie-decided":
                    if msg["swap"]:
                        m.swapped = not m.swapped
                    m.phase, m.turn = "shooting", m.then
                    waiting = False
                elif kind == "turn-passed":
                    m.turn = "black" if msg["side"] == "white" else "white"
                    waiting = False
                elif kind == "match-over":
                    m.result = msg["result"]
                    break
                elif kind == "error":
                    log("refused:", msg["code"], msg.get("message"))
                    if msg["code"] in ("bad-token", "no-such-match"):
                        raise SystemExit(f"cannot play: {msg['code']}")
                    resync = True  # out of step: a fresh match-state
                    break
                if m.result is not None:
                    break
                if waiting:
                    continue
                if m.phase == "shooting" and m.turn == m.me:
                    piece, velocity = brain.shot(m.config, m.board, m.me)
                    ws.send(json.dumps({"type": "shot", "piece": piece, "velocity": velocity}))
                    waiting = True
                elif m.phase == "pie-decision" and m.me == "black":
                    swap = brain.pie(m.board, m.then or "black")
                    log("pie decision: swap" if swap else "pie decision: keep")
                    ws.send(json.dumps({"type": "pie-decision", "swap": swap}))
                    waiting = True
            else:
                if not resync:
                    log("the connection closed; reconnecting")
            time.sleep(0.1 if resync else 0.5)
    return m.result


def stdio(brain: Brain) -> int:
    """Local games (`bots match --bot "python bot.py --stdio"`): one request
    per line on stdin ({"me": side, "view": the match view}), one decision
    per line on stdout, the same messages as on the socket; no server."""
    for line in sys.stdin:
        request = json.loads(line)
        me, view = request["me"], request["view"]
        if view["phase"]["phase"] == "pie-decision":
            answer: Message = {"type": "pie-decision", "swap": brain.pie(view["board"], view["turn"])}
        else:
            piece, velocity = brain.shot(view["config"], view["board"], me)
            answer = {"type": "shot", "piece": piece, "velocity": velocity}
        print(json.dumps(answer), flush=True)
    return 0


def main() -> int:
    ap = argparse.ArgumentParser(description="A Chapaev bot in Python: plays one whole match.")
    ap.add_argument("--server", default="http://127.0.0.1:8080", help="the server's base URL")
    ap.add_argument("--join", metavar="MATCH_ID", help="join this match instead of creating one")
    ap.add_argument("--level", default="easy", help="the built-in level to play (easy, medium, hard)")
    ap.add_argument("--rules", default="standard", help="casual or standard")
    ap.add_argument("--turn-seconds", type=int, default=None)
    ap.add_argument("--seed", type=int, default=1, help="the seed of the bot's own noise draws")
    ap.add_argument("--match-seed", type=int, default=None,
                    help="a public seed for the created match's noise (as 'bots match --seed')")
    ap.add_argument("--draws", type=int, default=4, help="noise draws per candidate")
    ap.add_argument("--budget", type=float, default=2.0, help="seconds of search per shot at most")
    ap.add_argument("--stdio", action="store_true",
                    help="answer requests on stdin instead of playing on a server (bots match)")
    args = ap.parse_args()
    if args.stdio:
        return stdio(Brain(args.seed, args.draws, args.budget))

    if args.join:
        grant = post(args.server, f"/api/matches/{args.join}/join", {"name": "python-example"})
    else:
        body: Message = {"name": "python-example", "opponent": "bot", "bot_level": args.level, "rules": args.rules}
        if args.turn_seconds:
            body["turn_seconds"] = args.turn_seconds
        if args.match_seed is not None:
            body["seed"] = args.match_seed
        grant = post(args.server, "/api/matches", body)
    # The first line on stdout: the match id (for scripts and tests).
    print(json.dumps({"match_id": grant["match_id"], "seat": grant["seat"]}), flush=True)
    result = play(args.server, grant, Brain(args.seed, args.draws, args.budget))
    print(json.dumps({"match_id": grant["match_id"], "result": result}), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
