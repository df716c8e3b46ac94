#!/usr/bin/env python3
"""The layout of a checkout: per folder, its C++ files (a .h and its .cc
as one) with their lines, largest first, and the folder's total.

    python3 scripts/layout.py [CHECKOUT]
"""

import collections
import pathlib
import subprocess
import sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
files = subprocess.run(["git", "ls-files", "*.cc", "*.h"], cwd=root, check=True, capture_output=True, text=True).stdout.split()
folders = collections.defaultdict(collections.Counter)
for name in files:
    path = pathlib.PurePosixPath(name)
    with open(root / path, errors="replace") as text:
        folders[str(path.parent)][path.stem] += sum(1 for _ in text)
for folder in sorted(folders):
    units = folders[folder]
    listing = ", ".join(f"{stem} {lines}" for stem, lines in units.most_common())
    print(f"{folder}/ ({sum(units.values())}): {listing}")
