// One source for units and labels: the page's physical controls (label, unit, help) and its
// advanced panel (key [unit], tooltip) show what the served scene schema says (title, x-unit,
// description), and the schema is the engine's field table (tests/codec: SceneFieldsCodec). Fails
// on any drift between the UI and the schema, for a rigid scene and for a deforming one.
// Usage: node units.test.mjs SPINFOLD_BINARY
import assert from "node:assert/strict";

import { runSuite, startServer, test } from "./harness.mjs";

const [binary] = process.argv.slice(2);
const started = startServer(binary, 26000);
const { base } = started;

// The schema of a scene field by its dotted path (a deformation field: the abc branch's).
function schemaField(schema, path) {
  const [section, ...rest] = path.split(".");
  let spec = schema.properties[section];
  for (const key of rest) {
    if (key !== "deformation" && spec.oneOf) spec = spec.oneOf.find((b) => b.properties?.kind?.const === "abc");
    spec = spec?.properties?.[key];
  }
  return spec;
}
// The page's rule for showing a unit: a pure number says so, an angle is shown in degrees.
const shown = (unit) => ({ "1": "pure number", rad: "degrees" })[unit] ?? unit;

// The physical rows as rendered: field, label, unit, help, and whether derived (greyed).
const physicalRows = (page) => page.$$eval("#physical .phys[data-key]", (rows) => rows.map((row) => ({
  key: row.dataset.key, field: row.dataset.field, label: row.querySelector("label").textContent,
  unit: row.querySelector(".unit").textContent, help: row.querySelector(".help").textContent,
  title: row.querySelector('input.number').title,
})));

function checkPhysical(schema, rows) {
  let checked = 0;
  for (const row of rows) {
    if (row.key === "scale") { assert.equal(row.field, undefined); continue; }  // the picture's, not the scene's
    assert.ok(row.field, `physical row ${row.key} names no scene field`);
    const spec = schemaField(schema, row.field);
    assert.ok(spec, `${row.field} is not in the schema`);
    assert.ok(spec.title && spec["x-unit"] && spec.description, `${row.field}: title, x-unit and description`);
    assert.equal(row.label.replace(/ ↺$/, ""), spec.title, `${row.field}: label`);
    assert.equal(row.unit, shown(spec["x-unit"]), `${row.field}: unit`);
    assert.ok(row.help.endsWith(spec.description), `${row.field}: help "${row.help}" vs "${spec.description}"`);
    assert.equal(row.title, row.help, `${row.field}: tooltip`);
    ++checked;
  }
  return checked;
}

async function checkAdvanced(page, schema) {
  const fields = await page.$$eval("#controls .field", (rows) => rows.map((row) => ({
    name: row.querySelector("input, select").name, label: row.querySelector("label").textContent,
    title: row.querySelector("input, select").title,
  })));
  let numbers = 0;
  for (const f of fields) {
    const spec = f.name === "potential.deformation.kind" ? null : schemaField(schema, f.name);
    if (!spec || !spec["x-unit"]) continue;
    const key = f.name.split(".").at(-1);
    assert.equal(f.label, spec["x-unit"] === "1" ? key : `${key} [${spec["x-unit"]}]`, `${f.name}: label`);
    assert.equal(f.title, spec.description, `${f.name}: tooltip`);
    ++numbers;
  }
  return numbers;
}

await runSuite(started, async (browser) => {
  const schema = await (await fetch(base + "api/v1/schema")).json();
  const page = await browser.newPage({ viewport: { width: 1366, height: 900 }, bypassCSP: true });
  await page.goto(base);
  await page.waitForSelector("body[data-ready=true]", { timeout: 20000 });

  await test("rigid scene: every physical and advanced control shows the schema's label, unit and help", async () => {
    const rows = await physicalRows(page);
    assert.ok(checkPhysical(schema, rows) >= 7, JSON.stringify(rows));
    assert.ok(await checkAdvanced(page, schema) >= 20);
  });

  await test("deforming scene: the stretches and the shape spring C too; C is an energy (λ, μ pure numbers)", async () => {
    await page.click('.preset[data-name="breathing_ellipse_sphere"]');
    await page.waitForFunction(() => document.querySelector(".preset.active")?.dataset.name === "breathing_ellipse_sphere");
    await page.waitForSelector('#physical [data-key="C"]');
    const rows = await physicalRows(page);
    assert.ok(checkPhysical(schema, rows) >= 9);
    assert.ok(await checkAdvanced(page, schema) >= 20);
    const unit = (key) => rows.find((r) => r.key === key).unit;
    assert.equal(unit("C"), "energy");
    assert.equal(unit("mu"), "pure number");
    assert.equal(unit("gamma"), "energy (sphere); energy·length² (pseudosphere, plane)");
  });
});
