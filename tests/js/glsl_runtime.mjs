// Shades the points of tests/test_glsl_runtime.cpp with probe.glsl in WebGL2 (headless Chromium, SwiftShader)
// and writes the results for the test to compare with the C++ runtime.
// Usage: node glsl_runtime.mjs PROBE_GLSL DIR
//   DIR/input.json  uniforms (RuntimeParams, local probes, buffer offsets), point count, picture layout
//   DIR/data.f32    every buffer the runtime reads (iblData), DIR/points.f32 16 floats per point,
//   DIR/cpp.f32     the C++ results (8 floats per point: diffuse, local alpha, specular, 0), for the picture
// Writes DIR/glsl.f32 (the same 8 floats per point from the GPU) and DIR/glsl_runtime.png (rows: GLSL, C++,
// |difference| / max channel x 1000). Exit code 1 on any WebGL or shader error.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';

const here = path.dirname(fileURLToPath(import.meta.url));
const [glslFile, dir] = process.argv.slice(2);
if (!glslFile || !dir) {
  console.error('usage: node glsl_runtime.mjs PROBE_GLSL DIR');
  process.exit(2);
}
const base64 = (file) => fs.readFileSync(path.join(dir, file)).toString('base64');
const args = {
  probe: fs.readFileSync(glslFile, 'utf8'),
  main: fs.readFileSync(path.join(here, 'glsl_runtime_points.frag'), 'utf8'),
  input: JSON.parse(fs.readFileSync(path.join(dir, 'input.json'), 'utf8')),
  data: base64('data.f32'),
  points: base64('points.f32'),
  cpp: base64('cpp.f32'),
};

const browser = await puppeteer.launch({
  executablePath: '/usr/bin/chromium',
  headless: true,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
         '--allow-file-access-from-files'],
});
try {
  const page = await browser.newPage();
  page.on('console', (message) => console.log(`page: ${message.text()}`));
  await page.goto(`file://${path.join(here, 'glsl_runtime.html')}`);
  const result = await page.evaluate((a) => window.shadePoints(a), args);
  if (result.error) {
    console.error(result.error);
    process.exitCode = 1;
  } else {
    fs.writeFileSync(path.join(dir, 'glsl.f32'), Buffer.from(result.glsl, 'base64'));
    fs.writeFileSync(path.join(dir, 'glsl_runtime.png'),
                     Buffer.from(result.png.replace(/^data:image\/png;base64,/, ''), 'base64'));
    console.log(`WebGL2: ${result.renderer}; ${args.input.pointCount} points shaded`);
  }
} finally {
  await browser.close();
}
