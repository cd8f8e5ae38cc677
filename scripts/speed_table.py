#!/usr/bin/env python3
"""Certified whole-process time of `ssitrace trace SCENE --method validated` next to
OpenCASCADE's uncertified `GeomInt_IntSS::Perform` on the same two patches, in one run.

Usage (from the project root, after `cargo build --release`):

    python3 scripts/speed_table.py [--repeat N] [--tolerance T] [--baseline BIN] [SCENE.json ...]

For each scene it prints the median wall time of N whole ssitrace processes (search, march,
certification, straying check, output), OCCT's `time_ms` (the driver's own median of timed
runs, `Perform` alone), their ratio, and per certified branch its steps and proven tolerance.
The peer driver is looked up at $SSITRACE_PEERS (default /tmp/ssitrace-peers, built by
../shared/peers/build.sh); when it or the scene converter is missing the OCCT columns say so and
the ssitrace columns are still measured. The `cpu` column is the median CPU time (user + system,
all threads) of the same runs: on a machine busy with other work it moves far less than the wall
time. Where OCCT misses a loop (OCCT_WRONG) the ratio is
taken against max(OCCT, 12 ms), and the median and largest ratio close the table. With
`--baseline BIN` (e.g. a build of `main`) each scene also runs that binary, taking turns with
this one run by run, and prints its row under the same OCCT time.
"""

import argparse
import json
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time

DEFAULT_SCENES = [
    "scenes/wu_andrade_fig7.json",
    "scenes/cylinders_full.json",
    "scenes/cylinders.json",
    "scenes/bicubic_transversal.json",
    "scenes/two_loops_s31_s32.json",
    "scenes/sphere_patch_plane.json",
    "scenes/viviani.json",
    "scenes/cubic_quadratic_tangential.json",
    "scenes/small_loop.json",
]

# Scenes where OCCT's answer is wrong (misses a loop or returns nothing): the ratio is taken
# against the larger of OCCT's own time and YARDSTICK_MS, its median time over the scenes it gets
# right (issue #10), since a fast wrong answer is no yardstick.
OCCT_WRONG = {
    "wu_andrade_fig7.json",
    "viviani.json",
    "cubic_quadratic_tangential.json",
    "small_loop.json",
    "concentric_circles_0_002.json",
}
YARDSTICK_MS = 12.0

PEERS = os.environ.get("SSITRACE_PEERS", "/tmp/ssitrace-peers")
CONVERTER_CANDIDATES = [
    os.environ.get("SSITRACE_SCENE2TXT", ""),
    "../shared/peers/scene2txt.py",
    "/work/shared/peers/scene2txt.py",
]

CERT_RE = re.compile(r"certified: (\d+) steps, tolerance ([0-9.eE+-]+)")


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_ssitrace(binary, scene, tolerance):
    """Wall and CPU seconds (user + system, all threads) of one process, its branches, error."""
    cmd = [binary, "trace", scene, "--method", "validated"]
    if tolerance is not None:
        cmd += ["--tolerance", str(tolerance)]
    c0 = children_cpu()
    t0 = time.perf_counter()
    out = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    cpu = children_cpu() - c0
    if out.returncode != 0:
        return wall, cpu, None, out.stderr.strip().splitlines()[-1:] or ["failed"]
    branches = [(int(m.group(1)), float(m.group(2))) for m in CERT_RE.finditer(out.stdout)]
    return wall, cpu, branches, None


