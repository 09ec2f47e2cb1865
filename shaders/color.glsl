// Transfer curves; the same functions as libs/core/src/color.cpp.
float srgb_to_linear(float c) { return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4); }
float linear_to_srgb(float c) { return c <= 0.0031308 ? c * 12.92 : 1.055 * pow(c, 1.0 / 2.4) - 0.055; }
vec3 srgb_to_linear(vec3 c) { return vec3(srgb_to_linear(c.r), srgb_to_linear(c.g), srgb_to_linear(c.b)); }
vec3 linear_to_srgb(vec3 c) { return vec3(linear_to_srgb(c.r), linear_to_srgb(c.g), linear_to_srgb(c.b)); }

// Encoding 0 = exact sRGB, 1 = pow(c, 1/2.2). Input clamped to [0,1].
vec3 encode_display(int encoding, vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return encoding == 1 ? pow(c, vec3(1.0 / 2.2)) : linear_to_srgb(c);
}
