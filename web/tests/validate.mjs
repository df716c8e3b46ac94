// The Khronos glTF validator (npm gltf-validator) on each file named: its
// errors listed; exit 1 if any file has one. Warnings and infos are counted.
// Usage: node validate.mjs FILE.glb...
import { readFileSync } from 'node:fs';
import validator from 'gltf-validator';

let failed = 0;
for (const file of process.argv.slice(2)) {
  const report = await validator.validateBytes(new Uint8Array(readFileSync(file)), { maxIssues: 100 });
  const errors = report.issues.messages.filter((m) => m.severity === 0);
  console.log(`${errors.length ? 'FAIL' : 'ok  '} ${file}: the Khronos validator reports ${report.issues.numErrors} errors, ${report.issues.numWarnings} warnings` +
    errors.slice(0, 5).map((m) => `\n     ${m.code} ${m.pointer} ${m.message}`).join(''));
  failed += errors.length > 0;
}
process.exit(failed ? 1 : 0);
