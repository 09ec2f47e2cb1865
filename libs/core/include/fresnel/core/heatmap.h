#pragma once
// Error maps as pictures: the magma colour map (as FLIP shows its errors), a heat map with a
// legend bar, and a tiny built-in bitmap font for the legend's labels.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "fresnel/core/image.h"

namespace fresnel {

using Rgb8 = std::array<std::uint8_t, 3>;

// matplotlib's magma (van der Walt and Smith, CC0) at t in [0,1] (clamped; NaN reads 0):
// 33 samples of it, interpolated linearly (within 2/255 of the 256-entry table).
Rgb8 magma(float t);

// `map` (width*height values in [0,1], rows top to bottom) in magma, above a legend band: a
// colour bar from 0 to 1 with ticks and labels at 0, 0.25, 0.5, 0.75 and 1, and `caption` below
// it. The picture is at least 200 pixels wide (the map sits at the left, the rest is the
// band's colour); the band and the font scale up for maps 480 pixels wide or more.
Image8 error_heatmap(const std::vector<float>& map, int width, int height, std::string_view caption);

// The built-in 5x7 font (digits, '.', '-', '%', ':', space and the capitals
// A D E F H I K L M N O P R S; lower case is drawn as upper case; anything else as a box).
// Each glyph advances 6 columns; `scale` multiplies every font pixel. Draws into RGB or RGBA
// images (alpha set to 255), clipped to the image.
int text_width(std::string_view text, int scale);
void draw_text(Image8& image, int x, int y, std::string_view text, int scale, Rgb8 color);

}  // namespace fresnel
