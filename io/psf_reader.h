// io/psf_reader.h — CHARMM / NAMD / X-PLOR PSF topologies (the usual companion of a DCD
// trajectory; gemmi cannot read them). Only what drawing needs: atoms with name, residue,
// segment (as the chain) and element, and the bonds of !NBOND. Angles and the rest are skipped.
#pragma once

#include <string>

#include "io/molecule.h"

namespace softmol::io {

// Reads a PSF (standard, EXT or X-PLOR flavour: fields are read as whitespace-separated words).
// Element from the mass (the nearest standard atomic weight within 0.1 u), else from the atom
// name; vdwRadius/color from the element table; positions zero until a frame is applied
// (ApplyFrame in io/trajectory.h). Throws InputError naming the file and line on bad input.
Molecule ReadPsfTopology(const std::string& path);

}  // namespace softmol::io
