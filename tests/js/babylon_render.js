// What the Babylon.js pages share: `meshes` seen by `camera`, rendered into a size x size 32-bit float target
// once they and their materials are ready, and read back; RGBA pixels as an array (what page.evaluate hands
// back), rows bottom to top.
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

export async function renderFloatPixels(scene, camera, meshes, size) {
  const target = new BABYLON.RenderTargetTexture('float target', { width: size, height: size }, scene, {
    generateMipMaps: false, type: BABYLON.Constants.TEXTURETYPE_FLOAT,
    samplingMode: BABYLON.Constants.TEXTURE_NEAREST_SAMPLINGMODE });
  target.renderList = meshes;
  target.activeCamera = camera;
  target.clearColor = new BABYLON.Color4(0, 0, 0, 0);
  scene.activeCamera = camera;
  await scene.whenReadyAsync();
  const ready = () => target.isReadyForRendering() && meshes.every((mesh) => mesh.isReady(true) &&
    mesh.material.isReady(mesh) && (!mesh.material.reflectionTexture || mesh.material.reflectionTexture.isReady()));
  for (let attempt = 0; attempt < 200 && !ready(); ++attempt) {
    scene.render();
    await sleep(50);
  }
  if (!ready()) throw new Error('the meshes of the float render never became ready');
  // Under load Babylon can hand back a target it has not drawn into yet (all zero): render again until
  // some pixel holds light, so the checks read the environment and not an empty frame.
  let pixels;
  for (let attempt = 0; attempt < 20; ++attempt) {
    target.render();
    pixels = await target.readPixels();
    if (pixels.some((v) => Number.isFinite(v) && v > 0)) break;
    scene.render();
    await sleep(50);
  }
  target.dispose();
  return Array.from(pixels);
}
