// Times a context-sensitive derivation with the npm package lindenmayer, for bench/context.lua.
// usage: node context_lindenmayer.js MODEL_JSON
//   MODEL_JSON: {"axiom": "...", "productions": {"0<0>0": "0", ...}, "ignore": "+-F",
//                "steps": N}
// Prints one JSON line: {"modules", "length", "seconds", "peak_kib", "version", "hash"}
// modules = sum of the string lengths over all steps; seconds = best of 3 derivations;
// hash = a 32-bit FNV-1a of the final string, to compare with lsys's.
'use strict';
const path = require('path');
const LSystem = require('lindenmayer');
const version = require(path.join(path.dirname(require.resolve('lindenmayer')), '..',
  'package.json')).version;

const spec = JSON.parse(process.argv[2] || 'null');
if (!spec || typeof spec.axiom !== 'string' || !(spec.steps >= 0)) {
  console.error('usage: node context_lindenmayer.js MODEL_JSON');
  process.exit(2);
}

function fnv1a (s) {
  let h = 0x811c9dc5;
  for (let i = 0; i < s.length; i++) {
    h ^= s.charCodeAt(i);
    h = Math.imul(h, 0x01000193) >>> 0;
  }
  return h;
}

let best = Infinity, modules = 0, final = '';
for (let run = 0; run < 3; run++) {
  const ls = new LSystem({ axiom: spec.axiom, productions: spec.productions,
                           ignoredSymbols: spec.ignore || '', branchSymbols: '[]' });
  let sum = 0;
  const t0 = process.hrtime.bigint();
  for (let i = 0; i < spec.steps; i++) sum += ls.iterate(1).length;
  const t1 = process.hrtime.bigint();
  best = Math.min(best, Number(t1 - t0) / 1e9);
  modules = sum;
  final = ls.getString();
}
console.log(JSON.stringify({
  modules, length: final.length, seconds: best, peak_kib: process.resourceUsage().maxRSS,
  version, hash: fnv1a(final),
}));
