// io/multimodel_reader.cpp — multi-model PDB (MODEL ... ENDMDL blocks, e.g. written by GROMACS
// trjconv or PyMOL) and mmCIF (the _atom_site loop, models told apart by pdbx_PDB_model_num) read
// as trajectories: one frame per model, atoms in the order of the first model. Both stream
// through zlib's gz* functions, which read plain and gzipped files alike: the open scan keeps
// only each model's offset, line and time; a frame reads one model's lines.
// A GROMACS "TITLE ... t= 20.00000" line before a PDB model gives that frame's time.
#include <zlib.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "io/detail/trajectory_formats.h"

namespace softmol::io::detail {
namespace {

// One gzFile with line reading and line numbers.
class LineFile {
 public:
  explicit LineFile(const std::string& path) : path_(path) {
    file_ = gzopen(path.c_str(), "rb");
    if (!file_) throw InputError(FileLoc(path), "cannot open");
    gzbuffer(file_, 1 << 17);
  }
  ~LineFile() { gzclose(file_); }
  LineFile(const LineFile&) = delete;
  LineFile& operator=(const LineFile&) = delete;

  // Offset (uncompressed) of the next line, and its 1-based number.
  int64_t tell() const { return gztell(file_); }
  long nextLine() const { return line_ + 1; }

  void SeekTo(int64_t offset, long lineBefore) {
    if (gzseek(file_, offset, SEEK_SET) != offset)
      throw InputError(FileLoc(path_, {}, lineBefore + 1), "cannot seek in the file");
    line_ = lineBefore;
  }

  // The next line without its end-of-line; false at the end of the file. A line longer than the
  // buffer keeps only its first part (no PDB record needs more than 80 columns).
  bool Next(std::string_view& out) {
    if (!gzgets(file_, buf_, sizeof buf_)) {
      int err = 0;
      const char* msg = gzerror(file_, &err);
      // zlib reports a gzip stream that ends early as Z_BUF_ERROR.
      if (err == Z_BUF_ERROR) throw InputError(FileLoc(path_, {}, line_ + 1), "truncated compressed data");
      if (err != Z_OK) throw InputError(FileLoc(path_, {}, line_ + 1), std::string("read error: ") + msg);
      return false;
    }
    ++line_;
    CheckBomb();
    size_t n = std::strlen(buf_);
    bool complete = n > 0 && buf_[n - 1] == '\n';
    if (!complete && !gzeof(file_)) {
      char rest[1024];  // drop the remainder of an over-long line
      while (gzgets(file_, rest, sizeof rest)) {
        CheckBomb();
        size_t r = std::strlen(rest);
        if (r > 0 && rest[r - 1] == '\n') break;
      }
    }
    while (n > 0 && (buf_[n - 1] == '\n' || buf_[n - 1] == '\r')) --n;
    out = std::string_view(buf_, n);
    return true;
  }

  long line() const { return line_; }
  const std::string& path() const { return path_; }

 private:
  // A gzip bomb is refused as it streams, with the bound of io/structure_reader.cpp: past
  // 16 MiB of text, more than 256 text bytes per compressed byte read so far (real PDB/mmCIF
  // text deflates 3-10×). Checked every 4096 reads (cheap: two integer reads from zlib).
  void CheckBomb() {
    if ((++reads_ & 4095) != 0 || gzdirect(file_)) return;
    const int64_t text = gztell(file_), packed = gzoffset(file_);
    if (text > (int64_t(16) << 20) && text > 256 * std::max<int64_t>(packed, 1))
      throw InputError(FileLoc(path_, {}, line_), "gzip data inflates more than 256× (" + std::to_string(packed) +
                                                      " bytes to " + std::to_string(text) +
                                                      " so far): not a trajectory (a gzip bomb?)");
  }

  uint64_t reads_ = 0;
  std::string path_;
  gzFile file_ = nullptr;
  long line_ = 0;
  char buf_[4096];
};

bool IsRecord(std::string_view line, std::string_view name) { return line.substr(0, name.size()) == name; }
bool IsAtom(std::string_view line) { return IsRecord(line, "ATOM  ") || IsRecord(line, "HETATM"); }

// A fixed-column number (PDB columns are 1-based, inclusive), blanks allowed around it.
bool ParseColumn(std::string_view line, size_t first, size_t last, double& out) {
  if (first < 1 || last < first || line.size() < last) return false;
  std::string_view f = line.substr(first - 1, last - first + 1);
  while (!f.empty() && f.front() == ' ') f.remove_prefix(1);
  while (!f.empty() && f.back() == ' ') f.remove_suffix(1);
  if (f.empty()) return false;
  auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), out);
  return ec == std::errc() && end == f.data() + f.size();
}

