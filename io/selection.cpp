// io/selection.cpp — tokenizer, recursive-descent parser and evaluator of selections.
#include "io/selection.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <gemmi/resinfo.hpp>

#include "common/binning.h"
#include "io/elements.h"
#include "io/error.h"

namespace softmol::io {
namespace {

using Kind = Selection::Kind;

struct Token {
  std::string text;
  int column = 0;  // 1-based
};

std::string Upper(std::string_view s) {
  std::string u(s);
  for (char& c : u) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return u;
}

std::vector<Token> Tokenize(std::string_view text) {
  std::vector<Token> tokens;
  size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '(' || c == ')') {
      tokens.push_back({std::string(1, c), int(i) + 1});
      ++i;
    } else {
      const size_t start = i;
      while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i])) &&
             text[i] != '(' && text[i] != ')')
        ++i;
      tokens.push_back({std::string(text.substr(start, i - start)), int(start) + 1});
    }
  }
  return tokens;
}

struct Keyword {
  const char* word;
  Kind kind;
};
constexpr Keyword kSimple[] = {
    {"ALL", Kind::kAll},         {"NONE", Kind::kNone},       {"HETATM", Kind::kHetatm},
    {"PROTEIN", Kind::kProtein}, {"NUCLEIC", Kind::kNucleic}, {"WATER", Kind::kWater},
    {"ION", Kind::kIon},         {"LIGAND", Kind::kLigand},   {"HYDROGEN", Kind::kHydrogen},
    {"POLYMER", Kind::kPolymer},
};
constexpr const char* kValued[] = {"CHAIN", "RESN", "NAME", "ELEM", "RESI"};

bool IsOperatorWord(const std::string& upper) {
  return upper == "AND" || upper == "OR" || upper == "NOT" || upper == "(" || upper == ")" ||
         upper == "WITHIN" || upper == "OF";
}

// Parses a whole-string integer; false if it is not one (or overflows int32).
bool ParseInt(std::string_view s, int32_t& out) {
  if (s.empty() || s.size() > 11) return false;
  size_t i = 0;
  bool negative = false;
  if (s[0] == '-' || s[0] == '+') negative = s[i++] == '-';
  if (i == s.size()) return false;
  int64_t v = 0;
  for (; i < s.size(); ++i) {
    if (s[i] < '0' || s[i] > '9') return false;
    v = v * 10 + (s[i] - '0');
  }
  v = negative ? -v : v;
  if (v < INT32_MIN || v > INT32_MAX) return false;
  out = int32_t(v);
  return true;
}

class Parser {
 public:
  explicit Parser(std::string_view text) : tokens_(Tokenize(text)), end_(int(text.size()) + 1) {
    sel_.text = std::string(text);
  }

  Selection Parse() {
    if (tokens_.empty()) Fail(end_, "empty selection");
    sel_.root = ParseOr();
    if (pos_ < tokens_.size())
      Fail(tokens_[pos_].column, "unexpected '" + tokens_[pos_].text +
                                     "' after a complete selection (missing 'and' or 'or'?)");
    return std::move(sel_);
  }

 private:
  [[noreturn]] void Fail(int column, const std::string& message) const {
    throw InputError(SourceLocation("selection", 1, column), message);
  }
  bool AtEnd() const { return pos_ >= tokens_.size(); }
  std::string PeekUpper() const { return AtEnd() ? std::string() : Upper(tokens_[pos_].text); }
  std::string Found() const {
    return AtEnd() ? "end of selection" : "'" + tokens_[pos_].text + "'";
  }
  int Column() const { return AtEnd() ? end_ : tokens_[pos_].column; }

  int Add(Selection::Node node) {
    sel_.nodes.push_back(std::move(node));
    return int(sel_.nodes.size()) - 1;
  }

  int ParseOr() {
    int lhs = ParseAnd();
    while (PeekUpper() == "OR") {
      ++pos_;
      Selection::Node n;
      n.kind = Kind::kOr;
      n.lhs = lhs;
      n.rhs = ParseAnd();
      lhs = Add(std::move(n));
    }
    return lhs;
  }

  int ParseAnd() {
    int lhs = ParseUnary();
    while (PeekUpper() == "AND") {
      ++pos_;
      Selection::Node n;
      n.kind = Kind::kAnd;
      n.lhs = lhs;
      n.rhs = ParseUnary();
      lhs = Add(std::move(n));
    }
    return lhs;
  }

