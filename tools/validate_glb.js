#!/usr/bin/env node
// Validates .glb (or .gltf) files with the Khronos glTF validator and prints every issue.
// Exits 1 when a file has errors (or warnings, with --strict), 2 on bad usage or an
// unreadable file.
//
//   npm ci --prefix tools            # once: installs gltf-validator into tools/node_modules
//   node tools/validate_glb.js [--strict] file.glb ...
'use strict';

const fs = require('fs');
const path = require('path');

let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.error('gltf-validator is not installed: run `npm ci --prefix tools`');
  process.exit(2);
}

const SEVERITY = ['error', 'warning', 'info', 'hint'];

async function validate(file, strict) {
  let bytes;
  try {
    bytes = new Uint8Array(fs.readFileSync(file));
  } catch (e) {
    console.error(`${file}: ${e.message}`);
    return 2;
  }
  let report;
  try {
    report = await validator.validateBytes(bytes, {
      uri: path.basename(file),
      maxIssues: 0, // no limit
      externalResourceFunction: (uri) => Promise.reject(new Error(`external resource ${uri}`)),
    });
  } catch (e) {
    console.error(`${file}: ${e}`);
    return 1;
  }
  const is = report.issues;
  for (const m of is.messages) {
    const where = m.pointer ? ` at ${m.pointer}` : (m.offset !== undefined ? ` at byte ${m.offset}` : '');
    console.log(`${file}: ${SEVERITY[m.severity] || m.severity}: ${m.code}${where}: ${m.message}`);
  }
  const info = report.info || {};
  console.log(`${file}: ${is.numErrors} errors, ${is.numWarnings} warnings, ${is.numInfos} infos, ` +
              `${is.numHints} hints (${info.drawCallCount || 0} draw calls, ` +
              `${info.totalTriangleCount || 0} triangles, ${info.totalVertexCount || 0} vertices)`);
  return is.numErrors > 0 || (strict && is.numWarnings > 0) ? 1 : 0;
}

async function main() {
  const args = process.argv.slice(2);
  const strict = args.includes('--strict');
  const files = args.filter((a) => a !== '--strict');
  if (files.length === 0) {
    console.error('usage: node tools/validate_glb.js [--strict] file.glb ...');
    process.exit(2);
  }
  let status = 0;
  for (const f of files) status = Math.max(status, await validate(f, strict));
  process.exit(status);
}

main();
