// @ts-check
// A background job on the server followed from a panel (a recording, a work-precision
// measurement), one way for all: a POST starts it and answers with its url; GET url is polled for
// its status and progress until it is done, failed or cancelled (or gone: an expired or unknown job
// answers with a problem, whose detail is said); DELETE url cancels it. The panel gives its
// buttons, its progress bar, its status line and what to say and show; no physics here.

/**
 * A job's status as GET url answers it (the fields every job has; each kind adds its own).
 * @typedef {{url: string, status: "queued" | "running" | "done" | "failed" | "cancelled",
 *   progress: number, reason?: string, [field: string]: any}} Job
 */

/**
 * The panel of a kind of job.
 * @typedef {object} JobPanel
 * @property {HTMLButtonElement} start the button that starts a job (disabled while one runs)
 * @property {HTMLButtonElement} cancel shown while a job runs
 * @property {HTMLProgressElement} progress the job's progress, 0…1
 * @property {(text: string) => void} say the panel's status line
 * @property {number} every the polling interval, ms
 * @property {string} queued what a job waiting for another one says
 * @property {(job: Job) => string} running what a running job says
 * @property {(job: Job) => string} done shows a finished job's result; what the status line says
 * @property {boolean} [hideProgress] the progress bar goes when the job ends or fails to start
 */

/**
 * The jobs of one panel: one followed at a time (a job started later replaces the one followed).
 * @param {JobPanel} panel
 * @returns {{start: (url: string, body: () => any) => Promise<void>, cancel: () => Promise<void>}}
 */
export function jobs(panel) {
  /** @type {string | null} */
  let current = null; // the job followed now: its url

  const ended = () => {
    panel.start.disabled = false;
    if (panel.hideProgress) panel.progress.hidden = true;
  };

  /** @param {string} url */
  async function follow(url) {
    for (;;) {
      if (current !== url) return;
      const res = await fetch(url);
      const job = await res.json();
      if (!res.ok) {
        panel.say(job.detail || job.title);
        break;
      }
      panel.progress.value = job.progress;
      if (job.status === "queued") panel.say(panel.queued);
      else if (job.status === "running") panel.say(panel.running(job));
      else {
        if (job.status === "done") panel.say(panel.done(job));
        else panel.say(job.status === "failed" ? `Failed: ${job.reason}` : "Cancelled.");
        break;
      }
      await new Promise((resolve) => setTimeout(resolve, panel.every));
    }
    ended();
    panel.cancel.hidden = true;
  }

  return {
    /** Starts a job: POST `url` with `body()`, then follows it to its end. */
    async start(url, body) {
      panel.progress.hidden = false;
      panel.progress.value = 0;
      panel.start.disabled = true;
      panel.say("Starting…");
      try {
        const res = await fetch(url, {
          method: "POST",
          headers: { "Content-Type": "application/json" },
          body: JSON.stringify(body()),
        });
        const job = await res.json();
        if (!res.ok) throw new Error(job.detail || job.title);
        current = job.url;
        panel.cancel.hidden = false;
        await follow(job.url);
      } catch (e) {
        panel.say(/** @type {Error} */ (e).message);
        ended();
      }
    },
    /** Cancels the job followed (its status then says so). */
    async cancel() {
      if (current) await fetch(current, { method: "DELETE" });
    },
  };
}
