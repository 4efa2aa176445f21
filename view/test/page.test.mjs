// skyfuse's own page as a person sees it: Debian's Chromium, driven by playwright-core, opens the
// page a live run serves, follows the run to its last round, and must show one error series per
// peer plus the center, a drawn scene and the strip of contributions. It saves a screenshot
// (SKYFUSE_SCREENSHOT, default in the test's folder), which the docs show. A recording of many
// aircraft must show every track with its id, the scans, the GOSPA series and the counts
// (screenshot: SKYFUSE_PICTURE_SCREENSHOT).
import { test } from "node:test";
import assert from "node:assert/strict";
import { spawn } from "node:child_process";
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { chromium } from "playwright-core";
import { registeredScenario } from "./registered_scenario.mjs";

const skyfuse = process.env.SKYFUSE_BIN;
const browserPath = process.env.SKYFUSE_CHROMIUM ?? "/usr/bin/chromium";
const scenarios = process.env.SKYFUSE_SCENARIOS;
const domain = process.env.SKYFUSE_DOMAIN ?? "215";
const stations = 4;
const steps = 400;

function untilLine(child, pattern) {
  let output = "";
  return new Promise((resolve, reject) => {
    child.stdout.on("data", (chunk) => {
      output += chunk;
      const m = pattern.exec(output);
      if (m) resolve(m);
    });
    child.stderr.on("data", (chunk) => { output += chunk; });
    child.on("exit", () => reject(new Error(output)));
  });
}

// The colours ("r,g,b") of the fully opaque pixels of the canvas `selector` finds.
function opaqueColours(page, selector) {
  return page.evaluate((sel) => {
    const c = document.querySelector(sel);
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    const seen = new Set();
    for (let i = 0; i < d.length; i += 4) if (d[i + 3] === 255) seen.add(`${d[i]},${d[i + 1]},${d[i + 2]}`);
    return [...seen];
  }, selector);
}

// Records a run (`runArgs` after `skyfuse run`) into `file`, next to it its results, and serves
// the recording with `skyfuse view`: the server process and the page's address.
async function recordAndServe(file, runArgs) {
  const recorded = spawn(skyfuse, ["run", ...runArgs, "--domain", domain, "--out", `${file}.out`,
    "--record", file], { stdio: "ignore" });
  assert.equal(await new Promise((resolve) => recorded.on("exit", resolve)), 0);
  const server = spawn(skyfuse, ["view", file, "--port", "0"], { stdio: ["ignore", "pipe", "pipe"] });
  const [url] = await untilLine(server, /http:\/\/127\.0\.0\.1:\d+\/\?recording=run\.mcap&name=run\.mcap/);
  return { server, url };
}

const launchOptions = {
  executablePath: browserPath,
  args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync"],
};

test("skyfuse view shows a recording, and its slider moves through the rounds", { skip: !existsSync(browserPath) && `no ${browserPath}` }, async () => {
  assert.ok(skyfuse, "SKYFUSE_BIN names the build's skyfuse");
  const dir = mkdtempSync(join(tmpdir(), "skyfuse-view-"));
  const browser = await chromium.launch(launchOptions);
  let server = null;
  try {
    const file = join(dir, "run.mcap");
    let url;
    ({ server, url } = await recordAndServe(file, ["--stations", "4", "--steps", "200"]));
    const page = await browser.newPage({ viewport: { width: 1400, height: 800 } });
    const errors = [];
    page.on("pageerror", (e) => errors.push(e.message));
    await page.goto(url);
    await page.waitForFunction(() => window.skyfuseView?.recordingRounds === 200, null, { timeout: 30_000 });
    await page.waitForFunction(() => document.getElementById("round-counter").textContent === "199");
    assert.equal(await page.evaluate(() => window.skyfuseView.series.size), 5);
    await page.$eval("#time", (slider) => {
      slider.value = "100";
      slider.dispatchEvent(new Event("input"));
    });
    await page.waitForFunction(() => document.getElementById("round-counter").textContent === "100");
    const errorPoints = await page.evaluate(() => window.skyfuseView.series.get(0).steps.length);
    assert.equal(errorPoints, 101, "the center's errors up to round 100");
    assert.equal(await page.textContent("#source"), "recording: run.mcap", "the header names the file");
    assert.deepEqual(errors, []);

    // The file served was checked when the server started; one that is damaged afterwards is
    // named as such in the header, not shown as an empty page.
    writeFileSync(file, readFileSync(file).subarray(0, 1000));
    await page.reload();
    await page.waitForFunction(() => window.skyfuseView?.recordingError, null, { timeout: 30_000 });
    assert.match(await page.textContent("#source"), /^recording run\.mcap cannot be shown: /);
  } finally {
    server?.kill("SIGINT");
    await browser.close();
    rmSync(dir, { recursive: true, force: true });
  }
});

