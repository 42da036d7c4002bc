#!/usr/bin/env node
// Runs the Khronos glTF validator (npm package gltf-validator, a library) over
// .gltf/.glb files, loading external buffers and images beside each file.
//
// usage: node validate_gltf.js [--json] FILE...
//   Finds gltf-validator through NODE_PATH, or in $RAYFORM_NODE_TOOLS/node_modules
//   (scripts/install-node-tools installs it).
// Prints one line per file:  FILE: errors E, warnings W, infos I, hints H
// followed by every error and warning (code, pointer, message); --json prints
// the validator's full reports instead. Exit status: 0 when no file has an
// error, 1 when some file has, 2 on bad usage or a missing validator.
'use strict';
const fs = require('fs');
const path = require('path');

function loadValidator() {
  const tries = ['gltf-validator'];
  if (process.env.RAYFORM_NODE_TOOLS) tries.push(path.resolve(process.env.RAYFORM_NODE_TOOLS, 'node_modules', 'gltf-validator'));
  for (const t of tries) {
    try { return require(t); } catch (e) { /* next */ }
  }
  console.error('validate_gltf.js: gltf-validator not found (run scripts/install-node-tools and set RAYFORM_NODE_TOOLS)');
  process.exit(2);
}

async function validate(validator, file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  return validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0,  // no limit
    externalResourceFunction: (uri) => new Promise((resolve, reject) => {
      const p = path.resolve(path.dirname(file), decodeURIComponent(uri));
      fs.readFile(p, (err, data) => (err ? reject(err.toString()) : resolve(new Uint8Array(data))));
    }),
  });
}

async function main() {
  const args = process.argv.slice(2);
  const json = args[0] === '--json';
  const files = json ? args.slice(1) : args;
  if (files.length === 0) {
    console.error('usage: node validate_gltf.js [--json] FILE...');
    process.exit(2);
  }
  const validator = loadValidator();
  let failed = false;
  for (const file of files) {
    let report;
    try {
      report = await validate(validator, file);
    } catch (e) {
      console.log(`${file}: validator failed: ${e}`);
      failed = true;
      continue;
    }
    const s = report.issues;
    if (json) {
      console.log(JSON.stringify(report, null, 2));
    } else {
      console.log(`${file}: errors ${s.numErrors}, warnings ${s.numWarnings}, infos ${s.numInfos}, hints ${s.numHints}`);
      for (const m of s.messages) {
        if (m.severity > 1) continue;  // 0 error, 1 warning, 2 info, 3 hint
        console.log(`  ${m.severity === 0 ? 'ERROR' : 'WARNING'} ${m.code} ${m.pointer || ''}: ${m.message}`);
      }
    }
    if (s.numErrors > 0) failed = true;
  }
  process.exit(failed ? 1 : 0);
}

main();
