// The served API description checked by a validator that shares no code with the server:
// @seriousme/openapi-schema-validator (the OpenAPI Initiative's published JSON Schemas for 3.0,
// 3.1 and 3.2, run by Ajv; offline once installed). Fetches openapi.json from a `spinfold serve`
// of its own, or reads a file given with --file (to check a saved document).
// Usage: node openapi_validate.mjs <spinfold binary> | --file <openapi.json>
import { readFileSync } from "node:fs";
import { createRequire } from "node:module";
import path from "node:path";
import { fileURLToPath } from "node:url";
import { results, startServer, test } from "./harness.mjs";

const require = createRequire(path.join(path.dirname(fileURLToPath(import.meta.url)), "../../web/package.json"));
const { Validator } = await import(require.resolve("@seriousme/openapi-schema-validator"));
const Ajv2020 = require("ajv/dist/2020").default;

let doc;
let server, base;
if (process.argv[2] === "--file") {
  doc = JSON.parse(readFileSync(process.argv[3], "utf8"));
} else {
  const started = startServer(process.argv[2], 24000);
  server = started.server;
  await started.ready();
  base = started.base;
  const res = await fetch(base + "api/v1/openapi.json");
  doc = await res.json();
}

try {
  await test("the served document is valid OpenAPI (independent validator)", async () => {
    const validator = new Validator();
    const verdict = await validator.validate(doc);
    const errors = verdict.errors ?? [];
    console.log(`openapi ${doc.openapi}: ${verdict.valid ? "valid" : "invalid"}, ${errors.length} errors`);
    for (const e of errors.slice(0, 20)) console.log(`  ${e.instancePath} ${e.message} ${JSON.stringify(e.params)}`);
    if (!verdict.valid) throw new Error(`${errors.length} validation errors`);
    if (validator.version !== "3.1") throw new Error(`validated as OpenAPI ${validator.version}, 3.1 expected`);
  });

  await test("every operation has a unique snake_case operationId", async () => {
    const ids = [];
    for (const [p, item] of Object.entries(doc.paths))
      for (const [method, op] of Object.entries(item)) {
        if (!/^[a-z]+(_[a-z0-9]+)*$/.test(op.operationId ?? "")) throw new Error(`${method} ${p}: operationId ${op.operationId}`);
        ids.push(op.operationId);
      }
    if (new Set(ids).size !== ids.length) throw new Error(`duplicate operationIds: ${ids.join(" ")}`);
  });
  // The OpenAPI schema leaves Schema Objects to the dialect (jsonSchemaDialect): check each against
  // the JSON Schema 2020-12 meta-schema (Ajv's copy), which the validator above does not do.
  await test("every Schema Object is valid JSON Schema 2020-12", async () => {
    const ajv = new Ajv2020({ strict: false });
    const schemas = Object.entries(doc.components.schemas).map(([name, s]) => [`components.schemas.${name}`, s]);
    for (const [p, item] of Object.entries(doc.paths))
      for (const [method, op] of Object.entries(item)) {
        for (const param of op.parameters ?? []) schemas.push([`${method} ${p} ${param.name}`, param.schema]);
        for (const [type, c] of Object.entries(op.requestBody?.content ?? {})) schemas.push([`${method} ${p} body ${type}`, c.schema]);
        for (const [status, r] of Object.entries(op.responses)) {
          for (const [type, c] of Object.entries(r.content ?? {})) schemas.push([`${method} ${p} ${status} ${type}`, c.schema]);
          for (const [name, h] of Object.entries(r.headers ?? {})) schemas.push([`${method} ${p} ${status} ${name}`, h.schema]);
        }
      }
    for (const [where, schema] of schemas)
      if (!ajv.validateSchema(schema)) throw new Error(`${where}: ${ajv.errorsText(ajv.errors)}`);
    console.log(`  ${schemas.length} schemas checked`);
  });

  // The Problem schema is what the server sends: real errors validate against it.
  if (base)
    await test("the server's errors are application/problem+json of the Problem schema", async () => {
      const problem = new Ajv2020({ strict: false }).compile(doc.components.schemas.Problem);
      // Once more when the transport fails: fetch reuses a kept-alive connection that the server may
      // have closed while the schemas above were checked (its keep-alive timeout is 5 s).
      const fetch = (url, init) => globalThis.fetch(url, init).catch(() => globalThis.fetch(url, init));
      const answers = [
        await fetch(base + "api/v1/sessions/no-such-session"),
        await fetch(base + "api/v1/sessions", { method: "POST", headers: { "Content-Type": "application/json" }, body: '{"preset": 5}' }),
        await fetch(base + "api/v1/sessions", { method: "POST", headers: { "Content-Type": "application/json" }, body: "{" }),
        await fetch(base + "api/v1/scenes?nonsense=1"),
        await fetch(base + "api/v1/scenes", { method: "DELETE" }),
      ];
      for (const res of answers) {
        const declared = doc.paths[new URL(res.url).pathname.replace(/sessions\/[^/]+$/, "sessions/{id}")];
        if (res.status < 400) throw new Error(`${res.url}: ${res.status}, an error expected`);
        if (res.headers.get("content-type") !== "application/problem+json") throw new Error(`${res.url}: ${res.headers.get("content-type")}`);
        const body = await res.json();
        if (!problem(body)) throw new Error(`${res.url} ${res.status}: ${JSON.stringify(problem.errors)} in ${JSON.stringify(body)}`);
        if (!declared) throw new Error(`${res.url}: path not in the document`);
      }
    });

  // Every error answer the document declares says so.
  await test("every error response is declared as problem+json with the shared Problem schema", async () => {
    let errors = 0;
    for (const [p, item] of Object.entries(doc.paths))
      for (const [method, op] of Object.entries(item))
        for (const [status, r] of Object.entries(op.responses)) {
          if (Number(status) < 400) continue;
          ++errors;
          const ref = r.content?.["application/problem+json"]?.schema?.$ref;
          if (ref !== "#/components/schemas/Problem") throw new Error(`${method} ${p} ${status}: ${JSON.stringify(r)}`);
        }
    if (errors === 0) throw new Error("no error responses declared");
    if (!Array.isArray(doc.security) || doc.security.length !== 0) throw new Error(`security: ${JSON.stringify(doc.security)}`);
    if (!/capabilit/.test(doc.info.description ?? "")) throw new Error("info.description does not say that ids are capabilities");
  });
} finally {
  server?.kill();
}
process.exit(results.failed ? 1 : 0);
