#include "raster/simd_target.h"

#include <hwy/targets.h>

#include <algorithm>
#include <cctype>
#include <cstdint>

#include "io/error.h"

namespace softmol::raster {
namespace {

std::string NameOf(int64_t target) {
  if (target == HWY_EMU128 || target == HWY_SCALAR) return "scalar";
  std::string s = hwy::TargetName(target);
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

std::string Join(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

std::vector<std::string> AvailableSimdTargets() {
  // Undo any earlier restriction: the list is what the CPU has, not what is forced.
  const std::string active = ActiveSimdTarget();
  std::vector<std::string> names;
  hwy::SetSupportedTargetsForTest(0);
  for (const int64_t t : hwy::SupportedAndGeneratedTargets()) names.push_back(NameOf(t));
  if (active != names.front()) ForceSimdTarget(active, "SIMD target");
  return names;
}

std::string ActiveSimdTarget() {
  // Dispatch picks the best (lowest) bit of the supported and generated targets.
  return NameOf(hwy::SupportedAndGeneratedTargets().front());
}

void ForceSimdTarget(std::string_view name, const std::string& where) {
  std::string wanted(name);
  std::transform(wanted.begin(), wanted.end(), wanted.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  hwy::SetSupportedTargetsForTest(0);
  std::vector<std::string> names;
  for (const int64_t t : hwy::SupportedAndGeneratedTargets()) {
    names.push_back(NameOf(t));
    if (names.back() == wanted) {
      hwy::SetSupportedTargetsForTest(t);  // also re-points every dispatch table
      return;
    }
  }
  throw io::InputError({where}, "SIMD target '" + wanted + "' is not available on this CPU and build (available: " +
                                    Join(names) + ")");
}

}  // namespace softmol::raster
