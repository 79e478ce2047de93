// Small DOM helpers shared by the panels.

// el('button', {class: 'x', onclick: f}, 'text', child...) -> the element.
export function el(tag, attributes = {}, ...children) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attributes)) {
    if (value === undefined || value === null || value === false) continue;
    if (key.startsWith('on') && typeof value === 'function') node.addEventListener(key.slice(2), value);
    else if (key === 'class') node.className = value;
    else if (key in node && typeof value !== 'string') node[key] = value;
    else node.setAttribute(key, value === true ? '' : value);
  }
  for (const child of children.flat()) {
    if (child === undefined || child === null || child === false) continue;
    node.append(child instanceof Node ? child : document.createTextNode(String(child)));
  }
  return node;
}

export const $ = (selector, root = document) => root.querySelector(selector);

// A number shown as a user reads it: at most `digits` decimals, no trailing zeros.
export function fmt(value, digits = 1) {
  if (value === null || value === undefined || Number.isNaN(value)) return '–';
  const text = Number(value).toFixed(digits);
  return (text.includes('.') ? text.replace(/\.?0+$/, '') : text).replace(/^-0$/, '0');
}

// Runs an async action from a button: the button is disabled while it runs, so a double
// click sends one request; a refused request is already shown by the error display.
export async function busy(button, action) {
  if (button) button.disabled = true;
  try { return await action(); } catch { return undefined; } finally { if (button) button.disabled = false; }
}
