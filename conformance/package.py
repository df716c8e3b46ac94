#!/usr/bin/env python3
"""Writes the conformance package, a release archive that a decoder team
runs without building m4mesh: both suites' streams and manifests, the
runner conform.py, a README (package-readme.md) and the normative docs the
suites follow (the 2D specification, ../shared/spec/mesh-bitstream.md, as
docs/mesh-bitstream.md; docs/decisions.md, container3d.md, base_mesh.md and
each 3D codec's).

    python3 conformance/package.py [-o m4mesh-conformance-VERSION.tar.gz]

VERSION is m4mesh's (the top CMakeLists.txt's project version); the
archive's folder is m4mesh-conformance-VERSION.

The archive is the same bytes for the same suites: its members in name
order, with no owner, mode 0644 (0755 for conform.py) and the time
SOURCE_DATE_EPOCH gives (else 0).
"""

import argparse
import gzip
import io
import os
import pathlib
import re
import sys
import tarfile
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
VERSION = re.search(r"project\(m4mesh VERSION (\S+)", (HERE.parent / "CMakeLists.txt").read_text()).group(1)
TOP = f"m4mesh-conformance-{VERSION}"


SPECIFICATION = HERE.parent.parent / "shared" / "spec" / "mesh-bitstream.md"


def members():
    """(name in the archive, file) for every file of the package."""
    if not SPECIFICATION.exists():
        sys.exit(f"package.py: {SPECIFICATION}: no such file: the 2D suite's normative text, which the package carries (docs/mesh-bitstream.md)")
    files = {"README.md": HERE / "package-readme.md", "conform.py": HERE / "conform.py", "docs/mesh-bitstream.md": SPECIFICATION}
    docs = HERE.parent / "docs"
    for name in ["decisions.md", "container3d.md", "base_mesh.md", *sorted(p.name for p in docs.glob("codec_*.md"))]:
        files[f"docs/{name}"] = docs / name
    for suite in ("", "mesh3d/"):
        files[suite + "manifest.json"] = HERE / suite / "manifest.json"
        for stream in (HERE / suite / "streams").iterdir():
            files[f"{suite}streams/{stream.name}"] = stream
    return sorted(files.items())


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-o", "--output", default=f"{TOP}.tar.gz", help="the archive to write (default: %(default)s)")
    args = parser.parse_args()
    output = pathlib.Path(args.output)
    if output.resolve().is_relative_to(HERE):
        parser.error("write the archive outside the conformance folder")
    entries = members()
    mtime = int(os.environ.get("SOURCE_DATE_EPOCH", "0"))
    packed = io.BytesIO()
    with tarfile.open(fileobj=packed, mode="w", format=tarfile.PAX_FORMAT) as tar:
        for name, path in entries:
            data = path.read_bytes()
            info = tarfile.TarInfo(f"{TOP}/{name}")
            info.size = len(data)
            info.mode = 0o755 if name == "conform.py" else 0o644
            info.mtime = mtime
            tar.addfile(info, io.BytesIO(data))
    # A file of this run's own beside the output, which takes its name only when complete.
    handle, partial = tempfile.mkstemp(dir=output.parent, prefix=output.name + ".", suffix=".tmp")
    try:
        with os.fdopen(handle, "wb") as raw, gzip.GzipFile(filename="", mode="wb", fileobj=raw, mtime=mtime) as zipped:
            zipped.write(packed.getvalue())
        os.chmod(partial, 0o644)
        os.replace(partial, output)
    except BaseException:
        os.unlink(partial)
        raise
    print(f"{output}: {len(entries)} files, {output.stat().st_size} bytes")
    return 0


if __name__ == "__main__":
    sys.exit(main())
