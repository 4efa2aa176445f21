// What the page's plots share.

// Away from the cursor a uPlot legend shows the latest point's values, not dashes.
export function showLatestInLegend(u) {
  const last = u.data[0].length - 1;
  if (u.cursor.idx == null && last >= 0) u.setLegend({ idx: last });
}

// A plot's `ready` hook: a legend set before the plot is ready is reset, so the latest values
// go in from here, and again whenever the cursor leaves the plot.
export function legendShowsLatest(u) {
  showLatestInLegend(u);
  u.over.addEventListener("mouseleave", () => showLatestInLegend(u));
}
