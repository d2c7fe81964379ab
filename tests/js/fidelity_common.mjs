// What the render-fidelity harnesses (render_fidelity.mjs: Babylon.js; three_fidelity.mjs: three.js) share:
// reading an engine's sphere render in the reference's pixel order, the per-roughness comparison, and the
// image of the renders.
import path from 'node:path';
import { luminance, writeToneMappedPng } from './consumer_common.mjs';

// The luminance of the pixels within maskRadius of the radius, in the reference's order (rows bottom to top,
// render_fidelity_reference). Both engines' cameras at (0, 0, -3) looking along +z show world +x on the left
// (Babylon through its left-handed glTF frame, three as a right-handed camera), so the engine's column c is
// the reference's column pixels - 1 - c.
export function maskedLuminance(rgba, pixels, maskRadius) {
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

// Ratio of means (engine / reference) and mean relative luminance error sum |engine - reference| / sum reference.
export function compare(engine, ref) {
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

export const cell = (c, digits = 1) => `${c.ratio.toFixed(3)}  ${(100 * c.error).toFixed(digits).padStart(4 + digits)}%`;

// The renders as one image: per roughness (columns) the rows `engines` (each [masked luminance per sphere]),
// the reference, and the error of the first engine x 2 (|engine - reference| / reference, 0 black to 50%
// white), all through the same tone curve. Returns the file's path.
export function writeFidelityImage(file, reference, engines) {
  const { pixels, maskRadius } = reference, rows = engines.length + 2, columns = reference.spheres.length;
  const width = pixels * columns, height = pixels * rows;
  const image = new Float32Array(width * height * 4);
  const put = (row, column, k, value) => {
    const y = (rows - 1 - row) * pixels + Math.floor(k / pixels), x = column * pixels + (k % pixels);
    const i = 4 * (y * width + x);
    image[i] = image[i + 1] = image[i + 2] = value;
    image[i + 3] = 1;
  };
  reference.spheres.forEach((sphere, column) => {
    const ref = sphere.luminance;
    let m = 0;
    for (let row = 0; row < pixels; ++row)
      for (let c = 0; c < pixels; ++c) {
        const x = ((c + 0.5) / pixels) * 2 - 1, y = ((row + 0.5) / pixels) * 2 - 1;
        if (x * x + y * y >= maskRadius * maskRadius) continue;
        const k = row * pixels + c;
        engines.forEach((engine, e) => put(e, column, k, engine[column][m]));
        put(engines.length, column, k, ref[m]);
        put(engines.length + 1, column, k, (2 * Math.abs(engines[0][column][m] - ref[m])) / ref[m]);
        ++m;
      }
  });
  writeToneMappedPng(path.resolve(file), width, height, image, 1);
  return file;
}
