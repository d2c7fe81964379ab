// three.js side of three_fidelity.mjs: white metal and white dielectric spheres lit by an environment (our
// `--profile three` chain through iblbakeCubeLoader.js, used as a PMREM texture as is, or three's own
// PMREMGenerator of the raw HDRI), each rendered head-on by an orthographic camera into a 32-bit float
// target and handed back.
// Served inside consumer_common.mjs enginePage (three, a 64-px canvas).

import * as THREE from 'three';
import { HDRLoader } from '/node_modules/three/examples/jsm/loaders/HDRLoader.js';
import { renderFloatPixels } from '/tests/three_render.js';
import { loadIblbakeCube } from '/runtime/iblbakeCubeLoader.js';

const renderer = new THREE.WebGLRenderer({ canvas: document.getElementById('canvas') });
renderer.toneMapping = THREE.NoToneMapping;

// three r187 features the reference does not model, none of which three can switch off; a variant removes
// them from its shader (each replacement must match, or three has changed):
// - specularAntiAliasing: lights_physical_fragment adds geometryRoughness, the largest screen-space change of
//   the normal (about 2 / pixels at the sphere's centre, more toward its rim), to the roughness, and clamps
//   it at 0.045 from below (Filament's MIN_PERCEPTUAL_ROUGHNESS);
// - multiScattering: RE_IndirectSpecular_Physical adds Fdez-Aguera's multiple scattering, multiScattering x
//   irradiance / pi; the reference is single scattering.
const removals = {
  specularAntiAliasing: ['lights_physical_fragment', [['material.roughness = max( roughnessFactor, 0.045 );',
                                                        'material.roughness = roughnessFactor;'],
                                                       ['material.roughness += geometryRoughness;', '']]],
  multiScattering: ['lights_physical_pars_fragment',
                    [['indirectSpecular += multiScattering * cosineWeightedIrradiance;', '']]],
};
function withFeatures(material, variant) {
  const off = Object.keys(removals).filter((feature) => !variant[feature]);
  if (off.length === 0) return;
  material.onBeforeCompile = (shader) => {
    for (const feature of off) {
      const [chunkName, replacements] = removals[feature];
      let chunk = THREE.ShaderChunk[chunkName];
      for (const [from, to] of replacements) {
        if (!chunk.includes(from)) throw new Error(`three changed ${chunkName}: no "${from}"`);
        chunk = chunk.replace(from, to);
      }
      shader.fragmentShader = shader.fragmentShader.replace(`#include <${chunkName}>`, chunk);
    }
  };
  material.customProgramCacheKey = () => off.join(' ');
}

// source: { ktx2: url } (our chain through the loader helper) or { hdr: url } (three's PMREMGenerator of the
// equirect). options: { roughness: [...], pixels, variants: [{ name, specularAntiAliasing, multiScattering }] }. Keyed
// '<variant>/metal', '<variant>/dielectric'.
window.runFidelity = async (source, options) => {
  let envMap, intensity = 1, rotation = new THREE.Euler();
  const facts = { threeRevision: THREE.REVISION };
  if (source.ktx2) {
    const loaded = await loadIblbakeCube(source.ktx2);
    envMap = loaded.texture;
    intensity = loaded.intensity;
    Object.assign(facts, { profile: loaded.profile, isPMREMTexture: envMap.isPMREMTexture === true,
                           mapping: loaded.keyValues['iblbake.roughnessMapping'] });
  } else {
    const equirect = await new HDRLoader().loadAsync(source.hdr);
    equirect.mapping = THREE.EquirectangularReflectionMapping;
    const pmrem = new THREE.PMREMGenerator(renderer);
    envMap = pmrem.fromEquirectangular(equirect).texture;
    pmrem.dispose();
    // three's equirectUv puts +X at the image centre, docs/conventions.md's lat-long +Z: a quarter turn.
    rotation = new THREE.Euler(0, -Math.PI / 2, 0);
    facts.isPMREMTexture = envMap.isPMREMTexture === true;
  }
  const mipmaps = envMap.isCompressedCubeTexture ? envMap.image[0].mipmaps : envMap.mipmaps;
  facts.levels = mipmaps.length;
  facts.faceSizes = mipmaps.map((m) => m.width);

  const scene = new THREE.Scene();
  const camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0.1, 10);
  camera.position.set(0, 0, -3);
  camera.lookAt(0, 0, 0);
  const sphere = new THREE.Mesh(new THREE.SphereGeometry(1, 128, 64));
  scene.add(sphere);
  const renders = {};
  for (const variant of options.variants)
    for (const [name, metalness] of [['metal', 1], ['dielectric', 0]]) {
      renders[`${variant.name}/${name}`] = [];
      for (const roughness of options.roughness) {
        const material = new THREE.MeshStandardMaterial({ color: 0xffffff, metalness, roughness, envMap,
                                                          envMapIntensity: intensity, envMapRotation: rotation });
        withFeatures(material, variant);
        sphere.material = material;
        renders[`${variant.name}/${name}`].push(renderFloatPixels(renderer, scene, camera, options.pixels));
        material.dispose();
      }
    }
  return { facts, renders };
};
window.threeReady = true;
