#!/usr/bin/python3
"""Two or more softmol builds side by side, as whole processes, on a machine too noisy to trust
one run (issue 17): before and after a change to a hot path.

Each round starts one `softmol render ... --repeat N --profile` process per build, the builds in
turn, so a slow spell of the machine falls on all of them. From each process's Chrome trace it
takes the first frame, the best warm frame and each pass's best warm time; it prints, per build,
the medians over the rounds of those, and first / warm (the "warm from the first frame" target).
The builds' images are compared byte for byte (an optimisation must not change them).

Run (from the repository root; the render arguments after --):
    bench/process_ab.py --rounds 5 --repeat 10 /tmp/softmol_before build/release/cli/softmol \\
        -- render data/4JSV.pdb --size 1920x1080 --ao none
Results: docs/PERFORMANCE.md, "Masked stores, dropped prefetches and the SSAA 1 resolve".
"""
import argparse, filecmp, json, os, statistics, subprocess, sys, tempfile


def one_process(softmol, args, repeat, out_dir, tag):
    """(first frame ms, best warm frame ms, {pass: best warm ms}, image path) of one process."""
    trace, image = os.path.join(out_dir, tag + ".json"), os.path.join(out_dir, tag + ".png")
    cmd = [softmol] + args + ["--repeat", str(repeat), "--profile", trace, "-q", "-o", image]
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(" ".join(cmd) + " failed:\n" + done.stderr)
    with open(trace) as f:
        t = json.load(f)
    events = t["traceEvents"] if isinstance(t, dict) else t
    frames = sorted((e for e in events if e.get("name") == "frame"), key=lambda e: e["ts"])
    if len(frames) < 2:
        sys.exit("need --repeat 2 or more: the first frame is compared with the warm ones")
    warm = frames[1:]
    passes = {}
    for e in events:  # a pass (or a raster stage) inside a warm frame
        if e.get("ph") != "X" or e.get("cat") not in ("pass", "raster"):
            continue
        if any(w["ts"] <= e["ts"] <= w["ts"] + w["dur"] for w in warm):
            passes[e["name"]] = min(passes.get(e["name"], float("inf")), e["dur"] / 1000)
    return frames[0]["dur"] / 1000, min(w["dur"] for w in warm) / 1000, passes, image


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--rounds", type=int, default=5)
    p.add_argument("--repeat", type=int, default=10, help="frames per process (the first is the cold one)")
    p.add_argument("builds", nargs="+", help="softmol binaries")
    argv = sys.argv[1:]
    if "--" not in argv:
        p.error("give the render arguments after --")
    split = argv.index("--")
    a = p.parse_args(argv[:split])
    render = argv[split + 1:]
    results = {b: [] for b in a.builds}
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(a.rounds):
            for i, b in enumerate(a.builds):
                results[b].append(one_process(b, render, a.repeat, tmp, "b%d_r%d" % (i, r)))
        images = [results[b][0][3] for b in a.builds]
        same = all(filecmp.cmp(images[0], im, shallow=False) for im in images[1:])
        print("| build | first frame | warm frame | first / warm | passes (best warm, medians) |")
        print("|---|---|---|---|---|")
        for b in a.builds:
            runs = results[b]
            first = statistics.median(x[0] for x in runs)
            warm = statistics.median(x[1] for x in runs)
            names = sorted({n for x in runs for n in x[2]})
            passes = ", ".join("%s %.2f" % (n, statistics.median(x[2][n] for x in runs if n in x[2])) for n in names)
            print("| %s | %.2f | %.2f | %.2f | %s |" % (b, first, warm, first / warm, passes))
        print("\nimages " + ("byte-identical" if same else "DIFFER"))
        return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
