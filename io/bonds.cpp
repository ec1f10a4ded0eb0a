// io/bonds.cpp — distance bonds on a uniform grid.
//
// Grid: cell edge = the largest possible bond length (2 × the largest covalent radius present
// + tolerance), so every partner of an atom lies in its own cell or one of the 26 around it.
// Atoms are bucketed by a counting sort (O(n), no per-cell allocation). The cell edge grows
// when the bounding box is so sparse that the grid would hold many more cells than atoms
// (a hollow capsid), so memory stays O(n). The box is the robust one (the 0.1 % and 99.9 %
// quantiles per axis) when the full box would make the grid sparse: a few far outliers are
// clamped into the border cells (clamping is monotone, so every pair within one cell edge stays
// in neighbouring cells) instead of coarsening the grid until everything shares one cell.
//
// Bounded work for any input: a cell takes at most kMaxCellAtoms atoms (the first ones by
// index; real structures hold < 30 per cell) and an atom at most kMaxBonds distance bonds (the
// first found in (i, j) order). Atoms past a cap take no further part, and one warning names
// the first such atom: N atoms at one position (a broken model) cost O(N), not O(N²).
//
// Determinism: atoms are cut into fixed chunks of kChunk indices, independent of the thread
// count; each chunk lists its pairs (i, j > i) in order of i, then j; chunks are concatenated
// in index order. The result is sorted by (i, j) for any number of threads and no sort of the
// whole list is needed.
#include "io/bonds.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "io/elements.h"

namespace softmol::io {
namespace {

constexpr size_t kChunk = 4096;
constexpr double kMinBondLength = 0.4;  // Å; closer atoms are duplicates, not bonded
constexpr uint32_t kMaxCellAtoms = 256;
constexpr uint16_t kMaxBonds = 16;  // distance bonds per atom (real valences are <= 8)

struct Grid {
  double minX = 0, minY = 0, minZ = 0, inv = 1;
  int64_t nx = 1, ny = 1, nz = 1;
  std::vector<uint32_t> cellStart;  // nx*ny*nz + 1 offsets into the packed atoms

