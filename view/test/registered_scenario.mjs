// scenarios/registration.yaml with the tracker estimating its stations' biases
// (docs/registration.md), written into `dir`: the registered run the view's tests record.
import { readFileSync, writeFileSync } from "node:fs";
import { join } from "node:path";

export function registeredScenario(scenarios, dir) {
  const path = join(dir, "registered.yaml");
  const text = readFileSync(join(scenarios, "registration.yaml"), "utf8");
  const registered = text.replace(/\ntracker:\n/, "\ntracker:\n  registration: {kind: least_squares}\n");
  if (registered === text) throw new Error("registration.yaml has no 'tracker:' block to register in");
  writeFileSync(path, registered);
  return path;
}
