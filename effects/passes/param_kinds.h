// effects/passes/param_kinds.h — parameter kinds that only the effects know: colours typed as
// sRGB hex or CSS names and stored as linear RGB (shading happens in linear light, DESIGN.md).
#pragma once

#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "effects/color.h"
#include "io/params.h"

namespace softmol::effects {

// The sRGB code that decodes to `c` (exact for colours that came from sRGB hex).
inline std::string SrgbHex(glm::vec3 c) {
  return io::FormatColor(uint32_t(LinearToSrgb8(c.x)) << 16 | uint32_t(LinearToSrgb8(c.y)) << 8 |
                         uint32_t(LinearToSrgb8(c.z)));
}

template <class Target, class Field>  // Field: glm::vec3&
io::Param<Target> ColorParam(std::string name, Field field, std::string help, std::string group) {
  io::Param<Target> p = io::Declare<Target>(std::move(name), "COLOR", std::move(help), std::move(group));
  p.set = [field](Target& t, std::string_view text, const io::SourceLocation& where) {
    field(t) = LinearFromSrgb(io::ParseColorValue(text, where));
  };
  p.get = [field](const Target& t) { return SrgbHex(field(t)); };
  return p;
}

// A colour that may follow another one when not given (the fog follows the background): ""
// leaves it unset.
template <class Target, class Field>  // Field: std::optional<glm::vec3>&
io::Param<Target> OptionalColorParam(std::string name, Field field, std::string help, std::string group) {
  io::Param<Target> p = io::Declare<Target>(std::move(name), "COLOR", std::move(help), std::move(group));
  p.set = [field](Target& t, std::string_view text, const io::SourceLocation& where) {
    if (text.empty()) field(t).reset();
    else field(t) = LinearFromSrgb(io::ParseColorValue(text, where));
  };
  p.get = [field](const Target& t) { return field(t) ? SrgbHex(*field(t)) : std::string(); };
  return p;
}

}  // namespace softmol::effects
