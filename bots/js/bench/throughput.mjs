// Simulated shots per CPU-second in Node: the JavaScript twin of
// `cargo run --release -p bots -- throughput --count N --seed S`, over the
// very same positions (one SplitMix64::new(S), N successive random_request
// calls, here `randomRequests(S, N)`).
//
//   node bots/js/bench/throughput.mjs --count 20000 --seed 1
//
// Prints one JSON line per entry point:
//   api "Simulator.play": each position converted and checked once (new
//     Simulator, untimed, as the native twin validates untimed), the shots
//     timed: the figure to set next to native;
//   api "Simulator.playMany": the same shots on the same prepared
//     Simulators, each through playMany (its one shot as 5 numbers in, 56
//     out), the compact answer instead of objects;
//   api "simulate": the whole request converted, checked and played per call.
// CPU time is process.cpuUsage() (user + system), as the native twin uses
// the process's CPU clock.
import { Simulator, simulate, randomRequests } from "../pkg/node/index.mjs";

const arg = (name, dflt) => {
  const k = process.argv.indexOf(`--${name}`);
  return k >= 0 ? process.argv[k + 1] : dflt;
};
const count = Number(arg("count", "20000"));
const seed = BigInt(arg("seed", "1"));
if (!Number.isSafeInteger(count) || count <= 0) {
  console.error("--count must be a positive integer");
  process.exit(2);
}

const cpu = (since) => {
  const d = process.cpuUsage(since);
  return (d.user + d.system) / 1e6;
};
const report = (api, seconds, knocked) =>
  console.log(JSON.stringify({
    binding: "js",
    api,
    shots: count,
    knocked_off: knocked,
    cpu_seconds: seconds,
    shots_per_cpu_second: count / seconds,
  }));

const requests = randomRequests(seed, count);
// A request's shot as playMany takes it (NaN, NaN: no noise draw).
const shotOf = (r) =>
  new Float64Array([r.piece, r.velocity[0], r.velocity[1], r.noise?.angle ?? NaN, r.noise?.speed ?? NaN]);

// Warm-up, untimed: V8 compiles wasm in tiers (a quick baseline first, the
// optimised code in background threads for hot functions), and that
// compilation counts as process CPU time. 3,000 shots through each entry
// point get the hot code optimised before timing.
for (let k = 0; k < 3000; k++) {
  const r = requests[k % count];
  simulate(r);
  const s = new Simulator(r.config, r.board);
  s.play(r.piece, r.velocity, r.noise);
  s.playMany(shotOf(r));
  s.free();
}

{
  const prepared = requests.map((r) => [new Simulator(r.config, r.board), r]);
  let knocked = 0;
  const t = process.cpuUsage();
  for (const [sim, r] of prepared) knocked += sim.play(r.piece, r.velocity, r.noise).knocked_off.length;
  report("Simulator.play", cpu(t), knocked);
  for (const [sim] of prepared) sim.free();
}
{
  const prepared = requests.map((r) => [new Simulator(r.config, r.board), shotOf(r)]);
  let knocked = 0;
  const t = process.cpuUsage();
  for (const [sim, shot] of prepared) {
    const a = sim.playMany(shot);
    knocked += a[6] + a[7];
  }
  report("Simulator.playMany", cpu(t), knocked);
  for (const [sim] of prepared) sim.free();
}
{
  let knocked = 0;
  const t = process.cpuUsage();
  for (const r of requests) knocked += simulate(r).knocked_off.length;
  report("simulate", cpu(t), knocked);
}
