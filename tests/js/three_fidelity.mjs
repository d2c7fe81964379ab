// Render fidelity in three.js r187 (headless Chromium, float render targets): white metal (judged) and white
// dielectric (measured) spheres of perceptual roughness 0, 0.2, ..., 1, lit (1) by our `--profile three`
// chain through baker/runtime/js/iblbakeCubeLoader.js (a PMREM texture three samples as is) and (2) by
// three's own PMREMGenerator of the same HDRI (fromEquirectangular), against the brute-force GGX reference of
// the same pixels (render_fidelity_reference ... three: three's orthographic view direction, and the
// split-sum floor at three's bent read direction mix(R, N, r^4)). Per roughness: the ratio of means and the
// mean relative luminance error. three's multiple-scattering term (always on in r187; the reference is
// single scattering) is removed from the shader in the judged variant and kept in the stock one.
// Usage: node three_fidelity.mjs SPECULAR.ktx2 REFERENCE.json HDRI RUNTIME_JS_DIR ARTIFACT_DIR [--check]
//   --check: exit 1 unless, for our chain (features off): the loader returned a PMREM texture, the ratio of
//   means at r = 0 is within 2% of 1, the error at every r is at most 5% or, where three's own floor (the
//   split sum with three's DFG LUT) is above 3%, at most 2 points above that floor, and at every r >= 0.2
//   below three's own PMREM's.
import { mkdirSync, readFileSync } from 'node:fs';
import path from 'node:path';
import { halfToFloat, here, launchBrowser, openEnginePage, startServer } from './consumer_common.mjs';
import { cell, compare, maskedLuminance, writeFidelityImage } from './fidelity_common.mjs';

const [ktx2File, referenceFile, hdriFile, runtimeDir, artifactDir, mode] = process.argv.slice(2);
mkdirSync(artifactDir, { recursive: true });
const reference = JSON.parse(readFileSync(referenceFile, 'utf8'));
if (reference.engine !== 'three') throw new Error(`${referenceFile}: not a three reference (run it with "three")`);
const { pixels, maskRadius } = reference;
const roughness = reference.spheres.map((s) => s.roughness);
const variants = [{ name: 'features off', specularAntiAliasing: false, multiScattering: false },
                  { name: 'multiple scattering on', specularAntiAliasing: false, multiScattering: true },
                  { name: 'stock material', specularAntiAliasing: true, multiScattering: true }];
const engines = ['our chain', "three's PMREM"];

// three's own split-sum floor: what three shows with a perfect cube, the reference's floor with E(n.v) replaced
// by three's DFG term. three reads E = dfg.x + dfg.y (f0 = f90 = 1) from its 16 x 16 RG16F LUT
// (DFGLUTData.js; texel (i, j) holds r = (i + 0.5) / 16, n.v = (j + 0.5) / 16) at texture coordinates (r, n.v),
// bilinear, clamped to the edge texels: above r = 31/32 it reads r = 31/32 (at r = 1 and n.v = 1, E 0.345
// against 0.307).
const lutSource = readFileSync(path.join(here, 'node_modules/three/src/renderers/shaders/DFGLUTData.js'), 'utf8');
const lutWords = (lutSource.match(/new Uint16Array\(\s*\[([^\]]*)\]/) ?? [])[1]?.match(/0x[0-9a-f]+/gi)?.map(Number);
if (!lutWords || lutWords.length !== 16 * 16 * 2) throw new Error('three changed its DFG LUT (DFGLUTData.js)');
function threeDfgAlbedo(r, nv) {
  const texel = (u) => Math.min(15, Math.max(0, u * 16 - 0.5));
  const u = texel(r), v = texel(nv), i0 = Math.floor(u), j0 = Math.floor(v), i1 = Math.min(15, i0 + 1), j1 = Math.min(15, j0 + 1);
  const e = (i, j) => halfToFloat(lutWords[2 * (j * 16 + i)]) + halfToFloat(lutWords[2 * (j * 16 + i) + 1]);
  const fu = u - i0, fv = v - j0;
  return (1 - fv) * ((1 - fu) * e(i0, j0) + fu * e(i1, j0)) + fv * ((1 - fu) * e(i0, j1) + fu * e(i1, j1));
}
function threeFloor(sphere) {
  const values = [];
  for (let row = 0, m = 0; row < pixels; ++row)
    for (let column = 0; column < pixels; ++column) {
      const x = ((column + 0.5) / pixels) * 2 - 1, y = ((row + 0.5) / pixels) * 2 - 1;
      if (x * x + y * y >= maskRadius * maskRadius) continue;
      const nv = Math.sqrt(1 - x * x - y * y); // V = (0, 0, -1), n = (x, y, -nv)
      values.push((sphere.splitSumLuminance[m] * threeDfgAlbedo(sphere.roughness, nv)) / sphere.directionalAlbedo[m]);
      ++m;
    }
  return values;
}

const server = await startServer({ '/node_modules/': path.join(here, 'node_modules'), '/tests/': here,
                                   '/runtime/': path.resolve(runtimeDir),
                                   '/out/': path.dirname(path.resolve(ktx2File)),
                                   '/hdri/': path.dirname(path.resolve(hdriFile)) });
