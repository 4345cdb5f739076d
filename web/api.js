// @ts-check
// Requests to the HTTP API: the requests, the server's problem+json errors, and waiting out a full server.

export const api = "/api/v1";

export const sleep = (/** @type {number} */ ms) => new Promise((resolve) => setTimeout(resolve, ms));

/** An answer that is not 2xx: the server's problem+json (title, detail, field) and its status. */
export class ProblemError extends Error {
  /**
   * @param {{title?: string, detail?: string, [key: string]: any}} problem
   * @param {number} status
   * @param {number} retryAfter seconds (Retry-After), 0 when not given
   */
  constructor(problem, status, retryAfter) {
    super(problem.detail || problem.title || `HTTP ${status}`);
    this.problem = problem;
    this.status = status;
    this.retryAfter = retryAfter;
  }
}

/**
 * A JSON request under /api/v1: its answer's JSON, null for 204, a ProblemError otherwise.
 * A PATCH body is a JSON merge patch.
 * @param {string} method
 * @param {string} path under /api/v1
 * @param {any} [body]
 * @returns {Promise<any>}
 */
export async function request(method, path, body) {
  /** @type {RequestInit & {headers: Record<string, string>}} */
  const options = { method, headers: {} };
  if (body !== undefined) {
    options.headers["Content-Type"] = method === "PATCH" ? "application/merge-patch+json" : "application/json";
    options.body = JSON.stringify(body);
  }
  const res = await fetch(api + path, options);
  if (res.status === 204) return null;
  const data = await res.json().catch(() => ({ title: res.statusText }));
  if (!res.ok) throw new ProblemError(data, res.status, Number(res.headers.get("Retry-After")) || 0);
  return data;
}

/** @typedef {{show: (text: string) => void, hide: () => void}} BusyReport */

/** @type {BusyReport} */
let busy = { show: () => {}, hide: () => {} };
/** @type {(() => void) | null} */
let skipWait = null;

/**
 * Where withRetry says that the server is full (the page's banner).
 * @param {BusyReport} report
 */
export function reportBusyTo(report) {
  busy = report;
}

/** Ends the current wait of withRetry at once ("Try now"). */
export function retryNow() {
  if (skipWait) skipWait();
}

/**
 * The action, tried again while the server is full (429 or 503): waits its Retry-After or
 * 1, 2, 4 … 30 s, whichever is longer, counting down in the busy report.
 * @template T
 * @param {string} what what is being tried ("Opening the scene")
 * @param {() => Promise<T>} action
 * @returns {Promise<T>}
 */
export async function withRetry(what, action) {
  for (let attempt = 0; ; attempt++) {
    try {
      const result = await action();
      busy.hide();
      return result;
    } catch (e) {
      if (!(e instanceof ProblemError) || (e.status !== 429 && e.status !== 503)) throw e;
      const wait = Math.min(30, Math.max(e.retryAfter || 0, 2 ** Math.min(attempt, 5)));
      for (let left = wait; left > 0; left--) {
        busy.show(`The server is full (${e.message}). ${what}: trying again in ${left} s.`);
        const skipped = await Promise.race([
          sleep(1000).then(() => false),
          new Promise((resolve) => (skipWait = () => resolve(true))),
        ]);
        if (skipped) break;
      }
      busy.show(`${what}: trying again now…`);
    }
  }
}