// The serial of a MODEL record (columns 11-14, wider in some writers); `fallback` if absent.
int64_t ModelSerial(std::string_view line, size_t fallback) {
  std::string_view f = line.substr(std::min<size_t>(line.size(), 5));
  while (!f.empty() && f.front() == ' ') f.remove_prefix(1);
  int64_t n = 0;
  auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), n);
  (void)end;
  return ec == std::errc() ? n : static_cast<int64_t>(fallback);
}

// "t= 20.00000" in a GROMACS TITLE line; NaN when absent.
double TitleTime(std::string_view line) {
  size_t at = line.rfind("t=");
  if (at == std::string_view::npos) return std::nan("");
  std::string_view f = line.substr(at + 2);
  while (!f.empty() && f.front() == ' ') f.remove_prefix(1);
  double t = 0;
  auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), t);
  (void)end;
  return ec == std::errc() && std::isfinite(t) ? t : std::nan("");
}

class PdbModelsReader final : public TrajectoryReader {
 public:
  PdbModelsReader(const std::string& path, size_t topologyAtoms) : path_(path), file_(path) {
    info_.format = "pdb-models";
    Scan(topologyAtoms);
  }

  const TrajectoryInfo& Info() const override { return info_; }

  void Seek(size_t frameIndex) override {
    if (frameIndex > models_.size())
      throw InputError(FileLoc(path_, FrameDetail(frameIndex)),
                       "seek past the last model (the file has " + std::to_string(models_.size()) + ")");
    next_ = frameIndex;
  }

  bool Next(TrajectoryFrame& frame) override {
    if (next_ >= models_.size()) return false;
    const size_t index = next_;
    const Model& m = models_[index];
    if (file_.tell() != m.offset || file_.line() != m.lineBefore) file_.SeekTo(m.offset, m.lineBefore);
    const size_t n = info_.atomCount;
    frame.x.resize(n);
    frame.y.resize(n);
    frame.z.resize(n);
    size_t atom = 0;
    std::string_view line;
    bool first = true;
    while (file_.Next(line)) {
      if (IsRecord(line, "ENDMDL") || (IsRecord(line, "MODEL ") && !first)) break;
      first = false;
      if (!IsAtom(line)) continue;
      if (atom == n) break;  // the scan counted the atoms; only a changed file gets here
      double c[3];
      for (int k = 0; k < 3; ++k) {
        if (!ParseColumn(line, 31 + 8 * k, 38 + 8 * k, c[k]))
          throw InputError(FileLoc(path_, FrameDetail(index), file_.line()),
                           std::string(1, "xyz"[k]) + " coordinate is not a number: '" +
                               std::string(line.substr(std::min<size_t>(line.size(), 30 + 8 * k), 8)) + "'");
        if (!std::isfinite(c[k]))
          throw InputError(FileLoc(path_, FrameDetail(index), file_.line()), "coordinate is not finite");
      }
      frame.x[atom] = static_cast<float>(c[0]);
      frame.y[atom] = static_cast<float>(c[1]);
      frame.z[atom] = static_cast<float>(c[2]);
      ++atom;
    }
    if (atom != n)
      throw InputError(FileLoc(path_, FrameDetail(index), m.lineBefore + 1),
                       "model has " + std::to_string(atom) + " atoms, expected " + std::to_string(n) +
                           " (the file changed since it was opened?)");
    frame.timePs = std::isnan(m.timePs) ? 0 : m.timePs;
    frame.step = m.number;
    frame.index = index;
    ++next_;
    return true;
  }

 private:
  struct Model {
    int64_t offset = 0;   // of its MODEL line (or of the file when there is none)
    long lineBefore = 0;  // lines before it
    int64_t number = 0;   // the MODEL serial (1 when there is none)
    double timePs = 0;    // from a GROMACS TITLE "t=", NaN when absent
  };

