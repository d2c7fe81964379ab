// What the three.js pages share: `scene` seen by `camera`, rendered by `renderer` into a size x size 32-bit
// float target and read back; RGBA pixels as an array (what page.evaluate hands back), rows bottom to top.
import * as THREE from 'three';

export function renderFloatPixels(renderer, scene, camera, size) {
  const target = new THREE.WebGLRenderTarget(size, size, { type: THREE.FloatType });
  renderer.setRenderTarget(target);
  renderer.render(scene, camera);
  const pixels = new Float32Array(size * size * 4);
  renderer.readRenderTargetPixels(target, 0, 0, size, size, pixels);
  renderer.setRenderTarget(null);
  target.dispose();
  return Array.from(pixels);
}
