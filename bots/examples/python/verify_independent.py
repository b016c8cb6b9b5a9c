#!/usr/bin/env python3
"""Checks a finished Chapaev match's noise with nothing but the Python
standard library: no `chapaev` package, no Rust, no engine.

    python3 verify_independent.py RECORD.json...
    curl -s http://127.0.0.1:8080/api/matches/ID/record | python3 verify_independent.py -

For each record (format 4, as GET /api/matches/ID/record serves it once the
match is over) it checks that

1. the revealed secret hashes (SHA-256 of its 32 bytes) to the commitment
   the server published before the first shot, and
2. every shot's `played` velocity is, bit for bit, its `aimed` velocity
   under the draw the secret gives that shot: ChaCha20 keyed by the secret,
   the shot's number as the 64-bit nonce, the first 16 keystream bytes as
   two little-endian u64s, Box-Muller with the project's own polynomial ln
   and sin/cos (docs/protocol.md, "Provably fair noise").

Python's floats are IEEE doubles and + - * / and sqrt are correctly rounded,
so this reproduces the server's arithmetic exactly. It does not replay the
physics (what each shot knocked off): `bots verify` and `verify()` in the
JavaScript and Python packages do that too. Prints one JSON line per record,
{"record": ..., "verified": true, "shots": N} or {"verified": false,
"reason": ...}, and exits 1 if any record fails.
"""

import hashlib
import json
import math
import struct
import sys

MASK32 = 0xFFFFFFFF


def chacha20_block(key: bytes, counter: int, nonce: int) -> bytes:
    """One 64-byte ChaCha20 block (20 rounds, 64-bit counter and nonce)."""

    def rotl(v, n):
        return ((v << n) & MASK32) | (v >> (32 - n))

    def quarter(x, a, b, c, d):
        x[a] = (x[a] + x[b]) & MASK32
        x[d] = rotl(x[d] ^ x[a], 16)
        x[c] = (x[c] + x[d]) & MASK32
        x[b] = rotl(x[b] ^ x[c], 12)
        x[a] = (x[a] + x[b]) & MASK32
        x[d] = rotl(x[d] ^ x[a], 8)
        x[c] = (x[c] + x[d]) & MASK32
        x[b] = rotl(x[b] ^ x[c], 7)

    state = [0x61707865, 0x3320646E, 0x79622D32, 0x6B206574]
    state += list(struct.unpack("<8I", key))
    state += [counter & MASK32, counter >> 32, nonce & MASK32, nonce >> 32]
    x = state[:]
    for _ in range(10):
        quarter(x, 0, 4, 8, 12)
        quarter(x, 1, 5, 9, 13)
        quarter(x, 2, 6, 10, 14)
        quarter(x, 3, 7, 11, 15)
        quarter(x, 0, 5, 10, 15)
        quarter(x, 1, 6, 11, 12)
        quarter(x, 2, 7, 8, 13)
        quarter(x, 3, 4, 9, 14)
    return struct.pack("<16I", *((x[i] + state[i]) & MASK32 for i in range(16)))


def f64(bits: int) -> float:
    return struct.unpack("<d", struct.pack("<Q", bits))[0]


def bits(x: float) -> int:
    return struct.unpack("<Q", struct.pack("<d", x))[0]


LN_2 = 0.6931471805599453
SQRT_2 = 1.4142135623730951
FRAC_PI_2 = 1.5707963267948966
TAU = 6.283185307179586
PIO2_HI = 1.5707963267341256
PIO2_LO = 6.077100506506192e-11


def ln(x: float) -> float:
    """The game's ln: 2 atanh((m-1)/(m+1)) to 14 terms."""
    e = 0
    if x < 2.2250738585072014e-308:
        x *= float(1 << 54)
        e -= 54
    b = bits(x)
    e += ((b >> 52) & 0x7FF) - 1023
    m = f64((b & 0x000FFFFFFFFFFFFF) | 0x3FF0000000000000)
    if m > SQRT_2:
        m /= 2.0
        e += 1
    z = (m - 1.0) / (m + 1.0)
    z2 = z * z
    total = 0.0
    for k in range(13, -1, -1):
        total = total * z2 + 1.0 / float(2 * k + 1)
    return float(e) * LN_2 + 2.0 * z * total


