// The exported glTF in Babylon.js 9.28 (headless Chromium), checked by numbers Babylon decoded and
// rendered: the brightest sky spot against the KHR_lights_punctual sun, sky above the horizon on a mirror
// sphere, the mirror's brightest reflection, Babylon's SH irradiance against ours, and Babylon's decoded
// level 0 against our KTX2 level 0.
// Usage: node babylon_gltf.mjs SCENE.gltf BAKE_DIR ARTIFACT_DIR [--right-handed]
//   BAKE_DIR holds the specular.ktx2 and diffuse.json the glTF was exported from.
// Prints every measurement, "ok" lines and "FAIL" lines, the screenshots' paths; exits 1 on a failure.
import { mkdirSync, readFileSync } from 'node:fs';
import path from 'node:path';
import {
  angleDegrees, brightestSpot, cubeFaceDirection, cubeSamples, cubeTexel, here, launchBrowser, luminance,
  normalize, openEnginePage, ourIrradiance, pixelSamples, readKtx2Cube, reflection, startServer, unproject,
  writeToneMappedPng,
} from './consumer_common.mjs';

const [gltfFile, bakeDir, artifactDir, handedness] = process.argv.slice(2);
const rightHanded = handedness === '--right-handed';
const frame = rightHanded ? 'right-handed' : 'left-handed (default)';
mkdirSync(artifactDir, { recursive: true });
const failures = [];
const check = (ok, what) => { console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`); if (!ok) failures.push(what); };

// Where Babylon shows a cube direction c, in the glTF frame. In a left-handed scene the glTF loader's root
// turns glTF (x, y, z) into Babylon (-x, y, z) and cube lookups use the world direction as is; in a
// right-handed scene there is no root transform and lookups flip z (REFLECTIONMAP_OPPOSITEZ).
const gltfFromCube = rightHanded ? ([x, y, z]) => [x, y, -z] : ([x, y, z]) => [-x, y, z];
const gltfFromWorld = rightHanded ? (d) => d : ([x, y, z]) => [-x, y, z];
const cubeFromWorld = rightHanded ? ([x, y, z]) => [x, y, -z] : (d) => d;

// The sun's direction from the glTF itself: its node turns -Z (where the light shines) away from it.
const sunGltf = (() => {
  const gltf = JSON.parse(readFileSync(gltfFile, 'utf8'));
  const q = gltf.nodes[gltf.scenes[0].nodes[0]].rotation; // the sun's node turns -Z away from the sun
  const [x, y, z, w] = q, v = [0, 0, -1];
  const t = [2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0])];
  const r = [v[0] + w * t[0] + (y * t[2] - z * t[1]), v[1] + w * t[1] + (z * t[0] - x * t[2]),
             v[2] + w * t[2] + (x * t[1] - y * t[0])];
  return normalize(r.map((c) => -c));
})();
const server = await startServer({ '/node_modules/': path.join(here, 'node_modules'), '/tests/': here,
                                   '/out/': path.dirname(path.resolve(gltfFile)) });
const browser = await launchBrowser();
let b;
try {
  const page = await openEnginePage(browser, server, 'babylon', 'babylon_page.js', 256);
  // The mirror camera looks at the sphere from above the sun's side, so the sun's reflection and the
  // horizon are both on the sphere.
  const sunWorld = gltfFromWorld(sunGltf); // both maps are their own inverse
  const mirrorCamera = normalize([sunWorld[0], sunWorld[1] + 0.6, sunWorld[2]]);
  b = await page.evaluate((url, options) => window.runBabylon(url, options),
                          `${server.url}/out/${path.basename(gltfFile)}`,
                          { rightHanded, mirrorCamera, fov: 0.6, size: 256 });
  console.log(`Babylon.js ${b.babylonVersion}, ${frame} scene, environment ${b.size} px faces, level ${b.level}, ` +
              `gammaSpace ${b.gammaSpace} (renders at level ${b.renderLevel} show decoded^2.2 x level)`);
  check(angleDegrees(b.towardSun, sunWorld) < 1e-3,
        `Babylon's KHR light points to the glTF's sun (${angleDegrees(b.towardSun, sunWorld).toFixed(5)} deg)`);
} finally {
  await browser.close();
  server.close();
}

// Screenshots (tone-mapped from the float renders): the mirror sphere against the sky, and the sky toward
// the sun.
const suffix = rightHanded ? '_rh' : '';
for (const [name, view] of [[`babylon_mirror${suffix}.png`, b.mirrorView], [`babylon_sun${suffix}.png`, b.sunView]]) {
  const file = path.join(artifactDir, name);
  let mean = 0;
  for (let i = 0; i < view.pixels.length; i += 4) mean += luminance(view.pixels[i], view.pixels[i + 1], view.pixels[i + 2]);
  writeToneMappedPng(file, view.size, view.size, view.pixels, (2 * mean) / (view.pixels.length / 4));
  console.log(`screenshot ${file}`);
}

// 1. The brightest texel Babylon decoded, where Babylon shows it, against the KHR sun.
const decoded = b.faces.map((face) => Float32Array.from(face));
const spot = brightestSpot(cubeSamples(decoded, b.size));
const spotAngle = angleDegrees(gltfFromCube(spot.direction), gltfFromWorld(b.towardSun));
check(spotAngle < 2, `brightest spot Babylon decoded (${spot.count} texels) is ${spotAngle.toFixed(2)} deg from the KHR sun (limit 2)`);

// 2. Rendered: the brightest pixel of the sky toward the sun and of the mirror sphere's reflections.
const skyAngle = angleDegrees(brightestSpot(pixelSamples(b.sunView, (x, y) => unproject(b.sunView, x, y))).direction, b.towardSun);
check(skyAngle < 2, `brightest spot of the rendered sky is ${skyAngle.toFixed(2)} deg from the KHR sun (limit 2)`);

const mirrorSun = brightestSpot(pixelSamples(b.mirrorView, (x, y) => reflection(b.mirrorView, x, y)));
const mirrorAngle = angleDegrees(mirrorSun.direction, b.towardSun);
check(mirrorAngle < 2, `brightest spot the mirror sphere reflects is ${mirrorAngle.toFixed(2)} deg from the KHR sun (limit 2)`);
// Per hemisphere the median of each channel, not the mean: the render raises decoded values to 2.2 (the
// gamma quirk above), so a mean is ruled by the few texels beside the sun.
const hemisphere = [[[], [], []], [[], [], []]];
for (let py = 0; py < b.mirrorView.size; ++py)
  for (let px = 0; px < b.mirrorView.size; ++px) {
    const r = reflection(b.mirrorView, px, py);
    if (!r || Math.abs(r[1]) < 0.2) continue;
    const h = hemisphere[r[1] > 0 ? 0 : 1], i = 4 * (py * b.mirrorView.size + px);
    for (let c = 0; c < 3; ++c) h[c].push(b.mirrorView.pixels[i + c]);
  }
const median = (values) => values.sort((p, q) => p - q)[values.length >> 1];
const [up, down] = hemisphere.map((h) => h.map(median));
const blueness = (rgb) => rgb[2] / rgb[0];
console.log(`mirror: reflections above the horizon ${up.map((v) => v.toFixed(3)).join(' ')}, below ${down.map((v) => v.toFixed(3)).join(' ')} (median rendered RGB per channel)`);
check(luminance(...up) > luminance(...down) && blueness(up) > blueness(down),
      `mirror sphere: sky above the horizon (luminance up/down ${(luminance(...up) / luminance(...down)).toFixed(2)}, ` +
      `blue/red up ${blueness(up).toFixed(2)} vs down ${blueness(down).toFixed(2)})`);

// 3. Babylon's SH irradiance (the PBR shader's SPHERICAL_HARMONICS path: sum of the pre-scaled harmonics
// times 1, y, z, x, xy, yz, 3z^2 - 1, xz, x^2 - y^2 of the lookup direction, = E / pi, times the texture's
// level, computeEnvironmentIrradiance) against ours.
const prescaled = JSON.parse(readFileSync(path.join(bakeDir, 'diffuse.json'), 'utf8')).sh.irradiance;
const babylonIrradiance = (world) => {
  const m = b.reflectionMatrix, n = world;
  const rotated = [0, 1, 2].map((c) => n[0] * m[c] + n[1] * m[4 + c] + n[2] * m[8 + c]);
  const [x, y, z] = cubeFromWorld(rotated);
  const p = [1, y, z, x, x * y, y * z, 3 * z * z - 1, x * z, x * x - y * y];
  return [0, 1, 2].map((c) => Math.PI * b.level * b.preScaledHarmonics.reduce((e, h, i) => e + h[c] * p[i], 0));
};
const directions = [[0, 1, 0], [0, -1, 0], [1, 0, 0], [-1, 0, 0], [0, 0, 1], [0, 0, -1], [1, 1, 1],
                    [-0.3, 0.8, 0.5], [0.6, -0.2, -0.77]].map(normalize);
let worstSh = 0;
for (const n of directions) {
  const ours = luminance(...ourIrradiance(prescaled, n)), babylon = luminance(...babylonIrradiance(gltfFromWorld(n)));
  worstSh = Math.max(worstSh, Math.abs(babylon / ours - 1));
  console.log(`SH E(${n.map((c) => c.toFixed(2)).join(', ')}): Babylon ${babylon.toFixed(1)}, ours ${ours.toFixed(1)} (${(100 * (babylon / ours - 1)).toFixed(2)}%)`);
}
const ratio = (f) => luminance(...f([0, 1, 0])) / luminance(...f([0, -1, 0]));
const ourRatio = ratio((n) => ourIrradiance(prescaled, n)), babylonRatio = ratio((n) => babylonIrradiance(gltfFromWorld(n)));
check(Math.abs(babylonRatio / ourRatio - 1) < 0.05,
      `SH E(up)/E(down): Babylon ${babylonRatio.toFixed(3)}, ours ${ourRatio.toFixed(3)} (limit 5%)`);
check(worstSh < 0.03, `SH irradiance in 9 directions: worst ${(100 * worstSh).toFixed(2)}% from ours (limit 3%)`);

// 4. Babylon's decoded texels against our level 0, texel for texel where Babylon shows them: its shaders
// show decoded^2.2 x level (gammaSpace true), so decoded = (ours / level)^(1/2.2) (the babylon profile's
// encoding). The sun's texels are left out (the glTF carries the residual there when level 0 kept the sun).
const ours = readKtx2Cube(path.join(bakeDir, 'specular.ktx2'));
function texelMatch(map) {
  let worst = 0, sum = 0, count = 0, skipped = 0;
  for (let f = 0; f < 6; ++f)
    for (let y = 0; y < b.size; ++y)
      for (let x = 0; x < b.size; ++x) {
        const d = normalize(cubeFaceDirection(f, (x + 0.5) / b.size, (y + 0.5) / b.size));
        const g = map(d);
        if (angleDegrees(g, sunGltf) < 3) { ++skipped; continue; }
        const t = cubeTexel(g, ours.size), o = ours.levels[0][t.face], j = 4 * (t.y * ours.size + t.x);
        const i = 4 * (y * b.size + x), w = [0, 1, 2].map((c) => Math.pow(Math.max(o[j + c], 0) / b.level, 1 / 2.2));
        const scale = Math.max(...w, 1e-6);
        // Beyond RGBD's own rounding of this texel (bound as in tests/test_gltf.cpp rgbdBound).
        const dScale = Math.min(Math.max(Math.floor(Math.max(255 / scale, 1)), 1), 255) / 255;
        for (let c = 0; c < 3; ++c) {
          const g = Math.pow(Math.min(w[c] * dScale, 1), 1 / 2.2), h = 0.5 / 255;
          const rgbdStep = (Math.pow(Math.min(g + h, 1), 2.2) - Math.pow(Math.max(g - h, 0), 2.2)) / dScale;
          const e = Math.max(0, Math.abs(decoded[f][i + c] - w[c]) - rgbdStep) / scale;
          worst = Math.max(worst, e);
          sum += e;
          ++count;
        }
      }
  return { worst, mean: sum / count, skipped };
}
const asShown = texelMatch(gltfFromCube);
const sameDirection = texelMatch((d) => d);
const rowsReversed = texelMatch(([x, y, z]) => { // the same face, rows in the opposite order
  const t = cubeTexel([x, y, z], b.size);
  return normalize(cubeFaceDirection(t.face, (t.x + 0.5) / b.size, 1 - (t.y + 0.5) / b.size));
});
console.log(`decoded texels vs (our level 0 / level)^(1/2.2) (worst / mean error beyond RGBD's rounding, of the texel's brightest channel): where Babylon shows them ` +
            `${(100 * asShown.worst).toFixed(2)}% / ${(100 * asShown.mean).toFixed(3)}%; same cube direction ` +
            `${(100 * sameDirection.worst).toFixed(1)}% / ${(100 * sameDirection.mean).toFixed(2)}%; rows reversed ` +
            `${(100 * rowsReversed.worst).toFixed(1)}% / ${(100 * rowsReversed.mean).toFixed(2)}% (${asShown.skipped} sun texels left out)`);
check(asShown.worst < 0.01, `decoded texels^2.2 x level equal our level 0 where Babylon shows them (worst ${(100 * asShown.worst).toFixed(2)}% before the power, limit 1%)`);

process.exit(failures.length ? 1 : 0);
