#!/usr/bin/env python3
"""Mutation testing of the conformance suites (conformance/mutants.json).

Each mutant is one plausible mistake in normative decoding, made by
replacing one exact piece of m4mesh's source. The script copies the
checkout into a work folder, builds the m4mesh tool there once, then for
each mutant applies its edit, rebuilds, and runs `m4mesh conform` on the
mutant's suite (2D for area "2d", else the 3D suite). A mutant is killed
when at least one stream fails (a wrong MD5, a stream to reject accepted,
another error, a crash or a time-out). A mutant marked "equivalent" gives
the reason no output can change; it is still built and run, and reported
if it is killed after all.

    python3 scripts/mutants.py                 # every mutant
    python3 scripts/mutants.py --subset ci     # the fast subset CI runs
    python3 scripts/mutants.py --only lc-01    # one mutant (repeatable)
    python3 scripts/mutants.py --area lcc      # one area's mutants (repeatable)

Exit status 0 when every mutant not marked equivalent is killed and every
mutant applies and builds.
"""

import argparse
import collections
import json
import os
import pathlib
import shutil
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
AREAS = ["2d", "container", "base-mesh", "bfs3d", "affine-octree", "lcc", "cpca-wpt"]


def run(command, cwd, timeout=None, log=None):
    return subprocess.run(command, cwd=cwd, stdout=log or subprocess.DEVNULL, stderr=subprocess.STDOUT, timeout=timeout).returncode


def copy_checkout(work):
    """The checkout's files as git sees them (uncommitted and new ones too) into work/src."""
    files = subprocess.run(["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"], cwd=ROOT, check=True, capture_output=True).stdout.split(b"\0")
    src = work / "src"
    for name in files:
        if not name:
            continue
        relative = pathlib.Path(name.decode())
        if not (ROOT / relative).exists():
            continue
        target = src / relative
        target.parent.mkdir(parents=True, exist_ok=True)
        if not target.exists() or target.read_bytes() != (ROOT / relative).read_bytes():
            shutil.copyfile(ROOT / relative, target)  # a new mtime, so that make rebuilds what changed
    return src


def build(src, build_dir, log):
    # Configured every time (a no-op when nothing changed), so that a build folder of an older checkout takes today's options.
    launcher = ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"] if shutil.which("ccache") else []
    if shutil.which("clang++"):
        launcher.append("-DCMAKE_CXX_COMPILER=clang++")  # compiles the project about twice as fast as g++
    # Unoptimized: a mutant rebuilds in a third of the time, and the suites decode in a second or two. Scalar: the
    # mutants edit the scalar reference of each SIMD loop (tests pin the SIMD loops to them).
    code = run(["cmake", "-S", str(src), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=None", "-DCMAKE_CXX_FLAGS=-O0 -DNDEBUG",
                "-DM4MESH_BENCHMARKS=OFF", "-DM4MESH_CGAL=OFF", "-DM4MESH_WEB=OFF", "-DM4MESH_SIMD=OFF", *launcher], src, log=log)
    if code:
        return code
    return run(["cmake", "--build", str(build_dir), "-j", str(os.cpu_count() or 2), "--target", "m4mesh"], src, timeout=1800, log=log)


