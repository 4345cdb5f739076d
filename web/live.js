// @ts-check
// The live view: one connection per viewer (GET …/live, multipart/x-mixed-replace), parsed here so
// that only the newest frame is decoded and each decoded frame is painted once, at the display's
// refresh. Camera and view changes steer the same stream (PATCH …/live?viewer=), one request in
// flight and the latest waiting.
const boundary = "--spinfold-frame\r\n";
const decoder = new TextDecoder();

/**
 * The index of `pattern` in `bytes` from `from`, or −1.
 * @param {Uint8Array} bytes @param {Uint8Array} pattern @param {number} from
 */
function indexOf(bytes, pattern, from) {
  outer: for (let i = from; i + pattern.length <= bytes.length; i++) {
    for (let j = 0; j < pattern.length; j++) if (bytes[i + j] !== pattern[j]) continue outer;
    return i;
  }
  return -1;
}
const headEnd = new TextEncoder().encode("\r\n\r\n");

// Frames out of a multipart/x-mixed-replace body, as they complete: {type, info, bytes}.
/** @typedef {Record<string, string>} FrameInfo the X-Spinfold-Frame header's fields (seq, version, t, kind, …) */
/** @typedef {{type: string, info: FrameInfo, bytes: Uint8Array}} Part */
class MultipartParser {
  constructor() {
    this.buffer = new Uint8Array(0);
  }
  /**
   * @param {Uint8Array} chunk
   * @returns {Part[]}
   */
  push(chunk) {
    const joined = new Uint8Array(this.buffer.length + chunk.length);
    joined.set(this.buffer);
    joined.set(chunk, this.buffer.length);
    this.buffer = joined;
    const parts = [];
    for (;;) {
      const end = indexOf(this.buffer, headEnd, 0);
      if (end < 0) break;
      const head = decoder.decode(this.buffer.subarray(0, end));
      if (!head.startsWith(boundary)) throw new Error("live stream: not a part: " + head.slice(0, 40));
      /** @type {Record<string, string>} */
      const headers = {};
      for (const line of head.slice(boundary.length).split("\r\n")) {
        const colon = line.indexOf(":");
        if (colon > 0) headers[line.slice(0, colon).toLowerCase()] = line.slice(colon + 1).trim();
      }
      const length = Number(headers["content-length"]);
      if (this.buffer.length < end + 4 + length + 2) break;
      /** @type {FrameInfo} */
      const info = {};
      for (const item of (headers["x-spinfold-frame"] || "").split("; ")) {
        const eq = item.indexOf("=");
        if (eq > 0) info[item.slice(0, eq)] = item.slice(eq + 1);
      }
      parts.push({ type: headers["content-type"], info, bytes: this.buffer.slice(end + 4, end + 4 + length) });
      this.buffer = this.buffer.slice(end + 4 + length + 2);
    }
    return parts;
  }
}

export class LiveView {
  // canvas: where frames are painted; its width and height are the frames'.
  /** @param {HTMLCanvasElement} canvas */
  constructor(canvas) {
    this.canvas = canvas;
    this.context = /** @type {CanvasRenderingContext2D} */ (canvas.getContext("2d"));
    this.stats = { received: 0, decoded: 0, painted: 0, skipped: 0 };
    /** @type {((info: FrameInfo) => void) | null} */
    this.onPaint = null; // (info) after a frame is painted
    /** @type {(() => void) | null} */
    this.onGone = null; // () when the server no longer knows the session (404)
    this.abort = null;
    this.session = null;
    this.viewer = null;
    this.decoding = false;
    /** @type {Part | null} */
    this.newest = null; // the newest part not yet decoded
    /** @type {Part | null} */
    this.last = null; // the last part decoded (shown again after a hold)
    /** @type {{bitmap: ImageBitmap, info: FrameInfo, bytes: Uint8Array, type: string} | null} */
    this.ready = null; // {bitmap, info}: decoded, not yet painted
    this.steering = false;
    this.pendingSteer = null;
    this.held = false; // hold(): another picture is shown
    this.connected = false; // the server has answered the stream's request: the viewer exists
    const paint = () => {
      if (this.ready) {
        const { bitmap, info } = this.ready;
        this.ready = null;
        // The canvas takes the size of the frame it shows (a steer to a new size changes it when
        // that frame arrives, so the picture never goes blank in between).
        if (this.canvas.width !== bitmap.width) this.canvas.width = bitmap.width;
        if (this.canvas.height !== bitmap.height) this.canvas.height = bitmap.height;
        this.context.drawImage(bitmap, 0, 0, this.canvas.width, this.canvas.height);
        bitmap.close();
        this.stats.painted++;
        // What the canvas shows, for tests and tools: the frame's fields, a 3-D view's camera as
        // drawn and whether it glides (a held picture has only its own).
        const shown = {
          seq: info.seq,
          version: info.version,
          t: info.t,
          kind: info.kind,
          painted: String(this.stats.painted),
        };
        Object.assign(shown, { yaw: info.yaw, pitch: info.pitch, distance: info.distance, glide: info.glide });
        for (const [key, value] of Object.entries(shown))
          if (value === undefined) delete this.canvas.dataset[key];
          else this.canvas.dataset[key] = value;
        if (this.onPaint) this.onPaint(info);
      }
      requestAnimationFrame(paint);
    };
    requestAnimationFrame(paint);
  }

