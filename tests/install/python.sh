#!/bin/sh
# The Python package as a user installs it: `pip install ./python` in a
# fresh virtual environment, offline from Debian's packages (no index, no
# build isolation), writing nothing into the source tree, then, from
# outside the tree, a suite stream decoded to its MD5, a sequence encoded
# at a quality target, and a bad stream's error.
# Usage: python.sh SOURCE_DIR
set -eu
source=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 -m venv --system-site-packages "$work/env"
touch "$work/start"
"$work/env/bin/pip" install --no-build-isolation --no-index --quiet "$source/python"
# Nothing written into the source tree (setuptools' build/ and egg-info go elsewhere).
written=$(find "$source/python" -newer "$work/start" | head -n 3)
[ -z "$written" ] || { echo "pip install ./python wrote into the source tree: $written"; exit 1; }
cd "$work"
"$work/env/bin/python" - "$source/conformance/mesh3d" <<'PYTHON'
import hashlib, json, pathlib, sys
import numpy as np
import m4mesh

assert pathlib.Path(m4mesh.__file__).is_relative_to(sys.prefix), f"m4mesh from {m4mesh.__file__}, not the environment"
suite = pathlib.Path(sys.argv[1])
entry = next(e for e in json.loads((suite / "manifest.json").read_text())["streams"] if e["id"] == "lcc-01-stream")
frames, faces = m4mesh.decode((suite / entry["file"]).read_bytes())
assert hashlib.md5(frames.astype("<f4").tobytes()).hexdigest() == entry["decoded_md5"], "lcc-01-stream decodes to another MD5"

side, count = 12, 10
y, x = np.mgrid[0:side, 0:side]
sheet = np.stack([np.stack([x, y, np.sin(0.5 * x + 0.3 * f) * y / 6], axis=-1).reshape(-1, 3) for f in range(count)]).astype(np.float32)
quads = [(r * side + c, r * side + c + 1, (r + 1) * side + c + 1, (r + 1) * side + c) for r in range(side - 1) for c in range(side - 1)]
faces = np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))], dtype=np.int32)
stream = m4mesh.encode(sheet, faces, codec="cpca-wpt", target_kg=0.5)
decoded, _ = m4mesh.decode(stream)
kg = m4mesh.metrics(sheet, decoded, faces)["kg_error"]
assert decoded.shape == sheet.shape and kg <= 0.5, (decoded.shape, kg)

error = None
try:
    m4mesh.decode(stream[:5])
except m4mesh.Error as e:
    error = e
assert error is not None and error.kind == "truncated", error
print(f"pip install ./python: m4mesh {m4mesh.__file__}; lcc-01-stream's MD5; cpca-wpt {len(stream)} bytes at KG {kg:.3f} %; a cut stream: {error}")
PYTHON
