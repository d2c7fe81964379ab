// Loads an iblbake cube KTX2 (specular.ktx2, irradiance.ktx2, a probe's ld.ktx2; RGBA16F or RGBA32F) as a
// three.js cube texture that three's cube path (scene.background, PMREMGenerator.fromCubemap,
// MeshStandardMaterial.envMap) shows the right way round. three r187's KTX2Loader returns such a file
// as a 2D texture (its cube branch is for block-compressed formats), hence this helper.
//
//   import { loadIblbakeCube } from './iblbakeCubeLoader.js';
//   const { texture, intensity } = await loadIblbakeCube('specular.ktx2'); // `iblbake specular --profile three`
//   scene.environment = texture;           scene.environmentIntensity = intensity;
//
// A chain baked with `--profile three` (iblbake.roughnessMapping "filament-lod") holds at level m of N the
// roughness three r187's shader reads there (roughnessToMip: lod = (N - 1) r (2 - r)), down to 8-px faces as
// PMREMGenerator's: the texture is marked `isPMREMTexture`, so three samples it as is (WebGLEnvironments)
// instead of re-filtering it. Any other file (a standard chain, an irradiance cube) is a plain cube texture,
// which three's PMREMGenerator re-filters when it is used as an environment (or shown as scene.background).
//
// three samples a cube texture at (-x, y, z) of the world direction (flipEnvMap = -1), so a file baked with
// `--profile three` (key iblbake.profile = "three") is stored mirrored in x and is used as stored; a
// standard file is mirrored here on load (+X and -X swapped, every face's columns reversed). Every level
// of the file becomes a mip level. Stored texels are radiance x iblbake.storageScale (1 when absent):
// `intensity` = 1 / storageScale gives back the radiance.
import { CompressedCubeTexture, FloatType, HalfFloatType, LinearFilter, LinearMipmapLinearFilter,
         LinearSRGBColorSpace, RGBAFormat } from 'three';

const IDENTIFIER = [0xab, 0x4b, 0x54, 0x58, 0x20, 0x32, 0x30, 0xbb, 0x0d, 0x0a, 0x1a, 0x0a];
const FORMATS = { 97: { type: HalfFloatType, Array: Uint16Array }, 109: { type: FloatType, Array: Float32Array } };

// The file's header, levels (levels[m][face]: typed arrays of RGBA texels, first row t = 0) and
// key/value data, as stored.
export function parseIblbakeKtx2(buffer) {
  const bytes = new Uint8Array(buffer), view = new DataView(buffer);
  if (!IDENTIFIER.every((b, i) => bytes[i] === b)) throw new Error('not a KTX 2.0 file');
  const u32 = (offset) => view.getUint32(offset, true);
  const vkFormat = u32(12), size = u32(20), faceCount = u32(36), levelCount = Math.max(1, u32(40));
  const format = FORMATS[vkFormat];
  if (!format) throw new Error(`vkFormat ${vkFormat}: only RGBA16F (97) and RGBA32F (109) cubes are supported`);
  if (faceCount !== 6 || u32(24) !== size || u32(44) !== 0)
    throw new Error('not an uncompressed cube map (6 faces, square, no supercompression)');
  const keyValues = {};
  const kvdOffset = u32(56), kvdLength = u32(60);
  for (let at = kvdOffset; at < kvdOffset + kvdLength;) {
    const length = u32(at), entry = bytes.subarray(at + 4, at + 4 + length), nul = entry.indexOf(0);
    keyValues[new TextDecoder().decode(entry.subarray(0, nul))] =
      new TextDecoder().decode(entry.subarray(nul + 1)).replace(/\0$/, '');
    at += 4 + Math.ceil(length / 4) * 4;
  }
  const levels = [];
  for (let m = 0; m < levelCount; ++m) {
    const offset = Number(view.getBigUint64(80 + 24 * m, true)), n = Math.max(1, size >> m);
    const texels = n * n * 4, faceBytes = texels * format.Array.BYTES_PER_ELEMENT;
    const faces = [];
    for (let f = 0; f < 6; ++f) faces.push(new format.Array(buffer.slice(offset + f * faceBytes, offset + (f + 1) * faceBytes)));
    levels.push({ size: n, faces });
  }
  return { vkFormat, size, levels, keyValues };
}

// The standard layout mirrored in x, in place: +X and -X swapped, every face's columns reversed.
export function mirrorCubeX(levels) {
  for (const level of levels) {
    [level.faces[0], level.faces[1]] = [level.faces[1], level.faces[0]];
    for (const face of level.faces)
      for (let y = 0; y < level.size; ++y)
        for (let a = y * level.size, b = a + level.size - 1; a < b; ++a, --b)
          for (let c = 0; c < 4; ++c)
            [face[4 * a + c], face[4 * b + c]] = [face[4 * b + c], face[4 * a + c]];
  }
}

// A three.js cube texture of parsed levels, used as they are.
export function cubeTextureFromLevels(parsed) {
  const images = [0, 1, 2, 3, 4, 5].map((f) => ({
    width: parsed.size, height: parsed.size,
    mipmaps: parsed.levels.map((level) => ({ data: level.faces[f], width: level.size, height: level.size })),
  }));
  const texture = new CompressedCubeTexture(images, RGBAFormat, FORMATS[parsed.vkFormat].type);
  texture.colorSpace = LinearSRGBColorSpace;
  texture.generateMipmaps = false;
  texture.magFilter = LinearFilter;
  texture.minFilter = parsed.levels.length > 1 ? LinearMipmapLinearFilter : LinearFilter;
  texture.needsUpdate = true;
  return texture;
}

// Fetches and loads `url`: { texture, intensity, storageScale, profile, keyValues }.
export async function loadIblbakeCube(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
  const parsed = parseIblbakeKtx2(await response.arrayBuffer());
  const profile = parsed.keyValues['iblbake.profile'] ?? 'standard';
  if (profile !== 'three') mirrorCubeX(parsed.levels);
  const storageScale = Number(parsed.keyValues['iblbake.storageScale'] ?? 1);
  if (!(storageScale > 0)) throw new Error(`${url}: iblbake.storageScale ${parsed.keyValues['iblbake.storageScale']} is not positive`);
  const texture = cubeTextureFromLevels(parsed);
  texture.isPMREMTexture = parsed.keyValues['iblbake.roughnessMapping'] === 'filament-lod';
  texture.name = url;
  texture.userData.iblbake = { profile, storageScale, keyValues: parsed.keyValues };
  return { texture, intensity: 1 / storageScale, storageScale, profile, keyValues: parsed.keyValues };
}
