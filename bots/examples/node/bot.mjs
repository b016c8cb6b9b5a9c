// A Chapaev bot in Node.js. It plays one whole match on a server over the
// protocol of docs/protocol.md and, on each turn, searches its shots with
// the `chapaev` package's Simulator: the server's physics, bit for bit.
//
//   node bot.mjs [--server http://127.0.0.1:8080] [--level easy]
//                [--rules standard] [--match ID] [--name NodeBot]
//                [--samples 4] [--seed 1] [--quiet]
//   node bot.mjs --stdio     (local games: bots match --bot "node bot.mjs --stdio")
//
// Without --match it creates a match against a built-in level; with it, it
// joins that match's empty seat. It prints what happens, and at the end
// one JSON line: {"match_id": ..., "side": ..., "result": {...}}.
import WebSocket from "ws";
import { Simulator, NoiseRng, protocolVersion } from "chapaev";

// ---- options ---------------------------------------------------------------

const args = process.argv.slice(2);
const opt = (name, dflt) => {
  const k = args.indexOf(`--${name}`);
  return k >= 0 ? args[k + 1] : dflt;
};
const server = opt("server", "http://127.0.0.1:8080").replace(/\/$/, "");
const level = opt("level", "easy");
const rules = opt("rules", "standard");
const joinId = opt("match", null);
const name = opt("name", "NodeBot");
const samples = Number(opt("samples", "4"));
const rng = new NoiseRng(BigInt(opt("seed", "1")));
const quiet = args.includes("--quiet");
const log = (...a) => quiet || console.error(...a);

// ---- the search ------------------------------------------------------------

const other = (side) => (side === "white" ? "black" : "white");

/** Candidate shots: each of my pieces at each enemy piece, straight and
 * cut (the aim moved sideways by a fraction of a diameter), at 3 speeds. */
function candidates(config, board, me) {
  const out = [];
  const diameter = 2 * config.piece_radius;
  const mine = board.filter((p) => (p.id < 8) === (me === "white"));
  const theirs = board.filter((p) => (p.id < 8) !== (me === "white"));
  for (const p of mine) {
    for (const t of theirs) {
      const dx = t.pos[0] - p.pos[0];
      const dy = t.pos[1] - p.pos[1];
      const len = Math.hypot(dx, dy);
      if (len === 0) continue;
      const across = [-dy / len, dx / len];
      for (const cut of [0, -0.3, 0.3]) {
        const ax = dx + across[0] * cut * diameter;
        const ay = dy + across[1] * cut * diameter;
        const alen = Math.hypot(ax, ay);
        // Just under the maximum at full power: a direction of length 1
        // times max_speed can round a hair above it, which is refused.
        for (const f of [0.55, 0.8, 0.999]) {
          const speed = config.max_speed * f;
          out.push({ piece: p.id, velocity: [(ax / alen) * speed, (ay / alen) * speed] });
        }
      }
    }
  }
  return out;
}

/** How good a simulated shot is for `me`. */
function score(sim, me) {
  const lost = (side) => sim.knocked_off.filter((id) => (id < 8) === (side === "white")).length;
  let s = lost(other(me)) - 1.5 * lost(me);
  const v = sim.verdict;
  if (v.verdict === "shoot-again") s += 0.5;
  if (v.verdict === "round-over") s += v.result === "won" && v.side === me ? 10 : -10;
  return s;
}

/** The candidate with the best mean score over `samples` noise draws of our
 * own (the match's noise model is public, its draws are not). */
function bestShot(config, board, me) {
  const sim = new Simulator(config, board);
  const draws = config.variants.noise ? Array.from({ length: samples }, () => rng.draw()) : [null];
  let best = null;
  let tried = 0;
  try {
    for (const c of candidates(config, board, me)) {
      let total = 0;
      try {
        for (const d of draws) {
          total += score(sim.play(c.piece, c.velocity, d), me);
          tried++;
        }
      } catch (e) {
        log(`skipping ${JSON.stringify(c)}: ${e.code}: ${e.message}`);
        continue; // a shot the server would refuse too
      }
      const mean = total / draws.length;
      if (!best || mean > best.mean) best = { ...c, mean };
    }
  } finally {
    sim.free();
  }
  if (!best) {
    // Nothing to aim at (cannot happen mid-round): any legal flick.
    const p = board.find((q) => (q.id < 8) === (me === "white"));
    best = { piece: p.id, velocity: [0, me === "white" ? 1 : -1], mean: 0 };
  }
  return { best, tried };
}

/** Black's pie decision: take White's side when White's first shot left
 * White ahead. */
function pieSwap(board) {
  const count = (side) => board.filter((p) => (p.id < 8) === (side === "white")).length;
  return count("white") > count("black");
}

// ---- the match -------------------------------------------------------------