def conform(tool, suite, timeout):
    """True when every stream of the suite passes."""
    try:
        return run([str(tool), "conform", str(suite)], suite, timeout=timeout) == 0
    except subprocess.TimeoutExpired:
        return False


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--subset", choices=["ci"], help="only the mutants marked for CI")
    parser.add_argument("--only", action="append", default=[], metavar="ID", help="only this mutant (repeatable)")
    parser.add_argument("--area", action="append", default=[], choices=AREAS, help="only this area's mutants (repeatable)")
    parser.add_argument("--work", default="/tmp/m4mesh-mutants", help="work folder: the copy, its build and the log")
    parser.add_argument("--timeout", type=int, default=60, help="seconds a conformance run may take (it takes about one)")
    args = parser.parse_args()

    mutants = json.loads((ROOT / "conformance" / "mutants.json").read_text())
    ids = collections.Counter(m["id"] for m in mutants)
    duplicated = [i for i, n in ids.items() if n > 1]
    if duplicated:
        sys.exit(f"mutants.json: ids used twice: {', '.join(duplicated)}")
    if args.subset == "ci":
        mutants = [m for m in mutants if m.get("ci")]
    if args.area:
        mutants = [m for m in mutants if m["area"] in args.area]
    if args.only:
        unknown = set(args.only) - set(ids)
        if unknown:
            sys.exit(f"no mutant {', '.join(sorted(unknown))}")
        mutants = [m for m in mutants if m["id"] in args.only]

    work = pathlib.Path(args.work)
    work.mkdir(parents=True, exist_ok=True)
    src = copy_checkout(work)
    build_dir = work / "build"
    tool = build_dir / "cli" / "m4mesh"
    suites = {"2d": src / "conformance", "3d": src / "conformance" / "mesh3d"}
    log_path = work / "build.log"
    with open(log_path, "w") as log:
        print(f"building m4mesh in {build_dir} (log: {log_path})", flush=True)
        if build(src, build_dir, log) != 0:
            sys.exit(f"the unmutated build failed: see {log_path}")
        for name, suite in suites.items():
            if not conform(tool, suite, args.timeout):
                sys.exit(f"the unmutated decoder fails the {name} suite")

        results = []
        started = time.monotonic()
        for n, m in enumerate(mutants, 1):
            path = src / m["file"]
            original = path.read_text()
            if original.count(m["from"]) != 1:
                outcome = "stale"  # the edit no longer applies exactly once
            else:
                path.write_text(original.replace(m["from"], m["to"]))
                try:
                    if build(src, build_dir, log) != 0:
                        outcome = "no-build"
                    else:
                        outcome = "survived" if conform(tool, suites["2d" if m["area"] == "2d" else "3d"], args.timeout) else "killed"
                finally:
                    path.write_text(original)
            results.append((m, outcome))
            print(f"[{n}/{len(mutants)} {time.monotonic() - started:6.0f} s] {m['id']:<24} {outcome}", flush=True)
        build(src, build_dir, log)  # leave the copy's build unmutated

    table = collections.OrderedDict((a, collections.Counter()) for a in AREAS)
    problems = []
    for m, outcome in results:
        counts = table.setdefault(m["area"], collections.Counter())
        counts["made"] += 1
        if outcome == "killed":
            counts["killed"] += 1
        elif m.get("equivalent") and outcome == "survived":
            counts["equivalent"] += 1
        else:
            counts[outcome] += 1
            problems.append(f"{m['id']}: {outcome} ({m['file']}: {m['why']})")
        if m.get("equivalent") and outcome == "killed":
            problems.append(f"{m['id']}: marked equivalent but killed")
    print(f"\n{'area':<14} {'made':>5} {'killed':>7} {'equiv.':>7} {'survived':>9} {'broken':>7}")
    total = collections.Counter()
    for area, c in table.items():
        if not c["made"]:
            continue
        broken = c["stale"] + c["no-build"]
        print(f"{area:<14} {c['made']:>5} {c['killed']:>7} {c['equivalent']:>7} {c['survived']:>9} {broken:>7}")
        total.update(c)
    broken = total["stale"] + total["no-build"]
    print(f"{'total':<14} {total['made']:>5} {total['killed']:>7} {total['equivalent']:>7} {total['survived']:>9} {broken:>7}")
    for p in problems:
        print("  " + p)
    passed = total["killed"] + total["equivalent"]
    print(f"mutants: {passed} passed, {len(results) - passed} failed")
    return 0 if passed == len(results) else 1


if __name__ == "__main__":
    sys.exit(main())
