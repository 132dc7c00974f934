// The TextMate grammar of `.deriv` files, compiled by the engine VS Code uses
// (vscode-textmate on Oniguruma): every pattern compiles, and a derivation gets the
// scopes a theme colours. Run by `npm run check`, and by rigor's tests.
'use strict';

const fs = require('fs');
const path = require('path');
const assert = require('assert');
const oniguruma = require('vscode-oniguruma');
const textmate = require('vscode-textmate');

const wasm = fs.readFileSync(require.resolve('vscode-oniguruma/release/onig.wasm'));
const onigLib = oniguruma.loadWASM(wasm.buffer).then(() => ({
  createOnigScanner: (patterns) => new oniguruma.OnigScanner(patterns),
  createOnigString: (s) => new oniguruma.OnigString(s),
}));

const grammarPath = path.join(__dirname, '..', 'syntaxes', 'deriv.tmLanguage.json');
const registry = new textmate.Registry({
  onigLib,
  loadGrammar: async (scope) =>
    scope === 'source.rigor'
      ? textmate.parseRawGrammar(fs.readFileSync(grammarPath, 'utf8'), grammarPath)
      : null,
});

const sample = [
  '# A rod swinging about its end',
  'symbols m g L > 0   % the parameters',
  'time theta',
  '> The moment about the pivot is $M = -m g L/2 sin(theta)$.',
  'use [IO] from "lib.deriv" with d = L/2',
  "claim [acc] theta'' = -(3 g/(2 L)) sin(theta) by [eom]",
  'claim [IG] $$ I_G = \\frac{mL^2}{12} $$ by [IO]',
];

/// The scopes of the token that starts at `needle` on line `n`.
function scopesAt(tokens, line, needle) {
  const at = line.indexOf(needle);
  assert.ok(at >= 0, `${needle} is on the line`);
  const t = tokens.find((t) => t.startIndex <= at && at < t.endIndex);
  return t.scopes;
}

(async () => {
  const grammar = await registry.loadGrammar('source.rigor');
  assert.ok(grammar, 'the grammar loads');
  let state = textmate.INITIAL;
  const lines = sample.map((line) => {
    const r = grammar.tokenizeLine(line, state);
    state = r.ruleStack;
    return { line, tokens: r.tokens };
  });
  const expect = [
    [0, 'A rod', 'entity.name.section.rigor'],
    [1, 'symbols', 'storage.type.declaration.rigor'],
    [1, '% the', 'comment.line.percentage.rigor'],
    [1, '>', 'keyword.operator.relation.rigor'],
    [1, '0', 'constant.numeric.rigor'],
    [2, 'time', 'storage.type.declaration.rigor'],
    [3, 'The moment', 'markup.quote.rigor'],
    [3, 'sin', 'support.function.rigor'],
    [4, 'use', 'keyword.control.statement.rigor'],
    [4, 'IO', 'entity.name.label.rigor'],
    [4, '"lib.deriv"', 'string.quoted.double.rigor'],
    [4, 'with', 'keyword.other.rigor'],
    [5, 'claim', 'keyword.control.statement.rigor'],
    [5, "''", 'keyword.operator.derivative.rigor'],
    [5, 'by', 'keyword.other.rigor'],
    [5, 'eom', 'entity.name.label.rigor'],
    [6, '\\frac', 'support.function.latex.rigor'],
  ];
  for (const [n, needle, scope] of expect) {
    const { line, tokens } = lines[n];
    const scopes = scopesAt(tokens, line, needle);
    assert.ok(scopes.includes(scope), `line ${n + 1}, ${needle}: ${scope} not in ${scopes.join(' ')}`);
  }
  console.log(`grammar: ${expect.length} scopes as expected`);
})().catch((e) => {
  console.error(e.message || e);
  process.exit(1);
});
