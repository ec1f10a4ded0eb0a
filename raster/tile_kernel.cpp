// raster/tile_kernel.cpp — compiles raster/tile_kernel-inl.h once per SIMD target and
// dispatches to the best one once per tile (never per pixel).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "raster/tile_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "raster/tile_kernel-inl.h"

HWY_BEFORE_NAMESPACE();
namespace softmol::raster::HWY_NAMESPACE {

void RasterizeTileImpl(const detail::FrameConstants& frame, const detail::PrimArrays& prims,
                       std::span<const detail::BinEntry> entries, detail::TileView& tile,
                       detail::TileCounters& counters) {
  detail::ClearTile(frame, tile);
  if (frame.ortho) {
    RasterizeTileT<true>(frame, prims, entries, tile, counters);
  } else {
    RasterizeTileT<false>(frame, prims, entries, tile, counters);
  }
}

}  // namespace softmol::raster::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace softmol::raster::detail {
HWY_EXPORT(RasterizeTileImpl);

void RasterizeTile(const FrameConstants& frame, const PrimArrays& prims,
                   std::span<const detail::BinEntry> entries, TileView& tile,
                   TileCounters& counters) noexcept {
  HWY_DYNAMIC_DISPATCH(RasterizeTileImpl)(frame, prims, entries, tile, counters);
}
}  // namespace softmol::raster::detail
#endif