async function post(path, body) {
  const r = await fetch(server + path, {
    method: "POST",
    headers: { "content-type": "application/json" },
    body: JSON.stringify(body),
  });
  const json = await r.json();
  if (!r.ok) throw new Error(`POST ${path}: ${r.status} ${JSON.stringify(json)}`);
  return json;
}

// Local games (`bots match --bot "node bot.mjs --stdio"`): one request
// per line on stdin ({"me": side, "view": the match view}), one decision
// per line on stdout, the same messages as on the socket; no server.
if (args.includes("--stdio")) {
  const { createInterface } = await import("node:readline");
  for await (const line of createInterface({ input: process.stdin })) {
    const { me, view: v } = JSON.parse(line);
    let answer;
    if (v.phase.phase === "pie-decision") {
      answer = { type: "pie-decision", swap: pieSwap(v.board) };
    } else {
      const { best } = bestShot(v.config, v.board, me);
      answer = { type: "shot", piece: best.piece, velocity: best.velocity };
    }
    console.log(JSON.stringify(answer));
  }
  process.exit(0);
}

const grant = joinId
  ? await post(`/api/matches/${joinId}/join`, { name })
  : await post("/api/matches", { name, opponent: "bot", bot_level: level, rules });
log(`match ${grant.match_id}, seat ${grant.seat}`);

// What we know of the match, kept from match-state and every update.
let view = null; // the last match-state's view, board and turn kept current
let seat = grant.seat;
let result = null;
let acted = null; // the position we last answered (never twice)

const mySide = () => ((seat === "first") !== view.swapped ? "white" : "black");

function act(ws) {
  if (!view || result) return;
  const me = mySide();
  const key = `${view.shots}:${view.phase.phase}:${view.turn}`;
  if (acted === key) return;
  if (view.phase.phase === "pie-decision" && me === "black") {
    acted = key;
    const swap = pieSwap(view.board);
    log(`pie rule: ${swap ? "swap" : "keep"}`);
    ws.send(JSON.stringify({ type: "pie-decision", swap }));
  } else if (view.phase.phase === "shooting" && view.turn === me) {
    acted = key;
    const start = process.hrtime.bigint();
    const { best, tried } = bestShot(view.config, view.board, me);
    const ms = Number(process.hrtime.bigint() - start) / 1e6;
    log(`${me} shoots ${best.piece} at [${best.velocity.map((x) => x.toFixed(3))}] ` +
      `(mean ${best.mean.toFixed(2)}; ${tried} simulations in ${ms.toFixed(0)} ms)`);
    ws.send(JSON.stringify({ type: "shot", piece: best.piece, velocity: best.velocity }));
  }
}

function onMessage(ws, msg) {
  switch (msg.type) {
    case "match-state":
      view = msg.view;
      seat = msg.you ?? seat;
      acted = null;
      if (view.phase.phase === "over") result = view.phase.result;
      break;
    case "shot-played": {
      const o = msg.outcome;
      // The match as it stands after the shot: at a round end, the new
      // round's board, and in `turn` the side that opens it.
      view = msg.view;
      log(`shot ${o.number} by ${o.shooter}: knocked off [${o.knocked_off}]`);
      break;
    }
    case "pie-decided":
      view.swapped = msg.swap;
      view.phase = { phase: "shooting" };
      break;
    case "turn-passed":
      view.turn = other(msg.side);
      break;
    case "match-over":
      result = msg.result;
      break;
    case "error":
      // A refused move: read the match afresh (reconnecting sends match-state).
      log(`refused: ${msg.code}: ${msg.message}`);
      ws.close();
      return;
    default:
      break; // clock, chat, player-joined/left/back, turn-timed-out, welcome...
  }
  if (result) {
    ws.close();
    return;
  }
  act(ws);
}

// One connection at a time; reconnect (with the same token) until the end.
const wsUrl = server.replace(/^http/, "ws") + grant.ws;
for (let attempt = 0; !result; attempt++) {
  if (attempt > 0) await new Promise((r) => setTimeout(r, Math.min(2000, 100 * attempt)));
  if (attempt > 50) throw new Error("could not stay connected");
  await new Promise((resolve) => {
    const ws = new WebSocket(wsUrl);
    // The first message: hello with the seat token (never in the URL).
    ws.on("open", () =>
      ws.send(JSON.stringify({ type: "hello", protocol: protocolVersion(), name: "node-example", token: grant.token })),
    );
    ws.on("message", (data) => {
      try {
        onMessage(ws, JSON.parse(data.toString()));
      } catch (e) {
        console.error("bot error:", e);
        process.exit(1);
      }
    });
    ws.on("close", resolve);
    ws.on("error", (e) => log(`socket: ${e.message}`));
  });
}

log(`match over: ${JSON.stringify(result)}`);
console.log(JSON.stringify({ match_id: grant.match_id, side: mySide(), result }));
