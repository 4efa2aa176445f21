// skyfuse's own view of a run: connects to the server that served this page (`skyfuse run
// --live`) over the Foxglove WebSocket protocol, subscribes to every channel and draws the
// scene top-down, each track's error against time, who contributed to each round, the IMM's
// mode probabilities and the run's figures, and for a run of many aircraft its picture
// (picture.js). With ?recording=FILE (`skyfuse view FILE.mcap`) it
// reads a recording instead and shows it up to the time its slider is set to. Built with
// esbuild from locked npm packages; no CDN.
import { McapIndexedReader } from "@mcap/core";
import uPlot from "uplot";
import "uplot/dist/uPlot.min.css";
import "./page.css";
import { labelBox } from "./labels.js";
import { legendShowsLatest, showLatestInLegend } from "./plots.js";
import { drawDetections, drawPicturePlots, drawTrackLabel, emptyPicture, onPicture, onPictureDeletion,
  onPictureEntity } from "./picture.js";
import { drawRegistration, onRegistration } from "./registration.js";

window.NODRAW = new URLSearchParams(location.search).has("nodraw");
window.NOMSG = new URLSearchParams(location.search).has("nomsg");
const SUBPROTOCOL = "foxglove.websocket.v1";
const COLORS = { truth: "#26b340", center: "#ff8c00", peer: "#3373e6", site: "#777777" };
const STRIP_ROUNDS = 240;

// What the page knows, also read by the browser test (window.skyfuseView).
const view = {
  round: null, rounds: 0, firstRoundAt: null, latencyMs: null,
  sites: new Map(),          // id -> {x, y, label}
  entities: new Map(),       // entity id -> {x, y, ellipse, color} or {trail, color}
  series: new Map(),         // node -> {steps: [], errors: []}
  strip: [],                 // per round: [state of the center, of each station]
  stripNodes: [],            // the strip's rows: the center (0), then each station's id
  modes: null, summary: null,
  picture: emptyPicture(),   // a run of many aircraft: its tracks' series and last scans
  registration: null,        // a registered run's latest bias estimates
};
window.skyfuseView = view;

function nodeName(node) { return node === 0 ? "center" : `station ${node}`; }

