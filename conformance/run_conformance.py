#!/usr/bin/env python3
"""Runs the MRSV conformance vectors against any decoder or checker.

The decoder is given as a command template with {in} and {out}:

  decode mode (default): for a valid vector the command must exit 0 and write
    the canonical output (spec 3.4) to {out}; its SHA-256 must equal the
    manifest's. For an invalid vector it must exit non-zero, print the code
    as E<number> (e.g. E113) on stderr or stdout, and leave no file at {out}.
  check mode: {out} is not used; a valid vector must exit 0, an invalid one
    must exit non-zero and print its E<number>; with --check-offsets the line
    must also say "offset <n>" with the manifest's offset.

  --level-decoder (decode mode): a second template with {in}, {out} and
    {vertices} that writes the canonical output of a mesh's level with that
    many vertices (spec 6.8); every level a vector's manifest entry lists
    ("levels") must then hash as listed.
  --region-decoder (decode mode): a template with {in}, {out} and {region}
    (X0,Y0[,Z0],X1,Y1[,Z1]) that writes the canonical region output of spec 11.5;
    every region a vector lists ("regions") must then hash as listed.
  --profile P (repeatable): only the vectors of profiles P and "any" (spec 1.6),
    for a decoder that implements some profiles only.
  mesh mode: the command is a reconstructor (spec 8) with {in}, {out} and {args};
    it runs once for each entry of a vector's "reconstruct" list, {args} replaced
    by the entry's options (several words). It must exit 0 and write the canonical
    output of 8.2 with the entry's SHA-256, or, for an entry marked "refused", exit
    non-zero and leave no file at {out}. Vectors without "reconstruct" are skipped.
    With --known-failures, an entry marked "known_failure" (a reported disagreement
    of the reference reconstructor) must fail, and is counted apart. With --clause C
    (repeatable) only the vectors of spec chapter C run (8: 2-D insertion, 9: quadtree,
    10: 3-D insertion), for a reconstructor that implements some chapters only; with
    --skip-args WORD the cases whose options hold WORD are skipped.

Examples:
  run_conformance.py --decoder "build/mrsv decode --canonical {in} {out}"
  run_conformance.py --mode check --check-offsets --decoder "build/mrsv check {in}"
  run_conformance.py --decoder "build/mrsv decode --canonical {in} {out}" \
      --level-decoder "build/mrsv decode --canonical --vertices {vertices} {in} {out}"
  run_conformance.py --mode mesh --known-failures \
      --decoder "build/mrsv mesh --quiet --canonical {in} {out} {args}"
  run_conformance.py --mode mesh \
      --decoder "python3 conformance/reconstruct_reference.py --mrsv build/mrsv {in} {out} {args}"
"""
import argparse
import hashlib
import json
import os
import re
import shlex
import subprocess
import sys
import tempfile


def check_outputs(template, entries, key, label, args, path, out):
    """Each entry of a vector's list (`levels` of a mesh, spec 6.8; `regions` of a tiled grid,
    spec 11.5) decodes, by `template` with {key} replaced by the entry's value, to the listed
    canonical output."""
    for entry in entries:
        if os.path.exists(out):
            os.remove(out)
        value = str(entry[key])
        cmd = [part.replace("{in}", path).replace("{out}", out).replace("{" + key + "}", value)
               for part in shlex.split(template)]
        run = subprocess.run(cmd, capture_output=True, timeout=args.timeout)
        what = label.format(value)
        if run.returncode != 0 or not os.path.exists(out):
            return f"{what}: exit {run.returncode}"
        digest = hashlib.sha256(open(out, "rb").read()).hexdigest()
        if digest != entry["sha256"]:
            return f"{what}: sha256 {digest}, expected {entry['sha256']}"
    return None


def expand(template, path, out, args=()):
    cmd = []
    for part in shlex.split(template):
        if part == "{args}":
            cmd += list(args)
        else:
            cmd.append(part.replace("{in}", path).replace("{out}", out))
    return cmd