// Records a run of `rounds` rounds (`runArgs(dir)` after `skyfuse run`), serves it and opens
// it in Chromium at its last round; `use(page, errors, dir)` looks at it. Everything is closed
// and removed afterwards.
async function showRecordedRun(rounds, runArgs, use) {
  const dir = mkdtempSync(join(tmpdir(), "skyfuse-view-"));
  const browser = await chromium.launch(launchOptions);
  let server = null;
  try {
    let url;
    ({ server, url } = await recordAndServe(join(dir, "run.mcap"), [...runArgs(dir), "--steps", String(rounds)]));
    const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
    const errors = [];
    page.on("pageerror", (e) => errors.push(e.message));
    await page.goto(url);
    await page.waitForFunction((n) => window.skyfuseView?.recordingRounds === n, rounds, { timeout: 30_000 });
    await page.waitForFunction((n) => document.getElementById("round-counter").textContent === String(n - 1), rounds);
    await use(page, errors, dir);
  } finally {
    server?.kill("SIGINT");
    await browser.close();
    rmSync(dir, { recursive: true, force: true });
  }
}

test("skyfuse view shows a run of many aircraft: every track labelled, the scans, GOSPA and counts", { skip: !existsSync(browserPath) && `no ${browserPath}` }, async () => {
  assert.ok(skyfuse && scenarios, "SKYFUSE_BIN and SKYFUSE_SCENARIOS name the build's skyfuse and scenarios/");
  const rounds = 120;
  await showRecordedRun(rounds, () => ["--scenario", join(scenarios, "uam-city.yaml")], async (page, errors, dir) => {
    const seen = await page.evaluate(() => {
      const v = window.skyfuseView;
      const tracks = [...v.entities.entries()].filter(([id, e]) => id.startsWith("track/") && !e.trail);
      return { last: v.picture.last, gospa: v.picture.gospa.length, scans: v.picture.detections.size,
        labels: tracks.map(([id, e]) => [id, e.label]),
        aircraft: [...v.entities.keys()].filter((id) => id.startsWith("aircraft/")).length,
        figures: document.getElementById("picture-figures").textContent,
        pictureShown: !document.getElementById("picture-section").hidden,
        registrationShown: !document.getElementById("registration-section").hidden };
    });
    // Every track of the last round drawn with its id, as many as the picture holds.
    assert.equal(seen.labels.length, seen.last.confirmed + seen.last.tentative);
    // Each with its short number (what --asterix-record sends), one a track.
    for (const [, label] of seen.labels) assert.match(label, /^T\d{1,3}[?]?$/);
    assert.equal(new Set(seen.labels.map(([, label]) => label.replace(/[?]$/, ""))).size, seen.labels.length);
    assert.equal(seen.aircraft, seen.last.aircraft);
    assert.ok(seen.last.confirmed >= 18, `${seen.last.confirmed} confirmed tracks of uam-city's 20 aircraft`);
    assert.equal(seen.gospa, rounds, "a GOSPA point per round");
    assert.equal(seen.scans, 8, "the last scan of each of the eight radars");
    assert.ok(seen.pictureShown);
    assert.ok(!seen.registrationShown, "uam-city registers nothing");
    assert.match(seen.figures, /confirmed and \d+ tentative tracks, \d+ aircraft; GOSPA [\d.]+ m/);
    // The scene holds confirmed tracks' blue and the aircraft's green.
    const colours = await opaqueColours(page, "#scene");
    assert.ok(colours.includes("51,115,230") && colours.includes("38,179,64"), colours.slice(0, 20).join(" "));
    assert.deepEqual(errors, []);
    await page.screenshot({ path: process.env.SKYFUSE_PICTURE_SCREENSHOT ?? join(dir, "view-picture.png"), fullPage: true });
  });
});

