// Validates glTF / GLB files with the Khronos glTF-Validator (npm package gltf-validator).
// Usage: node scripts/validate-gltf.mjs VALIDATOR_DIR FILE...; exits 1 if any file has an error.
// VALIDATOR_DIR may be relative (CI's default target folder): createRequire needs an absolute path.
import { readFileSync } from "node:fs";
import { createRequire } from "node:module";
import { resolve, basename } from "node:path";

const [dir, ...files] = process.argv.slice(2);
const validator = createRequire(resolve(dir, "package.json"))("gltf-validator");
let failed = 0;
for (const file of files) {
  const report = await validator.validateBytes(new Uint8Array(readFileSync(file)), {
    uri: basename(file),
    maxIssues: 1000,
  });
  const { numErrors, numWarnings, numInfos, messages } = report.issues;
  console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos (glTF-Validator ${report.validatorVersion})`);
  for (const m of messages.filter((m) => m.severity <= 1)) {
    console.log(`  ${m.severity === 0 ? "error" : "warning"} ${m.code} ${m.pointer ?? ""}: ${m.message}`);
  }
  if (numErrors > 0) failed += 1;
}
console.log(`glTF-Validator: ${files.length - failed} passed, ${failed} failed`);
process.exit(failed > 0 ? 1 : 0);