def round_half_away(v: float) -> float:
    t = float(math.trunc(v))
    if abs(v - t) >= 0.5:
        t += math.copysign(1.0, v)
    return t


def sin_cos(x: float):
    """The game's sin and cos: quarter turns, then Taylor to degree 19."""
    k = round_half_away(x / FRAC_PI_2)
    r = (x - k * PIO2_HI) - k * PIO2_LO
    r2 = r * r
    s = c = 1.0
    for n in range(9, 0, -1):
        n = float(n)
        s = 1.0 - r2 / ((2.0 * n) * (2.0 * n + 1.0)) * s
        c = 1.0 - r2 / ((2.0 * n - 1.0) * (2.0 * n)) * c
    s = r * s
    return [(s, c), (c, -s), (-s, -c), (-c, s)][int(k) % 4]


def draw(secret: bytes, shot: int):
    """Shot `shot`'s two standard normal numbers (angle, speed)."""
    a, b = struct.unpack("<2Q", chacha20_block(secret, 0, shot)[:16])
    u1 = 1.0 - float(a >> 11) * (1.0 / float(1 << 53))
    u2 = float(b >> 11) * (1.0 / float(1 << 53))
    r = math.sqrt(-2.0 * ln(u1))
    s, c = sin_cos(TAU * u2)
    return r * c, r * s


def played(aimed, noise, max_speed, angle, speed_draw):
    """`aimed` turned by angle_sigma * angle, its speed scaled and clamped."""
    x, y = aimed
    speed = math.sqrt(x * x + y * y)
    if speed == 0.0:
        return [x, y]
    s, c = sin_cos(noise["angle_sigma"] * angle)
    tx, ty = x * c - y * s, x * s + y * c
    new = min(max(speed * (1.0 + noise["speed_sigma"] * speed_draw), 0.0), max_speed)
    k = new / speed
    return [tx * k, ty * k]


def check(record) -> dict:
    if record.get("version", 0) < 4 or "noise" not in record:
        return {"verified": False, "reason": "no commitment (a record before format 4)"}
    sealed = record["noise"]
    if sealed.get("scheme") != "chacha20":
        return {"verified": False, "reason": f"unknown scheme {sealed.get('scheme')!r}"}
    if "secret" not in sealed:
        return {"verified": False, "reason": "the secret is not revealed (the match is not over)"}
    secret = bytes.fromhex(sealed["secret"])
    if hashlib.sha256(secret).hexdigest() != sealed["commitment"]:
        return {"verified": False, "reason": "the secret does not hash to the commitment"}
    config = record.get("config", {})
    noise = config.get("variants", {}).get("noise")
    max_speed = config.get("max_speed", 2.0)
    shots = [m for m in record["moves"] if m["move"] == "shot"]
    for n, shot in enumerate(shots):
        if shot["number"] != n:
            return {"verified": False, "reason": f"shot {n} is numbered {shot['number']}"}
        want = list(shot["aimed"])
        if noise is not None:
            want = played(shot["aimed"], noise, max_speed, *draw(secret, n))
        if [bits(v) for v in want] != [bits(v) for v in shot["played"]]:
            return {"verified": False, "reason": f"shot {n} was not played with the secret's draw"}
    return {"verified": True, "shots": len(shots)}


def main() -> int:
    failed = 0
    for path in sys.argv[1:]:
        text = sys.stdin.read() if path == "-" else open(path, encoding="utf-8").read()
        verdict = {"record": path, **check(json.loads(text))}
        failed += not verdict["verified"]
        print(json.dumps(verdict))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