// A registered run (scenarios/registration.yaml's biased radars with the tracker estimating
// their biases): the page shows each radar's estimates beside their truths, the 2σ band and
// whether the truth lies in it, as the recording's last /skyfuse/registration message says.
test("skyfuse view shows a registered run's bias estimates against their truths", { skip: !existsSync(browserPath) && `no ${browserPath}` }, async () => {
  assert.ok(skyfuse && scenarios, "SKYFUSE_BIN and SKYFUSE_SCENARIOS name the build's skyfuse and scenarios/");
  const rounds = 80;
  await showRecordedRun(rounds, (dir) => ["--scenario", registeredScenario(scenarios, dir)], async (page, errors, dir) => {
    const seen = await page.evaluate(() => ({
      message: window.skyfuseView.registration,
      shown: !document.getElementById("registration-section").hidden,
      rows: [...document.querySelectorAll("#registration tbody tr")].map((r) =>
        [r.dataset.station, r.dataset.entry, ...[...r.cells].map((c) => c.textContent)]),
    }));
    assert.ok(seen.shown);
    assert.equal(seen.message.step, rounds - 1);
    // The three radars, each with range, azimuth, elevation and clock; the ADS-B station is the
    // reference and has none.
    assert.deepEqual(seen.message.stations.map((s) => s.station), [1, 2, 3]);
    assert.equal(seen.rows.length, 12);
    const truths = { 1: [150, 0.002618, 0.001745, 0], 2: [-150, -0.002618, 0.001745, 0],
      3: [150, -0.002618, -0.001745, 0] };
    seen.message.stations.forEach((s) => {
      assert.deepEqual(s.entries.map((e) => e.entry), ["range_m", "azimuth_rad", "elevation_rad", "time_s"]);
      s.entries.forEach((e, i) => {
        assert.equal(e.truth, truths[s.station][i]);
        assert.ok(e.sigma > 0 && Number.isFinite(e.estimate));
        assert.equal(e.within_2sigma, Math.abs(e.estimate - e.truth) <= 2 * e.sigma);
      });
      // After 80 scans of 4 s the range is known to metres: within 20 m of its 150.
      assert.ok(Math.abs(s.entries[0].estimate - s.entries[0].truth) < 20, JSON.stringify(s.entries[0]));
    });
    const [station, entry, , unit, truth, band, within] = [...seen.rows[0]];
    assert.deepEqual([station, entry, unit, truth], ["1", "range_m", "range (m)", "150.000"]);
    assert.match(band, /^-?[\d.]+ ± [\d.]+$/);
    assert.equal(within, seen.message.stations[0].entries[0].within_2sigma ? "yes" : "no");
    assert.deepEqual(errors, []);
    await page.locator("#registration-section").screenshot({
      path: process.env.SKYFUSE_REGISTRATION_SCREENSHOT ?? join(dir, "view-registration.png") });
  });
});