  // Opens the stream of a session with these frame parameters (URLSearchParams or object).
  /**
   * @param {string} session
   * @param {Record<string, string | number>} params
   */
  open(session, params) {
    this.close();
    this.pendingSteer = null; // the stream opens with the current parameters
    this.session = session;
    this.viewer = "v" + crypto.getRandomValues(new Uint32Array(2)).join("");
    const q = new URLSearchParams(/** @type {Record<string, string>} */ (params));
    q.set("viewer", this.viewer);
    const abort = (this.abort = new AbortController());
    this.read(`/api/v1/sessions/${session}/live?${q}`, abort).catch(() => {});
  }

  close() {
    this.connected = false;
    if (this.abort) this.abort.abort();
    this.abort = null;
    this.newest = null;
  }

  /**
   * @param {string} url
   * @param {AbortController} abort
   */
  async read(url, abort) {
    while (!abort.signal.aborted) {
      try {
        const res = await fetch(url, { signal: abort.signal, cache: "no-store" });
        if (res.status === 404 && this.onGone) {
          this.onGone();
          return;
        }
        if (!res.ok) throw new Error(`live stream: ${res.status}`);
        this.connected = true;
        if (this.pendingSteer) this.steer({}); // asked while the stream was connecting
        const parser = new MultipartParser();
        const reader = /** @type {ReadableStream<Uint8Array>} */ (res.body).getReader();
        for (;;) {
          const { value, done } = await reader.read();
          if (done) break;
          for (const part of parser.push(value)) {
            if (!part.type.startsWith("image/")) continue; // a heartbeat
            this.stats.received++;
            if (this.newest) this.stats.skipped++; // never decoded: a newer one came first
            this.newest = part;
            this.decode();
          }
        }
      } catch {
        if (abort.signal.aborted) return;
      }
      this.connected = false;
      await new Promise((r) => setTimeout(r, 1000)); // the server went away: try again
    }
  }

  async decode() {
    if (this.decoding || !this.newest) return;
    this.decoding = true;
    const part = this.newest;
    this.newest = null;
    try {
      const bitmap = await createImageBitmap(new Blob([/** @type {BlobPart} */ (part.bytes)], { type: part.type }));
      this.stats.decoded++;
      this.last = { bytes: part.bytes, type: part.type, info: part.info };
      // Another picture is shown (the scrubber's): this one is kept as `last` only, and the held
      // picture waiting in `ready` (hold() may have come while this one decoded) is left alone.
      if (this.held) bitmap.close();
      else {
        if (this.ready) {
          this.ready.bitmap.close();
          this.stats.skipped++;
        }
        this.ready = { bitmap, info: part.info, bytes: part.bytes, type: part.type };
      }
    } finally {
      this.decoding = false;
      this.decode();
    }
  }

  /**
   * Shows another picture in place of the stream's (a scrubber's frame of an earlier time) until
   * release(): frames arriving meanwhile are kept, not painted.
   * @param {ImageBitmap} bitmap
   * @param {FrameInfo} info
   */
  hold(bitmap, info) {
    this.held = true;
    if (this.ready) this.ready.bitmap.close();
    this.ready = { bitmap, info, bytes: new Uint8Array(), type: "" };
  }

  /** The stream's pictures again, from its last frame. */
  release() {
    if (!this.held) return;
    this.held = false;
    if (this.last && !this.newest) {
      this.newest = { type: this.last.type, info: this.last.info, bytes: this.last.bytes };
      this.decode();
    }
  }

  // Changes the stream's picture (frame parameters; aim: "body" puts the camera back on the body).
  /** @param {Record<string, string | number>} params */
  async steer(params) {
    if (!this.session) return;
    this.pendingSteer = { ...(this.pendingSteer || {}), ...params };
    // Until the stream is connected there is no viewer to steer: its answer sends what is pending.
    if (this.steering || !this.connected) return;
    this.steering = true;
    const { session, viewer } = this;
    // The steer belongs to this stream: when the page closes it, a steer still on its way is
    // cancelled too (else it reaches a viewer the server has just forgotten: a 404 in the console).
    const { signal } = /** @type {AbortController} */ (this.abort);
    let retries = 0;
    try {
      while (this.pendingSteer && !signal.aborted && this.session === session && this.viewer === viewer) {
        const q = new URLSearchParams(this.pendingSteer);
        this.pendingSteer = null;
        q.set("viewer", /** @type {string} */ (viewer));
        const res = await fetch(`/api/v1/sessions/${session}/live?${q}`, { method: "PATCH", body: "", signal });
        if (res.status === 429 || res.status === 404) {
          // Over the rate limit, or the stream is (re)connecting: the newest wish, a little later,
          // backing off to once a second. Never dropped (a dropped steer is a turn or a size the
          // picture never shows); it ends with this stream: open() starts the next with the wish.
          q.delete("viewer");
          this.pendingSteer = { ...Object.fromEntries(q), ...(this.pendingSteer || {}) };
          await new Promise((r) => setTimeout(r, Math.min(1000, 100 * 2 ** Math.min(retries++, 4))));
        }
      }
    } catch (e) {
      if (!signal.aborted) throw e; // aborted with its stream: the next opens with the parameters in force
    } finally {
      this.steering = false;
    }
  }
}
