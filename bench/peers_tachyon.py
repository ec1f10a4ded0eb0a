#!/usr/bin/env python3
"""bench/peers_tachyon.py - whole processes of `softmol render` against Tachyon (Debian's
`tachyon`) on the same molecules, sizes and camera (issue 17), timed as /usr/bin/time does
(wall clock around fork/exec/wait, max RSS from the child's rusage), several runs interleaved
job by job so both see the same load, medians. Tachyon's scene is written by
build/.../bench/tachyon_scene from softmol's own spheres and the camera that
`softmol render --print-view` printed (untimed), and rendered with one sample per pixel
(-aasamples 0), shadows on (-fullshade) and, where softmol has AO, Tachyon's AO with 16 samples.
Writes the table into docs/PERFORMANCE.md between the markers below (replacing it on re-run).

  bench/peers_tachyon.py [--build build/release] [--runs 5] [--no-doc] [--keep DIR]
  bench/peers_tachyon.py --check    # one tiny run (pept, 128x96): do both pictures cover the same pixels?

Python 3 standard library only. Exit 77 (ctest's skip) when tachyon is not installed.
"""
import argparse
import os
import re
import shutil
import statistics
import struct
import subprocess
import sys
import tempfile
import time
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BEGIN = "<!-- bench/peers_tachyon.py: begin (generated; re-run the script to replace) -->"
END = "<!-- bench/peers_tachyon.py: end -->"
SKIP = 77

# (label, molecule, assembly, size, softmol flags, Tachyon AO samples)
CASES = [
    ("1tii 1024×768, shadows", "data/1tii.pdb", "", "1024x768", ["--shadows"], 0),
    ("1tii 1024×768, shadows, softmol without its default AO (like for like)", "data/1tii.pdb", "", "1024x768",
     ["--shadows", "--ao", "none"], 0),
    ("1tii 1920×1080, shadows + cone AO", "data/1tii.pdb", "", "1920x1080", ["--shadows", "--ao", "cone"], 16),
    ("1tii 1920×1080, shadows + baked AO", "data/1tii.pdb", "", "1920x1080", ["--shadows", "--ao", "baked"], 16),
    ("3J6R assembly 1 (1.03 M atoms) 1920×1080, shadows + cone AO", "data/3J6R.pdb", "1", "1920x1080",
     ["--shadows", "--ao", "cone"], 16),
]
CHECK_CASE = ("pept 128×96, shadows", "data/pept.pdb", "", "128x96", ["--shadows"], 0)


def timed(cmd):
    """Runs cmd; returns (wall s, max RSS MiB, stdout). Fails loudly on a non-zero exit."""
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    out = proc.stdout.read()
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        sys.exit("peers_tachyon: %s exited %d:\n%s" % (" ".join(cmd), proc.returncode, out.decode(errors="replace")))
    return wall, usage.ru_maxrss / 1024.0, out.decode(errors="replace")


def softmol_cmd(softmol, case, out_png, extra=()):
    _, mol, assembly, size, flags, _ = case
    cmd = [softmol, "render", os.path.join(ROOT, mol), "--size", size, *flags, "-o", out_png, *extra]
    return cmd + (["--assembly", assembly] if assembly else [])


def write_tachyon_scene(softmol, writer, case, dat):
    """The camera softmol uses for this case, then Tachyon's scene from it (both untimed)."""
    _, mol, assembly, size, _, ao = case
    view_cmd = softmol_cmd(softmol, (None, mol, assembly, size, [], 0), os.path.join(os.path.dirname(dat), "view.png"),
                           ["--print-view"])  # no effects: the camera does not depend on them
    _, _, out = timed(view_cmd)
    m = re.search(r"--view '([^']*)'", out)
    if not m:
        sys.exit("peers_tachyon: no --view in the output of " + " ".join(view_cmd))
    cmd = [writer, os.path.join(ROOT, mol), "--view", m.group(1), "--size", size, "--ao-samples", str(ao), "-o", dat]
    timed(cmd + (["--assembly", assembly] if assembly else []))


