// The page's view of a run of many aircraft (docs/view.md): the tracks coloured by status with
// their ids, the last scan's detections of every station (false alarms in red), the aircraft,
// a GOSPA plot and the count of tracks against aircraft. main.js hands this module the scene's
// entities it recognises and the /skyfuse/picture messages.
import uPlot from "uplot";
import { LABEL_HEIGHT, placeLabel } from "./labels.js";
import { legendShowsLatest, showLatestInLegend } from "./plots.js";

const PICTURE_COLORS = { confirmed: "#3373e6", tentative: "#f2b31a", aircraft: "#26b340",
  detection: "#59596680", falseAlarm: "#d93333a0" };

export function emptyPicture() {
  return { steps: [], gospa: [], aircraft: [], confirmed: [], tentative: [], last: null,
    detections: new Map() };  // scan entity id -> [{x, y, z, falseAlarm}]
}

function rgba(c) {
  return `rgba(${Math.round(c.r * 255)}, ${Math.round(c.g * 255)}, ${Math.round(c.b * 255)}, ${c.a})`;
}

// A scene entity of a picture, or false for one of a run of one aircraft. A track's entity has
// its position and ellipsoid (spheres), its label and, every few rounds, its trail.
export function onPictureEntity(view, e, ellipseOf) {
  if (e.id.startsWith("scan/")) {
    view.picture.detections.set(e.id, e.cubes.map((c) => ({ ...c.pose.position, falseAlarm: c.color.r > 0.6 })));
    return true;
  }
  const track = e.id.startsWith("track/");
  if (!track && !e.id.startsWith("aircraft/")) return false;
  const p = e.spheres[0].pose.position;
  const color = track ? rgba({ ...e.spheres[0].color, a: 1 }) : PICTURE_COLORS.aircraft;
  view.entities.set(e.id, { x: p.x, y: p.y, z: p.z, color, layer: track ? 0 : 2,
    label: e.texts[0]?.text, ellipse: e.spheres.length > 1 ? ellipseOf(e.spheres[1]) : null });
  if (e.lines.length > 0) view.entities.set(`${e.id}/trail`, { trail: e.lines[0].points, color, layer: 0 });
  return true;
}

export function onPictureDeletion(view, id) {
  view.entities.delete(id);
  view.entities.delete(`${id}/trail`);
}

export function onPicture(view, m) {
  const p = view.picture;
  p.last = m;
  p.steps.push(m.step);
  p.gospa.push(m.gospa);
  p.aircraft.push(m.aircraft);
  p.confirmed.push(m.confirmed);
  p.tentative.push(m.tentative);
}

// Every station's detections of the last scan: small crosses, grey, red for false alarms.
export function drawDetections(g, at, view) {
  for (const points of view.picture.detections.values()) {
    for (const d of points) {
      const [u, v] = at(d);
      g.strokeStyle = d.falseAlarm ? PICTURE_COLORS.falseAlarm : PICTURE_COLORS.detection;
      g.lineWidth = 1;
      g.beginPath();
      g.moveTo(u - 3, v - 3); g.lineTo(u + 3, v + 3);
      g.moveTo(u - 3, v + 3); g.lineTo(u + 3, v - 3);
      g.stroke();
    }
  }
}

// `placed`: the boxes of the labels drawn so far in this drawing (labels.js).
export function drawTrackLabel(g, [u, v], e, placed) {
  if (!e.label) return;
  const [x, y] = placeLabel(placed, u, v, g.measureText(e.label).width, LABEL_HEIGHT);
  g.fillStyle = e.color;
  g.fillText(e.label, x, y);
}

const plots = { gospa: null, counts: null };

function plotInto(name, element, options, data) {
  if (plots[name] === null) {
    plots[name] = new uPlot({ width: 600, height: 220, scales: { x: { time: false } },
      hooks: { ready: [legendShowsLatest] }, ...options }, data, element);
  } else {
    plots[name].setData(data);
  }
  showLatestInLegend(plots[name]);
}

// The GOSPA of the first station's confirmed tracks, and the tracks against the aircraft present.
export function drawPicturePlots(view) {
  const p = view.picture;
  if (p.steps.length === 0) return;
  document.getElementById("picture-section").hidden = false;
  document.getElementById("errors-section").hidden = true;  // a run of one aircraft's
  document.getElementById("run-legend").hidden = true;
  document.getElementById("picture-legend").hidden = false;
  plotInto("gospa", document.getElementById("gospa"), {
    axes: [{ label: "step" }, { label: "GOSPA (m)" }],
    series: [{ label: "step" }, { label: "GOSPA", stroke: "#7b1fa2", width: 1.5 }],
  }, [p.steps, p.gospa]);
  plotInto("counts", document.getElementById("counts"), {
    axes: [{ label: "step" }, { label: "count" }],
    series: [{ label: "step" },
      { label: "aircraft", stroke: PICTURE_COLORS.aircraft, width: 2 },
      { label: "confirmed tracks", stroke: PICTURE_COLORS.confirmed, width: 1.5 },
      { label: "tentative tracks", stroke: PICTURE_COLORS.tentative, width: 1 }],
  }, [p.steps, p.aircraft, p.confirmed, p.tentative]);
  const last = p.last;
  document.getElementById("picture-figures").textContent =
    `step ${last.step}: ${last.confirmed} confirmed and ${last.tentative} tentative tracks, ` +
    `${last.aircraft} aircraft; GOSPA ${last.gospa.toFixed(1)} m; ${last.detections} detections ` +
    `(${last.false_alarms} false alarms); peers ${last.peers_agree ? "agree" : "apart"} (digest ${last.digest})`;
}
