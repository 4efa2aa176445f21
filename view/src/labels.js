// Where a track's label goes on the scene: beside its marker, on the first side where it covers
// no label already placed in this drawing — right, left, above, below — so that the labels of
// tracks that crowd together stay readable. Where every side is taken it goes on the right
// anyway: every track keeps its label.

export const LABEL_HEIGHT = 11;  // px: the scene's font

function overlaps(a, b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

// The box of a text `width` px wide whose left end and baseline are at (x, y).
export function labelBox(x, y, width, height = LABEL_HEIGHT) {
  return { x0: x, y0: y - height, x1: x + width, y1: y };
}

// The text's left end and baseline for a label `width` × `height` (px) beside a marker at (u, v);
// the label's box is added to `placed`.
export function placeLabel(placed, u, v, width, height) {
  const sides = [
    [u + 6, v + 4],                     // right, as a label was always drawn
    [u - 6 - width, v + 4],             // left
    [u - width / 2, v - 8],             // above
    [u - width / 2, v + 8 + height],    // below
  ];
  const boxOf = ([x, y]) => labelBox(x, y, width, height);
  const free = sides.find((side) => !placed.some((box) => overlaps(box, boxOf(side))));
  const chosen = free ?? sides[0];
  placed.push(boxOf(chosen));
  return chosen;
}