  int ParseUnary() {
    if (++depth_ > 200) Fail(Column(), "selection is nested too deeply");
    int result;
    const std::string word = PeekUpper();
    if (word == "NOT") {
      ++pos_;
      Selection::Node n;
      n.kind = Kind::kNot;
      n.lhs = ParseUnary();
      result = Add(std::move(n));
    } else if (word == "WITHIN") {
      ++pos_;
      Selection::Node n;
      n.kind = Kind::kWithin;
      const std::string number = AtEnd() ? "" : tokens_[pos_].text;
      char* endp = nullptr;
      const double d = number.empty() ? NAN : std::strtod(number.c_str(), &endp);
      if (number.empty() || endp != number.c_str() + number.size() || !std::isfinite(d) ||
          d < 0 || d > 1000)
        Fail(Column(), "expected a distance in Å (0 to 1000) after 'within', found " + Found());
      ++pos_;
      if (PeekUpper() != "OF")
        Fail(Column(), "expected 'of' after 'within " + number + "', found " + Found());
      ++pos_;
      n.distance = d;
      n.lhs = ParseUnary();
      result = Add(std::move(n));
    } else {
      result = ParsePrimary();
    }
    --depth_;
    return result;
  }

  int ParsePrimary() {
    if (AtEnd()) Fail(end_, "expected a selection, found end of selection");
    const Token& tok = tokens_[pos_];
    const std::string word = Upper(tok.text);
    if (word == "(") {
      ++pos_;
      const int inner = ParseOr();
      if (PeekUpper() != ")")
        Fail(Column(), "expected ')' to close '(' at column " + std::to_string(tok.column) +
                           ", found " + Found());
      ++pos_;
      return inner;
    }
    for (const Keyword& k : kSimple)
      if (word == k.word) {
        ++pos_;
        Selection::Node n;
        n.kind = k.kind;
        return Add(std::move(n));
      }
    for (const char* v : kValued)
      if (word == v) {
        ++pos_;
        return ParseValued(tok);
      }
    if (IsOperatorWord(word)) Fail(tok.column, "expected a selection, found '" + tok.text + "'");
    Fail(tok.column, "unknown keyword '" + tok.text +
                         "' (expected all, none, hetatm, protein, nucleic, water, ion, ligand, "
                         "hydrogen, polymer, chain, resn, resi, name, elem, within, not, '(')");
  }

  int ParseValued(const Token& keyword) {
    const std::string key = Upper(keyword.text);
    const std::string lowerKey = [&] {
      std::string s = key;
      for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
      return s;
    }();
    const char* what = key == "RESI" ? "a number" : key == "ELEM" ? "an element symbol"
                     : key == "CHAIN" ? "a chain name" : key == "RESN" ? "a residue name"
                                                       : "an atom name";
    if (AtEnd() || IsOperatorWord(Upper(tokens_[pos_].text)))
      Fail(Column(), std::string("expected ") + what + " after '" + lowerKey + "', found " +
                         Found());
    const Token& value = tokens_[pos_++];
    Selection::Node n;
    n.kind = key == "CHAIN" ? Kind::kChain : key == "RESN" ? Kind::kResn
           : key == "NAME" ? Kind::kName : key == "ELEM" ? Kind::kElem : Kind::kResi;
    // Values are joined by '+': "A+B", "ALA+GLY", "5+7+10-12".
    size_t start = 0;
    const std::string& s = value.text;
    while (start <= s.size()) {
      size_t plus = s.find('+', start);
      if (plus == std::string::npos) plus = s.size();
      const std::string part = s.substr(start, plus - start);
      const int column = value.column + int(start);
      if (part.empty())
        Fail(column, std::string("expected ") + what + " after '" + lowerKey + "', found '" +
                         value.text + "'");
      if (n.kind == Kind::kResi) {
        // "a", "a-b"; either may be negative: the range dash is the first '-' after a digit.
        size_t dash = std::string::npos;
        for (size_t i = 1; i < part.size(); ++i)
          if (part[i] == '-' && std::isdigit(static_cast<unsigned char>(part[i - 1]))) {
            dash = i;
            break;
          }
        int32_t a = 0, b = 0;
        const bool ok = dash == std::string::npos
                            ? ParseInt(part, a) && ParseInt(part, b)
                            : ParseInt(std::string_view(part).substr(0, dash), a) &&
                                  ParseInt(std::string_view(part).substr(dash + 1), b);
        if (!ok)
          Fail(column, "expected a number after 'resi', found '" + part + "'");
        if (b < a)
          Fail(column, "empty residue range '" + part + "' (the first number is larger)");
        n.ranges.emplace_back(a, b);
      } else if (n.kind == Kind::kElem) {
        const uint8_t z = ElementFromSymbol(part);
        if (z == 0) Fail(column, "unknown element '" + part + "' after 'elem'");
        n.elements.push_back(z);
      } else {
        n.words.push_back(n.kind == Kind::kChain ? part : Upper(part));
      }
      start = plus + 1;
    }
    return Add(std::move(n));
  }