def tachyon_cmd(dat, out_png):
    return ["tachyon", dat, "-aasamples", "0", "-fullshade", "-format", "PNG", "-o", out_png]


def read_png_rgb(path):
    """8-bit RGB or RGBA, non-interlaced PNG -> (width, height, rows of RGB bytes)."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit("peers_tachyon: %s is not a PNG" % path)
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            width, height, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or ctype not in (2, 6) or interlace:
                sys.exit("peers_tachyon: %s: only 8-bit RGB/RGBA non-interlaced PNGs are read" % path)
            bpp = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, stride, rows, prev = zlib.decompress(idat), width * bpp, [], bytearray(width * bpp)
    for y in range(height):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line[j] for j in range(stride) if j % bpp < 3))
        prev = line
    return width, height, rows


def coverage_iou(png_a, png_b):
    """Intersection over union of the molecule's pixels (anything not the white background)."""
    wa, ha, a = read_png_rgb(png_a)
    wb, hb, b = read_png_rgb(png_b)
    if (wa, ha) != (wb, hb):
        return 0.0
    inter = union = 0
    for ra, rb in zip(a, b):
        for x in range(wa):
            ca, cb = min(ra[3 * x:3 * x + 3]) < 250, min(rb[3 * x:3 * x + 3]) < 250
            inter += ca and cb
            union += ca or cb
    return inter / union if union else 0.0


def machine():
    model = "unknown CPU"
    for line in open("/proc/cpuinfo"):
        if line.startswith("model name"):
            model = line.split(":", 1)[1].strip()
            break
    return "%s, nproc %d" % (model, os.cpu_count())


def load():
    return "%.2f, %.2f, %.2f" % os.getloadavg()


def median(xs):
    return statistics.median(xs)


