#!/usr/bin/env python3
"""Runs the m4mesh conformance suites through any decoder; Python's standard
library only, so that a decoder team needs nothing of m4mesh but this folder.

    python3 conform.py --decoder "mydec {in} {out}"                 # both suites
    python3 conform.py --decoder "mydec --method {method} {in} {out}" --suite 2d
    python3 conform.py --decoder "mydec3d {in} {out}" --suite 3d --only 'x-*'

{in} is the stream; {out} the file the decoder writes: for the 2D suite the
decoded output in the §9 text format (a name ending in .txt), for the 3D
suite every frame's binary32 x, y, z per vertex, little-endian, frame after
frame (a name ending in .f32); {method} is the motion-vector method, 2, or 1
for the Method I streams, which are skipped without it. Each is quoted for
the shell. A stream to decode passes when the decoder exits 0 and its output
has the manifest's MD5; a stream to reject passes when the decoder exits
with a non-zero status of its own (a crash, a signal or a time-out fails
either). One line per stream, then "N passed, N failed[, N skipped]" per
suite; the exit status is 0 only when no stream failed (a skipped Method I
stream, informative in the specification, does not fail the run), and 2
for a command without {in} and {out}. `m4mesh conform --decoder` follows
the same rules.
"""

import argparse
import fnmatch
import hashlib
import json
import os
import pathlib
import shlex
import signal as signal_module
import subprocess
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
SUITES = {"2d": HERE / "manifest.json", "3d": HERE / "mesh3d" / "manifest.json"}


def md5_of(path):
    return hashlib.md5(path.read_bytes()).hexdigest()


def run_decoder(template, stream, out, method, timeout):
    """The decoder's exit status (None: it did not run to an exit) and a note."""
    command = template.replace("{in}", shlex.quote(str(stream))).replace("{out}", shlex.quote(str(out)))
    command = command.replace("{method}", str(method))
    # A session of its own, so that a time-out kills the decoder's every process, not only the shell.
    with subprocess.Popen(["/bin/sh", "-c", command], stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                          stderr=subprocess.PIPE, start_new_session=True) as done:
        try:
            _, stderr = done.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            os.killpg(done.pid, signal_module.SIGKILL)
            done.communicate()
            return None, f"no exit within {timeout:g} s"
    stderr = stderr.decode(errors="replace").replace("\n", " ").strip()[:300]
    note = f"; its stderr: {stderr}" if stderr else ""
    # A crash fails any stream: the shell reports a command killed by signal N as 128 + N.
    signal = -done.returncode if done.returncode < 0 else done.returncode - 128 if 128 < done.returncode < 160 else 0
    if signal:
        return None, f"killed by signal {signal}{note}"
    if done.returncode in (126, 127):
        return None, f"exit {done.returncode}: {'command not found' if done.returncode == 127 else 'command not executable'}{note}"
    return done.returncode, note


def check(entry, kind, stream, template, folder, timeout):
    """pass, FAIL or skip, and what was seen."""
    method = entry.get("method", 2)
    if kind == "mesh2d" and method != 2 and "{method}" not in template:
        return "skip", "needs Method I: put {method} in the decoder command"
    out = folder / (entry["id"] + (".f32" if kind == "mesh3d" else ".txt"))
    code, note = run_decoder(template, stream, out, method, timeout)
    if code is None:
        return "FAIL", note
    if entry["expect"] != "decode":
        if code == 0:
            return "FAIL", f"exit status 0 for a stream that must be rejected ({entry['error_kind']})"
        return "pass", f"rejected (exit {code})"
    if code != 0:
        return "FAIL", f"the decoder failed (exit {code}){note}"
    if not out.exists():
        return "FAIL", f"the decoder wrote no output{note}"
    md5 = md5_of(out)
    if md5 != entry["decoded_md5"]:
        return "FAIL", f"decoded MD5 {md5}, expected {entry['decoded_md5']}"
    return "pass", md5


def run_suite(manifest_path, template, only, timeout):
    manifest = json.loads(manifest_path.read_text())
    kind = manifest["kind"]
    counts = {"pass": 0, "FAIL": 0, "skip": 0}
    print(f"{'stream':<36} {'expect':<7} {'result':<6} detail")
    with tempfile.TemporaryDirectory(prefix="m4mesh-conform-") as temporary:
        for entry in manifest["streams"]:
            if only and not any(fnmatch.fnmatchcase(entry["id"], pattern) for pattern in only):
                continue
            stream = manifest_path.parent / entry["file"]
            stream_md5 = md5_of(stream) if stream.exists() else None
            if stream_md5 is None:
                status, detail = "FAIL", f"{stream}: no such file"
            elif stream_md5 != entry["stream_md5"]:
                status, detail = "FAIL", f"the stream file's MD5 is {stream_md5}, the manifest says {entry['stream_md5']}"
            else:
                status, detail = check(entry, kind, stream, template, pathlib.Path(temporary), timeout)
            counts[status] += 1
            expect = "decode" if entry["expect"] == "decode" else "reject"
            print(f"{entry['id']:<36} {expect:<7} {status:<6} {detail[:500]}", flush=True)
    summary = f"{counts['pass']} passed, {counts['FAIL']} failed"
    print(summary + (f", {counts['skip']} skipped" if counts["skip"] else ""))
    return counts


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog=__doc__.split("\n\n", 1)[1])
    parser.add_argument("--decoder", required=True, help='the decoder command, with {in}, {out} and (2D) {method}')
    parser.add_argument("--suite", choices=sorted(SUITES), action="append", help="2d or 3d (repeatable; default: both)")
    parser.add_argument("--only", action="append", metavar="PATTERN", help="stream ids matching this shell pattern, e.g. 'x-*' (repeatable)")
    parser.add_argument("--timeout", type=float, default=120, help="seconds a decoder may take on one stream (default 120)")
    args = parser.parse_args()
    if "{in}" not in args.decoder or "{out}" not in args.decoder:
        parser.error("the decoder command needs {in} (the stream) and {out} (the file it writes)")
    if not args.timeout > 0:
        parser.error("--timeout: a number of seconds above 0")
    total = {"pass": 0, "FAIL": 0, "skip": 0}
    for name in args.suite or sorted(SUITES):
        if not SUITES[name].exists():
            parser.error(f"{SUITES[name]}: no such manifest")
        print(f"== the {name} suite ({SUITES[name].relative_to(HERE)})")
        for status, count in run_suite(SUITES[name], args.decoder, args.only, args.timeout).items():
            total[status] += count
    if total["pass"] + total["FAIL"] + total["skip"] == 0:
        print("no stream matches --only", file=sys.stderr)
        return 2
    return 0 if total["FAIL"] == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
