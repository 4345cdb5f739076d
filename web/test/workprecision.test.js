// The work-precision panel's one rule of its own (web/workprecision.js): a recommendation already in
// force is said, not offered (issue 34: the panel proposed the setting in force).
import assert from "node:assert/strict";
import { test } from "node:test";
import { alreadyInForce } from "../workprecision.js";

test("a recommended integrator is in force when each of its fields has the value in force", () => {
  const inForce = { name: "dop853", tol: 1e-10, max_steps: 1000000 };
  assert.equal(alreadyInForce({ name: "dop853", tol: 1e-10 }, inForce), true);
  assert.equal(alreadyInForce({ name: "dop853", tol: 1e-8 }, inForce), false);
  assert.equal(alreadyInForce({ name: "auto", tol: 1e-10 }, inForce), false);
  assert.equal(alreadyInForce({ name: "rk4", dt: 0.01 }, inForce), false, "a field not in force");
  assert.equal(alreadyInForce({ name: "dop853" }, undefined), false, "nothing known in force");
});
