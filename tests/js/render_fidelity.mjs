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
import { here, launchBrowser, openEnginePage, startServer } from './consumer_common.mjs';
import { cell, compare, maskedLuminance as masked, writeFidelityImage } from './fidelity_common.mjs';

const [gltfFile, referenceFile, hdriFile, artifactDir, mode] = process.argv.slice(2);
mkdirSync(artifactDir, { recursive: true });
const reference = JSON.parse(readFileSync(referenceFile, 'utf8'));
const pixels = reference.pixels, maskRadius = reference.maskRadius;
const maskedLuminance = (rgba) => masked(rgba, pixels, maskRadius);
const roughness = reference.spheres.map((s) => s.roughness);

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
    const page = await openEnginePage(browser, server, 'babylon', 'render_fidelity_page.js', 64);
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
    const cells = ['our glTF', 'Babylon prefilter'].map((name) => cell(compare(
      maskedLuminance(results[name].renders[`${variant.name}/dielectric`][k]).map((v) => v / environmentScale), ref)));
    console.log(`  ${r.toFixed(1)}  |           ${cells[0]}  |                    ${cells[1]}`);
  });
}
console.log(`\nBabylon renders ${((Date.now() - start) / 1000).toFixed(1)} s`);

// The renders as an image (rows: our glTF, Babylon's prefilter, the reference, the error of ours x 2), features
// off.
const image = writeFidelityImage(path.join(artifactDir, 'babylon_fidelity.png'), reference,
  ['our glTF', 'Babylon prefilter'].map((name) => roughness.map((r, k) =>
    maskedLuminance(results[name].renders['features off/metal'][k]).map((v) => v / environmentScale))));
console.log(`image ${image} (rows: our glTF, Babylon prefilter, reference, error of ours x 2)`);

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
