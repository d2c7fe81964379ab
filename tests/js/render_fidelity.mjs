// Render fidelity in Babylon.js 9.28 (headless Chromium, float render targets): white metal (and, measured
// only, white dielectric) spheres of
// perceptual roughness 0, 0.2, ..., 1, lit (1) by our glTF through the stock loader and (2) by Babylon's own
// HDRCubeTexture prefilter of the same HDRI, against the brute-force GGX reference of the same pixels
// (render_fidelity_reference, converged; its own estimated error is printed). Per roughness: the ratio of
// means (engine / reference) and the mean relative luminance error sum |engine - reference| / sum reference.
// Features the reference does not model (Babylon's multiple-scattering energy conservation, horizon and
// radiance occlusion, the irradiance mixing of rough reflections) are off in the judged variant and
// measured on in the others.
// Usage: node render_fidelity.mjs SCENE.gltf REFERENCE.json HDRI ARTIFACT_DIR [--check]
//   --check: exit 1 unless, for our glTF (features off): the ratio of means at r = 0 is within 2% of 1, the
//   error at r <= 0.2 is at most 5%, and at every r within 3 points of both Babylon's own prefilter's and the
//   split-sum floor's (render_fidelity_reference: what any cube read in the mirror direction shows at best;
//   10-21% at r >= 0.4 on potsdamer_platz, so the 5% at r = 0.4 cannot be met by a cube).
import { mkdirSync, readFileSync } from 'node:fs';
import path from 'node:path';
import { here, launchBrowser, luminance, openPage, startServer, writeToneMappedPng } from './consumer_common.mjs';

const [gltfFile, referenceFile, hdriFile, artifactDir, mode] = process.argv.slice(2);
mkdirSync(artifactDir, { recursive: true });
const reference = JSON.parse(readFileSync(referenceFile, 'utf8'));
const pixels = reference.pixels, maskRadius = reference.maskRadius;
const roughness = reference.spheres.map((s) => s.roughness);

// Babylon's default scene is left-handed: the glTF loader shows glTF (x, y, z) at Babylon (-x, y, z), so
// Babylon's column c is the reference's column pixels - 1 - c (the reference's pixel order: rows bottom to
// top, masked pixels only).
function maskedLuminance(rgba) {
  const values = [];
  for (let row = 0; row < pixels; ++row)
    for (let column = 0; column < pixels; ++column) {
      const x = ((column + 0.5) / pixels) * 2 - 1, y = ((row + 0.5) / pixels) * 2 - 1;
      if (x * x + y * y >= maskRadius * maskRadius) continue;
      const i = 4 * (row * pixels + (pixels - 1 - column));
      values.push(luminance(rgba[i], rgba[i + 1], rgba[i + 2]));
    }
  return values;
}

function compare(engine, ref) {
  if (engine.length !== ref.length) throw new Error(`${engine.length} pixels against ${ref.length}`);
  let sumEngine = 0, sumReference = 0, sumError = 0;
  for (let k = 0; k < ref.length; ++k) {
    if (!Number.isFinite(engine[k])) throw new Error('the engine rendered a non-finite pixel');
    sumEngine += engine[k];
    sumReference += ref[k];
    sumError += Math.abs(engine[k] - ref[k]);
  }
  return { ratio: sumEngine / sumReference, error: sumError / sumReference };
}

// The judged variant has every feature the reference lacks off; the others turn them on.
const variants = [
  { name: 'features off', energyConservation: false, horizonOcclusion: false, mixIrradiance: false },
  { name: 'irradiance mixing on', energyConservation: false, horizonOcclusion: false, mixIrradiance: true },
  { name: 'stock material', energyConservation: true, horizonOcclusion: true, mixIrradiance: true },
];
// Keeps the PBR shader's output (clamped at 30 with image processing in a post-process) in range.
const environmentScale = 1 / 16;
// Babylon's HDRCubeTexture shows the lat-long where the glTF loader shows our glTF of it (in the default
// left-handed scene both show our direction (x, y, z) at Babylon's (-x, y, z)): no reflection matrix.

const server = await startServer({ '/node_modules/': path.join(here, 'node_modules'), '/tests/': here,
                                   '/out/': path.dirname(path.resolve(gltfFile)),
                                   '/hdri/': path.dirname(path.resolve(hdriFile)) });
const browser = await launchBrowser();
const results = {};
const start = Date.now();
try {
  const options = { roughness, pixels, variants, environmentScale };
  for (const [name, source] of [
    ['our glTF', { gltf: `${server.url}/out/${path.basename(gltfFile)}` }],
    ['Babylon prefilter', { hdr: `${server.url}/hdri/${path.basename(hdriFile)}`, faceSize: reference.faceSize }]]) {
    const page = await openPage(browser, `${server.url}/tests/render_fidelity_page.html`);
    results[name] = await page.evaluate((s, o) => window.runFidelity(s, o), source, options);
    await page.close();
  }
} finally {
  await browser.close();
  server.close();
}

const f = results['our glTF'].facts;
console.log(`Babylon.js ${f.babylonVersion}; our glTF: ${f.size}-px faces, level ${f.level}, gammaSpace ${f.gammaSpace}, ` +
            `linearSpecularLOD ${f.linearSpecularLOD}, lodGenerationScale ${f.lodGenerationScale}, offset ` +
            `${f.lodGenerationOffset}; Babylon's prefilter: ${results['Babylon prefilter'].facts.size}-px faces`);
