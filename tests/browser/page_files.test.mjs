// The page's files agree with each other, without a server or a browser: the boot script's
// module list (index.html) names every app module and every script of web/vendor.txt (a
// module missing from it loads without the token: a 401 on a non-loopback listen), each
// vendored file exists, and every import in the app resolves to an embedded file.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';

const web = path.resolve(new URL('../../web', import.meta.url).pathname);
const html = fs.readFileSync(path.join(web, 'public/index.html'), 'utf8');
const vendor = new Map(fs.readFileSync(path.join(web, 'vendor.txt'), 'utf8').split('\n')
  .map((l) => l.trim()).filter((l) => l && !l.startsWith('#')).map((l) => l.split(/\s+/)));
const appDir = path.join(web, 'public/assets/app');
const appModules = fs.readdirSync(appDir).filter((f) => f.endsWith('.js')).map((f) => `/assets/app/${f}`);

function bootList() {
  const app = html.match(/const app = \[([^\]]*)\]/)[1].match(/'([^']+)'/g).map((s) => `/assets/app/${s.slice(1, -1)}.js`);
  const vendored = html.match(/const modules = \[([^\]]*)\]/)[1].match(/'([^']+)'/g).map((s) => `/assets/vendor/${s.slice(1, -1)}`);
  return { app, vendored };
}

test('the boot script lists every app module and every vendored script', () => {
  const { app, vendored } = bootList();
  assert.deepEqual([...app].sort(), [...appModules].sort());
  const scripts = [...vendor.keys()].filter((u) => u.endsWith('.js')).sort();
  assert.deepEqual([...vendored].sort(), scripts);
});

test('every file of web/vendor.txt exists (npm ci in web/)', () => {
  for (const [url, file] of vendor) assert.ok(fs.existsSync(path.join(web, file)), `${url}: ${file}`);
});

test('every import of the app and of the vendored scripts resolves to an embedded file', () => {
  const bare = { three: '/assets/vendor/three/build/three.module.js', 'urdf-loader': '/assets/vendor/urdf-loader/src/URDFLoader.js' };
  const served = new Set([...appModules, ...vendor.keys()]);
  const fileOf = (url) => (url.startsWith('/assets/app/') ? path.join(web, 'public', url) : path.join(web, vendor.get(url)));
  for (const url of served) {
    if (!url.endsWith('.js')) continue;
    const source = fs.readFileSync(fileOf(url), 'utf8');
    for (const m of source.matchAll(/^\s*(?:import|export)\s[^'"]*?from\s*['"]([^'"]+)['"]/gm)) {
      const spec = m[1];
      let target;
      if (spec in bare) target = bare[spec];
      else if (spec.startsWith('three/examples/jsm/')) target = `/assets/vendor/${spec}`;
      else if (spec.startsWith('.') || spec.startsWith('/')) target = new URL(spec, `http://x${url}`).pathname;
      else assert.fail(`${url} imports '${spec}', which the import map does not name`);
      assert.ok(served.has(target), `${url} imports '${spec}' (${target}), which is not embedded`);
    }
  }
});
