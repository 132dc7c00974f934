#!/usr/bin/env bash
# Builds the browser playground into web/dist: the checker compiled to WebAssembly
# (a plain C-ABI export, web/wasm), the page, its script and styles, KaTeX from the npm
# registry (web/package-lock.json), and the handout's derivations as examples.
# Serve it with any static server: python3 -m http.server -d web/dist
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
dist="$here/dist"

if command -v rustup >/dev/null 2>&1; then
  rustup target list --installed | grep -qx wasm32-unknown-unknown \
    || rustup target add wasm32-unknown-unknown
fi
cargo build --release --quiet --target wasm32-unknown-unknown \
  --manifest-path "$here/wasm/Cargo.toml" --target-dir "$root/target/web"

# KaTeX, at the version the lock file pins (installed again only when that changes).
want="$(cd "$here" && node -p 'require("./package-lock.json").packages["node_modules/katex"].version')"
have="$(cd "$here" && node -p 'require("./node_modules/katex/package.json").version' 2>/dev/null || true)"
if [ "$want" != "$have" ]; then
  (cd "$here" && npm ci --no-audit --no-fund --silent)
fi

rm -rf "$dist"
mkdir -p "$dist/vendor/katex"
cp "$here/src/index.html" "$here/src/app.js" "$here/src/worker.js" "$here/src/style.css" "$dist/"
cp "$root/target/web/wasm32-unknown-unknown/release/rigor_web.wasm" "$dist/rigor.wasm"
cp "$here/node_modules/katex/dist/katex.min.js" "$here/node_modules/katex/dist/katex.min.css" \
  "$here/node_modules/katex/LICENSE" "$dist/vendor/katex/"
cp -r "$here/node_modules/katex/dist/fonts" "$dist/vendor/katex/fonts"

# The handout's derivations, one click away; `use … from "rod.deriv"` resolves to them.
node -e '
  const fs = require("fs"), path = require("path");
  const dir = process.argv[1], out = {};
  for (const f of fs.readdirSync(dir).filter((f) => f.endsWith(".deriv")).sort())
    out[f] = fs.readFileSync(path.join(dir, f), "utf8");
  fs.writeFileSync(process.argv[2], JSON.stringify(out));
' "$root/derivations" "$dist/examples.json"

echo "built $dist ($(du -sh "$dist" | cut -f1)); serve it: python3 -m http.server -d web/dist"
