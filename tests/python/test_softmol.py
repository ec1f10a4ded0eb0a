"""tests/python/test_softmol.py — the Python module against the command: load, render, the
pixels of the command's PNG for the same options, AOVs, errors naming the option, molecules
from arrays, _repr_png_, and the MDAnalysis example's frames against `--trajectory` frames.

Run by ctest (tests/python/CMakeLists.txt sets PYTHONPATH, SOFTMOL_EXE, SOFTMOL_DATA_DIR and
SOFTMOL_EXAMPLES_DIR)."""
import importlib.util
import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest
from PIL import Image as PilImage

import softmol

DATA = pathlib.Path(os.environ["SOFTMOL_DATA_DIR"])
EXE = os.environ["SOFTMOL_EXE"]
PEPT = str(DATA / "pept.pdb")


def command(*args):
    """Runs `softmol render ARGS -q`; its stderr."""
    r = subprocess.run([EXE, "render", *args, "-q"], capture_output=True, text=True)
    return r


def command_png(path, *args):
    r = command(*args, "-o", str(path))
    assert r.returncode == 0, r.stderr
    return np.asarray(PilImage.open(path))


def test_load_and_render():
    mol = softmol.load(DATA / "pept.pdb")  # a str or any os.PathLike
    assert len(mol) == mol.atom_count == 107
    assert mol.positions.shape == (107, 3)
    img = mol.render(size=(64, 48), ao="none")
    assert (img.width, img.height) == (64, 48)
    assert img.rgba.shape == (48, 64, 4) and img.rgba.dtype == np.uint8
    assert img.depth is None and img.id is None
    assert (img.rgba[..., 3] == 255).all()
    assert len(np.unique(img.rgba.reshape(-1, 4), axis=0)) > 10  # a molecule, not a blank


def test_rgba_is_a_view_of_the_image_buffer():
    img = softmol.load(PEPT).render(size=(32, 24), ao="none")
    a, b = img.rgba, img.rgba
    assert not a.flags.owndata
    assert np.shares_memory(a, b)
    del img  # the arrays keep the image alive
    assert a.sum() > 0


def test_pixels_are_the_commands_png(tmp_path):
    mol = softmol.load(PEPT)
    img = mol.render(size=(120, 90), style="balls", ao="baked", ao_directions=32, color="chain", contours=0.3)
    png = command_png(tmp_path / "cli.png", PEPT, "--size", "120x90", "--style", "balls", "--ao", "baked",
                      "--ao-directions", "32", "--color", "chain", "--contours", "0.3")
    assert png.shape == (90, 120, 3)
    assert np.array_equal(img.rgba[..., :3], png)
    # The same encoder: save() and _repr_png_ give the command's file, byte for byte.
    img.save(tmp_path / "api.png")
    assert (tmp_path / "api.png").read_bytes() == (tmp_path / "cli.png").read_bytes()
    assert img._repr_png_() == (tmp_path / "cli.png").read_bytes()


def test_sequences_and_repeatable_options(tmp_path):
    mol = softmol.load(PEPT)
    camera = (0, 0, 60, 0, 0, 0, 0, 1, 0)
    img = mol.render(size=(64, 48), ao="none", camera=camera, show=["resn ASP=balls", "resn GLY=licorice"],
                     rotate=(10, 20, 0), depth_cue=0.5)
    png = command_png(tmp_path / "cli.png", PEPT, "--size", "64x48", "--ao", "none", "--camera", "0,0,60,0,0,0,0,1,0",
                      "--show", "resn ASP=balls", "--show", "resn GLY=licorice", "--rotate", "10,20,0",
                      "--depth-cue", "0.5")
    assert np.array_equal(img.rgba[..., :3], png)


def test_aovs_on_request():
    img = softmol.load(PEPT).render(size=(64, 48), ao="cone", aovs=("depth", "normal", "ao", "id"))
    assert img.depth.shape == (48, 64) and img.depth.dtype == np.float32
    assert img.normal.shape == (48, 64, 3) and img.normal.dtype == np.float32
    assert img.ao.shape == (48, 64) and img.ao.dtype == np.float32
    assert img.id.shape == (48, 64) and img.id.dtype == np.uint32
    background = np.isinf(img.depth)
    assert background.any() and not background.all()
    assert (img.id[background] == 0xFFFFFFFF).all() and (img.id[~background] != 0xFFFFFFFF).all()
    assert ((img.ao >= 0) & (img.ao <= 1)).all()
    assert np.allclose(np.linalg.norm(img.normal[~background], axis=1), 1, atol=1e-3)