def run_occt(scene, tol):
    driver = os.path.join(PEERS, "occt_scene")
    conv = next((c for c in CONVERTER_CANDIDATES if c and os.path.exists(c)), None)
    if not os.path.exists(driver):
        return None, f"no OCCT driver at {driver} (build it with ../shared/peers/build.sh)"
    if conv is None:
        return None, "scene2txt.py not found (set SSITRACE_SCENE2TXT)"
    with tempfile.NamedTemporaryFile(suffix=".txt", delete=False) as f:
        txt = f.name
    try:
        subprocess.run([sys.executable, conv, scene, txt], check=True, capture_output=True)
        out = subprocess.run([driver, txt, str(tol)], capture_output=True, text=True, check=True)
        d = json.loads(out.stdout)
        return (d["time_ms"], len(d.get("lines", []))), None
    except (subprocess.CalledProcessError, json.JSONDecodeError, KeyError) as e:
        return None, f"OCCT run failed: {e}"
    finally:
        os.unlink(txt)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("scenes", nargs="*", default=DEFAULT_SCENES)
    ap.add_argument("--binary", default="target/release/ssitrace")
    ap.add_argument("--repeat", type=int, default=1, help="ssitrace runs per scene (median)")
    ap.add_argument("--tolerance", type=float, default=None, help="--tolerance for ssitrace")
    ap.add_argument("--occt-tol", type=float, default=1e-7)
    ap.add_argument("--json", default=None, help="also write the rows here")
    ap.add_argument("--baseline", default=None, help="another ssitrace binary to run alongside")
    args = ap.parse_args()
    if not os.path.exists(args.binary):
        sys.exit(f"{args.binary} missing: run `cargo build --release` first")

    rows = []
    ratios = {}
    hdr = (
        f"{'scene':34} {'validated':>10} {'cpu':>9} {'OCCT':>9} {'lines':>5} {'ratio':>7}  "
        "branches (steps, tolerance)"
    )
    print(hdr)
    print("-" * len(hdr))
    binaries = [("", args.binary)]
    if args.baseline:
        binaries.insert(0, ("base ", args.baseline))
    for scene in args.scenes:
        # The binaries take turns, run by run, so that a change of load hits both alike.
        runs = {tag: ([], [], None, None) for tag, _ in binaries}
        for _ in range(max(1, args.repeat)):
            for tag, binary in binaries:
                w, c, b, e = run_ssitrace(binary, scene, args.tolerance)
                walls, cpus, _, _ = runs[tag]
                walls.append(w)
                cpus.append(c)
                runs[tag] = (walls, cpus, b, e)
        measured = [
            (tag, statistics.median(runs[tag][0]), statistics.median(runs[tag][1]), runs[tag][2], runs[tag][3])
            for tag, _ in binaries
        ]
        occt, why = run_occt(scene, args.occt_tol)
        for tag, wall, cpu, branches, err in measured:
            name = tag + os.path.basename(scene)
            if occt is None:
                occt_s, lines_s, ratio_s = "-", "-", "-"
            else:
                occt_s = f"{occt[0]:.1f}ms"
                lines_s = str(occt[1])
                ref = occt[0]
                if os.path.basename(scene) in OCCT_WRONG:
                    ref = max(ref, YARDSTICK_MS)
                    occt_s += "*"
                ratio_s = f"{1000 * wall / ref:.1f}x" if ref > 0 else "-"
                ratios.setdefault(tag, []).append(1000 * wall / ref)
            br = "; ".join(f"{s}, {t:.2e}" for s, t in branches) if branches else (err or ["none"])[0]
            print(
                f"{name:34} {1000 * wall:>8.0f}ms {1000 * cpu:>7.0f}ms {occt_s:>9} {lines_s:>5} "
                f"{ratio_s:>7}  {br}"
            )
            rows.append(
                {
                    "scene": scene,
                    "binary": tag.strip() or "new",
                    "validated_ms": 1000 * wall,
                    "cpu_ms": 1000 * cpu,
                    "occt_ms": occt[0] if occt else None,
                    "occt_lines": occt[1] if occt else None,
                    "branches": branches,
                }
            )
        if why:
            print(f"{'':34} ({why})")
        sys.stdout.flush()
    if any(ratios.values()):
        print(f"(* OCCT's answer is wrong there: ratio against max(OCCT, {YARDSTICK_MS:g} ms))")
    for tag, rs in ratios.items():
        name = tag.strip() or "this build"
        print(f"{name}: median ratio {statistics.median(rs):.2f}x, max {max(rs):.1f}x")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
