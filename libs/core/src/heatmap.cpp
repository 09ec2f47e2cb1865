#include "fresnel/core/heatmap.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "fresnel/core/error.h"

namespace fresnel {

namespace {

// magma at t = i/32, 8-bit (sampled from matplotlib's table).
constexpr Rgb8 kMagma[33] = {
    {0, 0, 4},       {3, 3, 18},      {10, 8, 34},     {19, 13, 52},    {29, 17, 71},    {41, 17, 90},
    {54, 16, 107},   {68, 15, 118},   {81, 18, 124},   {93, 23, 127},   {106, 28, 129},  {118, 33, 129},
    {131, 38, 129},  {144, 42, 129},  {156, 46, 127},  {170, 51, 125},  {183, 55, 121},  {196, 60, 117},
    {208, 65, 111},  {220, 72, 105},  {231, 82, 99},   {239, 93, 94},   {245, 107, 92},  {249, 121, 93},
    {252, 137, 97},  {253, 152, 105}, {254, 167, 114}, {254, 182, 124}, {254, 196, 136}, {254, 211, 149},
    {253, 226, 163}, {252, 240, 178}, {252, 253, 191},
};

// 5x7 glyphs, one row per byte, bit 4 = leftmost column.
struct Glyph {
    char c;
    std::uint8_t rows[7];
};
constexpr Glyph kFont[] = {
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}}, {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}}, {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}}, {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}}, {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}}, {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}}, {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
    {'%', {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}}, {':', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}},
    {' ', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}}, {'A', {0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
    {'D', {0x1E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1E}}, {'E', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}},
    {'F', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10}}, {'H', {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
    {'I', {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}}, {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}},
    {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F}}, {'M', {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}},
    {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}}, {'O', {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}},
    {'P', {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10}}, {'R', {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11}},
    {'S', {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}},
};
constexpr std::uint8_t kUnknown[7] = {0x1F, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1F};

const std::uint8_t* glyph(char c) {
    const char u = char(std::toupper(static_cast<unsigned char>(c)));
    for (const Glyph& g : kFont)
        if (g.c == u) return g.rows;
    return kUnknown;
}

void put(Image8& img, int x, int y, Rgb8 c) {
    if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
    std::uint8_t* p = img.at(x, y);
    for (int k = 0; k < 3 && k < img.channels; ++k) p[k] = c[k];
    if (img.channels == 4) p[3] = 255;
}

void fill(Image8& img, int x0, int y0, int x1, int y1, Rgb8 c) {
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) put(img, x, y, c);
}

}  // namespace

Rgb8 magma(float t) {
    if (std::isnan(t)) t = 0;
    const float s = std::clamp(t, 0.0f, 1.0f) * 32.0f;
    const int i = std::min(int(s), 31);
    const float f = s - float(i);
    Rgb8 out;
    for (int c = 0; c < 3; ++c)
        out[c] = std::uint8_t(std::lround(float(kMagma[i][c]) * (1 - f) + float(kMagma[i + 1][c]) * f));
    return out;
}

int text_width(std::string_view text, int scale) {
    return text.empty() ? 0 : (int(text.size()) * 6 - 1) * scale;
}

void draw_text(Image8& img, int x, int y, std::string_view text, int scale, Rgb8 color) {
    for (std::size_t i = 0; i < text.size(); ++i) {
        const std::uint8_t* rows = glyph(text[i]);
        const int gx = x + int(i) * 6 * scale;
        for (int r = 0; r < 7; ++r)
            for (int col = 0; col < 5; ++col)
                if (rows[r] & (0x10 >> col)) fill(img, gx + col * scale, y + r * scale, gx + (col + 1) * scale, y + (r + 1) * scale, color);
    }
}

Image8 error_heatmap(const std::vector<float>& map, int width, int height, std::string_view caption) {
    if (width <= 0 || height <= 0 || map.size() != std::size_t(width) * height)
        throw Error("", "", "error map size does not match " + std::to_string(width) + "x" + std::to_string(height));
    const int s = width >= 480 ? 2 : 1;  // font and band scale
    const int margin = 10 * s, bar_h = 12 * s, tick = 3 * s, glyph_h = 7 * s;
    const int band = 6 * s + bar_h + tick + 2 * s + glyph_h + 5 * s + glyph_h + 6 * s;
    const int out_w = std::max(width, std::max(200 * s, text_width(caption, s) + 2 * margin));
    if (std::int64_t(out_w) * (height + band) > (std::int64_t(1) << 30)) throw Error("", "", "heat map too large");
    Image8 img(out_w, height + band, 3);
    const Rgb8 background = {24, 24, 24}, ink = {235, 235, 235};
    fill(img, 0, 0, out_w, height + band, background);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) put(img, x, y, magma(map[std::size_t(y) * width + x]));

    // Colour bar with ticks and labels.
    const int bar_y = height + 6 * s, x0 = margin, x1 = out_w - margin;  // bar spans [x0, x1)
    for (int x = x0; x < x1; ++x) {
        const Rgb8 c = magma(float(x - x0) / float(std::max(1, x1 - x0 - 1)));
        fill(img, x, bar_y, x + 1, bar_y + bar_h, c);
    }
    const char* labels[5] = {"0", "0.25", "0.5", "0.75", "1"};
    const int label_y = bar_y + bar_h + tick + 2 * s;
    for (int k = 0; k < 5; ++k) {
        const int tx = x0 + int(std::lround(k / 4.0 * (x1 - x0 - 1)));
        fill(img, tx - (s - 1) / 2, bar_y + bar_h, tx - (s - 1) / 2 + s, bar_y + bar_h + tick, ink);
        const int tw = text_width(labels[k], s);
        const int lx = std::clamp(tx - tw / 2, 0, out_w - tw);
        draw_text(img, lx, label_y, labels[k], s, ink);
    }
    draw_text(img, x0, label_y + glyph_h + 5 * s, caption, s, ink);
    return img;
}

}  // namespace fresnel
