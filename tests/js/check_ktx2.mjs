// Reads a KTX 2.0 file with ktx-parse (an implementation independent of iblbake's reader) and checks it
// against what the writer promised.
// Usage: node check_ktx2.mjs FILE.ktx2 '{"vkFormat": 97, "pixelWidth": 64, ["pixelHeight": 64,] "levelCount": 7,
//        "faceCount": 6, "layerCount": 0, ["alphaPremultiplied": true,] "keys": ["iblbake.product", ...],
//        "keyValues": {"k": "v"}}'   (alphaPremultiplied: the DFD's flag, expected clear when not given)
// Exits 0 and prints "ok ..." when every check holds; otherwise prints each failure and exits 1.
import { readFileSync } from 'node:fs';
import { read, KHR_DF_FLAG_ALPHA_PREMULTIPLIED, KHR_DF_MODEL_RGBSDA, KHR_DF_PRIMARIES_BT709, KHR_DF_TRANSFER_LINEAR }
  from 'ktx-parse';

const [file, expectText] = process.argv.slice(2);
const expect = JSON.parse(expectText);
const failures = [];
const check = (ok, what) => { if (!ok) failures.push(what); };

// What the Khronos Data Format Specification and Vulkan give for each format iblbake writes:
// texel block bytes, typeSize, and the samples (channel id | qualifiers, bit offset, bit length); BC6H's
// texel block is 4 x 4 texels of colour model KHR_DF_MODEL_BC6H (131), one 128-bit sample (KDF "BC6H").
const FLOAT = 0x80, SIGNED = 0x40, EXPONENT = 0x20;
const FORMATS = {
  97: { name: 'R16G16B16A16_SFLOAT', bytes: 8, typeSize: 2,
        samples: [[0 | FLOAT | SIGNED, 0, 16], [1 | FLOAT | SIGNED, 16, 16], [2 | FLOAT | SIGNED, 32, 16], [15 | FLOAT | SIGNED, 48, 16]] },
  109: { name: 'R32G32B32A32_SFLOAT', bytes: 16, typeSize: 4,
         samples: [[0 | FLOAT | SIGNED, 0, 32], [1 | FLOAT | SIGNED, 32, 32], [2 | FLOAT | SIGNED, 64, 32], [15 | FLOAT | SIGNED, 96, 32]] },
  122: { name: 'B10G11R11_UFLOAT_PACK32', bytes: 4, typeSize: 4,
         samples: [[0 | FLOAT, 0, 11], [1 | FLOAT, 11, 11], [2 | FLOAT, 22, 10]] },
  123: { name: 'E5B9G9R9_UFLOAT_PACK32', bytes: 4, typeSize: 4,
         samples: [[0, 0, 9], [0 | EXPONENT, 27, 5], [1, 9, 9], [1 | EXPONENT, 27, 5], [2, 18, 9], [2 | EXPONENT, 27, 5]] },
  131: { name: 'BC6H_UFLOAT_BLOCK', bytes: 16, typeSize: 1, block: 4, model: 131, samples: [[0 | FLOAT, 0, 128]] },
};

const bytes = new Uint8Array(readFileSync(file));
let ktx;
try {
  ktx = read(bytes);
} catch (e) {
  console.log(`FAIL ${file}: ktx-parse refused it: ${e.message}`);
  process.exit(1);
}

const format = FORMATS[ktx.vkFormat];
check(ktx.vkFormat === expect.vkFormat, `vkFormat ${ktx.vkFormat}, expected ${expect.vkFormat}`);
check(format !== undefined, `vkFormat ${ktx.vkFormat} is not one iblbake writes`);
const expectHeight = expect.pixelHeight ?? expect.pixelWidth; // cube faces are square
check(ktx.pixelWidth === expect.pixelWidth && ktx.pixelHeight === expectHeight,
      `size ${ktx.pixelWidth}x${ktx.pixelHeight}, expected ${expect.pixelWidth}x${expectHeight}`);
check(ktx.pixelDepth === 0, `pixelDepth ${ktx.pixelDepth}, expected 0 (not a 3D texture)`);
check(ktx.faceCount === expect.faceCount, `faceCount ${ktx.faceCount}, expected ${expect.faceCount}`);
check(ktx.layerCount === expect.layerCount, `layerCount ${ktx.layerCount}, expected ${expect.layerCount}`);
check(ktx.levelCount === expect.levelCount, `levelCount ${ktx.levelCount}, expected ${expect.levelCount}`);
check(ktx.levels.length === Math.max(1, expect.levelCount), `${ktx.levels.length} levels in the index`);
check(ktx.supercompressionScheme === 0, `supercompressionScheme ${ktx.supercompressionScheme}, expected 0`);

