// @ts-check
// Full screen, themes, the tab's icon and the embedded layout (?embed=1).
import { $, el } from "./dom.js";
import { say } from "./readout.js";

export function toggleFullscreen() {
  if (document.fullscreenElement) document.exitFullscreen().catch(() => {});
  else
    $("frame-box")
      .requestFullscreen()
      .then(() => $("frame").focus())
      .catch((/** @type {Error} */ e) => say(`Full screen refused: ${e.message}`));
}

/** @param {boolean} dark */
function setTheme(dark) {
  document.documentElement.dataset.theme = dark ? "dark" : "light";
  $("theme").setAttribute("aria-pressed", String(dark));
  $("theme").textContent = dark ? "Light theme" : "Dark theme";
  try {
    localStorage.setItem("spinfold.theme", dark ? "dark" : "light");
  } catch {
    /* not kept */
  }
}

// The tab's icon, made here as a blob: URL: the page's Content-Security-Policy allows images from
// 'self' and blob: only (a data: icon is refused), and without an icon the browser would ask
// for /favicon.ico, which the server does not have.
function setIcon() {
  const svg =
    `<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 32 32"><circle cx="16" cy="16" r="14" fill="#233"/>` +
    `<ellipse cx="16" cy="16" rx="9" ry="5" fill="#f90" transform="rotate(-30 16 16)"/></svg>`;
  const link = el("link", { rel: "icon" });
  link.href = URL.createObjectURL(new Blob([svg], { type: "image/svg+xml" }));
  document.head.append(link);
}

/** @returns {boolean} whether the page is embedded (?embed=1: no gallery, no header) */
export function setupPresentation() {
  setIcon();
  const embed = new URLSearchParams(location.search).get("embed") === "1";
  if (embed) document.body.classList.add("embed");
  let dark = matchMedia("(prefers-color-scheme: dark)").matches;
  try {
    dark = (localStorage.getItem("spinfold.theme") ?? (dark ? "dark" : "light")) === "dark";
  } catch {
    /* the system's */
  }
  setTheme(dark);
  $("theme").onclick = () => setTheme(document.documentElement.dataset.theme !== "dark");
  $("fullscreen").onclick = () => toggleFullscreen();
  document.addEventListener("fullscreenchange", () =>
    document.body.classList.toggle("fullscreen", Boolean(document.fullscreenElement)),
  );
  return embed;
}
