// What --live costs a run: lock-step rounds/s at M = 4 without a live stream, and with one that
// a Foxglove client follows (subscribed to every channel), alternating in one sitting.
// Usage: node bench/live-cost.mjs SKYFUSE_BIN [PAIRS] [STEPS]
import { spawn } from "node:child_process";
import { mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import wsProtocol from "@foxglove/ws-protocol";
import WebSocket from "ws";

const { FoxgloveClient } = wsProtocol;
const [skyfuse, pairs = "5", steps = "3000"] = process.argv.slice(2);
if (!skyfuse) {
  console.error("usage: node bench/live-cost.mjs SKYFUSE_BIN [PAIRS] [STEPS]");
  process.exit(2);
}

function run(live) {
  const dir = mkdtempSync(join(tmpdir(), "skyfuse-live-cost-"));
  const args = ["run", "--stations", "4", "--steps", steps, "--domain", "214", "--out", dir];
  if (live) args.push("--live", "127.0.0.1:0");
  const child = spawn(skyfuse, args, { stdio: ["ignore", "pipe", "ignore"] });
  let output = "";
  let client = null;
  let messages = 0;
  child.stdout.on("data", (chunk) => {
    output += chunk;
    const m = /live: ws:\/\/127\.0\.0\.1:(\d+)/.exec(output);
    if (m && !client) {
      client = new FoxgloveClient({ ws: new WebSocket(`ws://127.0.0.1:${m[1]}`, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
      client.on("advertise", (channels) => channels.forEach((c) => client.subscribe(c.id)));
      client.on("message", () => { messages += 1; });
    }
  });
  return new Promise((resolve) => child.on("exit", (code) => {
    client?.close();
    rmSync(dir, { recursive: true, force: true });
    const rate = Number(/rounds per second\s+(\d+)/.exec(output)?.[1]);
    resolve({ code, rate, messages });
  }));
}

const without = [];
const withLive = [];
for (let i = 0; i < Number(pairs); ++i) {
  const a = await run(false);
  const b = await run(true);
  without.push(a.rate);
  withLive.push(b.rate);
  console.log(`pair ${i + 1}: without ${a.rate} rounds/s, with --live and a client ${b.rate} rounds/s (${b.messages} messages received)`);
}
const median = (v) => [...v].sort((x, y) => x - y)[Math.floor(v.length / 2)];
console.log(`median: without ${median(without)}, with ${median(withLive)}, ratio ${(median(withLive) / median(without)).toFixed(3)}`);