  // Counts the atoms of every model; each must have the first model's count.
  void Scan(size_t topologyAtoms) {
    std::string_view line;
    size_t atoms = 0;
    bool inModel = false, sawModel = false;
    double pendingTime = std::nan("");
    auto close = [&](long line) {
      if (models_.size() == 1) {
        CheckAtomCount(path_, atoms, topologyAtoms);
        info_.atomCount = atoms;
      } else if (atoms != info_.atomCount) {
        const Model& m = models_.back();
        throw InputError(FileLoc(path_, "model " + std::to_string(m.number), m.lineBefore + 1),
                         "model has " + std::to_string(atoms) + " atoms but the first model has " +
                             std::to_string(info_.atomCount) + " (model ends at line " +
                             std::to_string(line) + ")");
      }
      atoms = 0;
      inModel = false;
    };
    while (true) {
      int64_t offset = file_.tell();
      long before = file_.line();
      if (!file_.Next(line)) break;
      if (IsRecord(line, "MODEL ") || line == "MODEL") {
        if (!sawModel && !models_.empty())
          throw InputError(FileLoc(path_, {}, file_.line()), "atom records before the first MODEL record");
        if (inModel) close(before);  // a MODEL with no ENDMDL before the next one
        Model m;
        m.offset = offset;
        m.lineBefore = before;
        m.number = ModelSerial(line, models_.size() + 1);
        m.timePs = pendingTime;
        pendingTime = std::nan("");
        models_.push_back(m);
        inModel = sawModel = true;
      } else if (IsRecord(line, "ENDMDL")) {
        if (inModel) close(file_.line());
      } else if (IsRecord(line, "TITLE ")) {
        pendingTime = TitleTime(line);
      } else if (IsAtom(line)) {
        if (inModel) {
          ++atoms;
        } else if (!sawModel) {
          // No MODEL records so far: the whole file is one model starting at its beginning.
          if (models_.empty()) models_.push_back(Model{0, 0, 1, pendingTime});
          ++atoms;
        } else {
          throw InputError(FileLoc(path_, {}, file_.line()), "atom record outside MODEL/ENDMDL");
        }
      }
    }
    if (inModel || (!sawModel && !models_.empty())) close(file_.line());
    if (models_.empty() || info_.atomCount == 0)
      throw InputError(FileLoc(path_), "no ATOM or HETATM records: not a PDB trajectory");
    info_.frameCount = models_.size();
    if (models_.size() >= 2 && !std::isnan(models_[0].timePs) && !std::isnan(models_[1].timePs))
      info_.timeStepPs = models_[1].timePs - models_[0].timePs;
    file_.SeekTo(0, 0);
  }

  std::string path_;
  LineFile file_;
  TrajectoryInfo info_;
  std::vector<Model> models_;
  size_t next_ = 0;
};

// ---- mmCIF ----

// Splits CIF rows into values: whitespace-separated words, 'quoted' or "quoted" values (a quote
// ends only before whitespace), and ;-delimited text fields spanning lines. Comments (#) outside
// quotes end a line.
class CifTokens {
 public:
  explicit CifTokens(LineFile& file) : file_(file) {}

  // Offset and line count before the line that holds the next value (valid after Peek()).
  int64_t lineOffset() const { return lineOffset_; }
  long lineBefore() const { return lineBefore_; }

  // The next value without consuming it; false at the end of the file.
  bool Peek(std::string_view& value, bool& quoted) {
    if (pendingText_) {
      value = text_;
      quoted = true;
      return true;
    }
    while (pos_ >= line_.size() || !SkipSpace()) {
      lineOffset_ = file_.tell();
      lineBefore_ = file_.line();
      std::string_view next;
      if (!file_.Next(next)) return false;
      if (!next.empty() && next[0] == ';') {  // a text field: its lines up to a lone ';'
        text_.assign(next.substr(1));
        while (true) {
          if (!file_.Next(next))
            throw InputError(FileLoc(file_.path(), {}, file_.line()), "unterminated ;-text field");
          if (!next.empty() && next[0] == ';') break;
          text_.append("\n").append(next);
        }
        line_.assign(next.substr(1));
        pos_ = 0;
        value = text_;
        quoted = true;
        pendingText_ = true;
        return true;
      }
      line_.assign(next);
      pos_ = 0;
    }
    size_t start = pos_, end = pos_;
    quoted = false;
    char q = line_[pos_];
    if (q == '\'' || q == '"') {
      end = pos_ + 1;
      while (end < line_.size() && !(line_[end] == q && (end + 1 == line_.size() || IsSpace(line_[end + 1])))) ++end;
      if (end >= line_.size())
        throw InputError(FileLoc(file_.path(), {}, file_.line()), "unterminated quoted value");
      value = std::string_view(line_).substr(start + 1, end - start - 1);
      quoted = true;
      next_ = end + 1;
      return true;
    }
    while (end < line_.size() && !IsSpace(line_[end])) ++end;
    value = std::string_view(line_).substr(start, end - start);
    next_ = end;
    return true;
  }

