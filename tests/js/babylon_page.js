// Babylon.js side of babylon_gltf.mjs: loads an exported glTF as a user would (the glTF loader's
// EXT_lights_image_based and KHR_lights_punctual), then hands back what Babylon decoded and rendered.
// Served inside consumer_common.mjs enginePage (babylon, a 256-px canvas).

import { renderFloatPixels } from '/tests/babylon_render.js';

// options: { rightHanded, mirrorCamera: [x, y, z] direction from the sphere, fov (radians) }
// renderFloatPixels, with what the checks need to map pixels to directions: { size, pixels, cameraPosition,
// inverseViewProjection } (Babylon's row-vector layout).
async function renderFloat(scene, camera, meshes, size) {
  const pixels = await renderFloatPixels(scene, camera, meshes, size);
  const inverse = BABYLON.Matrix.Invert(camera.getTransformationMatrix().clone());
  return { size, pixels, cameraPosition: camera.position.asArray(), inverseViewProjection: Array.from(inverse.m) };
}

window.runBabylon = async (gltfUrl, options) => {
  const engine = new BABYLON.Engine(document.getElementById('canvas'), false, { preserveDrawingBuffer: true });
  const scene = new BABYLON.Scene(engine);
  scene.useRightHandedSystem = !!options.rightHanded;
  // Materials write linear values (no tone mapping or gamma): the float targets hold radiance.
  scene.imageProcessingConfiguration.applyByPostProcess = true;
  scene.imageProcessingConfiguration.toneMappingEnabled = false;
  const slash = gltfUrl.lastIndexOf('/') + 1;
  await BABYLON.SceneLoader.AppendAsync(gltfUrl.slice(0, slash), gltfUrl.slice(slash), scene);
  const environment = scene.environmentTexture;
  for (let attempt = 0; attempt < 100 && !environment.isReady(); ++attempt)
    await new Promise((r) => setTimeout(r, 50));

  const sun = scene.lights.find((l) => l instanceof BABYLON.DirectionalLight);
  sun.computeWorldMatrix(true);
  sun.computeTransformedInformation();
  const towardSun = (sun.transformedDirection ?? sun.direction).scale(-1).normalize().asArray();
  sun.setEnabled(false); // the renders show the environment alone

  const size = environment.getSize().width;
  const faces = [];
  for (let f = 0; f < 6; ++f) faces.push(Array.from(await environment.readPixels(f, 0)));
  const harmonics = environment.sphericalPolynomial.preScaledHarmonics;
  const preScaledHarmonics = ['l00', 'l1_1', 'l10', 'l11', 'l2_2', 'l2_1', 'l20', 'l21', 'l22']
    .map((k) => harmonics[k].asArray());

  const skybox = scene.createDefaultSkybox(environment, true, 1000, 0);
  // Babylon's PBR shader clamps its output to 30 when image processing is left to a post-process, and
  // the loader's RawCubeTexture keeps gammaSpace = true, so the shader raises the decoded values to 2.2
  // (GAMMAREFLECTION) before the level: the renders run at a level that keeps 255^2.2 below 30. They
  // are read for directions (brightest spot, sky above the horizon), not for absolute values.
  const level = environment.level, renderLevel = 1e-4, gammaSpace = environment.gammaSpace;
  environment.level = renderLevel;
  skybox.material.reflectionTexture.level = renderLevel;
  const sphere = BABYLON.MeshBuilder.CreateSphere('mirror', { diameter: 2, segments: 128 }, scene);
  const mirror = new BABYLON.PBRMaterial('mirror', scene);
  mirror.metallic = 1;
  mirror.roughness = 0;
  mirror.albedoColor = new BABYLON.Color3(1, 1, 1);
  sphere.material = mirror;

  // The mirror sphere seen from options.mirrorCamera (4 radii away), and the sky toward the sun.
  const distance = 4;
  const mirrorCamera = new BABYLON.UniversalCamera('mirror camera',
    BABYLON.Vector3.FromArray(options.mirrorCamera).normalize().scale(distance), scene);
  mirrorCamera.setTarget(BABYLON.Vector3.Zero());
  mirrorCamera.fov = options.fov;
  mirrorCamera.minZ = 0.1;
  const mirrorView = await renderFloat(scene, mirrorCamera, [skybox, sphere], options.size);

  const sunCamera = new BABYLON.UniversalCamera('sun camera', BABYLON.Vector3.Zero(), scene);
  sunCamera.setTarget(BABYLON.Vector3.FromArray(towardSun));
  sunCamera.fov = options.fov;
  sunCamera.minZ = 0.1;
  const sunView = await renderFloat(scene, sunCamera, [skybox], options.size);

  return {
    babylonVersion: BABYLON.Engine.Version, rightHanded: scene.useRightHandedSystem, towardSun,
    level, renderLevel, gammaSpace, size, textureType: environment.textureType, faces, preScaledHarmonics,
    reflectionMatrix: Array.from(environment.getReflectionTextureMatrix().m), invertZ: !!environment.invertZ,
    mirrorView, sunView,
  };
};
