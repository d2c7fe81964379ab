// Render fidelity in Filament 1.53.4 (its WebGL2 build in headless Chromium): white metal spheres of perceptual
// roughness 0, 0.2, ..., 1 (glTF metal-roughness materials through gltfio's ubershaders) lit by our
// `iblbake export-filament` NAME_ibl.ktx through engine.createIblFromKtx1, against the brute-force GGX reference
// of the same pixels (render_fidelity_reference, as for Babylon: docs/engines.md "Render fidelity"). Per
// roughness: the ratio of means (engine / reference) and the mean relative luminance error
// sum |engine - reference| / sum reference, beside the split-sum floor. Filament's output is linear with
// post-processing off, but the WebGL default framebuffer holds 8 bits: each pixel is read at the largest of
// several scales of the light's intensity that does not clip it.
// Usage: node filament_fidelity.mjs NAME_ibl.ktx INTENSITY REFERENCE.json ARTIFACT_DIR [--check]
//   REFERENCE.json: render_fidelity_reference HDRI FACE_SIZE PIXELS MASK_RADIUS OUT.json --projection-view
//   (Filament's V under an orthographic projection; with compensatedLuminance, Filament's multiple-scattering
//   compensation, which its lit materials apply, at its WebGL roughness floor of 0.089). ARTIFACT_DIR receives
//   filament_fidelity.png.
//   --check: exit 1 unless, against the reference with compensation, the ratio of means is within 3% of 1 at
//   every r, the error at r >= 0.4 is within 3 points of the split-sum floor's, and at r <= 0.2 at most 20%
//   (Filament clamps r to 0.089 on WebGL, which reads lod 0.5 of a 4-level chain: half the r = 0.18 level).
import { mkdirSync, readFileSync } from 'node:fs';
import path from 'node:path';
import { here, launchBrowser, openEnginePage, startServer, writeToneMappedPng } from './consumer_common.mjs';
import { cell, compare, maskedLuminance as maskedLuminanceOf } from './fidelity_common.mjs';

const [iblFile, intensityText, referenceFile, artifactDir, mode] = process.argv.slice(2);
mkdirSync(artifactDir, { recursive: true });
const reference = JSON.parse(readFileSync(referenceFile, 'utf8'));
const pixels = reference.pixels, maskRadius = reference.maskRadius;
const roughness = reference.spheres.map((s) => s.roughness);
const version = JSON.parse(readFileSync(path.join(here, 'node_modules', 'filament', 'package.json'), 'utf8')).version;

// The camera at (0, 0, -3) looks along +z with +y up in Filament's right-handed frame (ours), so the screen's
// right is our -x: Filament's column c is the reference's column pixels - 1 - c (rows bottom to top in both),
// as fidelity_common.mjs maskedLuminance reads it. A pixel that clipped at every exposure is read as
// non-finite, which compare refuses.
const maskedLuminance = (rgba) => maskedLuminanceOf(rgba, pixels, maskRadius);

const server = await startServer({ '/node_modules/': path.join(here, 'node_modules'), '/tests/': here,
                                   '/out/': path.dirname(path.resolve(iblFile)) });
const browser = await launchBrowser();
const start = Date.now();
let result;
try {
  const page = await openEnginePage(browser, server, 'filament', 'filament_fidelity_page.js', 32);
  // Scales by factors of 2: every pixel is read with its brightest channel in [125, 250) of 255 (0.4-0.8%
  // quantization) unless it is darker than 125/255 at the largest (the spheres' pixels span ~1:1000 here).
  const scales = Array.from({ length: 14 }, (_, k) => 2 ** (6 - k));
  result = await page.evaluate((o) => window.runFilamentFidelity(o),
    { iblUrl: `${server.url}/out/${path.basename(iblFile)}`, intensity: Number(intensityText), roughness, pixels,
      scales });
  await page.close();
} finally {
  await browser.close();
  server.close();
}

console.log(`Filament ${version}: ${path.basename(iblFile)} via createIblFromKtx1, intensity ` +
            `${intensityText}; white metal spheres, ${pixels} px, pixels within ${maskRadius} of the radius; ` +
            `reference ${reference.faceSize}-px cube`);
console.log('  r    | ours vs reference: ratio  error   | vs reference with compensation: ratio  error   | ' +
            'split-sum floor: ratio  error');
const table = roughness.map((r, k) => {
  const sphere = reference.spheres[k];
  const rendered = maskedLuminance(result.renders[k]);
  const ours = compare(rendered, sphere.luminance);
  const compensated = compare(rendered, sphere.compensatedLuminance);
  const floor = compare(sphere.splitSumLuminance, sphere.luminance);
  console.log(`  ${r.toFixed(1)}  |                    ${cell(ours)}  |                                 ` +
              `${cell(compensated)}  |                  ${cell(floor)}`);
  return { roughness: r, ours, compensated, floor };
});
console.log(`Filament renders ${((Date.now() - start) / 1000).toFixed(1)} s`);

// The renders as an image: per roughness (columns) ours in Filament, the reference with compensation, and the
// error of ours (|ours - reference| / reference, x 2), through one tone curve.
{
  const width = pixels * roughness.length, height = pixels * 3;
  const image = new Float32Array(width * height * 4);
  roughness.forEach((r, column) => {
    const ours = maskedLuminance(result.renders[column]), ref = reference.spheres[column].compensatedLuminance;
    let m = 0;
    for (let row = 0; row < pixels; ++row)
      for (let c = 0; c < pixels; ++c) {
        const x = ((c + 0.5) / pixels) * 2 - 1, y = ((row + 0.5) / pixels) * 2 - 1;
        if (x * x + y * y >= maskRadius * maskRadius) continue;
        [ours[m], ref[m], (2 * Math.abs(ours[m] - ref[m])) / ref[m]].forEach((value, band) => {
          const i = 4 * (((2 - band) * pixels + row) * width + column * pixels + c);
          image[i] = image[i + 1] = image[i + 2] = value;
          image[i + 3] = 1;
        });
        ++m;
      }
  });
  const file = path.join(artifactDir, 'filament_fidelity.png');
  writeToneMappedPng(file, width, height, image, 1);
  console.log(`image ${file} (rows: ours in Filament, reference with compensation, error of ours x 2)`);
}

if (mode === '--check') {
  const failures = [];
  const percent = (e) => `${(100 * e).toFixed(1)}%`;
  for (const { roughness: r, compensated, floor } of table) {
    if (Math.abs(compensated.ratio - 1) > 0.03)
      failures.push(`ratio of means at r = ${r.toFixed(1)} is ${compensated.ratio.toFixed(3)} (limit 1 +- 0.03)`);
    if (r >= 0.4 - 1e-6 && compensated.error > floor.error + 0.03)
      failures.push(`error at r = ${r.toFixed(1)} is ${percent(compensated.error)}, more than 3 points above the ` +
                    `split-sum floor's ${percent(floor.error)}`);
    if (r < 0.4 - 1e-6 && compensated.error > 0.2)
      failures.push(`error at r = ${r.toFixed(1)} is ${percent(compensated.error)} (limit 20%)`);
  }
  for (const failure of failures) console.log(`FAIL ${failure}`);
  if (failures.length === 0) console.log('ok   our KTX1 in Filament within the limits');
  process.exit(failures.length ? 1 : 0);
}
