// tests/io/exr_stream_test.cpp — io::ExrStreamWriter: an EXR written band by band (rows of 1,
// of a zip block and a ragged last band; float and uint32 channels) is byte for byte the file
// WriteExr writes for the whole image and decodes to its values; a band that does not fit, a
// finish before the last row and an abandoned writer are errors that leave no file.
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/error.h"
#include "io/image_io.h"

namespace softmol::io {
namespace {

namespace fs = std::filesystem;

fs::path Scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("softmol_exr_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string Slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A width × height image with colour, depth and ids that differ at every pixel.
ImageFile TestImage(int width, int height) {
  ImageFile img;
  img.width = width, img.height = height;
  const size_t n = size_t(width) * size_t(height);
  for (const char* name : {"R", "G", "B", "A", "Z"}) {
    ImageChannel ch{name, std::vector<float>(n), {}};
    for (size_t i = 0; i < n; ++i) ch.values[i] = float(i % 977) / 977.0f + float(name[0]);
    img.channels.push_back(std::move(ch));
  }
  ImageChannel id{"id", {}, std::vector<uint32_t>(n)};
  for (size_t i = 0; i < n; ++i) id.ids[i] = uint32_t(i * 2654435761u);
  img.channels.push_back(std::move(id));
  return img;
}

// Rows [first, first + rows) of `img`.
ImageFile Rows(const ImageFile& img, int first, int rows) {
  ImageFile band;
  band.width = img.width, band.height = rows;
  const size_t begin = size_t(first) * size_t(img.width), end = begin + size_t(rows) * size_t(img.width);
  for (const ImageChannel& ch : img.channels) {
    ImageChannel c{ch.name, {}, {}};
    if (ch.ids.empty()) c.values.assign(ch.values.begin() + long(begin), ch.values.begin() + long(end));
    else c.ids.assign(ch.ids.begin() + long(begin), ch.ids.begin() + long(end));
    band.channels.push_back(std::move(c));
  }
  return band;
}

TEST(ExrStream, BandsWriteTheWholeImagesBytes) {
  const fs::path dir = Scratch("bands");
  const ImageFile img = TestImage(37, 53);
  WriteExr((dir / "whole.exr").string(), img);
  for (int rows : {1, 16, 20, 53}) {
    const std::string path = (dir / ("banded" + std::to_string(rows) + ".exr")).string();
    ExrStreamWriter exr(path, img.width, img.height);
    for (int y = 0; y < img.height; y += rows) exr.AddRows(Rows(img, y, std::min(rows, img.height - y)));
    exr.Finish();
    EXPECT_TRUE(Slurp(path) == Slurp(dir / "whole.exr")) << "bands of " << rows << " rows";
  }
  const ImageFile back = ReadExr((dir / "banded16.exr").string());
  ASSERT_EQ(back.channels.size(), img.channels.size());
  for (size_t c = 0; c < img.channels.size(); ++c) {
    EXPECT_EQ(back.channels[c].name, img.channels[c].name);
    EXPECT_EQ(back.channels[c].values, img.channels[c].values) << img.channels[c].name;
    EXPECT_EQ(back.channels[c].ids, img.channels[c].ids) << img.channels[c].name;
  }
}

TEST(ExrStream, MisuseIsAnErrorAndLeavesNoFile) {
  const fs::path dir = Scratch("misuse");
  const ImageFile img = TestImage(8, 10);
  const std::string path = (dir / "out.exr").string();
  {
    ExrStreamWriter exr(path, 8, 10);
    exr.AddRows(Rows(img, 0, 6));
    EXPECT_THROW(exr.AddRows(Rows(img, 0, 6)), InputError) << "more rows than the image has";
    EXPECT_THROW(exr.Finish(), InputError) << "finished after 6 of 10 rows";
  }
  {
    ExrStreamWriter exr(path, 8, 10);
    ImageFile other = Rows(img, 0, 5);
    exr.AddRows(other);
    other.channels.pop_back();
    EXPECT_THROW(exr.AddRows(other), InputError) << "a band with other channels";
    ImageFile narrow = TestImage(7, 5);
    EXPECT_THROW(exr.AddRows(narrow), InputError) << "a band of another width";
  }
  {
    ExrStreamWriter exr(path, 8, 10);  // abandoned half-way: a failed render
    exr.AddRows(Rows(img, 0, 4));
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::is_empty(dir)) << "no temporary left behind";
}

}  // namespace
}  // namespace softmol::io
