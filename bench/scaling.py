#!/usr/bin/python3
"""How softmol's frame time grows with atoms, pixels and threads, and a fitted cost model (issue 12).

Runs whole `softmol render` processes, each a small turntable (--turntable N) written with
--profile (Chrome trace JSON: one `frame` event per frame, the passes inside it), and takes each
pass's median over the warm frames (the first frame is dropped). Passes done once per structure
(the AO bake, the occupancy pyramid: "(reused)" in later frames) are reported as setup costs, from
the first frame. Every configuration runs REPEAT processes and keeps, per pass, the lowest of their
medians (the least disturbed by other work on the machine); the process's CPU time over its wall
time is kept too (how many cores it really got). Then fits, per pass, t = a*atoms + b*pixels + c
by least squares weighted by 1/t (so the relative error is what is minimised) over the runs at the
default thread count, then again with a term in covered pixels, t = a*atoms + b*pixels +
d*covered + c, for the passes whose work follows what the pixels show (cone AO, PCF): covered is
the "covered samples" counter of the shadow runs' profiles, which have the same cameras as the
other runs of their molecule and size. Prints a Markdown section (or writes it to --out).
Needs python3 with numpy. Results: docs/PERFORMANCE.md, "How time grows".

Run (from the repository root; ~2 minutes on 2 quiet cores, ~4 when they are shared):
    /usr/bin/python3 bench/scaling.py --softmol build/release/cli/softmol --out /tmp/scaling.md
"""
import argparse, json, os, re, resource, statistics, subprocess, sys, tempfile, time
import numpy as np

ATOMS = ["data/pept.pdb", "data/il2.pdb", "data/1tii.pdb", "data/4JSV.pdb", "data/3J6R.pdb",
         "data/3J6R.pdb --assembly 1"]
SIZES = ["320x240", "640x480", "1280x960", "1920x1080", "2560x1920"]
SETUP = ("ao bake", "occupancy pyramid")
COVERED_PASSES = ("cone ao", "shadows", "baked ao lookup", "shading")
REPEAT, FRAMES = 2, 7


def runs():
    """(molecule, size, ao, shadows, threads, frames) for every process to start."""
    F = FRAMES
    r = [(m, "1280x960", "none", False, 0, F) for m in ATOMS]
    r += [("data/1tii.pdb", s, "none", False, 0, F) for s in SIZES if s != "1280x960"]
    r += [(m, "1920x1080", "none", False, t, F) for m in ("data/1tii.pdb", "data/4JSV.pdb") for t in (1, 2)]
    few = ["data/pept.pdb", "data/1tii.pdb", "data/4JSV.pdb", "data/3J6R.pdb"]
    for ao, shadows in (("cone", False), ("baked", False), ("none", True)):
        r += [(m, "1280x960", ao, shadows, 0, F) for m in few]
        r += [("data/1tii.pdb", s, ao, shadows, 0, F) for s in ("640x480", "1920x1080")]
    r += [("data/3J6R.pdb --assembly 1", "1280x960", ao, False, 0, 3) for ao in ("cone", "baked")]
    return r