def test_errors_name_the_option_as_the_command_does():
    mol = softmol.load(PEPT)
    with pytest.raises(softmol.Error) as e:
        mol.render(ao_directions=0)
    assert isinstance(e.value, ValueError)
    r = command(PEPT, "--ao-directions", "0", "-o", "/nonexistent/x.png")
    assert r.returncode == 2
    assert r.stderr == f"softmol: {e.value}\n"
    with pytest.raises(softmol.Error, match=r"^--size: "):
        mol.render(size=(0, 0))
    with pytest.raises(softmol.Error, match=r"^--no-such-option: unknown option"):
        mol.render(no_such_option=1)
    with pytest.raises(softmol.Error, match=r"^--style: "):
        mol.render(style="sticks")
    with pytest.raises(softmol.Error, match="no_such.pdb"):
        softmol.load(str(DATA / "no_such.pdb"))
    with pytest.raises(softmol.Error, match=r"^positions: "):
        mol.render(positions=np.zeros((3, 3)))


def test_from_arrays():
    xyz = np.array([[0, 0, 0], [0.96, 0, 0], [-0.24, 0.93, 0]])
    computed = softmol.Molecule.from_arrays(xyz, ["O", "H", "H"])
    given = softmol.Molecule.from_arrays(xyz, ["O", "H", "H"], bonds=[[0, 1], [0, 2]])
    one = softmol.Molecule.from_arrays(xyz, ["O", "H", "H"], bonds=np.array([[0, 1]]))
    big = softmol.Molecule.from_arrays(xyz, ["O", "H", "H"], radii=[2.0, 0.5, 0.5])
    opts = dict(size=(64, 48), style="balls", ao="none")
    a = computed.render(**opts).rgba
    assert np.array_equal(a, given.render(**opts).rgba)  # the distance bonds are the O-H bonds
    assert not np.array_equal(a, one.render(**opts).rgba)
    assert not np.array_equal(computed.render(size=(64, 48), ao="none").rgba, big.render(size=(64, 48), ao="none").rgba)
    with pytest.raises(softmol.Error, match="unknown element 'Qq'"):
        softmol.Molecule.from_arrays(xyz, ["O", "H", "Qq"])
    with pytest.raises(softmol.Error, match=r"^xyz: "):
        softmol.Molecule.from_arrays(np.zeros(9), ["O", "H", "H"])


def test_repr_png_shows_in_a_notebook():
    png = softmol.load(PEPT).render(size=(32, 24), ao="none", transparent=True)._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert PilImage.open(__import__("io").BytesIO(png)).mode == "RGBA"


def test_positions_move_the_atoms_in_a_fixed_view():
    mol = softmol.load(PEPT)
    still = mol.render(size=(64, 48), ao="none").rgba.copy()
    moved = mol.positions + np.array([1.0, 0, 0])
    mol.positions = moved
    assert np.array_equal(mol.positions, moved)
    shifted = mol.render(size=(64, 48), ao="none").rgba
    assert not np.array_equal(still, shifted)  # the camera did not follow the atoms


def load_example():
    path = pathlib.Path(os.environ["SOFTMOL_EXAMPLES_DIR"]) / "mdanalysis_frames.py"
    spec = importlib.util.spec_from_file_location("mdanalysis_frames", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_mdanalysis_frames_are_the_commands_trajectory_frames(tmp_path):
    example = load_example()
    # A copy: MDAnalysis caches the XTC's frame offsets in a file beside it.
    shutil.copy(DATA / "md.xtc", tmp_path / "md.xtc")
    paths = example.render_frames(DATA / "md.pdb", tmp_path / "md.xtc", tmp_path / "py", slice(2, 4), size="96x72")
    assert [p.name for p in paths] == ["md_00000.png", "md_00001.png"]
    (tmp_path / "cli").mkdir()
    r = command(str(DATA / "md.pdb"), "--trajectory", str(DATA / "md.xtc"), "--frames", "2:3", "--size", "96x72",
                "-o", str(tmp_path / "cli" / "md_%05d.png"))
    assert r.returncode == 0, r.stderr
    for p in paths:
        ours = np.asarray(PilImage.open(p)).astype(int)
        theirs = np.asarray(PilImage.open(tmp_path / "cli" / p.name)).astype(int)
        # MDANALYSIS_ROUNDING: MDAnalysis rounds an XTC coordinate twice (to float32 nm, then
        # times 10: 31.170002 Å) where softmol's reader rounds once (31.17), so a few pixels
        # may differ by one level (measured: 2 of 6912, by 1). The same positions as softmol's
        # reader gives are the same bytes (tests/api/api_test.cpp).
        differing = (np.abs(ours - theirs).max(axis=2) > 0).mean()
        assert np.abs(ours - theirs).max() <= 1 and differing <= 0.01, (p.name, differing)
    assert not np.array_equal(np.asarray(PilImage.open(paths[0])), np.asarray(PilImage.open(paths[1])))