def run(args):
    softmol = os.path.join(args.build, "cli", "softmol")
    writer = os.path.join(args.build, "bench", "tachyon_scene")
    for exe in (softmol, writer):
        if not os.access(exe, os.X_OK):
            sys.exit("peers_tachyon: %s not built (cmake --build %s --target softmol tachyon_scene)" % (exe, args.build))
    cases = [CHECK_CASE] if args.check else [c for c in CASES if os.path.exists(os.path.join(ROOT, c[1]))]
    work = args.keep or tempfile.mkdtemp(prefix="peers_tachyon_")
    os.makedirs(work, exist_ok=True)
    # Tachyon scenes, one per molecule/size/AO (the baked and cone AO rows share one).
    scenes = {}
    for case in cases:
        key = (case[1], case[2], case[3], case[5])
        if key not in scenes:
            scenes[key] = os.path.join(work, "tachyon_%d.dat" % len(scenes))
            write_tachyon_scene(softmol, writer, case, scenes[key])
    jobs = [("softmol", i, softmol_cmd(softmol, c, os.path.join(work, "softmol_%d.png" % i)))
            for i, c in enumerate(cases)]
    jobs += [("tachyon", key, tachyon_cmd(dat, dat[:-4] + ".png")) for key, dat in scenes.items()]
    load_before = load()
    results = {(kind, key): [] for kind, key, _ in jobs}
    for r in range(1 if args.check else args.runs):
        order = jobs[r % len(jobs):] + jobs[:r % len(jobs)]  # rotate, so no job always runs first
        for kind, key, cmd in order:
            results[(kind, key)].append(timed(cmd))
    load_after = load()
    if args.check:
        iou = coverage_iou(os.path.join(work, "softmol_0.png"), list(scenes.values())[0][:-4] + ".png")
        print("peers_tachyon --check: coverage IoU softmol vs Tachyon = %.3f" % iou)
        if not args.keep:
            shutil.rmtree(work)
        return 0 if iou >= 0.9 else 1
    rows, shared = [], set()
    for i, case in enumerate(cases):
        s = results[("softmol", i)]
        t = results[("tachyon", (case[1], case[2], case[3], case[5]))]
        sw, tw = median([x[0] for x in s]), median([x[0] for x in t])
        frame = [float(m.group(1)) for x in s for m in [re.search(r"frame: ([0-9.]+) ms", x[2])] if m]
        ray = [float(m.group(1)) for x in t for m in [re.search(r"Ray Tracing Time:\s+([0-9.]+)", x[2])] if m]
        key = (case[1], case[2], case[3], case[5])
        same = " (the run above)" if key in shared else ""
        shared.add(key)
        rows.append("| %s | %.3f s (frame %s), %.0f MiB | %.3f s (ray tracing %s), %.0f MiB%s | %.1f× |" % (
            case[0], sw, "%.0f ms" % median(frame) if frame else "?", median([x[1] for x in s]), tw,
            "%.2f s" % median(ray) if ray else "?", median([x[1] for x in t]), same, tw / sw))
    version = re.search(r"Version (\S+)", results[("tachyon", key)][0][2])
    flags = "" if args.runs == 5 else " --runs %d" % args.runs  # the command that makes this table
    text = "\n".join([
        BEGIN,
        "## Whole processes beside Tachyon (issue 17)",
        "",
        "`bench/peers_tachyon.py%s` on %s, %s (%s)." % (flags, time.strftime("%Y-%m-%d"), machine(),
                                                      subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"],
                                                                     capture_output=True, text=True).stdout.strip()),
        "Load average before %s, after %s%s." % (load_before, load_after,
                                                 " — measured under load (other builds on the same cores)"
                                                 if max(os.getloadavg()) > 0.5 * os.cpu_count() else ""),
        "Each process timed %d times, softmol and Tachyon runs interleaved; medians of wall clock and max RSS"
        % args.runs,
        "(`os.wait4`, what `/usr/bin/time -f '%%e %%M'` reports). softmol: `softmol render MOLECULE --size WxH"
        " FLAGS -o x.png`, all cores; its own `frame:` line in brackets. Tachyon %s (Debian's `tachyon`):"
        " `tachyon scene.dat -aasamples 0 -fullshade -format PNG -o x.png`, all cores, one ray per pixel,"
        " shadows from one directional light along softmol's, and for the AO rows Tachyon's ambient occlusion"
        " with 16 sample rays (softmol's cone AO traces 9 cones; its baked AO 128 directions once per process);"
        " the scene (`bench/tachyon_scene`: softmol's own spheres, radii, colours and `--print-view` camera) is"
        " written before the timing, so Tachyon's process reads a ready scene file while softmol's reads the PDB."
        " Tachyon's \"Ray Tracing Time\" in brackets." % (version.group(1) if version else "?"),
        "",
        "| work | softmol | Tachyon | Tachyon / softmol |",
        "|---|---|---|---|",
        *rows,
        END,
    ])
    print(text)
    if not args.no_doc:
        doc = os.path.join(ROOT, "docs", "PERFORMANCE.md")
        old = open(doc).read()
        if BEGIN in old and END in old:
            new = old[:old.index(BEGIN)] + text + old[old.index(END) + len(END):]
        else:
            new = old.rstrip("\n") + "\n\n" + text + "\n"
        open(doc, "w").write(new)
    if not args.keep:
        shutil.rmtree(work)
    return 0


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build", "release"), help="softmol build folder")
    p.add_argument("--runs", type=int, default=5, help="timed runs of each process (median)")
    p.add_argument("--no-doc", action="store_true", help="print the table only")
    p.add_argument("--keep", help="keep scenes and images in this folder (to look at them)")
    p.add_argument("--check", action="store_true", help="one tiny run; exit 1 unless the pictures overlap")
    args = p.parse_args()
    if args.runs < 1:
        p.error("--runs must be at least 1")
    if shutil.which("tachyon") is None:
        print("peers_tachyon: tachyon is not installed (apt-get install tachyon); skipped")
        return SKIP
    return run(args)


if __name__ == "__main__":
    sys.exit(main())
