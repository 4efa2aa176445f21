// The scene's label placement (src/labels.js): labels of tracks that crowd together go to
// another side of their marker rather than over each other, and every track keeps one.
import assert from "node:assert/strict";
import { test } from "node:test";
import { placeLabel } from "../src/labels.js";

const overlap = (a, b) => a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;

test("a lone label sits right of its marker, as before", () => {
  const placed = [];
  assert.deepEqual(placeLabel(placed, 100, 50, 24, 11), [106, 54]);
  assert.equal(placed.length, 1);
});

test("four tracks on one spot take four sides, no label over another", () => {
  const placed = [];
  const spots = [0, 1, 2, 3].map(() => placeLabel(placed, 200, 200, 24, 11));
  assert.equal(new Set(spots.map(String)).size, 4);
  for (let i = 0; i < placed.length; ++i) {
    for (let j = i + 1; j < placed.length; ++j) assert.ok(!overlap(placed[i], placed[j]), `${i} over ${j}`);
  }
});

test("a fifth on the same spot still gets its label, on the right", () => {
  const placed = [];
  for (let i = 0; i < 4; ++i) placeLabel(placed, 200, 200, 24, 11);
  assert.deepEqual(placeLabel(placed, 200, 200, 24, 11), [206, 204]);
  assert.equal(placed.length, 5);
});

test("tracks far apart keep the right side", () => {
  const placed = [];
  assert.deepEqual(placeLabel(placed, 10, 10, 24, 11), [16, 14]);
  assert.deepEqual(placeLabel(placed, 300, 300, 24, 11), [306, 304]);
});
