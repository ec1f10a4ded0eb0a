#!/usr/bin/env python3
"""examples/python/mdanalysis_frames.py — frames of an MDAnalysis trajectory rendered by softmol.

MDAnalysis reads the trajectory; softmol reads the same topology once and gets each frame's
positions. The camera stays where the topology framed it (as `softmol render --trajectory`
does) and the automatic AO is cone AO, rebuilt per frame. The images are numbered 0, 1, 2, ...
so that `ffmpeg -i md_%05d.png md.mp4` reads them. (MDAnalysis writes its cache of the XTC's
frame offsets beside the file: .md.xtc_offsets.npz.)

    PYTHONPATH=build/release/python python3 examples/python/mdanalysis_frames.py \
        data/md.pdb data/md.xtc out/ --frames 0:10 --size 640x480
"""
import argparse
import pathlib
import warnings

import MDAnalysis as mda

import softmol


def render_frames(topology, trajectory, out_dir, frames=slice(None), **options):
    """Writes out_dir/md_00000.png, ... for the frames; returns their paths."""
    with warnings.catch_warnings():  # MDAnalysis warns about PDB fields it guesses
        warnings.simplefilter("ignore")
        universe = mda.Universe(str(topology), str(trajectory))
    molecule = softmol.load(topology)
    if len(molecule) != len(universe.atoms):
        raise SystemExit(f"{topology}: softmol reads {len(molecule)} atoms, MDAnalysis {len(universe.atoms)}")
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    paths = []
    for number, _ in enumerate(universe.trajectory[frames]):
        image = molecule.render(positions=universe.atoms.positions, **options)
        path = out_dir / f"md_{number:05d}.png"
        image.save(path)
        paths.append(path)
    return paths


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("topology")
    parser.add_argument("trajectory")
    parser.add_argument("out_dir")
    parser.add_argument("--frames", default=":", help="A:B[:STEP], Python slice of the frames (default all)")
    parser.add_argument("--size", default="640x480")
    args = parser.parse_args()
    frames = slice(*[int(p) if p else None for p in args.frames.split(":")])
    for path in render_frames(args.topology, args.trajectory, args.out_dir, frames, size=args.size):
        print(path)


if __name__ == "__main__":
    main()
