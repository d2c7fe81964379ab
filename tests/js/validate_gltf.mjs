// Validates a .gltf (and the images it references) with Khronos' glTF-Validator.
// Usage: node validate_gltf.mjs FILE.gltf
// Prints the issue counts and every message that is not an error too, then one JSON line
// ("report {...}") with the counts; exits 1 when the validator reports an error.
import { readFileSync } from 'node:fs';
import path from 'node:path';
import validator from 'gltf-validator';

const file = process.argv[2];
const dir = path.dirname(file);
const report = await validator.validateBytes(new Uint8Array(readFileSync(file)), {
  uri: path.basename(file),
  format: 'gltf',
  maxIssues: 0,
  writeTimestamp: false,
  externalResourceFunction: (uri) =>
    new Promise((resolve, reject) => {
      try {
        resolve(new Uint8Array(readFileSync(path.join(dir, decodeURIComponent(uri)))));
      } catch (e) {
        reject(e.message);
      }
    }),
});
const severities = ['error', 'warning', 'info', 'hint'];
for (const m of report.issues.messages)
  console.log(`${severities[m.severity]} ${m.code} ${m.pointer ?? ''}: ${m.message}`);
const counts = {
  errors: report.issues.numErrors,
  warnings: report.issues.numWarnings,
  infos: report.issues.numInfos,
  hints: report.issues.numHints,
  images: report.info?.resources?.filter((r) => r.image).length ?? 0,
};
console.log(`report ${JSON.stringify(counts)}`);
process.exit(counts.errors > 0 ? 1 : 0);