  void Consume() {
    if (pendingText_) pendingText_ = false;
    else pos_ = next_;
  }

  // Drops what is left of the current line (used after seeking).
  void Reset() {
    line_.clear();
    pos_ = 0;
    pendingText_ = false;
  }

 private:
  static bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r'; }
  // Moves to the next value on the line; false when the rest is blank or a comment.
  bool SkipSpace() {
    while (pos_ < line_.size() && IsSpace(line_[pos_])) ++pos_;
    if (pos_ >= line_.size() || line_[pos_] == '#') {
      pos_ = line_.size();
      return false;
    }
    return true;
  }

  LineFile& file_;
  std::string line_, text_;
  size_t pos_ = 0, next_ = 0;
  bool pendingText_ = false;
  int64_t lineOffset_ = 0;
  long lineBefore_ = 0;
};

// A CIF number: "12.345", "-1.2e3", "12.345(6)" (a standard uncertainty follows in brackets).
bool ParseCifNumber(std::string_view v, double& out) {
  size_t paren = v.find('(');
  if (paren != std::string_view::npos) v = v.substr(0, paren);
  if (v.empty()) return false;
  auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), out);
  return ec == std::errc() && end == v.data() + v.size();
}

class CifModelsReader final : public TrajectoryReader {
 public:
  CifModelsReader(const std::string& path, size_t topologyAtoms) : path_(path), file_(path), tokens_(file_) {
    info_.format = "cif-models";
    Scan(topologyAtoms);
  }

  const TrajectoryInfo& Info() const override { return info_; }

  void Seek(size_t frameIndex) override {
    if (frameIndex > models_.size())
      throw InputError(FileLoc(path_, FrameDetail(frameIndex)),
                       "seek past the last model (the file has " + std::to_string(models_.size()) + ")");
    next_ = frameIndex;
  }

  bool Next(TrajectoryFrame& frame) override {
    if (next_ >= models_.size()) return false;
    const size_t index = next_;
    const Model& m = models_[index];
    file_.SeekTo(m.offset, m.lineBefore);
    tokens_.Reset();
    const size_t n = info_.atomCount;
    frame.x.resize(n);
    frame.y.resize(n);
    frame.z.resize(n);
    for (size_t atom = 0; atom < n; ++atom) {
      if (!ReadRow(FrameDetail(index)))
        throw InputError(FileLoc(path_, FrameDetail(index)), "the atom_site loop ends inside the model");
      if (modelCol_ >= 0 && row_[modelCol_] != m.numberText)
        throw InputError(FileLoc(path_, FrameDetail(index), rowLine_), "model has fewer atoms than at open");
      double c[3];
      for (int k = 0; k < 3; ++k) {
        if (!ParseCifNumber(row_[xyzCol_[k]], c[k]))
          throw InputError(FileLoc(path_, FrameDetail(index), rowLine_),
                           std::string("Cartn_") + "xyz"[k] + " is not a number: '" + row_[xyzCol_[k]] + "'");
        if (!std::isfinite(c[k]))
          throw InputError(FileLoc(path_, FrameDetail(index), rowLine_), "coordinate is not finite");
      }
      frame.x[atom] = static_cast<float>(c[0]);
      frame.y[atom] = static_cast<float>(c[1]);
      frame.z[atom] = static_cast<float>(c[2]);
    }
    frame.timePs = 0;
    frame.step = m.number;
    frame.index = index;
    ++next_;
    return true;
  }

 private:
  struct Model {
    int64_t offset = 0;  // of the line holding its first row
    long lineBefore = 0;
    int64_t number = 0;
    std::string numberText;
  };

