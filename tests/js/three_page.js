// three.js side of three_cube.mjs: our cube KTX2 through three's cube path (scene.background, and
// MeshStandardMaterial.envMap: a --profile three chain as the PMREM texture it is, any other cube through
// PMREMGenerator), rendered into float targets and handed back.
// Served inside consumer_common.mjs enginePage (three, a 256-px canvas).

import * as THREE from 'three';
import { renderFloatPixels } from '/tests/three_render.js';
import { cubeTextureFromLevels, loadIblbakeCube, parseIblbakeKtx2 } from '/runtime/iblbakeCubeLoader.js';

const renderer = new THREE.WebGLRenderer({ canvas: document.getElementById('canvas') });
renderer.toneMapping = THREE.NoToneMapping;

// renderFloatPixels, with what the checks need to map pixels to directions: { size, pixels,
// cameraPosition, inverseViewProjection }.
function renderFloat(scene, camera, size) {
  const pixels = renderFloatPixels(renderer, scene, camera, size);
  camera.updateMatrixWorld();
  const viewProjection = new THREE.Matrix4().multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse);
  return { size, pixels, cameraPosition: camera.position.toArray(),
           inverseViewProjection: viewProjection.invert().elements.slice() };
}

// options: { url, asStored (build the texture from the file's bytes without the helper's handling),
// towardSun, mirrorCamera, fov (degrees), size }
window.runThree = async (options) => {
  let texture, intensity = 1, profile;
  if (options.asStored) {
    const parsed = parseIblbakeKtx2(await (await fetch(options.url)).arrayBuffer());
    texture = cubeTextureFromLevels(parsed);
    profile = parsed.keyValues['iblbake.profile'];
  } else {
    ({ texture, intensity, profile } = await loadIblbakeCube(options.url));
  }
  const sky = new THREE.Scene();
  sky.background = texture;
  sky.backgroundIntensity = intensity;
  const sunCamera = new THREE.PerspectiveCamera(options.fov, 1, 0.1, 100);
  sunCamera.lookAt(new THREE.Vector3(...options.towardSun));
  const sunView = renderFloat(sky, sunCamera, options.size);

  // A `--profile three` chain is a PMREM texture (iblbakeCubeLoader.js) used as is; any other cube goes
  // through three's PMREMGenerator.
  const envMap = texture.isPMREMTexture ? texture : new THREE.PMREMGenerator(renderer).fromCubemap(texture).texture;
  const mirror = new THREE.Mesh(new THREE.SphereGeometry(1, 256, 128), new THREE.MeshStandardMaterial({
    color: 0xffffff, metalness: 1, roughness: 0, envMap, envMapIntensity: intensity }));
  sky.add(mirror);
  const mirrorCamera = new THREE.PerspectiveCamera(options.fov, 1, 0.1, 100);
  mirrorCamera.position.set(...options.mirrorCamera).normalize().multiplyScalar(4);
  mirrorCamera.lookAt(0, 0, 0);
  const mirrorView = renderFloat(sky, mirrorCamera, options.size);
  return {
    threeRevision: THREE.REVISION, profile, isCubeTexture: texture.isCubeTexture === true,
    isPMREMTexture: texture.isPMREMTexture === true,
    images: texture.image.length, mipLevels: texture.image[0].mipmaps.length, type: texture.type,
    sunView, mirrorView,
  };
};
window.threeReady = true;