console.log(`white metal spheres, ${pixels} px, pixels within ${maskRadius} of the radius; reference ` +
            `${reference.faceSize}-px cube, estimated error ` +
            reference.spheres.map((s) => `${(100 * s.errorEstimate).toFixed(2)}%`).join(' / '));
const table = {};
for (const variant of variants) {
  console.log(`\n${variant.name}:`);
  console.log('  r    | our glTF: ratio  error   | Babylon prefilter: ratio  error   | split-sum floor: ratio  error');
  table[variant.name] = roughness.map((r, k) => {
    const ref = reference.spheres[k].luminance;
    const [ours, theirs] = ['our glTF', 'Babylon prefilter'].map((name) =>
      compare(maskedLuminance(results[name].renders[`${variant.name}/metal`][k]).map((v) => v / environmentScale), ref));
    const floor = compare(reference.spheres[k].splitSumLuminance, ref);
    const cell = (c) => `${c.ratio.toFixed(3)}  ${(100 * c.error).toFixed(1).padStart(5)}%`;
    console.log(`  ${r.toFixed(1)}  |           ${cell(ours)}  |                    ${cell(theirs)}  |` +
                `                  ${cell(floor)}`);
    return { roughness: r, ours, theirs, floor };
  });
}
// White dielectric spheres (measured, not judged): Babylon's diffuse and its dielectric energy split differ
// from the reference's Lambert (no (1 - F) weight), so both engines share a bias there.
for (const variant of variants) {
  console.log(`\ndielectric, ${variant.name}:`);
  console.log('  r    | our glTF: ratio  error   | Babylon prefilter: ratio  error');
  roughness.forEach((r, k) => {
    const ref = reference.dielectricSpheres[k].luminance;
    const cells = ['our glTF', 'Babylon prefilter'].map((name) => {
      const c = compare(maskedLuminance(results[name].renders[`${variant.name}/dielectric`][k])
        .map((v) => v / environmentScale), ref);
      return `${c.ratio.toFixed(3)}  ${(100 * c.error).toFixed(1).padStart(5)}%`;
    });
    console.log(`  ${r.toFixed(1)}  |           ${cells[0]}  |                    ${cells[1]}`);
  });
}
console.log(`\nBabylon renders ${((Date.now() - start) / 1000).toFixed(1)} s`);

// The renders as an image: per roughness (columns) our glTF, Babylon's prefilter, the reference, and the
// error of ours (|ours - reference| / reference, 0 black to 20% white), features off.
{
  const width = pixels * roughness.length, height = pixels * 4;
  const image = new Float32Array(width * height * 4);
  const put = (row, column, k, value) => {
    const y = (3 - row) * pixels + Math.floor(k / pixels), x = column * pixels + (k % pixels), i = 4 * (y * width + x);
    image[i] = image[i + 1] = image[i + 2] = value;
    image[i + 3] = 1;
  };
  roughness.forEach((r, column) => {
    const ref = reference.spheres[column].luminance;
    const rows = ['our glTF', 'Babylon prefilter'].map((name) =>
      maskedLuminance(results[name].renders['features off/metal'][column]).map((v) => v / environmentScale));
    let m = 0;
    for (let row = 0; row < pixels; ++row)
      for (let c = 0; c < pixels; ++c) {
        const x = ((c + 0.5) / pixels) * 2 - 1, y = ((row + 0.5) / pixels) * 2 - 1;
        if (x * x + y * y >= maskRadius * maskRadius) continue;
        const k = row * pixels + c;
        put(0, column, k, rows[0][m]);
        put(1, column, k, rows[1][m]);
        put(2, column, k, ref[m]);
        put(3, column, k, (2 * Math.abs(rows[0][m] - ref[m])) / ref[m]);
        ++m;
      }
  });
  const file = path.join(artifactDir, 'babylon_fidelity.png');
  writeToneMappedPng(file, width, height, image, 1);
  console.log(`image ${file} (rows: our glTF, Babylon prefilter, reference, error of ours x 2)`);
}

if (mode === '--check') {
  const failures = [];
  const judged = table['features off'];
  const percent = (e) => `${(100 * e).toFixed(1)}%`;
  if (Math.abs(judged[0].ours.ratio - 1) > 0.02)
    failures.push(`ratio of means at r = 0 is ${judged[0].ours.ratio.toFixed(3)} (limit 1 +- 0.02)`);
  for (const { roughness: r, ours, theirs, floor } of judged) {
    if (r <= 0.2 + 1e-6 && ours.error > 0.05)
      failures.push(`error at r = ${r.toFixed(1)} is ${percent(ours.error)} (limit 5%)`);
    if (ours.error > theirs.error + 0.03)
      failures.push(`error at r = ${r.toFixed(1)} is ${percent(ours.error)}, more than 3 points above Babylon's ` +
                    `own prefilter's ${percent(theirs.error)}`);
    if (ours.error > floor.error + 0.03)
      failures.push(`error at r = ${r.toFixed(1)} is ${percent(ours.error)}, more than 3 points above the ` +
                    `split-sum floor's ${percent(floor.error)}`);
  }
  for (const failure of failures) console.log(`FAIL ${failure}`);
  if (failures.length === 0) console.log('ok   our glTF in stock Babylon within the limits');
  process.exit(failures.length ? 1 : 0);
}