test("the live page follows a run to its last round", { skip: !existsSync(browserPath) && `no ${browserPath}` }, async () => {
  assert.ok(skyfuse, "SKYFUSE_BIN names the build's skyfuse");
  const dir = mkdtempSync(join(tmpdir(), "skyfuse-page-"));
  // playwright gives the browser a new, empty profile of its own.
  const browser = await chromium.launch(launchOptions);
  try {
    const page = await browser.newPage({ viewport: { width: 1400, height: 800 } });
    const errors = [];
    page.on("pageerror", (e) => errors.push(e.message));
    // Real time at 50 Hz: 8 s, long enough for a person (and the page) to watch.
    const run = spawn(skyfuse, ["run", "--stations", String(stations), "--steps", String(steps),
      "--domain", domain, "--realtime-deadline-ms", "15", "--out", join(dir, "out"),
      "--live", "127.0.0.1:0"], { stdio: ["ignore", "pipe", "pipe"] });
    let output = "";
    const exited = new Promise((resolve) => run.on("exit", (code) => resolve(code)));
    run.stderr.on("data", (c) => { output += c; });
    const port = await new Promise((resolve, reject) => {
      run.stdout.on("data", (chunk) => {
        output += chunk;
        const m = /live: ws:\/\/127\.0\.0\.1:(\d+)/.exec(output);
        if (m) resolve(Number(m[1]));
      });
      exited.then(() => reject(new Error(output)));
    });
    await page.goto(`http://127.0.0.1:${port}/`);
    await page.waitForFunction((last) => window.skyfuseView?.round === last, steps - 1, { timeout: 60_000 });
    assert.equal(await exited, 0, output);
    await page.waitForTimeout(300);  // a frame after the last round

    await page.screenshot({ path: process.env.SKYFUSE_SCREENSHOT ?? join(dir, "view.png"), fullPage: true });
    assert.equal(await page.textContent("#round-counter"), String(steps - 1));
    const series = await page.evaluate(() => [...window.skyfuseView.series.keys()]);
    assert.deepEqual(series.sort((a, b) => a - b), [0, 1, 2, 3, 4], "the center and every peer");
    assert.equal(await page.locator("#errors .u-legend .u-series").count(), 1 + stations + 1,
      "uPlot's legend: the step column and one series per track");
    // Away from the cursor the legend holds the last round's step and errors, not dashes.
    const legend = await page.locator("#errors .u-legend .u-series .u-value").allTextContents();
    assert.equal(legend[0], String(steps - 1), "the legend's step");
    for (const value of legend.slice(1)) assert.match(value, /^\d+(\.\d+)?$/, "an error in metres");
    // The error plot shows the center's series and the peers' although their errors are equal:
    // uPlot draws its series in legend order, and the center's comes last, dashed.
    const labels = await page.locator("#errors .u-legend .u-series .u-label").allTextContents();
    assert.equal(labels.at(-1), "center", `the center's series is drawn last: ${labels.join(", ")}`);
    const plotColours = await opaqueColours(page, "#errors canvas");
    for (const rgb of ["255,140,0", "51,115,230"]) {
      assert.ok(plotColours.includes(rgb), `error plot has ${rgb}: ${plotColours.slice(0, 12).join(" ")}`);
    }
    // The scene is drawn: pixels of the truth's, the center's, the peers' and the stations' colours.
    const colours = await opaqueColours(page, "#scene");
    for (const rgb of ["38,179,64", "255,140,0", "51,115,230", "119,119,119"]) {
      assert.ok(colours.includes(rgb), `scene has ${rgb}: ${colours.slice(0, 12).join(" ")}`);
    }
    // The 3-D view is drawn too, and turns when dragged.
    const drawn3d = () => page.evaluate(() => {
      const c = document.getElementById("scene3d");
      const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
      let opaque = 0;
      let hash = 0;
      for (let i = 3; i < d.length; i += 4) if (d[i] === 255) { opaque += 1; hash = (hash * 31 + i) % 1000003; }
      return { opaque, hash };
    });
    const before = await drawn3d();
    assert.ok(before.opaque > 100, `3-D view: ${before.opaque} pixels drawn`);
    await page.locator("#scene3d").scrollIntoViewIfNeeded();
    const box = await page.locator("#scene3d").boundingBox();
    await page.mouse.move(box.x + 200, box.y + 200);
    await page.mouse.down();
    await page.mouse.move(box.x + 320, box.y + 230, { steps: 5 });
    await page.mouse.up();
    await page.waitForTimeout(100);
    assert.notEqual((await drawn3d()).hash, before.hash, "dragging turns the 3-D view");
    const strip = await page.evaluate(() => window.skyfuseView.strip.length);
    assert.ok(strip > 100, `strip of ${strip} rounds`);
    assert.deepEqual(errors, [], "no error in the page");
  } finally {
    await browser.close();
    rmSync(dir, { recursive: true, force: true });
  }
});
