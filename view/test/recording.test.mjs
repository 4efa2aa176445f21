// Recordings as Foxglove and Lichtblick read them: for every scenario in scenarios/, a short
// real run with `skyfuse run --record`, read back with @mcap/core (the format's own reader):
// the index is valid and the CRCs hold, the channels have the schema names and encodings the
// tools know, every foxglove.* payload validates against @foxglove/schemas (and every payload
// against the schema recorded with it), and the counts equal the run's CSV files.
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { mkdtempSync, readFileSync, readdirSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import * as foxglove from "@foxglove/schemas/jsonschema.js";
import Ajv from "ajv";
import { registeredScenario } from "./registered_scenario.mjs";

const skyfuse = process.env.SKYFUSE_BIN;
const scenarios = process.env.SKYFUSE_SCENARIOS;
assert.ok(skyfuse && scenarios, "SKYFUSE_BIN and SKYFUSE_SCENARIOS name the build's skyfuse and scenarios/");
const domain = process.env.SKYFUSE_DOMAIN ?? "212";
const ajv = new Ajv({ strict: false, allErrors: true });
const official = new Map();  // "foxglove.X" -> validator of @foxglove/schemas' X

function officialValidator(schemaName) {
  if (!official.has(schemaName)) {
    const schema = foxglove[schemaName.replace(/^foxglove\./, "")];
    assert.ok(schema, `@foxglove/schemas has no ${schemaName}`);
    official.set(schemaName, ajv.compile(schema));
  }
  return official.get(schemaName);
}

function csvRows(path) {
  const lines = readFileSync(path, "utf8").trim().split("\n");
  return lines.slice(1).map((line) => line.split(","));
}

async function readRecording(path) {
  const bytes = readFileSync(path);
  const readable = {
    size: async () => BigInt(bytes.length),
    read: async (offset, length) => bytes.subarray(Number(offset), Number(offset + length)),
  };
  const reader = await McapIndexedReader.Initialize({ readable });
  const messages = [];
  for await (const m of reader.readMessages()) messages.push(m);
  // The whole file again, record by record, with every CRC checked.
  const stream = new McapStreamReader({ validateCrcs: true });
  stream.append(bytes);
  let streamed = 0;
  for (let record; (record = stream.nextRecord()); ) if (record.type === "Message") streamed += 1;
  assert.ok(stream.done(), "the stream reader reaches the footer");
  return { reader, messages, streamed };
}

// Every channel's payloads, checked: JSON with JSON schemas, as many as the statistics count,
// each valid against the schema recorded with it and a foxglove.* one against @foxglove/schemas.
function topicsOf(reader, messages) {
  const topics = new Map();  // topic -> { channel, schema, payloads }
  for (const channel of reader.channelsById.values()) {
    const schema = reader.schemasById.get(channel.schemaId);
    assert.equal(channel.messageEncoding, "json", channel.topic);
    assert.equal(schema.encoding, "jsonschema", channel.topic);
    topics.set(channel.topic, { channel, schema, payloads: [] });
  }
  const byId = new Map([...topics.values()].map((t) => [t.channel.id, t]));
  const decoder = new TextDecoder();
  for (const m of messages) byId.get(m.channelId).payloads.push(JSON.parse(decoder.decode(m.data)));
  for (const count of reader.statistics.channelMessageCounts.entries()) {
    assert.equal(BigInt(byId.get(count[0]).payloads.length), count[1]);
  }
  for (const [topic, { schema, payloads }] of topics) {
    const own = ajv.compile(JSON.parse(decoder.decode(schema.data)));
    const check = schema.name.startsWith("foxglove.") ? officialValidator(schema.name) : null;
    for (const p of payloads) {
      assert.ok(own(p), `${topic} against its recorded schema: ${ajv.errorsText(own.errors)}`);
      if (check) assert.ok(check(p), `${topic} against @foxglove/schemas: ${ajv.errorsText(check.errors)}`);
    }
  }

  return topics;
}

// Scenarios with one aircraft here; a run of many (`traffic:`) has channels of its own, below.
const names = readdirSync(scenarios)
  .filter((f) => f.endsWith(".yaml"))
  .filter((f) => !/^traffic:/m.test(readFileSync(join(scenarios, f), "utf8")))
  .sort();
assert.ok(names.length >= 8, `scenarios found in ${scenarios}: ${names}`);

for (const name of names) {
  test(`a run of ${name} records what its CSV files hold`, async () => {
    const dir = mkdtempSync(join(tmpdir(), "skyfuse-record-"));
    try {
      const file = join(dir, "run.mcap");
      // Four stations, or all of a scenario with fewer (paper 002 has three).
      const listed = readFileSync(join(scenarios, name), "utf8").match(/^\s*- (\{ *)?id:/gm).length;
      const m = Math.min(4, listed);
      execFileSync(skyfuse, ["run", "--scenario", join(scenarios, name), "--stations", String(m),
        "--steps", "30", "--domain", domain, "--out", dir, "--record", file],
        { stdio: ["ignore", "ignore", "pipe"], timeout: 120_000 });
      const { reader, messages, streamed } = await readRecording(file);

      // The index: one chunk index per chunk, statistics that match what was read.
      assert.ok(reader.chunkIndexes.length > 0);
      assert.equal(reader.statistics.messageCount, BigInt(messages.length));
      assert.equal(streamed, messages.length);

      const topics = topicsOf(reader, messages);
      const expectSchema = { "/scene": "foxglove.SceneUpdate", "/stations": "foxglove.SceneUpdate",
        "/tf": "foxglove.FrameTransform", "/center/location": "foxglove.LocationFix",
        "/truth/location": "foxglove.LocationFix", "/skyfuse/round": "skyfuse.Round",
        "/skyfuse/track_error": "skyfuse.TrackError", "/skyfuse/summary": "skyfuse.RunSummary" };
      for (const [topic, schemaName] of Object.entries(expectSchema)) {
        assert.ok(topics.has(topic), `${topic} recorded`);
        assert.equal(topics.get(topic).schema.name, schemaName);
      }
      // One scene and one round message per step; one error entry per track; the modes of an
      // IMM run per row of modes.csv.
      const steps = csvRows(join(dir, "steps.csv"));
      const tracks = csvRows(join(dir, "tracks.csv")).filter((row) => row.at(-1) === "0");  // live
      assert.equal(steps.length, 30);
      assert.equal(topics.get("/scene").payloads.length, steps.length);
      assert.equal(topics.get("/skyfuse/round").payloads.length, steps.length);
      const errors = topics.get("/skyfuse/track_error").payloads.flatMap((p) => p.tracks);
      assert.equal(errors.length, tracks.length);
      for (const e of errors) assert.ok(Number.isFinite(e.error_m) && e.nees >= 0, JSON.stringify(e));
      // The scene holds the center and every peer, each with its ellipsoid.
      const lastScene = topics.get("/scene").payloads.at(-1);
      const ids = lastScene.entities.map((e) => e.id);
      assert.ok(ids.includes("truth") && ids.includes("center"), ids.join(" "));
      assert.equal(ids.filter((id) => id.startsWith("station/")).length, m);
      assert.equal(topics.get("/stations").payloads[0].entities.length, m);
      const summary = topics.get("/skyfuse/summary").payloads;
      assert.equal(summary.length, 1);
      assert.equal(summary[0].steps, 30);
      if (topics.has("/skyfuse/modes")) {
        const modes = csvRows(join(dir, "modes.csv"));
        const entries = topics.get("/skyfuse/modes").payloads.flatMap((p) => p.tracks);
        assert.equal(entries.length, modes.length);
      }
    } finally {
      rmSync(dir, { recursive: true, force: true });
    }
  });
}

// A run of many aircraft: its picture, scans and scores as picture_rounds.csv counts them.
test("a run of many aircraft records every track, scan and score its CSV file holds", async () => {
  const dir = mkdtempSync(join(tmpdir(), "skyfuse-record-"));
  try {
    const file = join(dir, "run.mcap");
    const steps = 40;
    execFileSync(skyfuse, ["run", "--scenario", join(scenarios, "uam-city.yaml"), "--stations", "4",
      "--steps", String(steps), "--domain", domain, "--out", dir, "--record", file],
      { stdio: ["ignore", "ignore", "pipe"], timeout: 120_000 });
    const { reader, messages, streamed } = await readRecording(file);
    assert.equal(reader.statistics.messageCount, BigInt(messages.length));
    assert.equal(streamed, messages.length);
    const topics = topicsOf(reader, messages);
    const expectSchema = { "/scene": "foxglove.SceneUpdate", "/stations": "foxglove.SceneUpdate",
      "/tracks/geojson": "foxglove.GeoJSON", "/skyfuse/round": "skyfuse.Round",
      "/skyfuse/picture": "skyfuse.Picture", "/skyfuse/summary": "skyfuse.RunSummary" };
    for (const [topic, schemaName] of Object.entries(expectSchema)) {
      assert.ok(topics.has(topic), `${topic} recorded`);
      assert.equal(topics.get(topic).schema.name, schemaName);
    }

    // The first station's row of each step: its tracks, confirmed ones and digest.
    const rows = csvRows(join(dir, "picture_rounds.csv"));
    const firstStation = new Map();
    for (const [step, station, digest, tracks, confirmed] of rows) {
      if (station !== "0" && !firstStation.has(step)) firstStation.set(step, { digest, tracks: +tracks, confirmed: +confirmed });
    }
    assert.equal(firstStation.size, steps);
    const scenes = topics.get("/scene").payloads;
    const pictures = topics.get("/skyfuse/picture").payloads;
    const geo = topics.get("/tracks/geojson").payloads;
    assert.equal(scenes.length, steps);
    assert.equal(pictures.length, steps);
    assert.equal(topics.get("/skyfuse/round").payloads.length, steps);
    let falseAlarms = 0;
    pictures.forEach((p, k) => {
      const row = firstStation.get(String(k));
      assert.equal(p.step, k);
      assert.equal(p.digest, row.digest, `step ${k}`);
      assert.equal(p.confirmed, row.confirmed, `step ${k}`);
      assert.equal(p.confirmed + p.tentative, row.tracks, `step ${k}`);
      assert.ok(p.peers_agree && Number.isFinite(p.gospa) && p.gospa >= 0, JSON.stringify(p));
      assert.ok(p.completeness >= 0 && p.completeness <= 1 && p.spuriousness >= 0 && p.spuriousness <= 1);
      if (p.aircraft > 0) assert.equal(p.completeness, p.tracked / p.aircraft);
      const tracks = scenes[k].entities.filter((e) => e.id.startsWith("track/"));
      assert.equal(tracks.length, row.tracks, `step ${k}: a scene entity per track`);
      // Each track labelled with its short number (what --asterix-record sends), one a track,
      // beside its long id.
      const numbers = new Set();
      for (const t of tracks) {
        const meta = Object.fromEntries(t.metadata.map((m) => [m.key, m.value]));
        assert.equal(meta.track_id, t.id.slice(6));
        assert.equal(t.texts[0].text.replace(/[?]$/, ""), `T${meta.track_number}`);
        assert.ok(+meta.track_number >= 1 && +meta.track_number < 1000, meta.track_number);
        numbers.add(meta.track_number);
      }
      assert.equal(numbers.size, tracks.length, `step ${k}: a number per track`);
      const scans = scenes[k].entities.filter((e) => e.id.startsWith("scan/"));
      assert.equal(scans.length, 4);
      assert.equal(scans.reduce((n, e) => n + e.cubes.length, 0), p.detections, `step ${k}`);
      assert.equal(JSON.parse(geo[k].geojson).features.length, p.confirmed, `step ${k}`);
      falseAlarms += p.false_alarms;
    });
    // uam-city over four radars: a dozen aircraft in view after 40 scans, all but the newest
    // confirmed, with clutter in every scan.
    const last = pictures.at(-1);
    assert.ok(last.aircraft >= 10 && last.confirmed >= last.aircraft - 2, JSON.stringify(last));
    assert.ok(falseAlarms > steps * 4, `${falseAlarms} false alarms`);
    assert.equal(topics.get("/stations").payloads[0].entities.length, 4);
    const summary = topics.get("/skyfuse/summary").payloads;
    assert.equal(summary.length, 1);
    assert.equal(summary[0].steps, steps);
    assert.equal(summary[0].picture_digest_at_end, firstStation.get(String(steps - 1)).digest);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

// A registered run (scenarios/registration.yaml, the tracker estimating the radars' biases):
// one /skyfuse/registration message a round, valid against its recorded schema (topicsOf), the
// three radars' entries each beside the scenario's truth.
test("a registered run records every round's bias estimates beside their truths", async () => {
  const dir = mkdtempSync(join(tmpdir(), "skyfuse-record-"));
  try {
    const file = join(dir, "run.mcap");
    const steps = 40;
    const scenario = registeredScenario(scenarios, dir);
    execFileSync(skyfuse, ["run", "--scenario", scenario, "--steps", String(steps), "--domain", domain,
      "--out", dir, "--record", file], { stdio: ["ignore", "ignore", "pipe"], timeout: 120_000 });
    const { reader, messages } = await readRecording(file);
    const topics = topicsOf(reader, messages);
    assert.equal(topics.get("/skyfuse/registration").schema.name, "skyfuse.Registration");
    const estimates = topics.get("/skyfuse/registration").payloads;
    assert.equal(estimates.length, steps);
    estimates.forEach((m, k) => {
      assert.equal(m.step, k);
      assert.deepEqual(m.stations.map((s) => s.station), [1, 2, 3]);
      for (const s of m.stations) {
        assert.deepEqual(s.entries.map((e) => e.entry), ["range_m", "azimuth_rad", "elevation_rad", "time_s"]);
        assert.equal(Math.abs(s.entries[0].truth), 150);
      }
    });
    // The first round's are the prior's (nothing learnt before a track is confirmed); the last
    // round's range is known to metres.
    assert.equal(estimates[0].stations[0].entries[0].sigma, 500);
    const last = estimates.at(-1).stations[0].entries[0];
    assert.ok(last.sigma < 10 && Math.abs(last.estimate - last.truth) < 30, JSON.stringify(last));
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});
