// PNG previews of a frame's layers, for a person looking at out/: a mosaic of tiles, each one layer
// mapped to 8-bit sRGB. The tile order is listed in docs/buffers.md ("Previews").
#pragma once

#include "core/frame.h"
#include "filters/image.h"

#include <string>

namespace rtdr {

void write_preview_png(const std::string& path, const Frame& frame);

// A display-referred image (linear, in [0, 1], e.g. a method's `display` layer) as an 8-bit sRGB PNG.
void write_display_png(const std::string& path, const RgbPlane& display);

}  // namespace rtdr
