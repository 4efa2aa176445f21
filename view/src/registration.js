// The page's view of a registered run's bias estimates (docs/registration.md): the latest
// /skyfuse/registration message as a table, each station's entries beside their truths with the
// 2σ band, and whether the truth lies in it. Shown only when the run registers its stations.

// Units as the entries are named: radians and seconds read better in mrad and ms.
const SHOWN = { range_m: ["range", 1, "m"], azimuth_rad: ["azimuth", 1000, "mrad"],
  elevation_rad: ["elevation", 1000, "mrad"], time_s: ["clock", 1000, "ms"] };

export function onRegistration(view, m) {
  view.registration = m;
}

function cell(row, text, className) {
  const td = row.insertCell();
  td.textContent = text;
  if (className) td.className = className;
}

export function drawRegistration(view) {
  const m = view.registration;
  const section = document.getElementById("registration-section");
  if (!m) {
    section.hidden = true;
    return;
  }
  section.hidden = false;
  document.getElementById("registration-step").textContent = `step ${m.step}`;
  const body = document.getElementById("registration").tBodies[0];
  body.replaceChildren();
  for (const station of m.stations) {
    for (const e of station.entries) {
      const [name, scale, unit] = SHOWN[e.entry] ?? [e.entry, 1, ""];
      const row = body.insertRow();
      row.dataset.station = String(station.station);
      row.dataset.entry = e.entry;
      cell(row, String(station.station));
      cell(row, `${name} (${unit})`);
      cell(row, (e.truth * scale).toFixed(3));
      cell(row, `${(e.estimate * scale).toFixed(3)} ± ${(2 * e.sigma * scale).toFixed(3)}`);
      cell(row, e.within_2sigma ? "yes" : "no", e.within_2sigma ? "all" : "none");
    }
  }
}
