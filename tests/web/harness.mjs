// What every browser test needs, once: Debian's Chromium through playwright-core, a spinfold
// server of the test's own on a port of its own, and the ok/FAIL lines with the exit status.
import { spawn } from "node:child_process";
import { createRequire } from "node:module";
import path from "node:path";
import { fileURLToPath } from "node:url";

const require = createRequire(path.join(path.dirname(fileURLToPath(import.meta.url)), "../../web/package.json"));
const { chromium } = require("playwright-core");

// `spinfold serve` on portBase + pid % 1000 (each test file its own base, so they can run side
// by side); `base` is its URL.
export function startServer(binary, portBase) {
  const port = portBase + (process.pid % 1000);
  const server = spawn(binary, ["serve", "--port", String(port), "--no-store"], { stdio: ["ignore", "pipe", "inherit"] });
  const base = `http://127.0.0.1:${port}/`;
  const ready = async () => {
    for (let i = 0; i < 100; ++i) {
      try { if ((await fetch(base + "api/v1/health")).ok) return; } catch (e) { /* not yet */ }
      await new Promise((r) => setTimeout(r, 100));
    }
    throw new Error("server did not start");
  };
  return { server, base, ready };
}

// Headless Chromium without the network chatter of a desktop browser.
export const launchBrowser = () =>
  chromium.launch({
    executablePath: "/usr/bin/chromium",
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
           "--disable-background-networking", "--disable-component-update", "--disable-sync"],
  });

// The outcome of a file's tests: any failure makes the process exit 1.
export const results = { failed: false };

// WEB_TEST_ONLY=text runs only the tests whose names contain it (while working on one).
export async function test(name, body) {
  if (process.env.WEB_TEST_ONLY && !name.includes(process.env.WEB_TEST_ONLY)) return;
  try {
    await body();
    console.log(`ok   ${name}`);
  } catch (e) {
    results.failed = true;
    console.log(`FAIL ${name}\n${e.stack}`);
  }
}

// A test file's run: waits for its server, gives `body` a browser, and exits 1 on any failure (a
// test() that failed or an error thrown outside one), the server stopped either way.
export async function runSuite({ server, ready }, body) {
  try {
    await ready();
    const browser = await launchBrowser();
    await body(browser);
    await browser.close();
  } catch (e) {
    results.failed = true;
    console.log(e.stack);
  } finally {
    server.kill();
  }
  process.exit(results.failed ? 1 : 0);
}
