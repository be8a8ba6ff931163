#!/usr/bin/env bash
# The web page's tests (issue 26): builds it (scripts/web.sh build) and drives it in headless
# Chromium (web/tests/browser.mjs, puppeteer-core from npm, pinned); pictures and assets it makes go
# to target/web-test. Run by test.sh; needs what scripts/setup.sh installs. --build-only stops
# before the tests (the page, the CLI and the npm tools built).
set -euo pipefail
cd "$(dirname "$0")/.."
target=${CARGO_TARGET_DIR:-target}
tools=$target/web-tools
if ! grep -qs '"version": "24.43.1"' "$tools/node_modules/puppeteer-core/package.json" \
    || ! grep -qs '"version": "7.0.0"' "$tools/node_modules/pngjs/package.json"; then
    mkdir -p "$tools"
    npm install --prefix "$tools" --no-save --no-audit --no-fund --loglevel=error puppeteer-core@24.43.1 pngjs@7.0.0
fi
./scripts/web.sh build
cargo build --release --locked --bin chamfer
if [[ "${1:-}" == --build-only ]]; then
    exit 0  # what scripts/bench-web.sh needs
fi
node web/tests/browser.mjs "$target/web" "$target/release/chamfer" "$target/web-test" "$tools/node_modules"
