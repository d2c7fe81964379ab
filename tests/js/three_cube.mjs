// Our cube KTX2 in three.js r187 (headless Chromium) through three's cube-texture path, loaded with the
// shipped helper baker/runtime/js/iblbakeCubeLoader.js: the brightest spot of scene.background and of a
// mirror sphere (MeshStandardMaterial.envMap: the --profile three chain as the PMREM texture the helper
// returns, a standard cube through PMREMGenerator) against the sun, sky above the horizon;
// and, to show what the profile fixes, a standard file built into a texture as stored (mirrored in x).
// Usage: node three_cube.mjs THREE_PROFILE.ktx2 STANDARD.ktx2 SUN.json RUNTIME_JS_DIR ARTIFACT_DIR
// Prints every measurement, "ok" / "FAIL" lines and the screenshots' paths; exits 1 on a failure.
import { mkdirSync, readFileSync } from 'node:fs';
import path from 'node:path';
import {
  angleDegrees, brightestSpot, here, launchBrowser, luminance, normalize, openEnginePage, pixelSamples,
  reflection, startServer, unproject, writeToneMappedPng,
} from './consumer_common.mjs';

const [threeFile, standardFile, sunFile, runtimeDir, artifactDir] = process.argv.slice(2);
mkdirSync(artifactDir, { recursive: true });
const failures = [];
const check = (ok, what) => { console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`); if (!ok) failures.push(what); };
const towardSun = normalize(JSON.parse(readFileSync(sunFile, 'utf8')).direction); // our frame = three's
const mirroredSun = [-towardSun[0], towardSun[1], towardSun[2]];
const mirrorCamera = normalize([towardSun[0], towardSun[1] + 0.6, towardSun[2]]);

const server = await startServer({ '/node_modules/': path.join(here, 'node_modules'), '/tests/': here,
                                   '/runtime/': path.resolve(runtimeDir), '/three/': path.dirname(path.resolve(threeFile)),
                                   '/standard/': path.dirname(path.resolve(standardFile)) });
const browser = await launchBrowser();
const runs = [
  { name: 'three profile, loader helper', url: `/three/${path.basename(threeFile)}`, shot: 'three_profile' },
  { name: 'standard profile, loader helper', url: `/standard/${path.basename(standardFile)}`, shot: 'three_standard_helper' },
  { name: 'standard profile as stored', url: `/standard/${path.basename(standardFile)}`, asStored: true, shot: 'three_standard_as_stored' },
];
try {
  const page = await openEnginePage(browser, server, 'three', 'three_page.js', 256);
  await page.waitForFunction(() => window.threeReady === true);
  for (const run of runs) {
    const t = await page.evaluate((options) => window.runThree(options),
                                  { url: `${server.url}${run.url}`, asStored: !!run.asStored, towardSun, mirrorCamera, fov: 34, size: 256 });
    console.log(`three.js r${t.threeRevision}, ${run.name}: iblbake.profile ${t.profile}, CubeTexture ${t.isCubeTexture}, ` +
                `PMREM texture ${t.isPMREMTexture}, ${t.images} faces, ${t.mipLevels} mip levels`);
    const sky = brightestSpot(pixelSamples(t.sunView, (x, y) => unproject(t.sunView, x, y)));
    const mirror = brightestSpot(pixelSamples(t.mirrorView, (x, y) => reflection(t.mirrorView, x, y)));
    run.angles = { sky: angleDegrees(sky.direction, towardSun), mirror: angleDegrees(mirror.direction, towardSun),
                   mirrorMirrored: angleDegrees(mirror.direction, mirroredSun) };
    console.log(`  brightest spot from the sun: background ${run.angles.sky.toFixed(2)} deg, mirror sphere ` +
                `${run.angles.mirror.toFixed(2)} deg (${run.angles.mirrorMirrored.toFixed(2)} deg from the sun mirrored in x)`);
    const hemisphere = [[0, 0, 0, 0], [0, 0, 0, 0]];
    for (let py = 0; py < t.mirrorView.size; ++py)
      for (let px = 0; px < t.mirrorView.size; ++px) {
        const r = reflection(t.mirrorView, px, py);
        if (!r || Math.abs(r[1]) < 0.2) continue;
        const h = hemisphere[r[1] > 0 ? 0 : 1], i = 4 * (py * t.mirrorView.size + px);
        for (let c = 0; c < 3; ++c) h[c] += t.mirrorView.pixels[i + c];
        h[3] += 1;
      }
    const [up, down] = hemisphere.map((h) => h.slice(0, 3).map((v) => v / h[3]));
    run.skyUp = luminance(...up) > luminance(...down) && up[2] / up[0] > down[2] / down[0];
    console.log(`  mirror sphere: luminance up/down ${(luminance(...up) / luminance(...down)).toFixed(2)}, ` +
                `blue/red up ${(up[2] / up[0]).toFixed(2)} vs down ${(down[2] / down[0]).toFixed(2)}`);
    for (const [suffix, view] of [['sky', t.sunView], ['mirror', t.mirrorView]]) {
      const file = path.join(artifactDir, `${run.shot}_${suffix}.png`);
      let mean = 0;
      for (let i = 0; i < view.pixels.length; i += 4) mean += luminance(view.pixels[i], view.pixels[i + 1], view.pixels[i + 2]);
      writeToneMappedPng(file, view.size, view.size, view.pixels, (2 * mean) / (view.pixels.length / 4));
      console.log(`  screenshot ${file}`);
    }
    if (!run.asStored) check(t.isCubeTexture && t.images === 6, `${run.name}: a cube texture of 6 faces`);
    if (!run.asStored)
      check(t.isPMREMTexture === (t.profile === 'three'),
            `${run.name}: ${t.profile === 'three' ? 'a PMREM texture three uses as is' : 'a cube three re-filters'}`);
  }
} finally {
  await browser.close();
  server.close();
}
for (const run of runs.slice(0, 2)) {
  check(run.angles.sky < 2, `${run.name}: scene.background's brightest spot ${run.angles.sky.toFixed(2)} deg from the sun (limit 2)`);
  check(run.angles.mirror < 2, `${run.name}: the PMREM mirror sphere's brightest reflection ${run.angles.mirror.toFixed(2)} deg from the sun (limit 2)`);
  check(run.skyUp, `${run.name}: sky above the horizon on the mirror sphere`);
}
const asStored = runs[2];
check(asStored.angles.mirrorMirrored < 2 && asStored.angles.mirror > 10,
      `standard file as stored is mirrored in three: the mirror sphere's spot ${asStored.angles.mirrorMirrored.toFixed(2)} deg ` +
      `from the sun mirrored in x, ${asStored.angles.mirror.toFixed(2)} deg from the sun`);
process.exit(failures.length ? 1 : 0);
