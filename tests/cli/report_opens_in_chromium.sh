#!/usr/bin/env bash
# Opens a small comparison report in headless Chromium and checks that every image loaded (the
# page's own load-time check), that the console logged no error, and that a screenshot renders.
# Skips (77) only when Chromium is missing outside CI; with CI=true a missing Chromium fails.
set -euo pipefail
penumbra="$1"
out="$2"
browser=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$browser" ]; then
  if [ "${CI:-}" = "true" ]; then echo "CI=true and no chromium: run scripts/install-deps"; exit 1; fi
  echo "chromium not installed: skipping"; exit 77
fi
rm -rf "$out"
"$penumbra" compare --scene contact --technique vsm,evsm4,pcf --shadow-size 256 --width 160 --height 90 \
  --frames 2 --supersample 2 --quiet --out "$out/report"
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
flags=(--headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking
       --disable-component-update --disable-sync --user-data-dir="$profile" --virtual-time-budget=10000
       --enable-logging=stderr --v=0)
page="file://$(realpath "$out/report/index.html")"
"$browser" "${flags[@]}" --dump-dom "$page" > "$out/dom.html" 2> "$out/console.log" || true
"$browser" "${flags[@]}" --window-size=1280,2400 --screenshot="$out/screenshot.png" "$page" \
  >> "$out/console.log" 2>&1 || true
loaded=$(grep -o 'data-images-loaded="[0-9]*"' "$out/dom.html" | grep -o '[0-9]*' || true)
broken=$(grep -o 'data-images-broken="[0-9]*"' "$out/dom.html" | grep -o '[0-9]*' || true)
expected=$(grep -o '<img ' "$out/report/index.html" | wc -l)
echo "images: $loaded loaded, $broken broken, $expected in the page"
[ -n "$loaded" ] || { echo "the page's load check did not run"; exit 1; }
[ "$broken" = "0" ] || { echo "broken images"; exit 1; }
[ "$loaded" = "$expected" ] || { echo "not every image loaded"; exit 1; }
if grep -E 'CONSOLE.*(Uncaught|Error|error)' "$out/console.log"; then
  echo "console errors"; exit 1
fi
[ -s "$out/screenshot.png" ] || { echo "no screenshot"; exit 1; }
echo "screenshot: $out/screenshot.png"
