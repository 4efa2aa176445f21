// A live run as Foxglove sees it: `skyfuse run --live` with a @foxglove/ws-protocol client that
// subscribes to every channel while the run goes on, checks the schema names, validates every
// foxglove.* payload against @foxglove/schemas and follows the run to its last round with one
// scene per round. Beside it, a client that sends what the server does not serve (answered with
// an error status and ignored) and a client that stops reading (dropped; the run goes on); and
// a stream capped to a display (the default), thinned but ending on the last round's scene.
// The first run is recorded too: every message streamed is in the file, stamped alike.
import { test } from "node:test";
import assert from "node:assert/strict";
import { spawn } from "node:child_process";
import { mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import wsProtocol from "@foxglove/ws-protocol";
const { FoxgloveClient } = wsProtocol;
import WebSocket from "ws";
import { McapIndexedReader } from "@mcap/core";
import { readFileSync } from "node:fs";
import * as foxglove from "@foxglove/schemas/jsonschema.js";
import Ajv from "ajv";

const skyfuse = process.env.SKYFUSE_BIN;
const scenarios = process.env.SKYFUSE_SCENARIOS;
assert.ok(skyfuse && scenarios, "SKYFUSE_BIN and SKYFUSE_SCENARIOS name the build's skyfuse and scenarios/");
const domain = process.env.SKYFUSE_DOMAIN ?? "213";
const steps = 1500;
const ajv = new Ajv({ strict: false, allErrors: true });

// Starts a run with --live on a free port; resolves with the process, its port and its exit.
// `sceneHz` 0: a scene every round, as a recording has.
// `record`: also write the run's recording there. `scenario`: a scenario file (the default one
// if null).
function startLiveRun(dir, { runSteps = steps, sceneHz = 0, record = null, scenario = null } = {}) {
  const run = spawn(skyfuse, ["run", ...(scenario ? ["--scenario", scenario] : []),
    "--stations", "4", "--steps", String(runSteps), "--domain", domain,
    "--out", join(dir, "out"), "--live", "127.0.0.1:0", "--live-scene-hz", String(sceneHz),
    ...(record ? ["--record", record] : [])],
    { stdio: ["ignore", "pipe", "pipe"] });
  let output = "";
  const exited = new Promise((resolve) => run.on("exit", (code) => resolve({ code, output })));
  const port = new Promise((resolve, reject) => {
    run.stdout.on("data", (chunk) => {
      output += chunk;
      const m = /live: ws:\/\/127\.0\.0\.1:(\d+)/.exec(output);
      if (m) resolve(Number(m[1]));
    });
    run.stderr.on("data", (chunk) => { output += chunk; });
    exited.then(() => reject(new Error(`run ended before it listened:\n${output}`)));
  });
  return { run, port, exited };
}

async function readRecording(path) {
  const bytes = readFileSync(path);
  return McapIndexedReader.Initialize({ readable: {
    size: async () => BigInt(bytes.length),
    read: async (offset, length) => bytes.subarray(Number(offset), Number(offset + length)),
  } });
}

// Every message of a recording, parsed, by "topic log-time".
async function recordedPayloads(path) {
  const reader = await readRecording(path);
  const decoder = new TextDecoder();
  const recorded = new Map();
  for await (const m of reader.readMessages()) {
    recorded.set(`${reader.channelsById.get(m.channelId).topic} ${m.logTime}`,
      JSON.parse(decoder.decode(m.data)));
  }
  return recorded;
}

function connect(port) {
  return new WebSocket(`ws://127.0.0.1:${port}`, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
}

// A client subscribed to every channel the server advertises: each channel by id, and each
// topic's payloads as they come, parsed, with their log time as __log_time.
function subscribeToEverything(port) {
  const client = new FoxgloveClient({ ws: connect(port) });
  const channels = new Map();
  const bySubscription = new Map();
  const payloads = new Map();
  client.on("advertise", (advertised) => {
    for (const c of advertised) {
      channels.set(c.id, c);
      payloads.set(c.topic, []);
      bySubscription.set(client.subscribe(c.id), c);
    }
  });
  const decoder = new TextDecoder();
  client.on("message", ({ subscriptionId, timestamp, data }) => {
    const p = JSON.parse(decoder.decode(data));
    p.__log_time = timestamp;
    payloads.get(bySubscription.get(subscriptionId).topic).push(p);
  });
  return { client, channels, payloads, drained: drainer(client) };
}

// The server closes every connection when the run ends, after its last message; the run's
// process may be seen to exit before a client has read what is still on its socket. The
// function returned waits for the close (10 s at most).
function drainer(client) {
  const closed = new Promise((resolve) => client.on("close", resolve));
  return () => Promise.race([closed, new Promise((resolve) => setTimeout(resolve, 10000))]);
}

test("a live run streams every channel to its last round, and ignores what it does not serve", async () => {
  const dir = mkdtempSync(join(tmpdir(), "skyfuse-live-"));
  try {
    const recording = join(dir, "run.mcap");
    const { port, exited } = startLiveRun(dir, { record: recording });
    const { client, channels, payloads, drained } = subscribeToEverything(await port);
    const statuses = [];
    let serverInfo = null;
    client.on("serverInfo", (info) => { serverInfo = info; });
    client.on("status", (s) => statuses.push(s));
    // What a publishing client would send, and garbage: each answered with an error status.
    const rude = connect(await port);
    await new Promise((resolve) => rude.on("open", resolve));
    const answers = [];
    rude.on("message", (data, binary) => { if (!binary) answers.push(JSON.parse(data.toString())); });
    rude.send("this is not JSON");
    rude.send(JSON.stringify({ op: "advertise", channels: [{ id: 1, topic: "/x", encoding: "json", schemaName: "x" }] }));
    rude.send(JSON.stringify({ op: "getParameters", parameterNames: [] }));
    rude.send(JSON.stringify({ op: "subscribe", subscriptions: [{ id: "one", channelId: 0 }] }));
    rude.send(Buffer.from([0x01, 1, 0, 0, 0, 42]));

    const { code, output } = await exited;
    assert.equal(code, 0, output);
    await drained();
    client.close();
    rude.close();

    assert.equal(serverInfo.name, "skyfuse");
    assert.deepEqual(serverInfo.capabilities, [], "it only publishes");
    const names = Object.fromEntries([...channels.values()].map((c) => [c.topic, c.schemaName]));
    assert.equal(names["/scene"], "foxglove.SceneUpdate");
    assert.equal(names["/stations"], "foxglove.SceneUpdate");
    assert.equal(names["/tf"], "foxglove.FrameTransform");
    assert.equal(names["/center/location"], "foxglove.LocationFix");
    assert.equal(names["/skyfuse/round"], "skyfuse.Round");
    for (const c of channels.values()) {
      assert.equal(c.encoding, "json");
      assert.equal(c.schemaEncoding, "jsonschema");
      if (!c.schemaName.startsWith("foxglove.")) continue;
      const check = ajv.compile(foxglove[c.schemaName.replace("foxglove.", "")]);
      for (const p of payloads.get(c.topic)) {
        const { __log_time, ...message } = p;
        assert.ok(check(message), `${c.topic}: ${ajv.errorsText(check.errors)}`);
      }
    }

    // Followed to the last round, with no round missing since the first one received, and one
    // scene per round.
    const rounds = payloads.get("/skyfuse/round").map((r) => r.step);
    assert.ok(rounds.length > steps / 2, `only ${rounds.length} rounds streamed`);
    assert.equal(rounds.at(-1), steps - 1);
    for (let i = 1; i < rounds.length; ++i) assert.equal(rounds[i], rounds[i - 1] + 1);
    assert.equal(payloads.get("/scene").length, rounds.length);
    assert.equal(payloads.get("/skyfuse/track_error").length, rounds.length);
    assert.equal(payloads.get("/skyfuse/summary").length, 1);
    assert.equal(payloads.get("/skyfuse/summary")[0].steps, steps);
    assert.equal(statuses.length, 0, "the well-behaved client got no status");

    // The stream and the recording of the run are one: every message streamed is in the
    // recording at the same log time on the same channel, with the same payload.
    const recorded = await recordedPayloads(recording);
    let compared = 0;
    for (const [topic, list] of payloads) {
      for (const { __log_time, ...message } of list) {
        assert.deepEqual(recorded.get(`${topic} ${__log_time}`), message, `${topic} at ${__log_time}`);
        compared += 1;
      }
    }
    assert.ok(compared > 4 * steps / 2, `${compared} messages compared`);

    // Five messages, five error statuses; the run went on regardless.
    assert.equal(answers.filter((a) => a.op === "status" && a.level === 2).length, 5,
      JSON.stringify(answers.filter((a) => a.op === "status")));
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test("a client that stops reading is dropped and the run goes on to its end", async () => {
  const dir = mkdtempSync(join(tmpdir(), "skyfuse-live-slow-"));
  try {
    // About 30 MB of messages: more than the kernel's socket buffers and the server's 8 MiB.
    const { port, exited } = startLiveRun(dir, { runSteps: 4000 });
    const slow = connect(await port);
    let closedWith = null;
    slow.on("close", (code) => { closedWith = code; });
    slow.on("message", (data, binary) => {
      if (binary) return;
      const m = JSON.parse(data.toString());
      if (m.op !== "advertise") return;
      slow.send(JSON.stringify({ op: "subscribe",
        subscriptions: m.channels.map((c, i) => ({ id: i, channelId: c.id })) }));
      // Then read nothing more: the kernel's buffers fill, then the server's.
      slow._socket.pause();
    });
    const { code, output } = await exited;
    assert.equal(code, 0, output);
    assert.match(output, /live: 1 client\(s\) dropped for falling behind/);
    assert.match(output, /rounds per second/, "the run finished and reported");
    slow._socket.resume();
    await new Promise((resolve) => setTimeout(resolve, 200));
    assert.notEqual(closedWith, null, "the connection is closed");
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test("a stream capped to a display thins the scenes and their trails, and ends on a full scene", async () => {
  const dir = mkdtempSync(join(tmpdir(), "skyfuse-live-capped-"));
  try {
    const runSteps = 3000;
    // Lock-step runs its rounds far faster than the 30 scenes and 5 trails a second sent.
    const { port, exited } = startLiveRun(dir, { runSteps, sceneHz: 30 });
    const client = new FoxgloveClient({ ws: connect(await port) });
    const drained = drainer(client);
    const topics = new Map();
    client.on("advertise", (advertised) => {
      for (const c of advertised) {
        if (c.topic === "/scene" || c.topic === "/skyfuse/round") topics.set(client.subscribe(c.id), c.topic);
      }
    });
    const scenes = [];
    const rounds = [];
    const decoder = new TextDecoder();
    client.on("message", ({ subscriptionId, data }) => {
      const p = JSON.parse(decoder.decode(data));
      (topics.get(subscriptionId) === "/scene" ? scenes : rounds).push(p);
    });
    const { code, output } = await exited;
    assert.equal(code, 0, output);
    await drained();
    client.close();

    const trailsOf = (scene) => scene.entities.filter((e) => e.id.startsWith("trail/")).map((e) => e.id).sort();
    assert.ok(scenes.length > 0 && scenes.length < runSteps, `${scenes.length} scenes for ${runSteps} rounds`);
    assert.ok(scenes.some((s) => trailsOf(s).length === 0), "scenes between trail updates carry no trails");
    // A viewer ends on the last round's scene, and holds all six trails as last sent (an entity
    // stays until replaced; trails are resent only once they have moved).
    assert.equal(rounds.at(-1).step, runSteps - 1);
    assert.deepEqual(scenes.at(-1).entities[0].timestamp, rounds.at(-1).timestamp);
    assert.deepEqual(trailsOf(scenes.findLast((s) => trailsOf(s).length > 0)),
      ["trail/center", "trail/station/1", "trail/station/2", "trail/station/3", "trail/station/4", "trail/truth"]);
    for (let i = 1; i < rounds.length; ++i) assert.ok(rounds[i].step > rounds[i - 1].step);
    assert.ok(rounds.length < runSteps, "figures are thinned too");
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

// A run of many aircraft: every round's picture streamed from the first one received to the
// last, each message as the recording holds it.
test("a live run of many aircraft streams the picture of every round, as its recording holds it", async () => {
  const dir = mkdtempSync(join(tmpdir(), "skyfuse-live-"));
  try {
    const recording = join(dir, "run.mcap");
    const runSteps = 300;
    const { port, exited } = startLiveRun(dir, { runSteps, record: recording,
      scenario: join(scenarios, "uam-city.yaml") });
    const { client, channels, payloads, drained } = subscribeToEverything(await port);
    const { code, output } = await exited;
    await drained();
    assert.equal(code, 0, output);
    client.close();

    const names = Object.fromEntries([...channels.values()].map((c) => [c.topic, c.schemaName]));
    assert.equal(names["/scene"], "foxglove.SceneUpdate");
    assert.equal(names["/tracks/geojson"], "foxglove.GeoJSON");
    assert.equal(names["/skyfuse/picture"], "skyfuse.Picture");
    for (const c of channels.values()) {
      if (!c.schemaName.startsWith("foxglove.")) continue;
      const check = ajv.compile(foxglove[c.schemaName.replace("foxglove.", "")]);
      for (const { __log_time, ...message } of payloads.get(c.topic)) {
        assert.ok(check(message), `${c.topic}: ${ajv.errorsText(check.errors)}`);
      }
    }
    const steps = payloads.get("/skyfuse/picture").map((p) => p.step);
    assert.ok(steps.length > runSteps / 2, `only ${steps.length} rounds streamed`);
    assert.equal(steps.at(-1), runSteps - 1);
    for (let i = 1; i < steps.length; ++i) assert.equal(steps[i], steps[i - 1] + 1);
    assert.equal(payloads.get("/scene").length, steps.length);
    assert.equal(payloads.get("/skyfuse/round").length, steps.length);
    assert.equal(payloads.get("/skyfuse/summary")[0].steps, runSteps);

    // Every message as the recording holds it; the first scene streamed may also delete what
    // left before the client came, which the recording deleted as it left.
    const recorded = await recordedPayloads(recording);
    let compared = 0;
    for (const [topic, list] of payloads) {
      list.forEach(({ __log_time, ...message }, i) => {
        const file = recorded.get(`${topic} ${__log_time}`);
        if (topic === "/scene" && i === 0) {
          assert.deepEqual(message.entities, file.entities);
        } else {
          assert.deepEqual(message, file, `${topic} at ${__log_time}`);
        }
        compared += 1;
      });
    }
    assert.ok(compared > 5 * runSteps / 2, `${compared} messages compared`);
    const { __log_time, ...last } = payloads.get("/skyfuse/picture").at(-1);
    assert.ok(last.peers_agree && last.confirmed >= 10, JSON.stringify(last));
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});
