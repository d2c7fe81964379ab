// Shared pieces of the consumer pages (babylon_gltf.mjs, three_cube.mjs): a static HTTP server on
// 127.0.0.1 (no network), headless Chromium through puppeteer-core, OpenGL cube addressing (docs/conventions.md,
// kernels/cube.h), our KTX2 cube read with ktx-parse, and PNG artifacts.
import { createServer } from 'node:http';
import { readFileSync, statSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { deflateSync } from 'node:zlib';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';
import { read } from 'ktx-parse';

export const here = path.dirname(fileURLToPath(import.meta.url));

const MIME = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript',
               '.json': 'application/json', '.gltf': 'model/gltf+json', '.png': 'image/png',
               '.ktx2': 'image/ktx2' };

// The engines' scripts, in the head of every page: three as an ES module (import map), Babylon.js and
// Filament as the global scripts their packages ship.
const ENGINE_HEADS = {
  three: '<script type="importmap">{ "imports": { "three": "/node_modules/three/build/three.module.js" } }</script>',
  babylon: '<script src="/node_modules/babylonjs/babylon.js"></script>\n' +
           '<script src="/node_modules/babylonjs-loaders/babylonjs.loaders.js"></script>',
  filament: '<script src="/node_modules/filament/filament.js"></script>',
};

// A consumer page: the engine's scripts, a canvas of `canvas` pixels and the page's own module script.
function enginePage(engine, script, canvas) {
  return `<!doctype html>\n<html>\n<head>\n<meta charset="utf-8">\n${ENGINE_HEADS[engine]}\n</head>\n<body>\n` +
         `<canvas id="canvas" width="${canvas}" height="${canvas}"></canvas>\n` +
         `<script type="module" src="/tests/${script}"></script>\n</body>\n</html>\n`;
}

// Serves /page?engine=E&script=S&canvas=N (enginePage) and each mount (URL prefix -> directory) read-only;
// anything else is 404. Resolves to { url, close } once listening on an ephemeral port.
export function startServer(mounts) {
  const server = createServer((req, res) => {
    const url = new URL(req.url, 'http://x');
    const urlPath = decodeURIComponent(url.pathname);
    const engine = url.searchParams.get('engine');
    if (urlPath === '/page' && engine in ENGINE_HEADS) {
      res.writeHead(200, { 'Content-Type': 'text/html' });
      res.end(enginePage(engine, path.basename(url.searchParams.get('script')), Number(url.searchParams.get('canvas'))));
      return;
    }
    for (const [prefix, dir] of Object.entries(mounts)) {
      if (!urlPath.startsWith(prefix)) continue;
      const file = path.join(dir, urlPath.slice(prefix.length));
      if (!file.startsWith(dir)) break;
      try {
        if (!statSync(file).isFile()) break;
        res.writeHead(200, { 'Content-Type': MIME[path.extname(file)] ?? 'application/octet-stream' });
        res.end(readFileSync(file));
        return;
      } catch {
        break;
      }
    }
    res.writeHead(404);
    res.end();
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () =>
    resolve({ url: `http://127.0.0.1:${server.address().port}`, close: () => server.close() })));
}

// Headless Chromium with WebGL 2 on SwiftShader (float render targets, linear float filtering).
export async function launchBrowser() {
  return puppeteer.launch({
    executablePath: process.env.IBLBAKE_CHROMIUM ?? '/usr/bin/chromium',
    headless: true,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
  });
}

// A page of the server whose console errors and exceptions are echoed (they explain a failed check).
export async function openPage(browser, url) {
  const page = await browser.newPage();
  page.on('console', (m) => { if (m.type() === 'error') console.log(`page console: ${m.text()}`); });
  page.on('pageerror', (e) => console.log(`page error: ${e.message}`));
  await page.goto(url);
  return page;
}

// The page of `script` (a module in tests/js) inside enginePage, from `server`.
export function openEnginePage(browser, server, engine, script, canvas) {
  return openPage(browser, `${server.url}/page?engine=${engine}&script=${script}&canvas=${canvas}`);
}

// --- Directions ----------------------------------------------------------------------------------
export const normalize = (v) => { const l = Math.hypot(...v); return v.map((c) => c / l); };
export const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
export const angleDegrees = (a, b) =>
  (Math.acos(Math.min(1, Math.max(-1, dot(normalize(a), normalize(b))))) * 180) / Math.PI;

// OpenGL "Selection of cube map images" (kernels/cube.h): unnormalized direction through (s, t) of a
// face; t = 0 is the first row in memory.
export function cubeFaceDirection(face, s, t) {
  const sc = 2 * s - 1, tc = 2 * t - 1;
  return [[1, -tc, -sc], [-1, -tc, sc], [sc, 1, tc], [sc, -1, -tc], [sc, -tc, 1], [-sc, -tc, -1]][face];
}

