#!/usr/bin/env bash
# Installs, builds the tool, the Python module (build/python) and the web
# site (build/web/site), and runs the main job: `m4mesh demo` on the
# embedded waving flag, drawing the decoded animation into
# build/demo-flag.gif.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
# Everything `cmake --install build` installs (the tool, the libraries, the site), and the Python module.
cmake --build build -j"$(nproc)" --target m4mesh m4mesh_shared m4mesh_static m4mesh_site m4mesh_python m4mesh_python_files
./build/cli/m4mesh demo --gif build/demo-flag.gif -y
echo "The web player and analyzer: build/cli/m4mesh serve, then open http://127.0.0.1:8080/ (docs/web.md)"
