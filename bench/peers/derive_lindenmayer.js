// Times the two fixed derivations of bench/derive.lua with the npm package lindenmayer.
// usage: node derive_lindenmayer.js a|b STEPS
// Prints one JSON line: {"model", "steps", "modules", "length", "seconds", "peak_kib", "version"}
// modules = sum of the string lengths over all steps; seconds = best of 3 derivations;
// peak_kib = process peak resident set size (resourceUsage().maxRSS).
'use strict';
const path = require('path');
const LSystem = require('lindenmayer');
const version = require(path.join(path.dirname(require.resolve('lindenmayer')), '..', 'package.json')).version;

const R = 1.456;

// (b) as a function production on objects {symbol, s}; modules without parameters are shared
// constant objects, as a JS user would write them.
const OPEN = { symbol: '[' }, CLOSE = { symbol: ']' }, PLUS = { symbol: '+' }, MINUS = { symbol: '-' };
function apex ({ part }) {
  const s = part.s, t = s / R;
  return [{ symbol: 'F', s }, OPEN, PLUS, { symbol: 'A', s: t }, CLOSE,
          OPEN, MINUS, { symbol: 'A', s: t }, CLOSE];
}

const models = {
  a: () => new LSystem({ axiom: 'F', productions: { F: 'F[+F]F[-F]F' } }),
  b: () => new LSystem({ axiom: [{ symbol: 'A', s: 1 }], productions: { A: apex } }),
};

const name = process.argv[2];
const steps = Number(process.argv[3]);
if (!models[name] || !(steps >= 0)) {
  console.error('usage: node derive_lindenmayer.js a|b STEPS');
  process.exit(2);
}

let best = Infinity, modules = 0, length = 0;
for (let run = 0; run < 3; run++) {
  let ls = models[name]();
  let sum = 0;
  const t0 = process.hrtime.bigint();
  for (let i = 0; i < steps; i++) sum += ls.iterate(1).length;
  const t1 = process.hrtime.bigint();
  best = Math.min(best, Number(t1 - t0) / 1e9);
  modules = sum;
  length = ls.getRaw().length;
  ls = null;
}
console.log(JSON.stringify({
  model: name, steps, modules, length, seconds: best,
  peak_kib: process.resourceUsage().maxRSS, version,
}));