const browser = await launchBrowser();
const results = {};
const start = Date.now();
try {
  const options = { roughness, pixels, variants };
  for (const [name, source] of [[engines[0], { ktx2: `${server.url}/out/${path.basename(ktx2File)}` }],
                                [engines[1], { hdr: `${server.url}/hdri/${path.basename(hdriFile)}` }]]) {
    const page = await openEnginePage(browser, server, 'three', 'three_fidelity_page.js', 64);
    await page.waitForFunction(() => window.threeReady === true);
    results[name] = await page.evaluate((s, o) => window.runFidelity(s, o), source, options);
    await page.close();
  }
} finally {
  await browser.close();
  server.close();
}

const ours = results[engines[0]].facts, theirs = results[engines[1]].facts;
console.log(`three.js r${ours.threeRevision}; our chain: profile ${ours.profile}, roughnessMapping ${ours.mapping}, ` +
            `isPMREMTexture ${ours.isPMREMTexture}, faces ${ours.faceSizes.join('/')} px; three's PMREM: ` +
            `isPMREMTexture ${theirs.isPMREMTexture}, faces ${theirs.faceSizes.join('/')} px`);
console.log(`white metal spheres, ${pixels} px, pixels within ${maskRadius} of the radius; reference ` +
            `${reference.faceSize}-px cube, estimated error ` +
            reference.spheres.map((s) => `${(100 * s.errorEstimate).toFixed(2)}%`).join(' / '));
const masked = (name, key, k) => maskedLuminance(results[name].renders[key][k], pixels, maskRadius);
const table = {};
for (const variant of variants) {
  console.log(`\n${variant.name}:`);
  console.log("  r    | our chain: ratio  error   | three's PMREM: ratio  error   | split-sum floor: ratio  error   " +
              "| with three's DFG: ratio  error");
  table[variant.name] = roughness.map((r, k) => {
    const ref = reference.spheres[k].luminance;
    const [ourCell, theirCell] = engines.map((name) => compare(masked(name, `${variant.name}/metal`, k), ref));
    const floor = compare(reference.spheres[k].splitSumLuminance, ref);
    const dfgFloor = compare(threeFloor(reference.spheres[k]), ref);
    console.log(`  ${r.toFixed(1)}  |          ${cell(ourCell, 2)}  |              ${cell(theirCell, 2)}  |` +
                `                  ${cell(floor, 2)}  |                   ${cell(dfgFloor, 2)}`);
    return { roughness: r, ours: ourCell, theirs: theirCell, floor, dfgFloor };
  });
}
// White dielectric spheres (measured, not judged): three's diffuse is weighted by 1 - (single + multiple
// scattering) and reads the chain's last level as irradiance / pi (getIBLIrradiance); the reference's is
// Lambert without a (1 - F) weight.
for (const variant of variants) {
  console.log(`\ndielectric, ${variant.name}:`);
  console.log("  r    | our chain: ratio  error  | three's PMREM: ratio  error");
  roughness.forEach((r, k) => {
    const ref = reference.dielectricSpheres[k].luminance;
    const cells = engines.map((name) => cell(compare(masked(name, `${variant.name}/dielectric`, k), ref)));
    console.log(`  ${r.toFixed(1)}  |          ${cells[0]}  |              ${cells[1]}`);
  });
}
console.log(`\nthree.js renders ${((Date.now() - start) / 1000).toFixed(1)} s`);

const image = writeFidelityImage(path.join(artifactDir, 'three_fidelity.png'), reference,
  engines.map((name) => roughness.map((r, k) => masked(name, `${variants[0].name}/metal`, k))));
console.log(`image ${image} (rows: our chain, three's PMREM, reference, error of ours x 2; features off)`);

if (mode === '--check') {
  const failures = [];
  const percent = (e) => `${(100 * e).toFixed(2)}%`;
  const judged = table[variants[0].name];
  if (!ours.isPMREMTexture) failures.push('the loader did not return a PMREM texture for the three profile');
  if (Math.abs(judged[0].ours.ratio - 1) > 0.02)
    failures.push(`ratio of means at r = 0 is ${judged[0].ours.ratio.toFixed(3)} (limit 1 +- 0.02)`);
  for (const { roughness: r, ours: o, theirs: t, dfgFloor } of judged) {
    const limit = dfgFloor.error > 0.03 ? Math.max(0.05, dfgFloor.error + 0.02) : 0.05;
    if (o.error > limit)
      failures.push(`error at r = ${r.toFixed(1)} is ${percent(o.error)} (limit ${percent(limit)}; three's floor ` +
                    `${percent(dfgFloor.error)})`);
    if (r >= 0.2 - 1e-6 && o.error >= t.error)
      failures.push(`error at r = ${r.toFixed(1)} is ${percent(o.error)}, not below three's own PMREM's ${percent(t.error)}`);
  }
  for (const failure of failures) console.log(`FAIL ${failure}`);
  if (failures.length === 0) console.log('ok   our chain in three.js within the limits');
  process.exit(failures.length ? 1 : 0);
}