// Face and texel (column, row) a direction hits on an n-texel face.
export function cubeTexel(d, n) {
  const [ax, ay, az] = d.map(Math.abs);
  let face, sc, tc, ma;
  if (ax >= ay && ax >= az) { face = d[0] >= 0 ? 0 : 1; ma = ax; sc = d[0] >= 0 ? -d[2] : d[2]; tc = -d[1]; }
  else if (ay >= az) { face = d[1] >= 0 ? 2 : 3; ma = ay; sc = d[0]; tc = d[1] >= 0 ? d[2] : -d[2]; }
  else { face = d[2] >= 0 ? 4 : 5; ma = az; sc = d[2] >= 0 ? d[0] : -d[0]; tc = -d[1]; }
  const clampTexel = (u) => Math.min(n - 1, Math.max(0, Math.floor(((u / ma + 1) / 2) * n)));
  return { face, x: clampTexel(sc), y: clampTexel(tc) };
}

// Rec. 709 luminance of an RGB triple.
export const luminance = (r, g, b) => 0.2126 * r + 0.7152 * g + 0.0722 * b;

// The brightest spot of a set of samples { direction, value, weight }: the value x weight weighted mean
// direction of the samples at least half as bright as the brightest. (A single brightest texel is not
// enough: an RGBA16F level clamps a patch around the sun to 65504, and the residual a glTF carries has a
// ring around the removed disk.)
export function brightestSpot(samples) {
  const nonFinite = samples.filter((s) => !Number.isFinite(s.value)).length;
  if (nonFinite > 0) throw new Error(`brightestSpot: ${nonFinite} of ${samples.length} samples are not finite`);
  const peak = samples.reduce((m, s) => Math.max(m, s.value), -Infinity);
  if (!(peak > 0)) throw new Error(`brightestSpot: all ${samples.length} samples are black (nothing was drawn)`);
  const sum = [0, 0, 0];
  let count = 0;
  for (const s of samples)
    if (s.value >= 0.5 * peak) {
      ++count;
      for (let c = 0; c < 3; ++c) sum[c] += s.direction[c] * s.value * s.weight;
    }
  return { direction: normalize(sum), peak, count };
}

// The samples of a cube level (faces: 6 RGBA float arrays, n x n, first row t = 0), each texel weighted
// by its solid angle (~ 1 / |d|^3 for the unnormalized face direction d).
export function cubeSamples(faces, n) {
  const samples = [];
  faces.forEach((pixels, face) => {
    for (let y = 0; y < n; ++y)
      for (let x = 0; x < n; ++x) {
        const d = cubeFaceDirection(face, (x + 0.5) / n, (y + 0.5) / n), i = 4 * (y * n + x);
        samples.push({ direction: normalize(d), value: luminance(pixels[i], pixels[i + 1], pixels[i + 2]),
                       weight: Math.hypot(...d) ** -3 });
      }
  });
  return samples;
}

// --- Rendered views: { size, pixels (RGBA float, rows bottom to top), cameraPosition,
// inverseViewProjection (x' = x m[0] + y m[4] + z m[8] + m[12], ...: Babylon's Matrix.m and three's
// Matrix4.elements alike) } -----------------------------------------------------------------------
// The world direction of pixel (px, py)'s ray.
export function unproject(view, px, py) {
  const m = view.inverseViewProjection;
  const point = (zNdc) => {
    const x = ((px + 0.5) / view.size) * 2 - 1, y = ((py + 0.5) / view.size) * 2 - 1;
    const w = x * m[3] + y * m[7] + zNdc * m[11] + m[15];
    return [0, 1, 2].map((c) => (x * m[c] + y * m[4 + c] + zNdc * m[8 + c] + m[12 + c]) / w);
  };
  const near = point(-1), far = point(1);
  return normalize([far[0] - near[0], far[1] - near[1], far[2] - near[2]]);
}
export function pixelSamples(view, directionOf) {
  const samples = [];
  for (let py = 0; py < view.size; ++py)
    for (let px = 0; px < view.size; ++px) {
      const direction = directionOf(px, py), i = 4 * (py * view.size + px);
      if (direction)
        samples.push({ direction, value: luminance(view.pixels[i], view.pixels[i + 1], view.pixels[i + 2]), weight: 1 });
    }
  return samples;
}
// The mirror sphere (radius 1 at the origin): a pixel's ray hits it at p, normal p, reflected ray r.
export function reflection(view, px, py) {
  const o = view.cameraPosition, d = unproject(view, px, py);
  const bHalf = dot(o, d), c = dot(o, o) - 1, disc = bHalf * bHalf - c;
  if (disc <= 0) return null;
  const t = -bHalf - Math.sqrt(disc), p = normalize([o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]]);
  if (-dot(d, p) < 0.3) return null; // grazing: the rim mixes sphere and sky
  const k = 2 * dot(d, p);
  return [d[0] - k * p[0], d[1] - k * p[1], d[2] - k * p[2]];
}
// --- Our files -----------------------------------------------------------------------------------
export function halfToFloat(h) {
  const sign = h & 0x8000 ? -1 : 1, exponent = (h >> 10) & 0x1f, mantissa = h & 0x3ff;
  if (exponent === 0) return sign * mantissa * 2 ** -24;
  if (exponent === 31) return mantissa ? NaN : sign * Infinity;
  return sign * (1 + mantissa / 1024) * 2 ** (exponent - 15);
}