  std::vector<Token> tokens_;
  int end_;
  size_t pos_ = 0;
  int depth_ = 0;
  Selection sel_;
};

// ---------------------------------------------------------------------------------------
// Evaluation.

template <class F>
void ForEachAtom(size_t n, std::vector<uint8_t>& out, F&& pred) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 8192), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) out[i] = pred(i) ? 1 : 0;
  });
}

std::string AtomNameUpper(const Molecule& mol, size_t i) {
  const auto& a = mol.atomName[i];
  return Upper(std::string_view(a.data(), strnlen(a.data(), a.size())));
}

// Atoms within `d` Å of any selected atom (same model), on a uniform grid of the selected
// atoms with cell edge d.
std::vector<uint8_t> Within(const Molecule& mol, const std::vector<uint8_t>& target, double d) {
  const size_t n = mol.atomCount();
  std::vector<uint8_t> out(n, 0);
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  size_t count = 0;
  for (size_t i = 0; i < n; ++i)
    if (target[i]) {
      lo[0] = std::min(lo[0], mol.x[i]), hi[0] = std::max(hi[0], mol.x[i]);
      lo[1] = std::min(lo[1], mol.y[i]), hi[1] = std::max(hi[1], mol.y[i]);
      lo[2] = std::min(lo[2], mol.z[i]), hi[2] = std::max(hi[2], mol.z[i]);
      ++count;
    }
  if (count == 0) return out;
  double cell = std::max(d, 0.5);
  int64_t dims[3];
  for (;;) {
    double cells = 1;
    for (int k = 0; k < 3; ++k) cells *= std::floor((hi[k] - lo[k]) / cell) + 1;
    if (cells <= 2.0 * double(count) + 4096) break;
    cell *= 1.25;
  }
  for (int k = 0; k < 3; ++k) dims[k] = int64_t(std::floor((hi[k] - lo[k]) / cell)) + 1;
  auto coord = [&](double v, int k) {
    return std::clamp<int64_t>(int64_t(std::floor((v - lo[k]) / cell)), 0, dims[k] - 1);
  };
  // Each cell's selected atoms, in atom order (common/binning.h).
  const size_t cells = size_t(dims[0] * dims[1] * dims[2]);
  Bins bins;
  std::vector<uint32_t> atoms;
  BinItems(
      n, cells,
      [&](size_t i, auto&& f) {
        if (target[i])
          f(size_t(coord(mol.x[i], 0) + dims[0] * (coord(mol.y[i], 1) + dims[1] * coord(mol.z[i], 2))));
      },
      [](size_t i) { return uint32_t(i); }, bins, atoms);
  const std::vector<uint32_t>& start = bins.start;
  const double d2 = d * d;
  ForEachAtom(n, out, [&](size_t i) {
    if (target[i]) return true;
    const double p[3] = {mol.x[i], mol.y[i], mol.z[i]};
    int64_t from[3], to[3];
    for (int k = 0; k < 3; ++k) {
      if (p[k] < lo[k] - d || p[k] > hi[k] + d) return false;
      from[k] = coord(p[k] - d, k), to[k] = coord(p[k] + d, k);
    }
    for (int64_t z = from[2]; z <= to[2]; ++z)
      for (int64_t y = from[1]; y <= to[1]; ++y)
        for (int64_t x = from[0]; x <= to[0]; ++x) {
          const size_t c = size_t(x + dims[0] * (y + dims[1] * z));
          for (uint32_t k = start[c]; k < start[c + 1]; ++k) {
            const uint32_t j = atoms[k];
            if (mol.modelIndex[j] != mol.modelIndex[i]) continue;
            const double dx = mol.x[j] - p[0], dy = mol.y[j] - p[1], dz = mol.z[j] - p[2];
            if (dx * dx + dy * dy + dz * dz <= d2) return true;
          }
        }
    return false;
  });
  return out;
}