def render(softmol, run, tmp):
    mol, size, ao, shadows, threads, frames = run
    trace = os.path.join(tmp, "trace.json")
    cmd = [softmol, "render", *mol.split(), "--size", size, "--ao", ao, "--threads", str(threads),
           "--turntable", str(frames), "--profile", trace, "-o", os.path.join(tmp, "f%05d.png")]
    if shadows:
        cmd.append("--shadows")
    t0, r0 = time.time(), resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    wall, r1 = time.time() - t0, resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    atoms = int(re.search(r": (\d+) atoms", out).group(1))
    doc = json.load(open(trace))["traceEvents"]
    ev = [e for e in doc if e.get("ph") == "X"]
    shadow_counters = [e for e in doc if e.get("ph") == "C" and e.get("name") == "shadow counters"]
    frames_ev = [e for e in ev if e.get("cat") == "frame"]
    per, covered = [], []  # per frame: {pass: ms}; covered samples where the shadows counted them
    for f in frames_ev:
        inside = lambda e: f["ts"] <= e["ts"] < f["ts"] + f["dur"]
        d = {"frame": f["dur"] / 1e3}
        for e in ev:
            if e.get("cat") == "pass" and inside(e):
                d[e["name"]] = d.get(e["name"], 0) + e["dur"] / 1e3
        per.append(d)
        covered += [e["args"]["covered samples"] for e in shadow_counters if inside(e)]
    setup = {k: per[0][k] for k in SETUP if k in per[0]}
    warm = per[1:]
    passes = {k: statistics.median(d[k] for d in warm) for k in warm[0] if "(reused)" not in k}
    return dict(mol=mol, size=size, ao=ao, shadows=shadows, threads=threads, atoms=atoms,
                pixels=int(size.split("x")[0]) * int(size.split("x")[1]), passes=passes,
                setup=setup, wall=wall, cores=cpu / wall, frames=len(warm),
                covered=statistics.median(covered[1:]) if len(covered) > 1 else None)


def best(reps):
    """Per pass, the lowest of the repetitions' medians."""
    p = dict(reps[0])
    for key in ("passes", "setup"):
        p[key] = {k: min(r[key][k] for r in reps) for k in reps[0][key]}
    p["cores"] = max(r["cores"] for r in reps)
    return p


def fit(points, name, terms=("atoms", "pixels")):
    """Weighted least squares t = sum(k_i * term_i) + c; returns the k_i in ns per unit, c (ms), errors."""
    A = np.array([[p[k] for k in terms] + [1.0] for p in points])
    t = np.array([p["passes"][name] for p in points])
    w = 1.0 / t
    coef = np.linalg.lstsq(A * w[:, None], t * w, rcond=None)[0]
    rel = np.abs(A @ coef - t) / t
    return [c * 1e6 for c in coef[:-1]], coef[-1], float(np.median(rel)), float(rel.max()), len(points)


def share_covered(res):
    """Gives each run the covered samples of a shadow run of its molecule and size (same cameras)."""
    known = {(p["mol"], p["size"]): p["covered"] for p in res if p["covered"] is not None}
    for p in res:
        if p["covered"] is None:
            p["covered"] = known.get((p["mol"], p["size"]))


def label(p):
    s = p["mol"].replace("data/", "").replace(".pdb", "")
    return s


def config(p):
    c = "ao " + p["ao"] + (" + shadows" if p["shadows"] else "")
    return c


