#!/usr/bin/env python3
"""Size of ssitrace's certified B-spline edges next to OpenCASCADE's own intersection curves.

Usage (from the project root, after `cargo build --release`):

    python3 scripts/edge_size_table.py [--tolerance T ...] [SCENE.json ...]

For each scene and each tolerance T it runs `ssitrace trace SCENE --method validated
--tolerance T --edges FILE` and reports, per edge, the control points of its 3D curve, its
degree and its proven edge tolerance; next to it, for the same two patches at the same T,
OpenCASCADE's `GeomInt_IntSS::Perform` (3D curves approximated, as `GeomAPI_IntSS` does) and
the pole count, degree and distinct knots of each B-spline it returns, with the tolerance it
says it reached (uncertified).

The OCCT side is `scripts/occt_edge_size.cpp`, compiled here with g++ against the Debian
OpenCASCADE packages (`../shared/peers/README.md` says how to install them) into a temporary
directory; the scenes are converted with `../shared/peers/scene2txt.py`. Without either, the
OCCT columns say so and ssitrace's are still reported.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile

DEFAULT_SCENES = [
    "scenes/wu_andrade_fig7.json",
    "scenes/cylinders_full.json",
    "scenes/bicubic_transversal.json",
    "scenes/two_loops_s31_s32.json",
    "scenes/sphere_patch_plane.json",
    "scenes/viviani.json",
]

CONVERTERS = [
    os.environ.get("SSITRACE_SCENE2TXT", ""),
    "../shared/peers/scene2txt.py",
    "/work/shared/peers/scene2txt.py",
]

OCCT_LIBS = ["-lTKGeomAlgo", "-lTKGeomBase", "-lTKG3d", "-lTKG2d", "-lTKMath", "-lTKernel"]


def build_occt(tmp):
    """The compiled OCCT driver, or (None, why not)."""
    src = os.path.join(os.path.dirname(os.path.abspath(__file__)), "occt_edge_size.cpp")
    exe = os.path.join(tmp, "occt_edge_size")
    cmd = ["g++", "-O2", "-std=c++17", "-Wno-deprecated-declarations",
           "-I/usr/include/opencascade", src, "-o", exe] + OCCT_LIBS
    try:
        subprocess.run(cmd, check=True, capture_output=True, text=True)
    except (OSError, subprocess.CalledProcessError) as e:
        return None, f"OCCT driver not built ({e})"
    return exe, None


def ours(binary, scene, tol, tmp):
    """Per edge (control points, degree, edge tolerance), or an error string."""
    out = os.path.join(tmp, "edges.json")
    cmd = [binary, "trace", scene, "--method", "validated", "--tolerance", str(tol),
           "--edges", out]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        return f"ssitrace failed: {r.stderr.strip()[:80]}"
    with open(out) as f:
        d = json.load(f)
    return [(len(e["curve"]["control_points"]), e["curve"]["degree"], e["edge_tolerance"])
            for e in d["edges"]]


def occt(exe, converter, scene, tol, tmp):
    """Per line (poles, degree, knots) and the tolerance OCCT reached, or an error string."""
    if exe is None or converter is None:
        return "no OCCT driver or scene converter"
    txt = os.path.join(tmp, "scene.txt")
    try:
        subprocess.run([sys.executable, converter, scene, txt], check=True, capture_output=True)
        r = subprocess.run([exe, txt, str(tol)], check=True, capture_output=True, text=True)
        d = json.loads(r.stdout)
    except (subprocess.CalledProcessError, json.JSONDecodeError) as e:
        return f"OCCT run failed: {e}"
    return [(l["poles"], l.get("degree"), l.get("knots")) for l in d["lines"]], d["tol_reached_3d"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("scenes", nargs="*", default=DEFAULT_SCENES)
    ap.add_argument("--binary", default="target/release/ssitrace")
    ap.add_argument("--tolerance", type=float, action="append",
                    help="tolerance(s) for both (default: 1e-9 and OCCT's usual 1e-7)")
    args = ap.parse_args()
    if not os.path.exists(args.binary):
        sys.exit(f"{args.binary} missing: run `cargo build --release` first")
    tols = args.tolerance or [1e-9, 1e-7]
    converter = next((c for c in CONVERTERS if c and os.path.exists(c)), None)
    with tempfile.TemporaryDirectory() as tmp:
        exe, why = build_occt(tmp)
        if why:
            print(why)
        print(f"{'scene':<26} {'tol':>7}  ssitrace: control points/degree (edge tolerance)"
              f"  |  OCCT: poles/degree [knots] (tol reached, uncertified)")
        for scene in args.scenes:
            name = os.path.basename(scene).removesuffix(".json")
            for tol in tols:
                mine = ours(args.binary, scene, tol, tmp)
                if isinstance(mine, str):
                    left = mine
                else:
                    left = ", ".join(f"{n}/{d} ({t:.1e})" for n, d, t in mine)
                theirs = occt(exe, converter, scene, tol, tmp)
                if isinstance(theirs, str):
                    right = theirs
                else:
                    lines, reached = theirs
                    right = ", ".join("not a B-spline" if n is None else f"{n}/{d} [{k}]"
                                      for n, d, k in lines) or "no curve"
                    right += f" ({reached:.1e})"
                print(f"{name:<26} {tol:>7.0e}  {left}  |  {right}")


if __name__ == "__main__":
    main()
