// Filament side of filament_fidelity.mjs: white metal spheres (glTF metal-roughness materials through
// gltfio's ubershaders) lit by our NAME_ibl.ktx through engine.createIblFromKtx1, each rendered head-on by an
// orthographic camera with post-processing off (linear output) and read back at several scales of the light's
// intensity, since the WebGL default framebuffer holds 8 bits per channel.
// Served inside consumer_common.mjs enginePage (filament, a 32-px canvas).

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// A unit UV sphere (positions = normals) with one glTF metal-roughness material, as a GLB.
function sphereGlb(roughness, metallic) {
  const columns = 128, rows = 64, positions = [], indices = [];
  for (let i = 0; i <= rows; ++i) {
    const theta = (Math.PI * i) / rows;
    for (let j = 0; j <= columns; ++j) {
      const phi = (2 * Math.PI * j) / columns;
      positions.push(Math.sin(theta) * Math.cos(phi), Math.cos(theta), Math.sin(theta) * Math.sin(phi));
    }
  }
  for (let i = 0; i < rows; ++i)
    for (let j = 0; j < columns; ++j) {
      const a = i * (columns + 1) + j, b = a + columns + 1;
      indices.push(a, a + 1, b, a + 1, b + 1, b);
    }
  const vertexBytes = positions.length * 4, indexBytes = indices.length * 4;
  const bin = new Uint8Array(2 * vertexBytes + indexBytes);
  new Float32Array(bin.buffer, 0, positions.length).set(positions);
  new Float32Array(bin.buffer, vertexBytes, positions.length).set(positions);
  new Uint32Array(bin.buffer, 2 * vertexBytes, indices.length).set(indices);
  const count = positions.length / 3;
  const gltf = {
    asset: { version: '2.0' }, scene: 0, scenes: [{ nodes: [0] }], nodes: [{ mesh: 0 }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0, NORMAL: 1 }, indices: 2, material: 0 }] }],
    materials: [{ pbrMetallicRoughness: { baseColorFactor: [1, 1, 1, 1], metallicFactor: metallic,
                                          roughnessFactor: roughness } }],
    accessors: [
      { bufferView: 0, componentType: 5126, count, type: 'VEC3', min: [-1, -1, -1], max: [1, 1, 1] },
      { bufferView: 1, componentType: 5126, count, type: 'VEC3' },
      { bufferView: 2, componentType: 5125, count: indices.length, type: 'SCALAR' }],
    bufferViews: [{ buffer: 0, byteOffset: 0, byteLength: vertexBytes },
                  { buffer: 0, byteOffset: vertexBytes, byteLength: vertexBytes },
                  { buffer: 0, byteOffset: 2 * vertexBytes, byteLength: indexBytes }],
    buffers: [{ byteLength: bin.length }],
  };
  let json = new TextEncoder().encode(JSON.stringify(gltf));
  const jsonLength = Math.ceil(json.length / 4) * 4;
  const glb = new Uint8Array(12 + 8 + jsonLength + 8 + bin.length);
  const view = new DataView(glb.buffer);
  view.setUint32(0, 0x46546c67, true); view.setUint32(4, 2, true); view.setUint32(8, glb.length, true);
  view.setUint32(12, jsonLength, true); view.setUint32(16, 0x4e4f534a, true);
  glb.fill(0x20, 20, 20 + jsonLength); glb.set(json, 20);
  view.setUint32(20 + jsonLength, bin.length, true); view.setUint32(24 + jsonLength, 0x004e4942, true);
  glb.set(bin, 28 + jsonLength);
  return glb;
}

// options: { iblUrl, intensity, roughness: [...], pixels, scales: [...] (largest first) }. Returns per
// roughness the linear RGBA of every pixel (rows bottom to top): for each pixel the value at the largest
// scale of the IndirectLight's intensity at which its brightest channel stays below 250/255, divided by that
// scale. The camera's exposure stays 1 (Camera::setExposure(1): aperture 1, shutter 1.2 s, ISO 100).
window.runFilamentFidelity = async (options) => {
  await new Promise((resolve) => Filament.init([options.iblUrl], resolve));
  const canvas = document.getElementById('canvas');
  const size = options.pixels;
  canvas.width = canvas.height = size;
  const engine = Filament.Engine.create(canvas, { preserveDrawingBuffer: true });
  const gl = canvas.getContext('webgl2'); // the context Filament.Engine.create made
  const scene = engine.createScene();
  const swapChain = engine.createSwapChain();
  const renderer = engine.createRenderer();
  renderer.setClearOptions({ clearColor: [0, 0, 0, 0], clear: true });
  const camera = engine.createCamera(Filament.EntityManager.get().create());
  camera.setProjection(Filament.Camera$Projection.ORTHO, -1, 1, -1, 1, 0.1, 10);
  camera.lookAt([0, 0, -3], [0, 0, 0], [0, 1, 0]);
  const view = engine.createView();
  view.setCamera(camera);
  view.setScene(scene);
  view.setViewport([0, 0, size, size]);
  view.setPostProcessingEnabled(false);
  camera.setExposureDirect(1);
  const ibl = engine.createIblFromKtx1(options.iblUrl);
  scene.setIndirectLight(ibl);
  const loader = engine.createAssetLoader();
  const facts = { shL00: ibl.shfloats.slice(0, 3) };

  const renders = [];
  for (const roughness of options.roughness) {
    const asset = loader.createAsset(sphereGlb(roughness, 1));
    await new Promise((resolve) => asset.loadResources(resolve, null, '' + document.location));
    scene.addEntities(asset.getEntities());
    const linear = new Float32Array(size * size * 4).fill(NaN);
    const bytes = new Uint8Array(size * size * 4);
    for (const scale of options.scales) {
      ibl.setIntensity(options.intensity * scale);
      // A few frames with pauses: the browser compiles the material's program asynchronously and Filament
      // draws it once compiled.
      for (let frame = 0; frame < 3; ++frame) {
        renderer.render(swapChain, view);
        await sleep(10);
      }
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
      gl.readPixels(0, 0, size, size, gl.RGBA, gl.UNSIGNED_BYTE, bytes);
      for (let p = 0; p < size * size; ++p) {
        if (!Number.isNaN(linear[4 * p])) continue;
        const top = Math.max(bytes[4 * p], bytes[4 * p + 1], bytes[4 * p + 2]);
        if (top >= 250) continue; // clipped: a smaller scale takes it
        for (let c = 0; c < 3; ++c) linear[4 * p + c] = bytes[4 * p + c] / 255 / scale;
        linear[4 * p + 3] = bytes[4 * p + 3] / 255;
      }
    }
    scene.removeEntities(asset.getEntities());
    loader.destroyAsset(asset);
    renders.push(Array.from(linear));
  }
  return { facts, renders };
};