def report(res, load, cmdline):
    L = ["Regenerate: `" + cmdline + "`", ""]
    L.append("Load average (1 min) sampled before every process: min %.2f, median %.2f, max %.2f "
             "(%d samples)." % (min(load), statistics.median(load), max(load), len(load)))
    L += ["", "Per pass, the lower of %d processes' medians over their %d warm turntable frames (ms; frame = "
          "the whole frame event; threads: all = --threads 0):" % (REPEAT, FRAMES - 1), ""]
    allpasses = []
    for p in res:
        for k in p["passes"]:
            if k not in allpasses and k != "frame":
                allpasses.append(k)
    L.append("| molecule | atoms | size | config | threads | frame | " + " | ".join(allpasses) + " | setup (first frame) |")
    L.append("|---" * (7 + len(allpasses)) + "|")
    for p in res:
        cells = ["%.1f" % p["passes"][k] if k in p["passes"] else "" for k in allpasses]
        setup = ", ".join("%s %.0f" % kv for kv in p["setup"].items())
        L.append("| %s | %d | %s | %s | %s | **%.1f** | %s | %s |" % (
            label(p), p["atoms"], p["size"], config(p), p["threads"] or "all", p["passes"]["frame"],
            " | ".join(cells), setup))
    L += ["", "Threads (1tii and 4JSV, 1920x1080, ao none): speed-up from 1 to 2 threads:", ""]
    L.append("| molecule | pass | 1 thread (ms) | 2 threads (ms) | speed-up | CPU/wall, 1 and 2 threads |")
    L.append("|---|---|---|---|---|---|")
    for m in ("data/1tii.pdb", "data/4JSV.pdb"):
        one = next(p for p in res if p["mol"] == m and p["threads"] == 1)
        two = next(p for p in res if p["mol"] == m and p["threads"] == 2)
        for k in one["passes"]:
            L.append("| %s | %s | %.1f | %.1f | %.2f× | %.2f, %.2f |" % (
                label(one), k, one["passes"][k], two["passes"][k], one["passes"][k] / two["passes"][k],
                one["cores"], two["cores"]))
    L += ["", "Cost model t = a·atoms + b·pixels + c per pass, least squares weighted by 1/t, over the "
          "runs at all cores (relative error |fit − t|/t over the same points):", ""]
    L.append("| pass | points | a (ns/atom) | b (ns/pixel) | c (ms) | median error | max error |")
    L.append("|---|---|---|---|---|---|---|")
    pts = [p for p in res if p["threads"] == 0]
    for k in ["frame (ao none)"] + allpasses + [s + " (setup)" for s in SETUP]:
        if k == "frame (ao none)":
            sub = [p for p in pts if p["ao"] == "none" and not p["shadows"]]
            sub = [dict(p, passes={k: p["passes"]["frame"]}) for p in sub]
        elif k.endswith(" (setup)"):
            sub = [dict(p, passes={k: p["setup"][k[:-8]]}) for p in pts if k[:-8] in p["setup"]]
        else:
            sub = [p for p in pts if k in p["passes"]]
        if len(sub) < 4:
            continue
        (a, b), c, med, mx, n = fit(sub, k)
        L.append("| %s | %d | %.1f | %.2f | %.2f | %.0f%% | %.0f%% |" % (k, n, a, b, c, 100 * med, 100 * mx))
    L += ["", "With a term in covered pixels, t = a·atoms + b·pixels + d·covered + c (covered: the samples "
          "showing a surface, the shadow runs' counter for the same molecule, size and cameras; runs "
          "without one are left out), for the passes that work per covered pixel:", ""]
    L.append("| pass | points | a (ns/atom) | b (ns/pixel) | d (ns/covered pixel) | c (ms) | median error | max error |")
    L.append("|---|---|---|---|---|---|---|---|")
    for k in COVERED_PASSES:
        sub = [p for p in pts if k in p["passes"] and p["covered"] is not None]
        if len(sub) < 5:
            continue
        (a, b, d), c, med, mx, n = fit(sub, k, ("atoms", "pixels", "covered"))
        L.append("| %s | %d | %.1f | %.2f | %.2f | %.2f | %.0f%% | %.0f%% |" % (k, n, a, b, d, c, 100 * med, 100 * mx))
    return "\n".join(L) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--softmol", default="build/release/cli/softmol")
    ap.add_argument("--out", help="write the Markdown here (default stdout)")
    args = ap.parse_args()
    res, load = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for r in runs():
            reps = []
            for _ in range(REPEAT):
                load.append(os.getloadavg()[0])
                reps.append(render(args.softmol, r, tmp))
            p = best(reps)
            print("%-28s %-9s %-5s sh=%d th=%d frame %.1f ms  (%.1f s, %.2f cores)" % (
                p["mol"], p["size"], p["ao"], p["shadows"], p["threads"], p["passes"]["frame"], p["wall"],
                p["cores"]), file=sys.stderr, flush=True)
            res.append(p)
    share_covered(res)
    md = report(res, load, "/usr/bin/python3 bench/scaling.py --softmol " + args.softmol)
    if args.out:
        open(args.out, "w").write(md)
    else:
        sys.stdout.write(md)


if __name__ == "__main__":
    main()
