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
  // Edge cueing gets its own instantiations, so the default kernel is exactly the code it
  // was without it (same bits, no extra work per lane).
  const bool edges = frame.contour || frame.capping;
  if (frame.ortho) {
    if (edges) RasterizeTileT<true, true>(frame, prims, entries, tile, counters);
    else RasterizeTileT<true, false>(frame, prims, entries, tile, counters);
  } else {
    if (edges) RasterizeTileT<false, true>(frame, prims, entries, tile, counters);
    else RasterizeTileT<false, false>(frame, prims, entries, tile, counters);
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