// A cube KTX2 of ours (RGBA16F or RGBA32F) as { size, levels: [[6 Float32Array RGBA]], keyValues, storageScale },
// the texels in radiance: stored RGB / iblbake.storageScale (docs/conventions.md "Float storage and the storage scale"; absent means 1).
export function readKtx2Cube(file) {
  const ktx = read(new Uint8Array(readFileSync(file)));
  if (ktx.faceCount !== 6) throw new Error(`${file}: not a cube (${ktx.faceCount} faces)`);
  if (ktx.vkFormat !== 97 && ktx.vkFormat !== 109) throw new Error(`${file}: vkFormat ${ktx.vkFormat} is not RGBA16F/32F`);
  const levels = ktx.levels.map(({ levelData }, m) => {
    const n = Math.max(1, ktx.pixelWidth >> m), texels = n * n * 4;
    const data = new DataView(levelData.buffer, levelData.byteOffset, levelData.byteLength);
    return [0, 1, 2, 3, 4, 5].map((f) => {
      const face = new Float32Array(texels);
      for (let i = 0; i < texels; ++i)
        face[i] = ktx.vkFormat === 97 ? halfToFloat(data.getUint16(2 * (f * texels + i), true))
                                      : data.getFloat32(4 * (f * texels + i), true);
      return face;
    });
  });
  const keyValues = {};
  for (const [k, v] of Object.entries(ktx.keyValue))
    keyValues[k] = typeof v === 'string' ? v.replace(/\0$/, '') : new TextDecoder().decode(v).replace(/\0$/, '');
  const storageScale = Number(keyValues['iblbake.storageScale'] ?? 1);
  if (!(storageScale > 0)) throw new Error(`${file}: iblbake.storageScale ${keyValues['iblbake.storageScale']} is not a positive number`);
  for (const level of levels)
    for (const face of level)
      for (let i = 0; i < face.length; i += 4)
        for (let c = 0; c < 3; ++c) face[i + c] /= storageScale;
  return { size: ktx.pixelWidth, levels, keyValues, storageScale };
}

// Our SH irradiance E(n) from diffuse.json's pre-scaled `sh.irradiance` c_i = A_l k_i L_i (docs/conventions.md
// order): E(n) = sum_i c_i p_i(n) with p = 1, y, z, x, xy, yz, 3z^2 - 1, xz, x^2 - y^2.
export function ourIrradiance(prescaled, [x, y, z]) {
  const p = [1, y, z, x, x * y, y * z, 3 * z * z - 1, x * z, x * x - y * y];
  return [0, 1, 2].map((c) => prescaled.reduce((e, ci, i) => e + ci[c] * p[i], 0));
}

// --- Artifacts -----------------------------------------------------------------------------------
const crcTable = Array.from({ length: 256 }, (_, n) => {
  let c = n;
  for (let k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c >>> 0;
});
function crc32(bytes) {
  let c = 0xffffffff;
  for (const b of bytes) c = crcTable[(c ^ b) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}
function chunk(type, data) {
  const out = Buffer.alloc(12 + data.length);
  out.writeUInt32BE(data.length, 0);
  out.write(type, 4, 'latin1');
  data.copy(out, 8);
  out.writeUInt32BE(crc32(out.subarray(4, 8 + data.length)), 8 + data.length);
  return out;
}

// Writes an 8-bit RGBA image (rows top to bottom) as PNG.
export function writePng(file, width, height, rgba) {
  const raw = Buffer.alloc(height * (1 + 4 * width));
  for (let y = 0; y < height; ++y) {
    raw[y * (1 + 4 * width)] = 0;
    Buffer.from(rgba.buffer, rgba.byteOffset + y * 4 * width, 4 * width).copy(raw, y * (1 + 4 * width) + 1);
  }
  const header = Buffer.alloc(13);
  header.writeUInt32BE(width, 0);
  header.writeUInt32BE(height, 4);
  header.set([8, 6, 0, 0, 0], 8);
  writeFileSync(file, Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', header),
                                     chunk('IDAT', deflateSync(raw)), chunk('IEND', Buffer.alloc(0))]));
}

// A linear float RGBA image (rows bottom to top, as readPixels returns them) tone-mapped for viewing:
// exposure so that `white` maps to 1, Reinhard, sRGB-like gamma; written top row first.
export function writeToneMappedPng(file, width, height, pixels, white) {
  const out = new Uint8Array(width * height * 4);
  for (let y = 0; y < height; ++y)
    for (let x = 0; x < width; ++x) {
      const src = 4 * ((height - 1 - y) * width + x), dst = 4 * (y * width + x);
      for (let c = 0; c < 3; ++c) {
        const v = Math.max(0, pixels[src + c] / white);
        out[dst + c] = Math.round(255 * Math.pow(v / (1 + v), 1 / 2.2));
      }
      out[dst + 3] = 255;
    }
  writePng(file, width, height, out);
}
