// Babylon.js side of render_fidelity.mjs: white metal spheres lit by an environment (our glTF through the
// stock loader, or Babylon's own HDRCubeTexture prefilter of the raw HDRI), each rendered head-on by an
// orthographic camera into a 32-bit float target and handed back.
// Served inside consumer_common.mjs enginePage (babylon, a 64-px canvas).

import { renderFloatPixels } from '/tests/babylon_render.js';

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// Renders white metal and white dielectric (metallic 0) spheres; keyed '<variant>/metal', '<variant>/dielectric'.
// source: { gltf: url } or { hdr: url, faceSize }. variants: [{ name, energyConservation, horizonOcclusion,
// mixIrradiance }]. environmentScale: multiplies the environment's level (a linear scale, undone by the
// caller) to keep the output below the PBR shader's clamp at 30.
window.runFidelity = async (source, options) => {
  const engine = new BABYLON.Engine(document.getElementById('canvas'), false, { preserveDrawingBuffer: true });
  const scene = new BABYLON.Scene(engine);
  // Materials write linear values (no tone mapping or gamma): the float targets hold radiance.
  scene.imageProcessingConfiguration.applyByPostProcess = true;
  scene.imageProcessingConfiguration.toneMappingEnabled = false;
  let environment;
  if (source.gltf) {
    const slash = source.gltf.lastIndexOf('/') + 1;
    await BABYLON.SceneLoader.AppendAsync(source.gltf.slice(0, slash), source.gltf.slice(slash), scene);
    environment = scene.environmentTexture;
    for (const light of scene.lights) light.setEnabled(false);
  } else {
    environment = new BABYLON.HDRCubeTexture(source.hdr, scene, source.faceSize, false, true, false, true);
    scene.environmentTexture = environment;
  }
  for (let attempt = 0; attempt < 600 && !environment.isReady(); ++attempt) await sleep(50);
  if (!environment.isReady()) throw new Error('the environment never became ready');
  const facts = { babylonVersion: BABYLON.Engine.Version, level: environment.level,
                  gammaSpace: environment.gammaSpace, linearSpecularLOD: !!environment.linearSpecularLOD,
                  lodGenerationScale: environment.lodGenerationScale,
                  lodGenerationOffset: environment.lodGenerationOffset, size: environment.getSize().width };
  environment.level *= options.environmentScale;

  const camera = new BABYLON.FreeCamera('camera', new BABYLON.Vector3(0, 0, -3), scene);
  camera.setTarget(BABYLON.Vector3.Zero());
  camera.mode = BABYLON.Camera.ORTHOGRAPHIC_CAMERA;
  camera.orthoLeft = -1; camera.orthoRight = 1; camera.orthoTop = 1; camera.orthoBottom = -1;
  camera.minZ = 0.1; camera.maxZ = 10;
  scene.activeCamera = camera;
  const sphere = BABYLON.MeshBuilder.CreateSphere('sphere', { diameter: 2, segments: 128 }, scene);
  const renders = {};
  for (const variant of options.variants)
    for (const [name, metallic] of [['metal', 1], ['dielectric', 0]]) {
    renders[`${variant.name}/${name}`] = [];
    for (const roughness of options.roughness) {
      const material = new BABYLON.PBRMaterial(`${name} ${roughness}`, scene);
      material.metallic = metallic;
      material.roughness = roughness;
      material.albedoColor = new BABYLON.Color3(1, 1, 1);
      material.brdf.useEnergyConservation = variant.energyConservation;
      material.brdf.mixIblRadianceWithIrradiance = variant.mixIrradiance;
      material.useHorizonOcclusion = variant.horizonOcclusion;
      material.useRadianceOcclusion = variant.horizonOcclusion;
      sphere.material = material;
      renders[`${variant.name}/${name}`].push(await renderFloatPixels(scene, camera, [sphere], options.pixels));
      material.dispose();
    }
  }
  engine.dispose();
  return { facts, renders };
};