def run_mesh_cases(args, vector, path, out):
    """spec 8: each reconstruction of the vector; returns (passed, failures, known failures)."""
    passed, failures, known = 0, [], 0
    for case in vector["reconstruct"]:
        if any(word in case["args"] for word in args.skip_args):
            continue
        if os.path.exists(out):
            os.remove(out)
        label = f"{vector['file']} {' '.join(case['args'])}"
        try:
            run = subprocess.run(expand(args.decoder, path, out, case["args"]), capture_output=True,
                                 timeout=args.timeout)
        except subprocess.TimeoutExpired:
            failures.append((label, f"no answer within {args.timeout} s"))
            continue
        text = (run.stdout + run.stderr).decode("utf-8", "replace")
        problem = None
        if run.returncode < 0:
            problem = f"killed by signal {-run.returncode}"
        elif case.get("refused"):
            if run.returncode == 0:
                problem = "exit 0 where spec 8 refuses"
            elif os.path.exists(out):
                problem = "an output file was left behind for a refused request"
        elif run.returncode != 0:
            problem = f"exit {run.returncode}: {text.strip()[:300]}"
        elif not os.path.exists(out):
            problem = "no output written"
        else:
            digest = hashlib.sha256(open(out, "rb").read()).hexdigest()
            if digest != case["sha256"]:
                problem = f"canonical mesh sha256 {digest}, expected {case['sha256']}"
        if args.known_failures and case.get("known_failure"):
            if problem:
                known += 1
                if args.verbose:
                    print(f"known {label}: {case['known_failure']}")
            else:
                failures.append((label, "passes now: remove its known_failure (" + case["known_failure"] + ")"))
            continue
        if problem:
            failures.append((label, problem))
        else:
            passed += 1
            if args.verbose:
                print(f"ok    {label}")
    return passed, failures, known


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--manifest", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "manifest.json"))
    parser.add_argument("--decoder", required=True, help="command template with {in} and {out}")
    parser.add_argument("--mode", choices=("decode", "check", "mesh"), default="decode")
    parser.add_argument("--known-failures", action="store_true",
                        help="mesh mode: cases marked known_failure must fail (the reference's reported bugs)")
    parser.add_argument("--check-offsets", action="store_true", help="also require 'offset <n>' in error output")
    parser.add_argument("--timeout", type=float, default=60.0, help="seconds allowed per vector")
    parser.add_argument("--level-decoder", help="command template with {in}, {out} and {vertices}")
    parser.add_argument("--region-decoder", help="command template with {in}, {out} and {region}")
    parser.add_argument("--profile", action="append", choices=("grid", "mesh", "tet"),
                        help="run only this profile's vectors (and those of no profile)")
    parser.add_argument("--clause", action="append",
                        help="mesh mode: only the vectors of this spec chapter (the manifest's clause; repeatable), "
                             "for a reconstructor of some chapters only")
    parser.add_argument("--skip-args", action="append", default=[],
                        help="mesh mode: skip the cases whose options hold this word (repeatable), for a "
                             "reconstructor without that option")
    parser.add_argument("--verbose", action="store_true")
    args = parser.parse_args()

    with open(args.manifest, encoding="utf-8") as f:
        manifest = json.load(f)
    base = os.path.dirname(os.path.abspath(args.manifest))
    passed, failures, known = 0, [], 0
    with tempfile.TemporaryDirectory(prefix="mrsv-conformance-") as tmp:
        for vector in manifest["vectors"]:
            if args.profile and vector.get("profile", "any") not in args.profile + ["any"]:
                continue
            path = os.path.join(base, vector["file"])
            out = os.path.join(tmp, "out.bin")
            if args.mode == "mesh":
                if "reconstruct" in vector and (not args.clause or vector.get("clause") in args.clause):
                    p, f, k = run_mesh_cases(args, vector, path, out)
                    passed, known = passed + p, known + k
                    failures += f
                continue
            if os.path.exists(out):
                os.remove(out)
            cmd = expand(args.decoder, path, out)
            try:
                run = subprocess.run(cmd, capture_output=True, timeout=args.timeout)
            except subprocess.TimeoutExpired:
                failures.append((vector["file"], f"no answer within {args.timeout} s (a decoder must not hang)"))
                continue
            text = (run.stdout + run.stderr).decode("utf-8", "replace")
            problem = None
            if run.returncode < 0:
                problem = f"killed by signal {-run.returncode} (a decoder must not crash)"
            elif vector["valid"]:
                if run.returncode != 0:
                    problem = f"exit {run.returncode} on a valid vector: {text.strip()[:300]}"
                elif args.mode == "decode":
                    if not os.path.exists(out):
                        problem = "no output written"
                    else:
                        digest = hashlib.sha256(open(out, "rb").read()).hexdigest()
                        if digest != vector["sha256"]:
                            problem = f"output sha256 {digest}, expected {vector['sha256']}"
                        elif args.level_decoder:
                            problem = check_outputs(args.level_decoder, vector.get("levels", []), "vertices",
                                                    "level of {} vertices", args, path, out)
                        if problem is None and args.region_decoder:
                            problem = check_outputs(args.region_decoder, vector.get("regions", []), "region",
                                                    "region {}", args, path, out)
            else:
                code = "E%d" % vector["error"]
                if run.returncode == 0:
                    problem = f"exit 0 on an invalid vector (expected {code} {vector['error_name']})"
                elif not re.search(r"\b%s\b" % code, text):
                    problem = f"expected {code} {vector['error_name']}, got: {text.strip()[:300]}"
                elif args.check_offsets and not re.search(r"\boffset %d\b" % vector["offset"], text):
                    problem = f"expected offset {vector['offset']}, got: {text.strip()[:300]}"
                elif args.mode == "decode" and os.path.exists(out):
                    problem = "an output file was left behind for an invalid stream"
            if problem:
                failures.append((vector["file"], problem))
            else:
                passed += 1
                if args.verbose:
                    print(f"ok    {vector['file']}")
    for name, problem in failures:
        print(f"FAIL  {name}: {problem}")
    print(f"conformance ({args.mode}): {passed} passed, {len(failures)} failed"
          + (f", {known} known failures of the reference (manifest: known_failure)" if known else ""))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