std::vector<uint8_t> Eval(const Selection& sel, int index, const Molecule& mol) {
  const Selection::Node& node = sel.nodes.at(size_t(index));
  const size_t n = mol.atomCount();
  std::vector<uint8_t> out(n, 0);
  auto residueMask = [&](auto&& pred) {
    std::vector<uint8_t> mask(mol.residues.size());
    for (size_t r = 0; r < mol.residues.size(); ++r) mask[r] = pred(mol.residues[r]) ? 1 : 0;
    return mask;
  };
  auto byResidue = [&](const std::vector<uint8_t>& mask) {
    ForEachAtom(n, out, [&](size_t i) { return mask[mol.residueIndex[i]] != 0; });
  };
  auto flagged = [&](uint8_t flag) {
    ForEachAtom(n, out, [&](size_t i) { return (mol.flags[i] & flag) != 0; });
  };
  auto residueName = [](const Residue& r) {
    return std::string(r.name.data(), strnlen(r.name.data(), r.name.size()));
  };
  switch (node.kind) {
    case Kind::kAll: std::fill(out.begin(), out.end(), 1); break;
    case Kind::kNone: break;
    case Kind::kHetatm: flagged(kHetatm); break;
    case Kind::kWater: flagged(kWater); break;
    case Kind::kIon: flagged(kIon); break;
    case Kind::kHydrogen: flagged(kHydrogen); break;
    case Kind::kPolymer: flagged(kPolymer); break;
    case Kind::kLigand:
      ForEachAtom(n, out, [&](size_t i) {
        return (mol.flags[i] & kHetatm) && !(mol.flags[i] & (kWater | kIon));
      });
      break;
    case Kind::kProtein:
      byResidue(residueMask([&](const Residue& r) {
        return gemmi::find_tabulated_residue(residueName(r)).is_amino_acid();
      }));
      break;
    case Kind::kNucleic:
      byResidue(residueMask([&](const Residue& r) {
        return gemmi::find_tabulated_residue(residueName(r)).is_nucleic_acid();
      }));
      break;
    case Kind::kChain:
      byResidue(residueMask([&](const Residue& r) {
        const std::string& name = mol.chains[r.chainIndex].name;
        return std::find(node.words.begin(), node.words.end(), name) != node.words.end();
      }));
      break;
    case Kind::kResn:
      byResidue(residueMask([&](const Residue& r) {
        const std::string name = Upper(residueName(r));
        return std::find(node.words.begin(), node.words.end(), name) != node.words.end();
      }));
      break;
    case Kind::kResi:
      byResidue(residueMask([&](const Residue& r) {
        for (const auto& [a, b] : node.ranges)
          if (r.seqNum >= a && r.seqNum <= b) return true;
        return false;
      }));
      break;
    case Kind::kName:
      ForEachAtom(n, out, [&](size_t i) {
        const std::string name = AtomNameUpper(mol, i);
        return std::find(node.words.begin(), node.words.end(), name) != node.words.end();
      });
      break;
    case Kind::kElem:
      ForEachAtom(n, out, [&](size_t i) {
        return std::find(node.elements.begin(), node.elements.end(), mol.element[i]) !=
               node.elements.end();
      });
      break;
    case Kind::kWithin: out = Within(mol, Eval(sel, node.lhs, mol), node.distance); break;
    case Kind::kNot:
      out = Eval(sel, node.lhs, mol);
      for (uint8_t& v : out) v = v ? 0 : 1;
      break;
    case Kind::kAnd: {
      out = Eval(sel, node.lhs, mol);
      const std::vector<uint8_t> rhs = Eval(sel, node.rhs, mol);
      for (size_t i = 0; i < n; ++i) out[i] = out[i] & rhs[i];
      break;
    }
    case Kind::kOr: {
      out = Eval(sel, node.lhs, mol);
      const std::vector<uint8_t> rhs = Eval(sel, node.rhs, mol);
      for (size_t i = 0; i < n; ++i) out[i] = out[i] | rhs[i];
      break;
    }
  }
  return out;
}

}  // namespace

Selection ParseSelection(std::string_view text) { return Parser(text).Parse(); }

Selection ParseSelection(std::string_view text, const SourceLocation& where) {
  try {
    return ParseSelection(text);
  } catch (const InputError& e) {
    SourceLocation at = where;
    at.column = e.where().column;
    throw InputError(at, e.message());
  }
}

std::vector<uint8_t> Evaluate(const Selection& selection, const Molecule& mol) {
  if (selection.root < 0) return std::vector<uint8_t>(mol.atomCount(), 0);
  return Eval(selection, selection.root, mol);
}

}  // namespace softmol::io
