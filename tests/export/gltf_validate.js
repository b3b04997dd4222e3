// Runs the Khronos glTF validator (npm package gltf-validator) on each file named on the command
// line and prints its issues. Exit status: 0 no errors, 1 errors, 77 validator not installed.
'use strict';
const fs = require('fs');
const path = require('path');

let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.log('gltf-validator is not installed (npm install --prefix BUILD/npm gltf-validator)');
  process.exit(77);
}

const severity = ['error', 'warning', 'info', 'hint'];

(async () => {
  let errors = 0;
  for (const file of process.argv.slice(2)) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
      uri: path.basename(file),
      maxIssues: 100,
    });
    const i = report.issues;
    console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ` +
                `${i.numInfos} infos, ${i.numHints} hints`);
    for (const m of i.messages) {
      console.log(`  ${severity[m.severity]} ${m.code} ${m.pointer || ''}: ${m.message}`);
    }
    errors += i.numErrors;
  }
  process.exit(errors > 0 ? 1 : 0);
})().catch((e) => {
  console.error(e);
  process.exit(2);
});
