// Runs a WASI command module (the engine's `sim` built for wasm32-wasip1)
// under Node, so CI can compare its output with the native build's.
// Usage: node .ci/wasi-run.mjs sim.wasm ARGS...   (the current folder is preopened)
import { readFile } from "node:fs/promises";
import { WASI } from "node:wasi";
import process from "node:process";

const [wasmPath, ...args] = process.argv.slice(2);
const wasi = new WASI({
  version: "preview1",
  args: ["sim", ...args],
  env: {},
  preopens: { ".": process.cwd() },
  returnOnExit: true,
});
const module = await WebAssembly.compile(await readFile(wasmPath));
const instance = await WebAssembly.instantiate(module, wasi.getImportObject());
process.exitCode = wasi.start(instance);