  // Clamped in double first: a far outlier must not overflow the integer conversion.
  int64_t Coord(double v, double lo, int64_t n) const {
    const double t = (v - lo) * inv;
    if (!(t > 0.0)) return 0;
    return t >= double(n - 1) ? n - 1 : static_cast<int64_t>(t);
  }
};

double Cells(const double lo[3], const double hi[3], double cell) {
  double cells = 1;
  for (int a = 0; a < 3; ++a) cells *= std::floor((hi[a] - lo[a]) / cell) + 1;
  return cells;
}

// Per axis, the coordinates at the 0.1 % and 99.9 % ranks of the included atoms.
void RobustBox(const Molecule& mol, const std::vector<float>& radius, double lo[3], double hi[3]) {
  const std::vector<double>* axes[3] = {&mol.x, &mol.y, &mol.z};
  std::vector<double> v;
  for (int a = 0; a < 3; ++a) {
    v.clear();
    for (size_t i = 0; i < radius.size(); ++i)
      if (radius[i] >= 0.f) v.push_back((*axes[a])[i]);
    const size_t k = v.size() / 1000;
    std::nth_element(v.begin(), v.begin() + ptrdiff_t(k), v.end());
    lo[a] = v[k];
    std::nth_element(v.begin(), v.end() - 1 - ptrdiff_t(k), v.end());
    hi[a] = v[v.size() - 1 - k];
  }
}

std::string AtomLabel(const Molecule& mol, size_t i) {
  std::string s = "atom " + std::to_string(i + 1);
  if (i < mol.serial.size()) s += " (serial " + std::to_string(mol.serial[i]);
  if (i < mol.atomName.size())
    s += ", " + std::string(mol.atomName[i].data(), strnlen(mol.atomName[i].data(), 4));
  if (i < mol.serial.size()) s += ")";
  char at[96];
  std::snprintf(at, sizeof at, " at (%.3f, %.3f, %.3f)", mol.x[i], mol.y[i], mol.z[i]);
  return s + at;
}

// One line per cap that was hit, naming the first atom it hit (deterministic: index order).
void WarnCapped(const Molecule& mol, size_t atom, const std::string& what) {
  std::fprintf(stderr, "softmol: warning: %s: %s %s\n", mol.sourcePath.empty() ? "molecule" : mol.sourcePath.c_str(),
               AtomLabel(mol, atom).c_str(), what.c_str());
}

}  // namespace

size_t ComputeDistanceBonds(Molecule& mol, const BondOptions& options) {
  const size_t n = mol.atomCount();
  if (n < 2) return 0;

  // Atoms that take part: everything but ions.
  std::vector<float> radius(n);
  float maxRadius = 0.f;
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  size_t included = 0;
  for (size_t i = 0; i < n; ++i) {
    if (mol.flags[i] & kIon) {
      radius[i] = -1.f;  // marks "excluded"
      continue;
    }
    radius[i] = Element(mol.element[i]).covalentRadius;
    maxRadius = std::max(maxRadius, radius[i]);
    lo[0] = std::min(lo[0], mol.x[i]), hi[0] = std::max(hi[0], mol.x[i]);
    lo[1] = std::min(lo[1], mol.y[i]), hi[1] = std::max(hi[1], mol.y[i]);
    lo[2] = std::min(lo[2], mol.z[i]), hi[2] = std::max(hi[2], mol.z[i]);
    ++included;
  }
  if (included < 2) return 0;
  const double tolerance = std::max(0.0, double(options.tolerance));

  // Cell edge: the longest possible bond, grown only when the grid would have more than
  // 8 cells per atom (a hollow capsid's box is mostly empty; a lone far outlier makes it
  // huge). Larger cells stay correct, they just hold more candidates.
  Grid grid;
  double cell = 2.0 * maxRadius + tolerance;
  const double maxCells = 8.0 * double(included) + 65536.0;
  if (Cells(lo, hi, cell) > maxCells) RobustBox(mol, radius, lo, hi);
  while (Cells(lo, hi, cell) > maxCells) cell *= 1.125;
  grid.nx = int64_t(std::floor((hi[0] - lo[0]) / cell) + 1);
  grid.ny = int64_t(std::floor((hi[1] - lo[1]) / cell) + 1);
  grid.nz = int64_t(std::floor((hi[2] - lo[2]) / cell) + 1);
  grid.minX = lo[0], grid.minY = lo[1], grid.minZ = lo[2], grid.inv = 1.0 / cell;
  const size_t cells = size_t(grid.nx * grid.ny * grid.nz);

  // Counting sort into cells, in index order; a full cell turns later atoms away.
  std::vector<uint32_t> cellOf(n, UINT32_MAX);
  grid.cellStart.assign(cells + 1, 0);
  size_t kept = 0, turnedAway = 0, firstTurnedAway = 0;
  for (size_t i = 0; i < n; ++i) {
    if (radius[i] < 0.f) continue;
    const int64_t c = grid.Coord(mol.x[i], grid.minX, grid.nx) +
                      grid.nx * (grid.Coord(mol.y[i], grid.minY, grid.ny) +
                                 grid.ny * grid.Coord(mol.z[i], grid.minZ, grid.nz));
    if (grid.cellStart[size_t(c) + 1] == kMaxCellAtoms) {
      if (turnedAway++ == 0) firstTurnedAway = i;
      continue;
    }
    cellOf[i] = uint32_t(c);
    ++grid.cellStart[size_t(c) + 1];
    ++kept;
  }
  if (turnedAway > 0) {
    char edge[32];
    std::snprintf(edge, sizeof edge, "%.2f", cell);
    WarnCapped(mol, firstTurnedAway,
               "is one of more than " + std::to_string(kMaxCellAtoms) + " atoms in one " + edge +
                   " Å grid cell (atoms on top of each other?): " + std::to_string(turnedAway) +
                   " atom(s) get no distance bonds");
  }
  for (size_t c = 0; c < cells; ++c) grid.cellStart[c + 1] += grid.cellStart[c];

  // What the inner loop reads, packed in cell order: the atoms of x-adjacent cells are
  // adjacent here, so the 27 neighbour cells are 9 contiguous runs of memory.
  struct Packed {
    double x, y, z;
    float radius;
    uint32_t atom;
    uint32_t residue;
    uint16_t model;
    uint8_t flags;
  };
  std::vector<Packed> packed(kept);
  {
    std::vector<uint32_t> fill(grid.cellStart.begin(), grid.cellStart.end() - 1);
    for (size_t i = 0; i < n; ++i)
      if (cellOf[i] != UINT32_MAX)
        packed[fill[cellOf[i]]++] = Packed{mol.x[i], mol.y[i], mol.z[i], radius[i],
                                           uint32_t(i), mol.residueIndex[i],
                                           mol.modelIndex[i], mol.flags[i]};
  }

  const size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> found(chunks);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<uint32_t> partners;
    for (size_t chunk = r.begin(); chunk != r.end(); ++chunk) {
      auto& out = found[chunk];
      out.reserve(kChunk + kChunk / 4);  // ~1.05 bonds per atom in proteins: one allocation
      const size_t end = std::min(n, (chunk + 1) * kChunk);
      for (size_t i = chunk * kChunk; i < end; ++i) {
        if (cellOf[i] == UINT32_MAX) continue;
        const double xi = mol.x[i], yi = mol.y[i], zi = mol.z[i];
        const double ri = double(radius[i]);
        const int64_t cx = grid.Coord(xi, grid.minX, grid.nx);
        const int64_t cy = grid.Coord(yi, grid.minY, grid.ny);
        const int64_t cz = grid.Coord(zi, grid.minZ, grid.nz);
        const uint16_t model = mol.modelIndex[i];
        const uint32_t residue = mol.residueIndex[i];
        const bool hydrogenI = mol.flags[i] & kHydrogen;
        const bool waterI = mol.flags[i] & kWater;
        const int64_t x0 = std::max<int64_t>(cx - 1, 0), x1 = std::min(cx + 1, grid.nx - 1);
        partners.clear();
        for (int64_t z = std::max<int64_t>(cz - 1, 0); z <= std::min(cz + 1, grid.nz - 1); ++z)
          for (int64_t y = std::max<int64_t>(cy - 1, 0); y <= std::min(cy + 1, grid.ny - 1); ++y) {
            const size_t row = size_t(grid.nx * (y + grid.ny * z));
            const uint32_t kEnd = grid.cellStart[row + size_t(x1) + 1];
            for (uint32_t k = grid.cellStart[row + size_t(x0)]; k < kEnd; ++k) {
              const Packed& p = packed[k];
              if (p.atom <= i || p.model != model) continue;
              if (hydrogenI && (p.flags & kHydrogen)) continue;
              if ((waterI || (p.flags & kWater)) && p.residue != residue) continue;
              const double dx = p.x - xi, dy = p.y - yi, dz = p.z - zi;
              const double d2 = dx * dx + dy * dy + dz * dz;
              const double maxLength = ri + double(p.radius) + tolerance;  
              if (d2 >= kMinBondLength * kMinBondLength && d2 <= maxLength * maxLength)
                partners.push_back(p.atom);
            }
          }
        std::sort(partners.begin(), partners.end());
        if (partners.size() > kMaxBonds) partners.resize(kMaxBonds);  // the degree cap below keeps <= kMaxBonds anyway
        for (const uint32_t j : partners) out.emplace_back(uint32_t(i), j);
      }
    }
  });

  // At most kMaxBonds distance bonds per atom, counting both ends, in (i, j) order: sequential,
  // so the same pairs survive for any thread count.
  std::vector<uint16_t> degree(n, 0);
  size_t capped = 0, firstCapped = 0;
  for (auto& f : found) {
    size_t keep = 0;
    for (const auto& [i, j] : f) {
      if (degree[i] >= kMaxBonds || degree[j] >= kMaxBonds) {
        if (capped++ == 0) firstCapped = degree[i] >= kMaxBonds ? i : j;
        continue;
      }
      ++degree[i], ++degree[j];
      f[keep++] = {i, j};
    }
    f.resize(keep);
  }
  if (capped > 0)
    WarnCapped(mol, firstCapped,
               "has more than " + std::to_string(kMaxBonds) + " atoms within bonding distance: " +
                   std::to_string(capped) + " distance bond(s) left out");

  // Merge the sorted record bonds already present with the sorted new pairs.
  size_t total = 0;
  for (const auto& f : found) total += f.size();
  std::vector<uint32_t> a, b;
  std::vector<BondSource> source;
  a.reserve(mol.bondCount() + total), b.reserve(mol.bondCount() + total);
  source.reserve(mol.bondCount() + total);
  size_t old = 0, added = 0;
  auto takeOld = [&] {
    a.push_back(mol.bondA[old]), b.push_back(mol.bondB[old]);
    source.push_back(mol.bondSource[old]);
    ++old;
  };
  for (const auto& f : found)
    for (const auto& [i, j] : f) {
      while (old < mol.bondCount() &&
             std::pair(mol.bondA[old], mol.bondB[old]) < std::pair(i, j))
        takeOld();
      if (old < mol.bondCount() && mol.bondA[old] == i && mol.bondB[old] == j) {
        takeOld();  // already known from a record (or an earlier call): keep its source
        continue;
      }
      a.push_back(i), b.push_back(j), source.push_back(BondSource::kDistance);
      ++added;
    }
  while (old < mol.bondCount()) takeOld();
  mol.bondA = std::move(a);
  mol.bondB = std::move(b);
  mol.bondSource = std::move(source);
  return added;
}

}  // namespace softmol::io