// The 2-D ellipse of a sphere primitive scaled and turned into a 3-D ellipsoid: the top-left
// 2 x 2 block of R diag(s/2)^2 R^T, as axes and angle.
function topDownEllipse(sphere) {
  const { x, y, z, w } = sphere.pose.orientation;
  const r = [
    [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
    [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
  ];
  const s = [sphere.size.x / 2, sphere.size.y / 2, sphere.size.z / 2].map((v) => v * v);
  const c = [[0, 0], [0, 0]];
  for (let i = 0; i < 2; ++i) for (let j = 0; j < 2; ++j) for (let k = 0; k < 3; ++k) c[i][j] += r[i][k] * s[k] * r[j][k];
  const tr = c[0][0] + c[1][1];
  const det = c[0][0] * c[1][1] - c[0][1] * c[0][1];
  const disc = Math.sqrt(Math.max(tr * tr / 4 - det, 0));
  const l1 = tr / 2 + disc;
  const l2 = Math.max(tr / 2 - disc, 0);
  const angle = Math.abs(c[0][1]) > 1e-15 ? Math.atan2(l1 - c[0][0], c[0][1]) : (c[0][0] >= c[1][1] ? 0 : Math.PI / 2);
  return { a: Math.sqrt(l1), b: Math.sqrt(l2), angle };
}

function onScene(update) {
  for (const d of update.deletions ?? []) onPictureDeletion(view, d.id);
  for (const e of update.entities) {
    if (onPictureEntity(view, e, topDownEllipse)) continue;
    // Peers below, the center above them, the truth on top: the tracks lie within decimetres
    // of each other and of the truth, so each is drawn smaller than the one beneath.
    const [color, layer] = e.id === "truth" || e.id === "trail/truth" ? [COLORS.truth, 2]
      : e.id.includes("center") ? [COLORS.center, 1] : [COLORS.peer, 0];
    if (e.lines.length > 0) {
      view.entities.set(e.id, { trail: e.lines[0].points, color, layer });
    } else if (e.spheres.length > 0) {
      const p = e.spheres[0].pose.position;
      view.entities.set(e.id, { x: p.x, y: p.y, z: p.z, color, layer,
        ellipse: e.spheres.length > 1 ? topDownEllipse(e.spheres[1]) : null });
    }
  }
}

function onStations(update) {
  for (const e of update.entities) {
    const p = e.cubes[0].pose.position;
    view.sites.set(e.id, { x: p.x, y: p.y, z: p.z, label: e.texts[0]?.text ?? e.id });
  }
}

function onRound(round) {
  view.round = round.step;
  view.rounds += 1;
  view.latencyMs = round.latency_ms;
  view.firstRoundAt ??= performance.now();
  // A run of many aircraft names no missing station, only how many scans a node fused.
  const some = (n) => n.missing.length > 0 || (n.scans_fused !== undefined && n.scans_fused < round.stations);
  view.strip.push(round.nodes.map((n) => (!n.delivered ? "none" : some(n) ? "some" : "all")));
  view.stripNodes = round.nodes.map((n) => n.node);
  if (view.strip.length > STRIP_ROUNDS) view.strip.shift();
}

function onTrackError(message) {
  for (const t of message.tracks) {
    if (!view.series.has(t.node)) view.series.set(t.node, { steps: [], errors: [] });
    const s = view.series.get(t.node);
    s.steps.push(message.step);
    s.errors.push(t.error_m);
  }
}

// ---- drawing ------------------------------------------------------------------------------

// Everything the scene holds, for fitting it to a canvas: stations, markers, trail points.
function scenePoints() {
  const points = [...view.sites.values()];
  for (const e of view.entities.values()) (e.trail ?? [e]).forEach((p) => points.push(p));
  return points;
}

// Peers below, the center above them, the truth on top, each marker smaller than the one under.
const MARKER_RADIUS = [7, 4.5, 2.5];
function layeredEntities() {
  return [...view.entities.values()].sort((a, b) => a.layer - b.layer);
}

function drawTrails(g, at, layered) {
  for (const e of layered) {
    if (!e.trail) continue;
    g.strokeStyle = e.color;
    g.lineWidth = 1.5;
    g.beginPath();
    e.trail.forEach((p, i) => { const [u, v] = at(p); i === 0 ? g.moveTo(u, v) : g.lineTo(u, v); });
    g.stroke();
  }
}

// A sensor kind as the scenes name it: short, so that the stations' names crowd the tracks less.
const SENSOR_NAMES = {
  range_azimuth_elevation: "3-D radar", range_azimuth: "2-D radar", range_azimuth_altitude: "Mode S",
  position_velocity: "ADS-B", multilateration: "mlat", tdoa_range_difference: "TDOA",
  tdoa_relative_constant_acceleration: "TDOA",
};
const siteName = (label) => label.replace(/\(([a-z0-9_]+)\)/, (all, kind) => `(${SENSOR_NAMES[kind] ?? kind})`);

// A station's square, and where its name goes: right of it, or left where the right would leave
// the canvas. Where `placed` is given, the name's box joins it, so that no track's label is put
// over it. The name itself is drawn last (drawSiteNames).
function drawSite(g, [u, v], label, placed = null) {
  g.fillStyle = COLORS.site;
  g.fillRect(u - 4, v - 4, 8, 8);
  const width = g.measureText(label).width;
  const x = u + 6 + width > g.canvas.width ? u - 6 - width : u + 6;
  placed?.push(labelBox(x, v - 6, width));
  return { label, x, y: v - 6 };
}

// The stations' names, over everything else on a halo of the scene's background, so that no
// ellipse, trail, marker or false alarm drawn near a station hides its name.
function drawSiteNames(g, names) {
  g.save();
  g.lineJoin = "round";
  g.lineWidth = 3;
  g.strokeStyle = "#ffffff";
  g.fillStyle = COLORS.site;
  for (const { label, x, y } of names) {
    g.strokeText(label, x, y);
    g.fillText(label, x, y);
  }
  g.restore();
}

function drawMarker(g, [u, v], e) {
  g.fillStyle = e.color;
  g.beginPath();
  g.arc(u, v, MARKER_RADIUS[e.layer], 0, 2 * Math.PI);
  g.fill();
}

// A canvas and its 2-D context, cleared for a new drawing.
function clearedCanvas(id) {
  const canvas = document.getElementById(id);
  const g = canvas.getContext("2d");
  g.clearRect(0, 0, canvas.width, canvas.height);
  return [canvas, g];
}

function drawScene() {
  const [canvas, g] = clearedCanvas("scene");
  const points = scenePoints();
  if (points.length === 0) return;
  const xs = points.map((p) => p.x);
  const ys = points.map((p) => p.y);
  const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
  const scale = 0.8 * Math.min(canvas.width / Math.max(x1 - x0, 1), canvas.height / Math.max(y1 - y0, 1));
  const cx = (x0 + x1) / 2;
  const cy = (y0 + y1) / 2;
  const at = (p) => [canvas.width / 2 + (p.x - cx) * scale, canvas.height / 2 - (p.y - cy) * scale];
  g.font = "11px system-ui";
  const placed = [];  // the labels drawn so far: a crowded track's goes where none is
  const names = [...view.sites.values()].map((s) => drawSite(g, at(s), siteName(s.label), placed));
  drawDetections(g, at, view);
  const layered = layeredEntities();
  drawTrails(g, at, layered);
  for (const e of layered) {
    if (e.trail) continue;
    const [u, v] = at(e);
    const radius = MARKER_RADIUS[e.layer];
    if (e.ellipse) {
      // At least this marker's size: decimetre ellipses over kilometres of scene.
      g.strokeStyle = e.color;
      g.lineWidth = 1.5;
      g.beginPath();
      g.ellipse(u, v, Math.max(e.ellipse.a * scale, 3 * radius), Math.max(e.ellipse.b * scale, 1.5 * radius),
        -e.ellipse.angle, 0, 2 * Math.PI);
      g.stroke();
    }
    drawMarker(g, [u, v], e);
    drawTrackLabel(g, [u, v], e, placed);
  }
  drawSiteNames(g, names);
}

// The 3-D view: the scene turned by `yaw` about the vertical and tilted by `pitch`, projected
// orthographically; dragging turns it.
const turn = { yaw: -0.6, pitch: 0.45 };

function drawScene3d() {
  const [canvas, g] = clearedCanvas("scene3d");
  const points = scenePoints();
  if (points.length === 0) return;
  const mid = ["x", "y", "z"].map((k) => {
    const v = points.map((p) => p[k]);
    return (Math.min(...v) + Math.max(...v)) / 2;
  });
  const [cy, sy, cp, sp] = [Math.cos(turn.yaw), Math.sin(turn.yaw), Math.cos(turn.pitch), Math.sin(turn.pitch)];
  const project = (p) => {
    const dx = p.x - mid[0];
    const dy = p.y - mid[1];
    const dz = p.z - mid[2];
    const across = cy * dx - sy * dy;
    const depth = sy * dx + cy * dy;
    return [across, -(dz * cp + depth * sp)];
  };
  // Fitted to what any turn about the vertical can show, so that the scale stays put while the
  // scene turns: the ground's radius across, tilted by the pitch and with the heights down.
  const radius = Math.max(...points.map((p) => Math.hypot(p.x - mid[0], p.y - mid[1])), 1);
  const halfHeight = Math.max(...points.map((p) => Math.abs(p.z - mid[2])));
  const scale = 0.9 * Math.min(canvas.width / 2 / radius, canvas.height / 2 / (radius * sp + halfHeight * cp));
  const at = (p) => {
    const [u, v] = project(p);
    return [canvas.width / 2 + u * scale, canvas.height / 2 + v * scale];
  };
  const dropLine = (p, color) => {
    const [u, v] = at(p);
    const [gu, gv] = at({ ...p, z: 0 });
    g.strokeStyle = color;
    g.setLineDash([3, 3]);
    g.beginPath();
    g.moveTo(u, v);
    g.lineTo(gu, gv);
    g.stroke();
    g.setLineDash([]);
  };
  g.font = "11px system-ui";
  const names = [...view.sites.values()].map((s) => {
    dropLine(s, COLORS.site);
    return drawSite(g, at(s), s.label.split(" ")[0]);
  });
  const layered = layeredEntities();
  drawTrails(g, at, layered);
  for (const e of layered) {
    if (e.trail) continue;
    if (e.layer === 2) dropLine(e, e.color);
    drawMarker(g, at(e), e);
  }
  drawSiteNames(g, names);
}

function enableTurning() {
  const canvas = document.getElementById("scene3d");
  let from = null;
  canvas.addEventListener("pointerdown", (e) => { from = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); });
  canvas.addEventListener("pointerup", () => { from = null; });
  canvas.addEventListener("pointermove", (e) => {
    if (!from) return;
    turn.yaw += (e.clientX - from[0]) * 0.01;
    turn.pitch = Math.min(Math.max(turn.pitch + (e.clientY - from[1]) * 0.01, 0), Math.PI / 2);
    from = [e.clientX, e.clientY];
    requestDraw();
  });
}

let plot = null;
let plotted = "";
// uPlot draws its series in legend order. The peers and the center agree to 1e-9 m, so the
// center's line goes last, wider and dashed, or the peers' would hide it.
function drawErrors() {
  const centerLast = (a, b) => (a === 0) - (b === 0) || a - b;
  const nodes = [...view.series.keys()].sort(centerLast);
  if (nodes.length === 0) return;
  const key = nodes.join(",");
  const center = view.series.get(0) ?? view.series.get(nodes[0]);
  const data = [center.steps, ...nodes.map((n) => {
    const s = view.series.get(n);
    return s.errors.slice(-center.steps.length);
  })];
  if (plot === null || key !== plotted) {
    plot?.destroy();
    plotted = key;
    plot = new uPlot({
      width: 600, height: 300, scales: { x: { time: false }, y: { distr: 3 } },
      // Away from the cursor the legend shows the latest round's errors, not dashes.
      hooks: { ready: [legendShowsLatest] },
      axes: [{ label: "step" }, { label: "position error (m)" }],
      series: [{ label: "step" }, ...nodes.map((n) => ({
        label: nodeName(n), stroke: n === 0 ? COLORS.center : COLORS.peer, width: n === 0 ? 2 : 1,
        dash: n === 0 ? [8, 6] : undefined,
      }))],
    }, data, document.getElementById("errors"));
  } else {
    plot.setData(data);
  }
  showLatestInLegend(plot);
}

// Row labels take the strip's left margin; with many stations only every few rows is named,
// so that names stay readable (at least STRIP_LABEL_PX apart).
const STRIP_LABEL_WIDTH = 64;
const STRIP_LABEL_PX = 11;
function drawStrip() {
  const [canvas, g] = clearedCanvas("strip");
  const rows = view.strip[0]?.length ?? 0;
  if (rows === 0) return;
  const w = (canvas.width - STRIP_LABEL_WIDTH) / STRIP_ROUNDS;
  const h = canvas.height / rows;
  const every = Math.ceil(STRIP_LABEL_PX / h);
  g.font = `${Math.min(11, Math.max(h, 8))}px system-ui, sans-serif`;
  g.textBaseline = "middle";
  g.fillStyle = "#555";
  view.stripNodes.forEach((node, row) => {
    if (row % every === 0) g.fillText(node === 0 ? "center" : `${node}`, 2, (row + 0.5) * h);
  });
  const fill = { all: "#4caf50", some: "#ff9800", none: "#e53935" };
  view.strip.forEach((round, i) => round.forEach((state, row) => {
    g.fillStyle = fill[state];
    g.fillRect(STRIP_LABEL_WIDTH + i * w, row * h, Math.max(w - 0.5, 1), Math.max(h - 1, 1));
  }));
}

function drawFigures() {
  document.getElementById("round-counter").textContent = view.round ?? "–";
  const seconds = view.firstRoundAt === null ? 0 : (performance.now() - view.firstRoundAt) / 1000;
  const rate = seconds > 0 ? (view.rounds / seconds).toFixed(0) : "–";
  const parts = view.recordingRounds ? [`${view.recordingRounds} rounds recorded`]
    : [`${rate} rounds/s received`];
  if (view.latencyMs !== null) parts.push(`round latency ${view.latencyMs.toFixed(2)} ms`);
  if (view.summary?.rmse_central_m !== undefined) {
    parts.push(`RMSE center ${view.summary.rmse_central_m.toFixed(3)} m, peers ${view.summary.rmse_p2p_m.toFixed(3)} m`);
  } else if (view.summary?.gospa_mean !== undefined) {
    parts.push(`GOSPA mean ${view.summary.gospa_mean.toFixed(2)}, peers ${view.summary.peers_identical ? "bit-identical" : "apart"} in every round`);
  }
  document.getElementById("figures").textContent = parts.join(" · ");
  if (view.modes) {
    document.getElementById("modes-section").hidden = false;
    const center = view.modes.tracks.find((t) => t.node === 0);
    if (center) {
      document.getElementById("modes").textContent = view.modes.modes
        .map((m, i) => `${m} ${center.probabilities[i].toFixed(3)}`).join(" · ");
    }
  }
}

function draw() {
  drawScene();
  drawScene3d();
  drawErrors();
  drawStrip();
  drawFigures();
  drawPicturePlots(view);
  drawRegistration(view);
}

// Drawn only when something changed, and at most DRAWS_PER_SECOND: a page open beside a run on
// the same cores takes what a display needs and no more (docs/view.md, what it costs).
const DRAWS_PER_SECOND = 10;
let drawPending = false;
let lastDrawAt = -Infinity;
function requestDraw() {
  if (drawPending) return;
  drawPending = true;
  const wait = Math.max(0, lastDrawAt + 1000 / DRAWS_PER_SECOND - performance.now());
  setTimeout(() => requestAnimationFrame(() => {
    drawPending = false;
    lastDrawAt = performance.now();
    if (!window.NODRAW) draw();
  }), wait);
}

// ---- the connection -------------------------------------------------------------------------

const handlers = {
  "/scene": onScene,
  "/stations": onStations,
  "/skyfuse/round": onRound,
  "/skyfuse/track_error": onTrackError,
  "/skyfuse/modes": (m) => { view.modes = m; },
  "/skyfuse/summary": (m) => { view.summary = m; },
  "/skyfuse/picture": (m) => onPicture(view, m),
  "/skyfuse/registration": (m) => onRegistration(view, m),
};

function resetView() {
  Object.assign(view, { round: null, rounds: 0, firstRoundAt: null, latencyMs: null,
    modes: null, summary: null, strip: [], stripNodes: [], picture: emptyPicture(),
    registration: null });
  view.entities.clear();
  view.series.clear();
}

// A recording: every message read once, then shown up to the slider's round. `name` is the
// file's own name, for the header.
async function loadRecording(url, name) {
  document.getElementById("source").textContent = `recording: ${name}`;
  const response = await fetch(url);
  if (!response.ok) throw new Error(`the server answered ${response.status} ${response.statusText}`);
  const bytes = new Uint8Array(await response.arrayBuffer());
  const reader = await McapIndexedReader.Initialize({ readable: {
    size: async () => BigInt(bytes.length),
    read: async (offset, length) => bytes.subarray(Number(offset), Number(offset + length)),
  } });
  const decoder = new TextDecoder();
  const messages = [];
  for await (const m of reader.readMessages()) {
    const topic = reader.channelsById.get(m.channelId).topic;
    if (handlers[topic]) messages.push({ time: m.logTime, topic, payload: JSON.parse(decoder.decode(m.data)) });
  }
  const roundTimes = messages.filter((m) => m.topic === "/skyfuse/round").map((m) => m.time);
  const slider = document.getElementById("time");
  slider.max = String(roundTimes.length - 1);
  slider.value = slider.max;
  const showUpTo = (index) => {
    resetView();
    // At the end, the summary (logged after the last round) too.
    const last = index === roundTimes.length - 1;
    const until = roundTimes[index];
    for (const m of messages) {
      if (!last && m.time > until) break;
      handlers[m.topic](m.payload);
    }
  };
  slider.oninput = () => {
    showUpTo(Number(slider.value));
    requestDraw();
  };
  document.getElementById("slider").hidden = false;
  showUpTo(roundTimes.length - 1);
  view.recordingRounds = roundTimes.length;
  requestDraw();
}

function connect() {
  const ws = new WebSocket(`ws://${location.host}/`, [SUBPROTOCOL]);
  ws.binaryType = "arraybuffer";
  const topicOfSubscription = new Map();
  const decoder = new TextDecoder();
  ws.onopen = () => { document.getElementById("source").textContent = `live: ws://${location.host}`; };
  ws.onclose = () => {
    document.getElementById("source").textContent = "live stream ended";
    requestDraw();
  };
  ws.onmessage = (event) => {
    if (typeof event.data === "string") {
      const message = JSON.parse(event.data);
      if (message.op === "advertise") {
        // Only the channels the page draws: each message costs the browser a task.
        const subscriptions = message.channels.filter((c) => handlers[c.topic]).map((c, i) => {
          topicOfSubscription.set(i, c.topic);
          return { id: i, channelId: c.id };
        });
        ws.send(JSON.stringify({ op: "subscribe", subscriptions }));
      }
      return;
    }
    if (window.NOMSG) return;
    const bytes = new DataView(event.data);
    if (bytes.getUint8(0) !== 1) return;
    const topic = topicOfSubscription.get(bytes.getUint32(1, true));
    const handler = handlers[topic];
    if (!handler) return;
    handler(JSON.parse(decoder.decode(new Uint8Array(event.data, 13))));
    requestDraw();
  };
}

// `skyfuse view` checked the file before serving it; if it changed since, or cannot be read
// after all, the header says so instead of showing an empty page.
function showRecording(url, name) {
  loadRecording(url, name).catch((error) => {
    const source = document.getElementById("source");
    source.textContent = `recording ${name} cannot be shown: ${error.message ?? error}`;
    source.classList.add("failed");
    view.recordingError = source.textContent;
  });
}

const query = new URLSearchParams(location.search);
const recording = query.get("recording");
if (recording) showRecording(recording, query.get("name") ?? recording); else connect();
enableTurning();
requestDraw();
