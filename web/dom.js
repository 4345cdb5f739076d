// @ts-check
// The one way the UI makes and finds DOM nodes: el() for new nodes (text set as text, never parsed
// as HTML), $() for the page's own elements by id.

/**
 * The page's element with this id (an error naming the id when the page has none).
 * @param {string} id
 * @returns {any} the element (any: its tag varies; callers know which they asked for)
 */
export function $(id) {
  const node = document.getElementById(id);
  if (!node) throw new Error(`the page has no #${id}`);
  return node;
}

/**
 * A new element: attributes set as attributes, except `text` (its text content), `class`, and
 * properties given in `props` (a listener, a value, checked). Children are nodes or strings.
 * @param {string} tag
 * @param {Record<string, string | number | boolean | undefined>} [attributes]
 * @param {...(Node | string)} children
 * @returns {any}
 */
export function el(tag, attributes = {}, ...children) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attributes)) {
    if (value === undefined || value === false) continue;
    if (key === "text") node.textContent = String(value);
    else node.setAttribute(key, value === true ? "" : String(value));
  }
  node.append(...children);
  return node;
}

/**
 * Removes every child of `node`; returns it.
 * @template {Element} N
 * @param {N} node
 * @returns {N}
 */
export function clear(node) {
  node.textContent = "";
  return node;
}
