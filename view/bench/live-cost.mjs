// What --live costs a run: lock-step rounds/s at M = 4 without a live stream; with one that a
// Foxglove client follows (subscribed to every channel); with skyfuse's page open in Debian's
// Chromium; and with a client that subscribed to everything and then stopped reading — the
// four alternating in one sitting.
// Usage: node bench/live-cost.mjs SKYFUSE_BIN [ROUNDS_OF_FOUR] [STEPS]
// KINDS=follow,page,stall picks the clients; RUN_CPUS and BROWSER_CPUS (taskset lists, e.g. 0
// and 1) keep the run and the browser on cores of their own, as if the page were on another
// machine: the baseline runs on RUN_CPUS too. BROWSER_IDLE=1 runs the browser in the idle
// scheduling class.
import { spawn } from "node:child_process";
import { mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import wsProtocol from "@foxglove/ws-protocol";
import WebSocket from "ws";

const { FoxgloveClient } = wsProtocol;
const [skyfuse, rounds = "5", steps = "8000"] = process.argv.slice(2);
if (!skyfuse) {
  console.error("usage: node bench/live-cost.mjs SKYFUSE_BIN [ROUNDS_OF_FOUR] [STEPS]");
  process.exit(2);
}

// A client that reads everything it is sent.
function follow(port, counts) {
  const client = new FoxgloveClient({ ws: new WebSocket(`ws://127.0.0.1:${port}`, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
  client.on("advertise", (channels) => channels.forEach((c) => client.subscribe(c.id)));
  client.on("message", () => { counts.messages += 1; });
  return () => client.close();
}

// A client that subscribes to everything and then reads nothing: the server must drop it.
function stall(port) {
  const ws = new WebSocket(`ws://127.0.0.1:${port}`, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
  ws.on("error", () => {});
  ws.on("message", (data, binary) => {
    if (binary) return;
    const m = JSON.parse(data.toString());
    if (m.op !== "advertise") return;
    ws.send(JSON.stringify({ op: "subscribe", subscriptions: m.channels.map((c, i) => ({ id: i, channelId: c.id })) }));
    ws._socket.pause();
  });
  return () => ws.terminate();
}

// skyfuse's own page, as a person would have it open: Debian's Chromium, started once before
// the runs, opens the page in a new tab for each run (DevTools protocol's Target domain only:
// a test driver's network tracing would cost the browser more than the page does).
const profile = mkdtempSync(join(tmpdir(), "skyfuse-live-cost-browser-"));
// `command args` on the cores `cpus` names (taskset), or anywhere.
const onCpus = (cpus, command, args) => (cpus ? ["taskset", ["-c", cpus, command, ...args]] : [command, args]);
// BROWSER_IDLE=1: the browser in the idle scheduling class (`chrt --idle 0`, inherited by its
// processes), drawing with the CPU the run leaves, as a person can run it beside a run.
const atIdle = (command, args) => (process.env.BROWSER_IDLE ? ["chrt", ["--idle", "0", command, ...args]] : [command, args]);
const browser = spawn(...onCpus(process.env.BROWSER_CPUS, ...atIdle(process.env.SKYFUSE_CHROMIUM ?? "/usr/bin/chromium", ["--headless",
  "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking",
  "--disable-component-update", "--disable-sync", "--remote-debugging-port=0", `--user-data-dir=${profile}`,
  "about:blank"])), { stdio: ["ignore", "ignore", "pipe"] });
const devtools = await new Promise((resolve, reject) => {
  let text = "";
  browser.stderr.on("data", (chunk) => {
    text += chunk;
    const m = /DevTools listening on (ws:\S+)/.exec(text);
    if (m) resolve(new WebSocket(m[1]));
  });
  browser.on("exit", () => reject(new Error(`chromium ended: ${text}`)));
});
await new Promise((resolve) => devtools.on("open", resolve));
let nextCommand = 0;
function browserCommand(method, params) {
  const id = ++nextCommand;
  devtools.send(JSON.stringify({ id, method, params }));
  return new Promise((resolve) => devtools.on("message", function answer(data) {
    const m = JSON.parse(data.toString());
    if (m.id !== id) return;
    devtools.off("message", answer);
    resolve(m.result);
  }));
}
function openPage(port, counts) {
  const opened = browserCommand("Target.createTarget", { url: `http://127.0.0.1:${port}/` });
  return async () => {
    const { targetId } = await opened;
    await browserCommand("Target.closeTarget", { targetId });

  };
}

// client: null (no --live), "follow", "page" or "stall".
function run(client) {
  const dir = mkdtempSync(join(tmpdir(), "skyfuse-live-cost-"));
  const args = ["run", "--stations", "4", "--steps", steps, "--domain", "214", "--out", dir];
  if (client) args.push("--live", "127.0.0.1:0");
  const child = spawn(...onCpus(process.env.RUN_CPUS, skyfuse, args), { stdio: ["ignore", "pipe", "ignore"] });
  let output = "";
  let close = null;
  const counts = { messages: 0 };
  child.stdout.on("data", (chunk) => {
    output += chunk;
    const m = /live: ws:\/\/127\.0\.0\.1:(\d+)/.exec(output);
    if (m && !close) {
      close = { follow, page: openPage, stall }[client](m[1], counts);
    }
  });
  return new Promise((resolve) => child.on("exit", async (code) => {
    await close?.();
    rmSync(dir, { recursive: true, force: true });
    const rate = Number(/rounds per second\s+(\d+)/.exec(output)?.[1]);
    const dropped = /live: (\d+) client\(s\) dropped/.exec(output)?.[1] ?? "0";
    const sent = /live: (\d+) message\(s\) sent/.exec(output)?.[1];
    resolve({ code, rate, messages: counts.messages, sent, dropped: Number(dropped) });
  }));
}

const median = (v) => [...v].sort((x, y) => x - y)[Math.floor(v.length / 2)];
const kinds = (process.env.KINDS ?? "follow,page,stall").split(",");
const rates = { without: [], follow: [], page: [], stall: [] };
const ratios = { follow: [], page: [], stall: [] };
for (let i = 0; i < Number(rounds); ++i) {
  const a = await run(null);
  rates.without.push(a.rate);
  const line = [`${i + 1}: without ${a.rate} rounds/s`];
  for (const kind of kinds) {
    const r = await run(kind);
    rates[kind].push(r.rate);
    ratios[kind].push(r.rate / a.rate);
    line.push({
      follow: `a client reading ${r.rate} (${r.messages} messages)`,
      page: `the page open ${r.rate} (${r.sent} messages sent)`,
      stall: `a client that stopped reading ${r.rate} (dropped: ${r.dropped})`,
    }[kind]);
  }
  console.log(line.join("; "));
}
devtools.close();
browser.kill();
await new Promise((resolve) => browser.on("exit", resolve));
rmSync(profile, { recursive: true, force: true });
const without = median(rates.without);
console.log(`medians: without ${without} rounds/s`);
for (const kind of kinds) {
  console.log(`  ${kind.padEnd(6)} ${median(rates[kind])} rounds/s: ratio of medians ` +
    `${(median(rates[kind]) / without).toFixed(3)}, median of the rounds' ratios ${median(ratios[kind]).toFixed(3)}`);
}
