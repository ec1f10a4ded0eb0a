// io/color_names.h — the 148 CSS named colours (CSS Color Module Level 4: "white", "orange",
// "steelblue", both spellings of grey), so every option that takes a colour also takes a name.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace softmol::io {

// The sRGB 0xRRGGBB of a CSS colour name, case-insensitive; nothing for an unknown name.
std::optional<uint32_t> NamedColor(std::string_view name);

}  // namespace softmol::io