if (format) {
  check(ktx.typeSize === format.typeSize, `typeSize ${ktx.typeSize}, expected ${format.typeSize} for ${format.name}`);
  // Level m holds max(1, layerCount) x faceCount images of max(1, size >> m) texels per axis in whole texel
  // blocks, nothing more or less.
  const images = Math.max(1, ktx.layerCount) * ktx.faceCount;
  const block = format.block ?? 1;
  ktx.levels.forEach((level, m) => {
    const w = Math.ceil(Math.max(1, ktx.pixelWidth >> m) / block), h = Math.ceil(Math.max(1, ktx.pixelHeight >> m) / block);
    const expected = images * w * h * format.bytes;
    check(level.levelData.byteLength === expected,
          `level ${m}: ${level.levelData.byteLength} bytes, expected ${expected} (${images} x ${w}x${h} x ${format.bytes})`);
    check(level.uncompressedByteLength === expected,
          `level ${m}: uncompressedByteLength ${level.uncompressedByteLength}, expected ${expected}`);
  });

  // The DFD: one basic block, RGBSDA (BC6H: its own model), BT.709, linear, 1x1x1x1 texels (BC6H: 4x4x1x1),
  // bytesPlane0 = texel block size, and the KDF's samples for the format.
  check(ktx.dataFormatDescriptor.length === 1, `${ktx.dataFormatDescriptor.length} DFD blocks, expected 1`);
  const dfd = ktx.dataFormatDescriptor[0];
  check(dfd.vendorId === 0 && dfd.descriptorType === 0 && dfd.versionNumber === 2,
        `DFD vendor/type/version ${dfd.vendorId}/${dfd.descriptorType}/${dfd.versionNumber}, expected 0/0/2`);
  const model = format.model ?? KHR_DF_MODEL_RGBSDA;
  check(dfd.colorModel === model, `DFD colorModel ${dfd.colorModel}, expected ${model}`);
  check(dfd.colorPrimaries === KHR_DF_PRIMARIES_BT709, `DFD colorPrimaries ${dfd.colorPrimaries}, expected BT709`);
  check(dfd.transferFunction === KHR_DF_TRANSFER_LINEAR, `DFD transferFunction ${dfd.transferFunction}, expected LINEAR`);
  const premultiplied = (dfd.flags & KHR_DF_FLAG_ALPHA_PREMULTIPLIED) !== 0;
  check(premultiplied === (expect.alphaPremultiplied ?? false),
        `DFD flags ${dfd.flags}: alpha ${premultiplied ? 'premultiplied' : 'straight'}, expected ` +
        `${expect.alphaPremultiplied ? 'premultiplied' : 'straight'}`);
  const dimensions = [block - 1, block - 1, 0, 0];
  check(dfd.texelBlockDimension.every((d, i) => d === dimensions[i]), `DFD texelBlockDimension ${dfd.texelBlockDimension}`);
  check(dfd.bytesPlane[0] === format.bytes && dfd.bytesPlane.slice(1).every((b) => b === 0),
        `DFD bytesPlane ${dfd.bytesPlane}, expected [${format.bytes}, 0...]`);
  check(dfd.samples.length === format.samples.length, `DFD ${dfd.samples.length} samples, expected ${format.samples.length}`);
  format.samples.forEach(([channelType, bitOffset, bitLength], i) => {
    const s = dfd.samples[i];
    if (!s) return;
    check(s.channelType === channelType && s.bitOffset === bitOffset && s.bitLength === bitLength - 1,
          `DFD sample ${i}: channelType 0x${s.channelType.toString(16)} offset ${s.bitOffset} length ${s.bitLength + 1}, ` +
          `expected 0x${channelType.toString(16)} ${bitOffset} ${bitLength}`);
  });
  // The samples cover exactly the texel block's bits.
  const bitsCovered = new Set();
  dfd.samples.forEach((s) => { for (let b = 0; b <= s.bitLength; ++b) bitsCovered.add(s.bitOffset + b); });
  check(Math.max(...bitsCovered) + 1 <= format.bytes * 8, `DFD samples reach past the ${format.bytes}-byte texel`);
}

// Key/value data: KTXwriter is ours, the required keys are there, the given values match exactly.
const kv = ktx.keyValue;
const text = (v) => (typeof v === 'string' ? v : new TextDecoder().decode(v).replace(/\0$/, ''));
check(typeof kv.KTXwriter !== 'undefined' && text(kv.KTXwriter).startsWith('iblbake '),
      `KTXwriter ${kv.KTXwriter === undefined ? 'missing' : JSON.stringify(text(kv.KTXwriter))}`);
for (const key of expect.keys ?? []) check(key in kv, `key ${key} missing`);
for (const [key, value] of Object.entries(expect.keyValues ?? {}))
  check(key in kv && text(kv[key]) === value, `key ${key} = ${JSON.stringify(kv[key] && text(kv[key]))}, expected ${JSON.stringify(value)}`);

if (failures.length) {
  for (const f of failures) console.log(`FAIL ${file}: ${f}`);
  process.exit(1);
}
console.log(`ok ${file}: ${format.name}, ${ktx.pixelWidth} px, ${ktx.levelCount} levels, ${ktx.faceCount} faces, ` +
            `${Object.keys(kv).length} keys`);