  // Reads one row of the atom_site loop into row_; false at the loop's end.
  bool ReadRow(const std::string& where) {
    std::string_view v;
    bool quoted = false;
    row_.clear();
    while (row_.size() < columns_) {
      if (!tokens_.Peek(v, quoted)) {
        if (row_.empty()) return false;
        throw InputError(FileLoc(path_, where, file_.line()), "the last atom_site row is incomplete");
      }
      // A tag, loop_, data_ or save_ ends the loop (unquoted only).
      if (!quoted && (v[0] == '_' || v == "loop_" || v.starts_with("data_") || v.starts_with("save_"))) {
        if (row_.empty()) return false;
        throw InputError(FileLoc(path_, where, file_.line()), "an atom_site row is cut short");
      }
      if (row_.empty()) {
        rowOffset_ = tokens_.lineOffset();
        rowLineBefore_ = tokens_.lineBefore();
        rowLine_ = file_.line();
      }
      row_.emplace_back(v);
      tokens_.Consume();
    }
    return true;
  }

  void Scan(size_t topologyAtoms) {
    // Find "loop_" followed by _atom_site.* tags.
    std::string_view v;
    bool quoted = false;
    std::vector<std::string> tags;
    bool found = false;
    while (!found && tokens_.Peek(v, quoted)) {
      tokens_.Consume();
      if (quoted || v != "loop_") continue;
      tags.clear();
      while (tokens_.Peek(v, quoted) && !quoted && v.starts_with("_")) {
        tags.emplace_back(v);
        tokens_.Consume();
      }
      found = !tags.empty() && tags[0].starts_with("_atom_site.");
    }
    if (!found) throw InputError(FileLoc(path_), "no _atom_site loop: not an mmCIF coordinate file");
    columns_ = tags.size();
    const char* names[3] = {"_atom_site.Cartn_x", "_atom_site.Cartn_y", "_atom_site.Cartn_z"};
    for (size_t c = 0; c < tags.size(); ++c) {
      for (int k = 0; k < 3; ++k)
        if (tags[c] == names[k]) xyzCol_[k] = static_cast<int>(c);
      if (tags[c] == "_atom_site.pdbx_PDB_model_num") modelCol_ = static_cast<int>(c);
    }
    for (int k = 0; k < 3; ++k)
      if (xyzCol_[k] < 0) throw InputError(FileLoc(path_), std::string("the atom_site loop has no ") + names[k]);

    size_t atoms = 0;
    std::unordered_set<std::string> seen;  // model numbers met so far
    auto close = [&] {
      if (models_.size() == 1) {
        CheckAtomCount(path_, atoms, topologyAtoms);
        info_.atomCount = atoms;
      } else if (atoms != info_.atomCount) {
        const Model& m = models_.back();
        throw InputError(FileLoc(path_, "model " + m.numberText, m.lineBefore + 1),
                         "model has " + std::to_string(atoms) + " atoms but the first model has " +
                             std::to_string(info_.atomCount));
      }
      atoms = 0;
    };
    while (ReadRow("atom_site")) {
      std::string number = modelCol_ >= 0 ? row_[modelCol_] : std::string("1");
      if (models_.empty() || number != models_.back().numberText) {
        if (!models_.empty()) close();
        if (!seen.insert(number).second)
          throw InputError(FileLoc(path_, {}, rowLine_), "model " + number + " appears twice (rows not grouped by model)");
        Model m;
        m.offset = rowOffset_;
        m.lineBefore = rowLineBefore_;
        m.numberText = number;
        int64_t num = 0;
        auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), num);
        (void)end;
        m.number = ec == std::errc() ? num : static_cast<int64_t>(models_.size() + 1);
        models_.push_back(std::move(m));
      }
      ++atoms;
    }
    if (models_.empty()) throw InputError(FileLoc(path_), "the atom_site loop has no rows");
    close();
    info_.frameCount = models_.size();
  }

  std::string path_;
  LineFile file_;
  CifTokens tokens_;
  TrajectoryInfo info_;
  std::vector<Model> models_;
  size_t columns_ = 0;
  int xyzCol_[3] = {-1, -1, -1};
  int modelCol_ = -1;
  std::vector<std::string> row_;
  int64_t rowOffset_ = 0;
  long rowLineBefore_ = 0, rowLine_ = 0;
  size_t next_ = 0;
};

}  // namespace

std::unique_ptr<TrajectoryReader> OpenPdbModels(const std::string& path, size_t topologyAtomCount) {
  return std::make_unique<PdbModelsReader>(path, topologyAtomCount);
}

std::unique_ptr<TrajectoryReader> OpenCifModels(const std::string& path, size_t topologyAtomCount) {
  return std::make_unique<CifModelsReader>(path, topologyAtomCount);
}

}  // namespace softmol::io::detail
