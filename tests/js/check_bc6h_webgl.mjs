// Decodes BC6H blocks with Chromium's WebGL2 EXT_texture_compression_bptc (SwiftShader: a decoder independent
// of iblbake's) and compares every texel with the values iblbake's decoder gave.
// Usage: node check_bc6h_webgl.mjs BLOCKS.bin EXPECTED.f32 WIDTH HEIGHT
//   BLOCKS.bin: WIDTH/4 x HEIGHT/4 BC6H (unsigned) blocks in rows; EXPECTED.f32: WIDTH x HEIGHT x RGB floats.
// The texture is drawn texel for texel (texelFetch) into an RGBA32F framebuffer and read back as floats.
// Exits 0 and prints "ok ..." when every texel matches; otherwise prints the first mismatches and exits 1.
import { readFileSync } from 'node:fs';
import puppeteer from 'puppeteer-core';

const [blocksFile, expectedFile, widthText, heightText] = process.argv.slice(2);
const width = Number(widthText), height = Number(heightText);
const blocks = readFileSync(blocksFile).toString('base64');
const expected = new Float32Array(new Uint8Array(readFileSync(expectedFile)).buffer);

const browser = await puppeteer.launch({
  executablePath: '/usr/bin/chromium',
  headless: true,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
});
let result;
try {
  const page = await browser.newPage();
  result = await page.evaluate((blocksBase64, w, h) => {
    const gl = document.createElement('canvas').getContext('webgl2');
    if (!gl) return { error: 'no WebGL2' };
    const bptc = gl.getExtension('EXT_texture_compression_bptc');
    if (!bptc) return { error: 'EXT_texture_compression_bptc is not exposed' };
    if (!gl.getExtension('EXT_color_buffer_float')) return { error: 'EXT_color_buffer_float is not exposed' };
    const data = Uint8Array.from(atob(blocksBase64), (c) => c.charCodeAt(0));
    const texture = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, texture);
    gl.compressedTexImage2D(gl.TEXTURE_2D, 0, bptc.COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT_EXT, w, h, 0, data);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    const target = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, target);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, w, h);
    const framebuffer = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, target, 0);
    const compile = (type, source) => {
      const shader = gl.createShader(type);
      gl.shaderSource(shader, source);
      gl.compileShader(shader);
      return shader;
    };
    const program = gl.createProgram();
    gl.attachShader(program, compile(gl.VERTEX_SHADER, `#version 300 es
      void main() { vec2 p = vec2(gl_VertexID & 1, gl_VertexID >> 1) * 4.0 - 1.0; gl_Position = vec4(p, 0, 1); }`));
    gl.attachShader(program, compile(gl.FRAGMENT_SHADER, `#version 300 es
      precision highp float; uniform highp sampler2D blocks; out vec4 colour;
      void main() { colour = texelFetch(blocks, ivec2(gl_FragCoord.xy), 0); }`));
    gl.linkProgram(program);
    if (!gl.getProgramParameter(program, gl.LINK_STATUS)) return { error: gl.getProgramInfoLog(program) };
    gl.useProgram(program);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, texture);
    gl.uniform1i(gl.getUniformLocation(program, 'blocks'), 0);
    gl.viewport(0, 0, w, h);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    const pixels = new Float32Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.FLOAT, pixels);
    const glError = gl.getError();
    if (glError !== gl.NO_ERROR) return { error: `GL error 0x${glError.toString(16)}` };
    return { renderer: gl.getParameter(gl.RENDERER), pixels: Array.from(pixels) };
  }, blocks, width, height);
} finally {
  await browser.close();
}

if (result.error) {
  console.log(`FAIL ${blocksFile}: ${result.error}`);
  process.exit(1);
}
// Row y of the framebuffer is texture row y (texelFetch at gl_FragCoord), the file's row y.
const failures = [];
for (let y = 0; y < height; ++y)
  for (let x = 0; x < width; ++x)
    for (let c = 0; c < 3; ++c) {
      const theirs = result.pixels[(y * width + x) * 4 + c], ours = expected[(y * width + x) * 3 + c];
      if (theirs !== ours) failures.push(`texel (${x}, ${y}) channel ${c}: WebGL ${theirs}, iblbake ${ours}`);
    }
if (failures.length) {
  for (const f of failures.slice(0, 10)) console.log(`FAIL ${blocksFile}: ${f}`);
  console.log(`FAIL ${blocksFile}: ${failures.length} of ${width * height * 3} channels differ`);
  process.exit(1);
}
console.log(`ok ${blocksFile}: ${width}x${height} BC6H texels decoded by ${result.renderer} as by iblbake`);
