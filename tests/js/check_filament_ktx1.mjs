// Reads `iblbake export-filament`'s files with Filament's own reader (npm filament 1.53.4: the WebAssembly
// build of libs/image Ktx1Bundle and libs/ktxreader Ktx1Reader) and checks them against what the export promised.
// Usage: node check_filament_ktx1.mjs DEPLOY_DIR NAME '{"size": 32, "levels": 2}'
// Reads DEPLOY_DIR/NAME_ibl.ktx, NAME_skybox.ktx and sh.txt. Exits 0 and prints "ok ..." when every check holds;
// otherwise prints each failure and exits 1.
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import vm from 'node:vm';
import { here } from './consumer_common.mjs';

const [deployDir, name, expectText] = process.argv.slice(2);
const expect = JSON.parse(expectText);
const failures = [];
const check = (ok, what) => { if (!ok) failures.push(what); };

// filament.js is an Emscripten script that replaces its global `Filament` with the module once the
// WebAssembly is compiled; run it as a script of this context so that the global is reachable.
const filamentDir = path.join(here, 'node_modules', 'filament');
globalThis.require = createRequire(import.meta.url);
globalThis.__dirname = filamentDir;
globalThis.__filename = path.join(filamentDir, 'filament.js');
vm.runInThisContext(readFileSync(globalThis.__filename, 'utf8'));
await new Promise((resolve) => globalThis.Filament.init([], resolve));
const F = globalThis.Filament;

// The KTX1 file through Filament's Ktx1Bundle, and what Ktx1Reader makes of its header.
function readBundle(file) {
  const bytes = new Uint8Array(readFileSync(file));
  const bundle = new F.Ktx1Bundle(F.Buffer(bytes));
  const info = bundle.info();
  const fields = ['glType', 'glTypeSize', 'glFormat', 'glInternalFormat', 'glBaseInternalFormat', 'pixelWidth',
                  'pixelHeight', 'pixelDepth'];
  return { bytes, bundle, header: Object.fromEntries(fields.map((f) => [f, info[f]])) };
}

function checkCube(label, file, levels) {
  const { bytes, bundle, header } = readBundle(file);
  check(bundle.isCubemap(), `${label}: not a cube map for Ktx1Bundle`);
  check(bundle.getArrayLength() === 1, `${label}: array length ${bundle.getArrayLength()}`);
  check(!bundle.isCompressed(), `${label}: Ktx1Reader thinks it compressed`);
  // What Ktx1Reader::createTexture builds the texture with (toTextureFormat, toPixelDataFormat, toPixelDataType).
  check(bundle.getInternalFormat(false) === F.Texture$InternalFormat.R11F_G11F_B10F,
        `${label}: texture format ${bundle.getInternalFormat(false).value}, expected R11F_G11F_B10F`);
  check(bundle.getPixelDataFormat() === F.PixelDataFormat.RGB,
        `${label}: pixel data format ${bundle.getPixelDataFormat().value}, expected RGB`);
  check(bundle.getPixelDataType() === F.PixelDataType.UINT_10F_11F_11F_REV,
        `${label}: pixel data type ${bundle.getPixelDataType().value}, expected UINT_10F_11F_11F_REV`);
  check(header.pixelWidth === expect.size && header.pixelHeight === expect.size && header.pixelDepth === 0,
        `${label}: size ${header.pixelWidth}x${header.pixelHeight}x${header.pixelDepth}, expected ${expect.size}`);
  check(bundle.getNumMipLevels() === levels, `${label}: ${bundle.getNumMipLevels()} levels, expected ${levels}`);
  // Every level's six faces of (size >> m)^2 packed 32-bit texels, and nothing after the last one.
  let levelBytes = 0;
  for (let m = 0; m < bundle.getNumMipLevels(); ++m) {
    const side = expect.size >> m, faceBytes = side * side * 4;
    for (let f = 0; f < 6; ++f) {
      const blob = bundle.getBlob([m, 0, f]);
      check(blob.length === faceBytes, `${label}: level ${m} face ${f}: ${blob.length} bytes, expected ${faceBytes}`);
    }
    levelBytes += 4 + 6 * faceBytes;
  }
  const keyValueBytes = new DataView(bytes.buffer).getUint32(60, true);
  check(bytes.length === 64 + keyValueBytes + levelBytes,
        `${label}: ${bytes.length} bytes, expected ${64 + keyValueBytes + levelBytes} (header, key/values, levels)`);
  return { bundle, header };
}

const ibl = checkCube('ibl', path.join(deployDir, `${name}_ibl.ktx`), expect.levels);
checkCube('skybox', path.join(deployDir, `${name}_skybox.ktx`), 1);

// The SH as createIblFromKtx1 reads it (27 numbers of the key "sh"), against sh.txt as Filament's samples
// read it (sscanf "(%f,%f,%f)" per line).
const shKey = ibl.bundle.getMetadata('sh');
const fromKey = shKey.split(/\s/, 9 * 3).map(parseFloat);
const fromText = readFileSync(path.join(deployDir, 'sh.txt'), 'utf8').trim().split('\n')
  .flatMap((line) => line.slice(line.indexOf('(') + 1, line.indexOf(')')).split(',').map(parseFloat));
check(fromKey.length === 27 && fromKey.every(Number.isFinite), `sh key: ${JSON.stringify(shKey)}`);
check(fromText.length === 27 && fromText.every(Number.isFinite), 'sh.txt: not 9 lines of 3 numbers');
let worst = 0;
fromKey.forEach((v, i) => { worst = Math.max(worst, Math.abs(v - fromText[i]) / Math.max(Math.abs(fromText[i]), 1e-12)); });
check(worst <= 1e-6, `sh key and sh.txt differ by ${worst} (relative)`);

if (failures.length) {
  for (const f of failures) console.log(`FAIL ${f}`);
  process.exit(1);
}
console.log(`ok Filament 1.53.4 Ktx1Bundle: ${name}_ibl.ktx ${expect.size} px, ${expect.levels} levels, R11F_G11F_B10F ` +
            `/ RGB / UINT_10F_11F_11F_REV; ${name}_skybox.ktx; sh key = sh.txt (worst ${worst.toExponential(1)}), ` +
            `L00 ${fromKey.slice(0, 3).map((v) => v.toPrecision(4)).join(' ')}`);
process.exit(0);
